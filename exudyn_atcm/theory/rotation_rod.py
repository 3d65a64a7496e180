"""Geometrically exact rotation-field rod in assumed modes: the mathematics of the ``rod`` cell.

The rod is the inextensible, shear-rigid (Euler-Bernoulli) plane beam of the ``ritz`` cell
(:mod:`exudyn_atcm.theory.ritz_beam`), here clamped at ``s = 0`` (the compiled kernels of
:mod:`exudyn_atcm.theory.rod_kernels` put it on a moving base), with its rotation field in the same
``n`` assumed modes ``theta(s, t) = sum_i q_i(t) phi_i(s / L)``, but *without* the ``ritz`` cell's
linearisation: position, inertia and end pose are the exact nonlinear functions of ``q``
(the rotation-field description of the plane elastica; Reissner 1972, Simo & Vu-Quoc 1986;
in the spirit of the geometric variable-strain Cosserat rods of Renda et al. 2018).

* Position ``r(s) = int_0^s (cos theta, sin theta) ds'``; the tip pose ``(r(L), theta(L))``,
  ``theta(L) = q_1`` (``phi_i(1) = 0`` for ``i >= 2``).
* Elastic energy ``1/2 int EI (theta' - kappa0)^2 ds``: exactly quadratic, ``K`` diagonal,
  the free curvature loads ``q_1`` only (``Q_1 = EI kappa0``); as in the ``ritz`` cell.
* Kinetic energy ``1/2 int (mu |r_dot|^2 + rho_I theta_dot^2) ds`` with the exact velocity
  ``r_dot(s) = sum_i a_i(s) q_dot_i``, ``a_i(s) = int_0^s (-sin theta, cos theta) phi_i ds'``:

      M(q) = int (mu a a^T + rho_I phi phi^T) ds,
      M(q) q_ddot + g(q, q_dot) + K q + D q_dot = Q,   g = mu int a^T b ds,
      b(s) = -int_0^s (cos theta, sin theta) theta_dot^2 ds'

  (``g``: the quadratic velocity vector, the time derivative of ``a`` applied to ``q_dot``).
* Quadrature: ``N`` Gauss-Legendre points ``xi_k`` on ``[0, 1]``; the integrals from ``0`` to
  each point are the spectral integration matrix ``S`` (exact for polynomials of degree
  ``< N``, :func:`quadrature`).  With ``N = 2 n + 8`` points (:func:`rule_points`) the mass
  matrix, the quadratic velocity vector and the tip pose of ``n`` = 3, 4, 8 modes with rotations
  up to 2.5 rad agree with a 64-point rule to round-off (3e-14, measured); ``2 n + 4`` points
  leave 1e-11.

The Exudyn realisation (:mod:`exudyn_atcm.mbs.chains.rod`) carries ``M``, ``g`` and the tip
pose's linearisation, re-evaluated in every step (:mod:`exudyn_atcm.theory.rod_kernels`, compiled
with numba); this module holds the numpy reference of the same formulas and the quadrature.

May import: numpy (and the ``ritz`` cell's shapes).
"""

from __future__ import annotations

import functools

import numpy as np
from numpy.polynomial import legendre

from . import ritz_beam

__all__ = ["rule_points", "quadrature", "RodShapes", "rod_shapes", "tip_pose", "mass_matrix",
           "quadratic_velocity_vector"]


def rule_points(n: int) -> int:
    """Quadrature points ``N = 2 n + 8`` for ``n`` modes (see the module's docstring)."""
    return 2 * int(n) + 8


