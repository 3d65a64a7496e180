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
from typing import Any, Callable

import numpy as np
from numpy.polynomial import legendre

from .._checks import shown
from . import ritz_beam

__all__ = ["rule_points", "quadrature", "RodShapes", "rod_shapes", "tip_pose", "mass_matrix",
           "quadratic_velocity_vector", "truncation_error", "truncation_estimator"]


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
        raise ValueError(f"n_points must be an integer >= 2, got {shown(n_points)}")
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
    modes, lengths : tuple
        Per segment: its number of modes and its length [m] (one segment: ``(n,)``, ``(length,)``).
        A rod of several segments has each segment's modes on its own length, its rotation
        continuous, its curvature free to jump at the segment ends (:func:`_composite`); the points,
        weights and integration matrix are then in units of the whole ``length``.
    """

    def __init__(self, n: int, length: float, modes: tuple[int, ...] | None = None,
                 lengths: tuple[float, ...] | None = None) -> None:
        self.modes = (int(n),) if modes is None else tuple(int(m) for m in modes)
        self.lengths = (float(length),) if lengths is None else tuple(float(a) for a in lengths)
        if len(self.modes) != len(self.lengths) or sum(self.modes) != int(n):
            raise ValueError(f"modes {self.modes} and lengths {self.lengths}: one entry per segment, summing to "
                             f"n = {n}")
        self.n = int(n)
        self.length = float(length)
        phi, weights, integration, phi_tip = _composite(self.modes, self.lengths, self.length)
        self.phi = np.ascontiguousarray(phi)
        self.weights = np.ascontiguousarray(weights)
        self.integration = np.ascontiguousarray(integration)
        self.phi_tip = np.ascontiguousarray(phi_tip)
        self.phi_hat = np.ascontiguousarray(np.column_stack([np.ones(len(weights)), self.phi]))
        self.phi_hat_tip = np.ascontiguousarray(np.concatenate([[1.0], self.phi_tip]))

    @property
    def first_modes(self) -> list[int]:
        """Index of each segment's first mode (the one its free curvature loads) in ``q``."""
        return [int(sum(self.modes[:j])) for j in range(len(self.modes))]

    def stiffness_matrix(self, bending_stiffness: float) -> np.ndarray:
        """``K`` [N m] of ``q``: each segment's block of the ``ritz`` cell's diagonal stiffness."""
        k = np.zeros((self.n, self.n))
        for first, m, a in zip(self.first_modes, self.modes, self.lengths):
            k[first:first + m, first:first + m] = ritz_beam.stiffness_matrix(m, a, bending_stiffness)
        return k

    def cell_rotations(self) -> np.ndarray:
        """Matrix ``G`` (``n x n``): the mean rotations ``G q`` [rad] of the cells, relative to the base:
        each segment's modes count as its cells, its ``m`` equal parts (a segment's rotation adds the
        earlier segments' end rotations, their first modes)."""
        g = np.zeros((self.n, self.n))
        for first, m in zip(self.first_modes, self.modes):
            g[first:first + m, :first] = self.phi_tip[:first]
            g[first:first + m, first:first + m] = ritz_beam.segment_rotation_matrix(m, m)
        return g


def _composite(modes: tuple[int, ...], lengths: tuple[float, ...], length: float):
    """Shapes, weights and integration matrix of a rod of segments (points and weights in units of ``length``).

    Segment ``j`` carries ``modes[j]`` modes of the ``ritz`` cell on its own ``s / L_j``; the rotation
    at a point of segment ``j`` adds the end rotations of the earlier segments (their first modes:
    ``phi_1(1) = 1``, ``phi_i(1) = 0`` else), so the rotation field is continuous and its curvature
    may jump at the segment ends (piecewise free curvature is represented exactly).  Each segment has
    its own Gauss rule (:func:`rule_points`); the integrals from the base to a point add the full
    weights of the earlier segments.  One segment gives :func:`quadrature`'s arrays themselves.
    """
    n = int(sum(modes))
    blocks_phi, blocks_w, starts = [], [], []
    total_points = sum(rule_points(m) for m in modes)
    integration = np.zeros((total_points, total_points))
    phi_tip = np.zeros(n)
    row = col = 0
    for j, (m, a) in enumerate(zip(modes, lengths)):
        xi, w, s = quadrature(rule_points(m))
        scale = a / length
        block = np.zeros((len(xi), n))
        block[:, :col] = phi_tip[:col]  # the earlier segments' end rotations
        block[:, col:col + m] = ritz_beam.rotation_shapes(m, xi)
        blocks_phi.append(block)
        blocks_w.append(w * scale if scale != 1.0 else w)
        for earlier, w_earlier in zip(starts, blocks_w[:-1]):
            integration[row:row + len(xi), earlier:earlier + len(w_earlier)] = w_earlier
        integration[row:row + len(xi), row:row + len(xi)] = s * scale if scale != 1.0 else s
        starts.append(row)
        phi_tip[col:col + m] = ritz_beam.rotation_shapes(m, np.array([1.0]))[0]
        row += len(xi)
        col += m
    return np.vstack(blocks_phi), np.concatenate(blocks_w), integration, phi_tip


@functools.lru_cache(maxsize=64)
def rod_shapes(n: int, length: float, modes: tuple[int, ...] | None = None,
               lengths: tuple[float, ...] | None = None) -> RodShapes:
    """Cached :class:`RodShapes` (``modes``, ``lengths``: per segment, for a rod of several segments)."""
    return RodShapes(n, length, modes, lengths)


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


