"""The ``cell="ritz"`` discretisation (issue 9, part 4): assumed modes of the rotation field.

Pure-numpy physics (:mod:`exudyn_atcm.ritz_beam`) against independent constructions: the
shifted Legendre polynomials of scipy, the Euler-Bernoulli assumed-modes mass built from the
lateral displacement shapes, the nested-integral definition of the bent mass matrix, the
clamped-free beam's eigenfrequencies (roots of ``1 + cos cosh = 0``) with Rayleigh's
first-order rotary-inertia correction.  The Exudyn model against the exact arc, the beam
elements, the modal solution of the cantilever under an end moment and the hysteresis
operator applied offline.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from numpy.polynomial import legendre
from scipy.linalg import eigh
from scipy.special import sh_legendre

from exudyn_atcm import beam_theory as bt
from exudyn_atcm import ritz_beam as rb

EI, MU, L = 0.0493, 0.2, 0.087  # N m^2, kg/m, m: the order of the paper's actuator
RHO_I = 1.5e-8  # kg m
#: roots beta_r L of 1 + cos cosh = 0 (clamped-free beam), r = 1, 2, 3
BETA_L = (1.8751040687119611, 4.6940911329741746, 7.8547574382376126)


def _gauss(order):
    x, w = legendre.leggauss(order)
    return 0.5 * (x + 1.0), 0.5 * w


def _phi_reference(n):
    """phi_1 = xi, phi_i = int_0^xi P~_{i-1} from scipy's shifted Legendre polynomials (poly1d)."""
    shapes = [np.poly1d([1.0, 0.0])]
    for i in range(2, n + 1):
        shapes.append(np.poly1d(sh_legendre(i - 1).coeffs).integ())  # antiderivative, zero at 0
    return shapes


def _mode(r, x):
    """Clamped-free Euler-Bernoulli mode r: shape w and slope w' (per unit xi) at xi = x."""
    b = BETA_L[r - 1]
    sig = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
    X = b * x
    w = np.cosh(X) - np.cos(X) - sig * (np.sinh(X) - np.sin(X))
    dw = b * (np.sinh(X) + np.sin(X) - sig * (np.cosh(X) - np.cos(X)))
    return w, dw


# ----------------------------------------------------------------------------- shape functions

def test_shapes_are_the_integrated_shifted_legendre_polynomials():
    xi = np.linspace(0.0, 1.0, 11)
    ref = _phi_reference(7)
    np.testing.assert_allclose(rb.rotation_shapes(7, xi), np.array([p(xi) for p in ref]).T, rtol=0, atol=1e-13)
    np.testing.assert_allclose(rb.integrated_shapes(7, xi), np.array([p.integ()(xi) for p in ref]).T,
                               rtol=0, atol=1e-13)
    # clamp: phi_i(0) = 0; tip: phi_1(1) = 1, phi_i(1) = 0 for i >= 2 (only q_1 is loaded)
    ends = rb.rotation_shapes(7, [0.0, 1.0])
    np.testing.assert_allclose(ends, [[0.0] * 7, [1.0] + [0.0] * 6], atol=1e-14)
    np.testing.assert_array_equal(rb.curvature_load_vector(4), [1.0, 0.0, 0.0, 0.0])


@pytest.mark.parametrize("n", [0, -1, 2.0, True])
def test_bad_mode_count_is_refused(n):
    with pytest.raises(ValueError, match="assumed modes"):
        rb.stiffness_matrix(n, L, EI)


# ----------------------------------------------------------------------------- stiffness and mass

