"""Assumed-modes (Rayleigh-Ritz) model of the inextensible bender in its rotation field.

The ``cell="ritz"`` discretisation of :class:`~exudyn_atcm.mechanism.actuator.BendingActuator`: pure
numpy physics (shape functions, stiffness, curvature-dependent mass matrix, kinematics); the
Exudyn system that carries these matrices is :mod:`exudyn_atcm.mbs.chains.ritz`.  The
derivation is on the theory page of the documentation ("Rotation-field Ritz model").

The cross-section's rotation ``theta(s, t)`` along the arc length ``s`` in ``[0, L]`` of an
inextensible, shear-rigid (Euler-Bernoulli) beam clamped at ``s = 0`` is expanded in ``n``
assumed modes (Rayleigh-Ritz; Meirovitch 2001), ``xi = s / L``::

    theta(s, t) = sum_i q_i(t) phi_i(xi),   phi_1 = xi,   phi_i = int_0^xi P~_{i-1},  i >= 2,

with ``P~_k`` the shifted Legendre polynomial on ``[0, 1]``.  All ``phi_i`` vanish at the
clamp, ``phi_i(1) = 0`` for ``i >= 2`` and ``phi_i' = P~_{i-1} / L``.  The position follows from
the rotation (inextensibility), ``r(s) = int_0^s (cos theta, sin theta) ds'`` (the
rotation-field description of the plane elastica; Reissner 1972, Simo & Vu-Quoc 1986).

* Elastic energy ``U = 1/2 int EI (theta' - kappa0)^2 ds`` is exactly quadratic: the stiffness
  matrix is diagonal, ``K_ii = EI / (L (2i - 1))`` (orthogonality of the Legendre polynomials),
  and the free curvature ``kappa0`` of the piezo layer loads only ``q_1``, with
  ``Q_1 = EI kappa0``.  The static solution under actuation alone, ``q = (kappa0 L, 0, ...)``,
  is the exact arc for any ``n``.
* Kinetic energy, linearised about the quasi-static arc ``theta = kappa s`` of the current
  free curvature: ``T = 1/2 qdot^T M(kappa) qdot`` with::

      M_ij(kappa) = mu int_0^L int_0^L phi_i(sig) phi_j(tau) cos(kappa (sig - tau)) (L - max(sig, tau)) dsig dtau
                    + rho_I int_0^L phi_i phi_j ds,

  (``mu`` mass per length, ``rho_I`` rotary inertia per length), the double-integral form of
  ``mu int_0^L a_i . a_j ds`` with ``a_i(s) = int_0^s (-sin kappa s', cos kappa s') phi_i ds'``.
  ``M`` is even in ``kappa``; at ``kappa = 0`` it is the Euler-Bernoulli assumed-modes mass
  ``mu L^3 int W_i W_j dxi + rho_I L int phi_i phi_j dxi``, ``W_i = int_0^xi phi_i``.

Validity: statics exact without tip loads (a tip load would add geometric stiffness terms that
this model leaves out: it is refused); dynamics linearised about the quasi-static arc (the
quadratic velocity terms and the change of inertia with the dynamic deviation's geometry are
neglected), see :data:`DYNAMIC_ROTATION_LIMIT`.
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np
from numpy.polynomial import legendre

from .._checks import shown
from ..errors import AccuracyWarning

__all__ = [
    "DYNAMIC_ROTATION_LIMIT",
    "rotation_shapes",
    "integrated_shapes",
    "stiffness_matrix",
    "curvature_load_vector",
    "mass_matrix",
    "rotation",
    "tip_position",
    "segment_rotation_matrix",
    "dynamic_rotation",
    "warn_large_dynamic_rotation",
]

#: Largest dynamic part of the tip rotation ``max |theta(L, t) - kappa(t) L|`` [rad] before a
#: warning.  The neglected quadratic velocity terms are of relative size ``delta`` against the
#: inertia forces of a vibration of amplitude ``delta`` (``theta_dot^2 ~ delta omega^2`` against
#: ``theta_ddot ~ omega^2``), so at 0.05 rad the dynamic deviation may be off by about 5 %
#: of itself (2.5e-3 rad).
DYNAMIC_ROTATION_LIMIT = 0.05


def _check_modes(n: int) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n (number of assumed modes) must be an integer >= 1, got {shown(n)}")
    return int(n)


def _coefficients(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Shifted-Legendre coefficients (rows) of ``phi_i`` and ``W_i = int_0^xi phi_i``, i = 1..n (read-only)."""
    return _coefficients_of(_check_modes(n))