@functools.lru_cache(maxsize=32)
def quadrature(n_points: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Gauss-Legendre points ``xi`` and weights ``w`` on ``[0, 1]`` and the integration matrix ``S``.

    ``S[j, k]``: weight of ``f(xi_k)`` in ``int_0^{xi_j} f dxi``, exact for polynomials of
    degree ``< n_points`` (read-only arrays).
    """
    if isinstance(n_points, bool) or not isinstance(n_points, (int, np.integer)) or n_points < 2:
        raise ValueError(f"n_points must be an integer >= 2, got {n_points!r}")
    y, w = legendre.leggauss(int(n_points))
    vander = legendre.legvander(y, n_points - 1)
    integrals = np.empty_like(vander)
    for m in range(n_points):
        coefficients = np.zeros(n_points)
        coefficients[m] = 1.0
        integrals[:, m] = legendre.legval(y, legendre.legint(coefficients, lbnd=-1.0, scl=0.5))
    s = np.linalg.solve(vander.T, integrals.T).T
    out = (0.5 * (y + 1.0), 0.5 * w, s)
    for a in out:
        a.flags.writeable = False
    return out


class RodShapes:
    """The sampled shapes of an ``n``-mode rod of length ``length`` [m] (contiguous float arrays).

    Attributes
    ----------
    phi : ndarray (N, n)
        ``phi_i(xi_k)`` at the quadrature points.
    weights : ndarray (N,)
        Quadrature weights on ``[0, 1]``.
    integration : ndarray (N, N)
        ``S`` of :func:`quadrature`.
    phi_tip : ndarray (n,)
        ``phi_i(1)`` (``(1, 0, ..., 0)``).
    phi_hat, phi_hat_tip : ndarray (N, n + 1), (n + 1,)
        The same with a first column of ones: the shapes of ``(Phi, q)`` in the absolute rotation
        ``Phi + sum q_i phi_i`` of a rod on a moving base (:mod:`exudyn_atcm.theory.rod_kernels`).
    """

    def __init__(self, n: int, length: float) -> None:
        self.n = int(n)
        self.length = float(length)
        xi, w, s = quadrature(rule_points(self.n))
        self.phi = np.ascontiguousarray(ritz_beam.rotation_shapes(self.n, xi))
        self.weights = np.ascontiguousarray(w)
        self.integration = np.ascontiguousarray(s)
        self.phi_tip = np.ascontiguousarray(ritz_beam.rotation_shapes(self.n, np.array([1.0]))[0])
        self.phi_hat = np.ascontiguousarray(np.column_stack([np.ones(len(xi)), self.phi]))
        self.phi_hat_tip = np.ascontiguousarray(np.concatenate([[1.0], self.phi_tip]))


@functools.lru_cache(maxsize=64)
def rod_shapes(n: int, length: float) -> RodShapes:
    """Cached :class:`RodShapes`."""
    return RodShapes(n, length)


def _velocity_shapes(shapes: RodShapes, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    theta = shapes.phi @ q
    c, s = np.cos(theta), np.sin(theta)
    ax = -shapes.length * shapes.integration @ (s[:, None] * shapes.phi)
    ay = shapes.length * shapes.integration @ (c[:, None] * shapes.phi)
    return theta, c, s, np.stack([ax, ay])


def tip_pose(shapes: RodShapes, q) -> np.ndarray:
    """Tip ``(x, y, theta)`` [m, m, rad] in the rod's frame (base at the origin, axis along x)."""
    q = np.asarray(q, dtype=float)
    theta = shapes.phi @ q
    lw = shapes.length * shapes.weights
    return np.array([lw @ np.cos(theta), lw @ np.sin(theta), shapes.phi_tip @ q])


def mass_matrix(shapes: RodShapes, q, mass_per_length: float, rotary_inertia: float) -> np.ndarray:
    """``M(q)`` [kg m^2] of the coordinates [rad] (numpy reference of the compiled kernel)."""
    _, _, _, a = _velocity_shapes(shapes, np.asarray(q, dtype=float))
    lw = shapes.length * shapes.weights
    m = mass_per_length * (np.einsum("k,dki,dkj->ij", lw, a, a))
    return m + rotary_inertia * (shapes.phi.T * lw) @ shapes.phi


def quadratic_velocity_vector(shapes: RodShapes, q, q_dot, mass_per_length: float) -> np.ndarray:
    """``g(q, q_dot)`` [N m] (on the left-hand side of the equations of motion)."""
    q, q_dot = np.asarray(q, dtype=float), np.asarray(q_dot, dtype=float)
    theta, c, s, a = _velocity_shapes(shapes, q)
    rate2 = (shapes.phi @ q_dot) ** 2
    b = -shapes.length * np.stack([shapes.integration @ (c * rate2), shapes.integration @ (s * rate2)])
    lw = shapes.length * shapes.weights
    return mass_per_length * np.einsum("k,dki,dk->i", lw, a, b)