def test_stiffness_is_diagonal_EI_over_L_times_2i_minus_1():
    # K_ij = int EI phi_i' phi_j' ds by Gauss quadrature of scipy's polynomials (phi' = P~ / L)
    n = 6
    x, w = _gauss(20)
    d = np.array([p.deriv()(x) for p in _phi_reference(n)]) / L
    K_ref = EI * L * (d * w) @ d.T
    K = rb.stiffness_matrix(n, L, EI)
    np.testing.assert_allclose(K, K_ref, rtol=0, atol=1e-13 * EI / L)
    np.testing.assert_allclose(np.diag(K), EI / (L * (2 * np.arange(1, n + 1) - 1)), rtol=1e-15)
    assert np.count_nonzero(K - np.diag(np.diag(K))) == 0


def test_straight_mass_is_the_euler_bernoulli_assumed_modes_mass():
    # independent route: lateral displacement shapes w_i(s) = int_0^s phi_i = L W_i(xi) of the
    # straight beam, M_ij = mu int w_i w_j ds + rho_I int phi_i phi_j ds, Gauss quadrature
    n = 6
    x, w = _gauss(20)
    ref = _phi_reference(n)
    W = np.array([L * p.integ()(x) for p in ref])
    P = np.array([p(x) for p in ref])
    M_ref = MU * L * (W * w) @ W.T + RHO_I * L * (P * w) @ P.T
    np.testing.assert_allclose(rb.mass_matrix(n, L, MU, RHO_I, 0.0), M_ref, rtol=0, atol=1e-13 * np.abs(M_ref).max())


def _nested_mass(n, kappa, order=48):
    """M(kappa) from its definition: a_i(s) = int_0^s (-sin kappa s', cos kappa s') phi_i ds' (slow)."""
    ref = _phi_reference(n)
    x, w = _gauss(order)
    M = np.zeros((n, n))
    for xo, wo in zip(x, w):
        xi_in, w_in = x * xo, w * xo  # inner rule on [0, xo]
        phi = np.array([p(xi_in) for p in ref])
        a = L * np.stack([(phi * -np.sin(kappa * L * xi_in) * w_in).sum(1),
                          (phi * np.cos(kappa * L * xi_in) * w_in).sum(1)], axis=1)  # (n, 2)
        M += MU * L * wo * a @ a.T
    P = np.array([p(x) for p in ref])
    return M + RHO_I * L * (P * w) @ P.T


@pytest.mark.parametrize("angle", [0.36, 1.0, 2.5])
@pytest.mark.parametrize("n", [1, 4, 8])
def test_bent_mass_equals_the_nested_integral_definition_and_is_even(n, angle):
    kappa = angle / L
    M = rb.mass_matrix(n, L, MU, RHO_I, kappa)
    M_ref = _nested_mass(n, kappa)
    # both quadratures converge to round-off for these smooth integrands (48 x 48 nested points)
    np.testing.assert_allclose(M, M_ref, rtol=0, atol=1e-12 * np.abs(M_ref).max())
    np.testing.assert_array_equal(M, rb.mass_matrix(n, L, MU, RHO_I, -kappa))
    np.testing.assert_allclose(M, M.T, rtol=0, atol=1e-15 * np.abs(M).max())
    # the bent beam's axis is closer to the clamp: less inertia about it in the first coordinate
    assert M[0, 0] < rb.mass_matrix(n, L, MU, RHO_I, 0.0)[0, 0]


def _frequencies(n, rho_i, count):
    K = rb.stiffness_matrix(n, L, EI)
    M = rb.mass_matrix(n, L, MU, rho_i, 0.0)
    return np.sqrt(eigh(K, M, eigvals_only=True)[:count]) / (2 * math.pi)