@functools.lru_cache(maxsize=64)
def _coefficients_of(n: int) -> tuple[np.ndarray, np.ndarray]:
    phi = np.zeros((n, n + 1))
    wint = np.zeros((n, n + 2))
    # in y = 2 xi - 1: d xi = dy / 2, so int_0^xi f d xi = legint(f, scl=1/2, lbnd=-1)
    for i in range(n):
        if i == 0:
            c = np.array([0.5, 0.5])  # xi = (1 + y) / 2
        else:
            basis = np.zeros(i + 1)  # P~_i
            basis[-1] = 1.0
            c = legendre.legint(basis, lbnd=-1.0, scl=0.5)
        phi[i, :c.size] = c
        w = legendre.legint(c, lbnd=-1.0, scl=0.5)
        wint[i, :w.size] = w
    phi.flags.writeable = False
    wint.flags.writeable = False
    return phi, wint


def _evaluate(coefficients: np.ndarray, xi: np.ndarray) -> np.ndarray:
    y = 2.0 * np.asarray(xi, dtype=float) - 1.0
    return legendre.legvander(y, coefficients.shape[1] - 1) @ coefficients.T


def rotation_shapes(n: int, xi) -> np.ndarray:
    """Rotation shape functions ``phi_i(xi)`` [-], shape ``(len(xi), n)``.

    Parameters
    ----------
    n : int
        Number of assumed modes, >= 1.
    xi : array_like
        Points ``s / L`` in ``[0, 1]`` [-].
    """
    return _evaluate(_coefficients(n)[0], np.atleast_1d(xi))


def integrated_shapes(n: int, xi) -> np.ndarray:
    """``W_i(xi) = int_0^xi phi_i`` [-], shape ``(len(xi), n)``.

    ``L W_i`` are the lateral displacement shapes of the straight beam.
    """
    return _evaluate(_coefficients(n)[1], np.atleast_1d(xi))


def stiffness_matrix(n: int, length: float, bending_stiffness: float) -> np.ndarray:
    """Bending stiffness matrix ``K = diag(EI / (L (2i - 1)))`` [N m] of the coordinates ``q_i`` [rad].

    ``K_ij = EI / L int_0^1 P~_{i-1} P~_{j-1} dxi`` with ``int_0^1 P~_k^2 = 1 / (2k + 1)``.
    """
    n = _check_modes(n)
    return np.diag(bending_stiffness / (length * (2.0 * np.arange(1, n + 1) - 1.0)))


def curvature_load_vector(n: int) -> np.ndarray:
    """Generalised force per unit ``EI kappa0`` [-]: ``phi_i(1)``, i.e. ``(1, 0, ..., 0)``.

    The virtual work of the free curvature, ``int EI kappa0 dtheta' ds = EI kappa0 dtheta(L)``,
    loads only ``q_1`` because ``phi_i(1) = 0`` for ``i >= 2``.
    """
    v = np.zeros(_check_modes(n))
    v[0] = 1.0
    return v