def truncation_error(shapes: RodShapes, bending_stiffness: float, base_angle: float, q, tip_force,
                     follower_force=(0.0, 0.0)) -> float:
    """Estimated tip-position error [m] of the rod ``shapes`` at ``q`` [rad] from the modes it leaves out.

    The hierarchical estimate: the rod with one more mode per segment (the modes are nested, so
    it contains this one, and ``(q, 0)`` satisfies its equations except for the new modes' rows,
    on which the force ``F`` [N] at the tip does the work ``Q = F . dP/dq_{m+1}``; the free curvature
    does none, ``phi_{m+1}(1) = 0``) takes one Newton step from ``(q, 0)``: ``T d = (0, Q)`` with its
    tangent ``T = K + sum_k L w_k (F . (cos, sin) theta_k) phi_k phi_k^T`` (the tip force's geometric
    stiffness) minus, for the part ``F_f`` of the force that turns with the tip (a follower force),
    ``J^T (-F_f,y, F_f,x) phi(1)^T``; the estimate is the tip's move ``|J d|`` (``J = dP/dq``).
    Statics only (the rod's own inertia is left out; the base held).  Measured against the
    elastica and a 24-mode rod (``tests/test_mechanism_rod.py``): 0.95-1.0 of the true tip error
    at 2 and 3 modes for dead forces of 5 and 10 EI/L^2 (0.6 at 4 modes, where the error is
    1.6e-5 L and the next left-out modes add to it), and for follower forces of 5-30 EI/L^2
    (tip rotations 1.7-3 rad) 0.9-1.1 at 2-8 modes; the first-mode-only estimate before (``Q/K``
    of the new mode, the kept modes held) gave 0.15-0.5 for follower forces.

    Parameters
    ----------
    shapes : RodShapes
        The rod's shapes (its modes per segment and lengths).
    bending_stiffness : float
        ``EI`` [N m^2].
    base_angle : float
        The base's absolute rotation ``Phi`` [rad].
    q : array_like
        The mode amplitudes [rad].
    tip_force : (float, float)
        Force at the tip [N] (global, the current value: dead and follower parts together).
    follower_force : (float, float), optional
        The part of ``tip_force`` that turns with the tip [N] (global, current value); default none.
    """
    return truncation_estimator(shapes, bending_stiffness)(base_angle, q, tip_force, follower_force)


def truncation_estimator(shapes: RodShapes, bending_stiffness: float) -> Callable[..., float]:
    """:func:`truncation_error` for one rod, with its shapes prepared once: ``estimate(base_angle, q,
    tip_force, follower_force=(0, 0))`` [m]; ``estimate.many(base_angles, q, tip_forces, follower_forces)``
    gives it for many states at once (a static sweep's points, read during the sweep, estimated after it)."""
    richer = rod_shapes(shapes.n + len(shapes.modes), shapes.length, tuple(m + 1 for m in shapes.modes),
                        shapes.lengths)
    extra = np.array([first + m for first, m in zip(richer.first_modes, shapes.modes)])
    kept = np.setdiff1d(np.arange(richer.n), extra)
    phi, phi_kept, phi_tip = richer.phi, richer.phi[:, kept], richer.phi_tip
    lw = richer.length * richer.weights
    stiffness = richer.stiffness_matrix(bending_stiffness)

    def estimate(base_angle: float, q, tip_force, follower_force=(0.0, 0.0)) -> float:
        theta = base_angle + phi_kept @ np.asarray(q, dtype=float)
        c, s = np.cos(theta), np.sin(theta)
        fx, fy = float(tip_force[0]), float(tip_force[1])
        jac = np.stack([-(lw * s) @ phi, (lw * c) @ phi])
        tangent = stiffness + (phi.T * (lw * (fx * c + fy * s))) @ phi
        turned = np.array([-float(follower_force[1]), float(follower_force[0])])
        tangent -= np.outer(jac.T @ turned, phi_tip)
        work = np.zeros(richer.n)
        work[extra] = fx * jac[0, extra] + fy * jac[1, extra]
        try:
            step = np.linalg.solve(tangent, work)
        except np.linalg.LinAlgError:  # a singular tangent (at a buckling load): the new modes alone
            step = np.zeros(richer.n)
            step[extra] = work[extra] / np.diag(stiffness)[extra]
        return float(np.hypot(*(jac @ step)))

    def many(base_angles, q, tip_forces, follower_forces) -> np.ndarray:
        """``estimate`` of ``P`` states at once [m], shape ``(P,)``: base angles ``(P,)``, amplitudes ``(P, n)``,
        tip and follower forces ``(P, 2)`` (the same algebra on stacked arrays: one call for a whole sweep)."""
        q = np.atleast_2d(np.asarray(q, dtype=float))
        forces = np.atleast_2d(np.asarray(tip_forces, dtype=float))
        followers = np.atleast_2d(np.asarray(follower_forces, dtype=float))
        theta = np.asarray(base_angles, dtype=float)[:, None] + q @ phi_kept.T
        c, s = np.cos(theta), np.sin(theta)
        fx, fy = forces[:, :1], forces[:, 1:2]
        jx, jy = -(lw * s) @ phi, (lw * c) @ phi
        tangent = stiffness + (phi.T[None, :, :] * (lw * (fx * c + fy * s))[:, None, :]) @ phi
        turned = followers[:, 1:2] * -jx + followers[:, :1] * jy  # J^T (-F_f,y, F_f,x), row per state
        tangent -= turned[:, :, None] * phi_tip[None, None, :]
        work = np.zeros((len(q), richer.n))
        work[:, extra] = fx * jx[:, extra] + fy * jy[:, extra]
        try:
            step = np.linalg.solve(tangent, work[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:  # a singular tangent somewhere: state by state (with its fallback)
            return np.array([estimate(a, qi, f, ff) for a, qi, f, ff in zip(base_angles, q, forces, followers)])
        return np.hypot(np.sum(jx * step, axis=1), np.sum(jy * step, axis=1))

    estimate.many = many
    return estimate