def test_frequencies_converge_to_the_clamped_free_beam_from_above():
    f_ref = np.array([b**2 / (2 * math.pi * L**2) * math.sqrt(EI / MU) for b in BETA_L])
    assert f_ref[0] == pytest.approx(bt.first_bending_frequency(EI, MU, L), rel=1e-14)
    errors = {n: _frequencies(n, 0.0, min(n, 3)) / f_ref[:min(n, 3)] - 1 for n in (2, 3, 4, 6, 8, 10)}
    # Rayleigh-Ritz: from above, monotone in n; measured f1 +4.7e-3 / +3.0e-4 / +1.5e-6 at n = 2 / 3 / 4
    for n_lo, n_hi in ((2, 3), (3, 4), (4, 6), (6, 8)):
        assert np.all(errors[n_hi][:min(n_lo, 3)] <= errors[n_lo][:min(n_lo, 3)] + 1e-12)
    assert np.all(errors[4] > -1e-12)
    assert errors[3][0] < 5e-4 and errors[4][0] < 5e-6
    # f1, f2, f3 at n = 10 to 1e-8 (measured 5e-13, 4e-12, 1.6e-9)
    np.testing.assert_allclose(errors[10], 0.0, atol=1e-8)


def test_rotary_inertia_shifts_the_frequencies_as_rayleighs_correction():
    # first order in rho_I: d(omega^2)/omega^2 = -rho_I int w'^2 / (mu int w^2) for the Euler-
    # Bernoulli mode w (Rayleigh); the remainder is of second order, ~delta^2 (delta = the
    # correction: 2.3e-5, 1.6e-4, 3.8e-4 for r = 1, 2, 3; measured remainder 3.7e-8 = 1.4 delta^2 at
    # r = 2), plus the Ritz error at n = 10 below 2e-9 (test above): tolerance 2 delta^2 + 2e-9
    x, w = _gauss(80)
    f0 = _frequencies(10, 0.0, 3)
    f = _frequencies(10, RHO_I, 3)
    for r in (1, 2, 3):
        shape, slope = _mode(r, x)
        ratio = (slope**2 @ w) / L**2 / (shape**2 @ w)
        delta = -0.5 * RHO_I / MU * ratio
        assert f[r - 1] / f0[r - 1] - 1 == pytest.approx(delta, abs=2 * delta**2 + 2e-9)


# ----------------------------------------------------------------------------- kinematics

@pytest.mark.parametrize("n", [1, 3, 8])
@pytest.mark.parametrize("angle", [-0.12, 0.36, 1.5, 3.0])
def test_tip_of_the_static_shape_is_the_exact_arc(n, angle):
    kappa = angle / L
    q = np.zeros(n)
    q[0] = angle  # the static solution under the free curvature: theta = kappa s
    x, y = rb.tip_position(q, L)
    xa, ya = bt.arc_point(kappa, L)
    assert float(x[0]) == pytest.approx(float(xa), abs=5e-15 * L)
    assert float(y[0]) == pytest.approx(float(ya), abs=5e-15 * L)
    means = rb.segment_rotation_matrix(n, n) @ q
    np.testing.assert_allclose(means, (np.arange(n) + 0.5) * angle / n, rtol=0, atol=1e-14)


def test_tip_of_a_general_shape_by_independent_quadrature():
    # a rotation with higher-mode content, integrated with scipy-built shapes and 100 points
    q = np.array([0.4, 0.2, -0.15, 0.05])
    x, w = _gauss(100)
    theta = sum(qi * p(x) for qi, p in zip(q, _phi_reference(4)))
    tx, ty = rb.tip_position(q, L)
    assert float(tx[0]) == pytest.approx(L * (np.cos(theta) @ w), abs=1e-15)
    assert float(ty[0]) == pytest.approx(L * (np.sin(theta) @ w), abs=1e-15)
    assert float(rb.rotation(q, 1.0)[0]) == pytest.approx(q[0], abs=1e-15)


def test_dynamic_rotation_warning():
    strain = np.array([0.0, 1e-3, 1e-3])
    cps = 100.0  # 1/m
    quasi = cps * strain * L
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert rb.warn_large_dynamic_rotation(quasi + 0.01, strain, cps, L) == pytest.approx(0.01)
    with pytest.warns(RuntimeWarning, match="cell='beam'"):
        assert rb.warn_large_dynamic_rotation(quasi + [0.0, 0.2, -0.1], strain, cps, L) == pytest.approx(0.2)