def _gauss01(order: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = legendre.leggauss(order)
    return 0.5 * (x + 1.0), 0.5 * w


def _mass_order(n: int, curvature_angle: float) -> int:
    # polynomial part of degree 2n + 2 in each direction, times cos(kappa L x (1 - u)), an entire
    # function whose Taylor terms decay like (kappa L)^k / k!: measured converged to round-off at
    # this order for n <= 12 and |kappa L| <= 4 (tests/test_actuator_ritz.py)
    return n + 12 + int(math.ceil(2.0 * abs(curvature_angle)))


def mass_matrix(n: int, length: float, mass_per_length: float, rotary_inertia: float,
                curvature: float = 0.0) -> np.ndarray:
    """Mass matrix ``M(kappa)`` [kg m^2] of the coordinates ``q_i`` [rad] about the arc of ``curvature``.

    Parameters
    ----------
    n : int
        Number of assumed modes, >= 1.
    length : float
        Beam length ``L`` [m].
    mass_per_length : float
        ``mu`` [kg/m].
    rotary_inertia : float
        Rotary inertia per length ``rho_I`` [kg m] (about the reference line).
    curvature : float, optional
        Curvature ``kappa`` [1/m] of the arc about which the kinetic energy is linearised.

    Notes
    -----
    The double integral over the square is ``S + S^T`` with ``S`` the integral over the
    triangle ``sig > tau``, where the kernel ``L - max(sig, tau) = L - sig`` is smooth.  ``S`` is
    integrated in collapsed (Duffy) coordinates ``tau = sig u`` with a Gauss-Legendre tensor
    rule::

        S_ij = mu L^3 int_0^1 int_0^1 phi_i(x) phi_j(x u) cos(kappa L x (1 - u)) (1 - x) x du dx.
    """
    n = _check_modes(n)
    m = mass_per_length * length**3 * _translational_mass(n, float(curvature * length))
    return m + rotary_inertia * length * _shape_products(n)


@functools.lru_cache(maxsize=64)
def _shape_products(n: int) -> np.ndarray:
    """``int_0^1 phi_i phi_j dxi`` (Gauss rule exact for the degree-2n products); read-only."""
    xg, wg = _gauss01(n + 2)
    phi_g = rotation_shapes(n, xg)
    out = (phi_g * wg[:, None]).T @ phi_g
    out.flags.writeable = False
    return out


@functools.lru_cache(maxsize=64)
def _duffy_rule(n: int, order: int) -> tuple:
    x, w = _gauss01(order)
    phi_x = rotation_shapes(n, x) * (w * (1.0 - x) * x)[:, None]  # (m, n), outer weights included
    phi_xu = rotation_shapes(n, np.outer(x, x).ravel()).reshape(order, order, n) * w[None, :, None]
    return x, phi_x, phi_xu


def _translational_mass(n: int, a: float) -> np.ndarray:
    """``M / (mu L^3)`` without rotary inertia, about the arc of total angle ``a = kappa L`` [rad]."""
    x, phi_x, phi_xu = _duffy_rule(n, _mass_order(n, a))
    kernel = np.cos(a * np.outer(x, 1.0 - x))  # cos(a x (1 - u)), (m, m)
    inner = np.einsum("ab,abj->aj", kernel, phi_xu)
    s = phi_x.T @ inner
    return s + s.T


def rotation(q, xi) -> np.ndarray:
    """Rotation ``theta(xi)`` [rad] for coordinates ``q`` (shape ``(n,)`` or rows ``(R, n)``)."""
    q = np.asarray(q, dtype=float)
    return q @ rotation_shapes(q.shape[-1], xi).T


def _tip_order(n: int) -> int:
    # cos/sin of a degree-n polynomial rotation: n + 12 Gauss points reach round-off (2e-15 of L)
    # for arcs up to kappa L = 3 rad with modal content of 10 % on the higher modes, n <= 8
    # (against 80 points; tests/test_actuator_ritz.py checks the arc)
    return n + 12


def tip_position(q, length: float) -> tuple[np.ndarray, np.ndarray]:
    """Tip ``(x, y)`` [m] of the inextensible beam: ``L int_0^1 (cos theta, sin theta) dxi``.

    ``q`` has shape ``(n,)`` or ``(R, n)`` (one row per state); Gauss-Legendre quadrature.
    """
    q = np.atleast_2d(np.asarray(q, dtype=float))
    shapes, w = _tip_rule(q.shape[1])
    theta = q @ shapes
    return length * (np.cos(theta) @ w), length * (np.sin(theta) @ w)


@functools.lru_cache(maxsize=64)
def _tip_rule(n: int) -> tuple:
    x, w = _gauss01(_tip_order(n))
    shapes = rotation_shapes(n, x).T
    shapes.flags.writeable = False
    w.flags.writeable = False
    return shapes, w


def segment_rotation_matrix(n: int, n_segments: int) -> np.ndarray:
    """Matrix ``G`` (``n_segments x n``) of the segments' mean rotations ``G q`` [rad].

    Segment ``k`` covers ``xi`` in ``[k, k + 1] / n_segments``; its mean rotation is
    ``n_segments sum_i q_i (W_i(xi_{k+1}) - W_i(xi_k))``.
    """
    edges = integrated_shapes(n, np.linspace(0.0, 1.0, n_segments + 1))
    return n_segments * np.diff(edges, axis=0)


def dynamic_rotation(tip_angle, strain, curvature_per_strain: float, length: float) -> float:
    """Dynamic part ``max |theta(L) - kappa L|`` [rad] of a run's tip rotation.

    ``kappa = curvature_per_strain * strain`` is the free curvature of the recorded strains;
    ``kappa L`` is the quasi-static tip rotation about which the model is linearised.
    """
    tip_angle = np.asarray(tip_angle, dtype=float)
    if tip_angle.size == 0:
        return 0.0
    quasi_static = curvature_per_strain * np.asarray(strain, dtype=float) * length
    return float(np.max(np.abs(tip_angle - quasi_static)))


def warn_large_dynamic_rotation(tip_angle, strain, curvature_per_strain: float, length: float,
                                limit: float = DYNAMIC_ROTATION_LIMIT, stacklevel: int = 2) -> float:
    """Warn (``RuntimeWarning``, once) when the dynamic part of the tip rotation exceeds ``limit`` [rad].

    ``tip_angle`` and ``strain`` are a run's recorded series (a thinned record is checked at its
    rows).  Returns the dynamic part (see :func:`dynamic_rotation`).
    """
    delta = dynamic_rotation(tip_angle, strain, curvature_per_strain, length)
    if delta > limit:
        warnings.warn(
            f"cell='ritz': the tip rotation deviates by up to {delta:.3g} rad from the quasi-static arc "
            f"(kappa(t) L; more than {limit:g} rad). The ritz model linearises the inertia about the "
            "quasi-static arc and neglects the quadratic velocity terms and the inertia change of the "
            f"dynamic deviation's geometry, errors of relative order {delta:.2g} in the dynamic part; "
            "check the run with cell='beam' (geometrically exact elements)",
            AccuracyWarning, stacklevel=stacklevel)
    return delta
