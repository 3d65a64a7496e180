"""The ``cell="ritz"`` discretisation (issue 9, part 4): assumed modes of the rotation field.

Pure-numpy physics (:mod:`exudyn_atcm.theory.ritz_beam`) against independent constructions: the
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

from exudyn_atcm import theory as bt
from exudyn_atcm.theory import ritz_beam as rb

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


# ----------------------------------------------------------------------------- Exudyn model

from exudyn_atcm.model.drive import PiezoDrive  # noqa: E402
from exudyn_atcm.model.parameter_sets import paper_strain_preisach  # noqa: E402
from exudyn_atcm.model.signals import PiecewiseLinear, Triangle  # noqa: E402
from exudyn_atcm.solve import run_actuator, eigenfrequencies, simulate, solve_static  # noqa: E402

from _actuator_geometries import GEOMETRIES, REF_A  # noqa: E402
from _actuator_runs import (LeakyOperator, check_in_step_hysteresis_equals_offline_replay,  # noqa: E402
                            check_run_starts_in_static_equilibrium, coarse_step_expected,
                            fast_triangle_actuator)

#: Settings that make Exudyn reject and repeat steps of the linear ritz system: the default
#: Newton settings converge in one iteration, so the step-rejecting settings of the other cells
#: (two full Newton iterations) reject nothing here.  Three modified-Newton iterations to an
#: absolute tolerance of 1e-12 fail on the steps after a mass-matrix update (stale Jacobian),
#: which Exudyn repeats with halved steps (measured: 56 of 604 attempts rejected).
REJECTING = {"timeIntegration.newton.maxIterations": 3, "timeIntegration.newton.absoluteTolerance": 1e-12}


def _composite_kappa(g, strain):
    return bt.free_curvature(g.E1, g.h1, g.E2, g.h2, g.width, strain)


@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: g.name)
@pytest.mark.parametrize("n_cells", [1, 3, 8])
@pytest.mark.parametrize("voltage", [1500.0, -500.0])
def test_static_actuation_is_the_exact_arc(geometry, n_cells, voltage):
    # the static solution q = (kappa L, 0, ...) is the arc theta = kappa s for any n; the static
    # Newton iteration is run to round-off (measured <= 3e-16 of L and of kappa L)
    g = geometry
    act = g.actuator(PiezoDrive(voltage), n_cells=n_cells, cell="ritz")
    r = solve_static(act)
    kappa = _composite_kappa(g, bt.piezo_strain(voltage))
    x, y = bt.arc_point(kappa, g.length)
    assert r["actuator.tip_angle"][0] == pytest.approx(kappa * g.length, rel=1e-14)
    assert r["actuator.tip_x"][0] == pytest.approx(float(x), abs=1e-14 * g.length)
    assert r["actuator.tip_y"][0] == pytest.approx(float(y), abs=1e-14 * g.length)
    angles = np.array([r[f"actuator.cell_angle_{j + 1}"][0] for j in range(n_cells)])
    np.testing.assert_allclose(angles, (np.arange(n_cells) + 0.5) * kappa * act.cell_length, rtol=1e-13)


def test_one_mode_is_exact_for_a_long_bender_without_the_coarse_cell_warning():
    # 300 mm of the paper's laminate at 1500 V: kappa L = 1.24 rad.  A chain of one rigid cell
    # warns (one cell turning by more than 0.5 rad is a coarse chain); n = 1 assumed mode is the
    # exact arc, so the ritz columns (segments of one rotation field) are not checked for it
    g = REF_A
    kappa = _composite_kappa(g, bt.piezo_strain(1500.0))
    act = g.actuator(PiezoDrive(1500.0), n_cells=1, cell="ritz")
    act = type(act)(1, 0.3, act.width, act.passive, act.active, act.drive, cell="ritz")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        r = solve_static(act)
    assert r["actuator.tip_angle"][0] == pytest.approx(kappa * 0.3, rel=1e-14)
    x, y = bt.arc_point(kappa, 0.3)
    assert (r["actuator.tip_x"][0], r["actuator.tip_y"][0]) == pytest.approx((float(x), float(y)), abs=1e-14 * 0.3)
    rigid = type(act)(1, 0.3, act.width, act.passive, act.active, act.drive, cell="rigid")
    with pytest.warns(RuntimeWarning, match="coarse discretisation"):
        solve_static(rigid)


def test_straight_f1_is_the_beams_and_exudyns_eigen_path_sees_the_ritz_matrices():
    g = REF_A
    mu = bt.mass_per_length(g.rho1, g.h1, g.rho2, g.h2, g.width)
    EI = bt.composite_bending_stiffness(g.E1, g.h1, g.E2, g.h2, g.width)
    f1 = bt.first_bending_frequency(EI, mu, g.length)
    act = g.actuator(PiezoDrive(0.0), n_cells=4, cell="ritz")
    f = eigenfrequencies(act, n=2)
    # Ritz error at n = 4 (+1.5e-6) plus the rotary inertia's -2.3e-5 (Rayleigh, test above): 5e-5
    assert f[0] == pytest.approx(f1, rel=5e-5)
    # the package's eigen path (numerical tangent of Exudyn's residual) against scipy on (K, M(0))
    K = rb.stiffness_matrix(4, g.length, EI)
    M = rb.mass_matrix(4, g.length, mu, act.laminate.rotary_inertia_per_length)
    np.testing.assert_allclose(f, np.sqrt(eigh(K, M, eigvals_only=True)[:2]) / (2 * math.pi), rtol=1e-9)


def test_bent_f1_agrees_with_the_converged_beam_elements():
    # f1 about the static state at 1500 V (kappa L = 0.36 rad) against the linear beam elements,
    # extrapolated (Richardson, second order) from 32 and 64 elements: the extrapolations from
    # 16/32 and 32/64 agree to 1e-6 of f1, so the reference is converged to ~1e-6.  The ritz
    # model's own error at n = 6 (Ritz 8e-11 of f1 in the straight state) is that of the mass
    # linearisation and of the beam elements' finite axial and shear stiffness: measured 6e-6;
    # tolerance 2e-5.  Without the curvature-dependent mass it would be -0.27 %.
    f = {n: eigenfrequencies(REF_A.actuator(PiezoDrive(0.0), n_cells=n, cell="beam"), n=1, voltage=1500.0)[0]
         for n in (16, 32, 64)}
    reference = (4 * f[64] - f[32]) / 3
    assert reference == pytest.approx((4 * f[32] - f[16]) / 3, rel=5e-6)
    act = REF_A.actuator(PiezoDrive(0.0), n_cells=6, cell="ritz")
    f_ritz = eigenfrequencies(act, n=1, voltage=1500.0)[0]
    assert f_ritz == pytest.approx(reference, rel=2e-5)
    assert abs(f_ritz / eigenfrequencies(act, n=1)[0] - 1) > 2e-3  # the bent state is visibly different
    # the eigen path linearises with M at the static state's exact free curvature (not the
    # 0.01 rad grid of the time integration): scipy on (K, M(kappa)) to the numerical tangent's 1e-9
    kappa = act.curvature_per_strain * act.drive.static_strain(1500.0)
    K = rb.stiffness_matrix(6, act.length, act.bending_stiffness)
    M = rb.mass_matrix(6, act.length, act.mass_per_length, act.laminate.rotary_inertia_per_length, kappa)
    assert f_ritz == pytest.approx(math.sqrt(eigh(K, M, eigvals_only=True)[0]) / (2 * math.pi), rel=1e-9)
    # n = 3 within its Ritz error (measured +3.2e-4)
    f3 = eigenfrequencies(REF_A.actuator(PiezoDrive(0.0), n_cells=3, cell="ritz"), n=1, voltage=1500.0)[0]
    assert 0.0 < f3 / reference - 1 < 5e-4


def test_modal_reference_is_static_for_slow_moments():
    # the reference itself: a moment rising 100x slower than the first mode, from rest with zero
    # slope, gives the static tip rotation M L / EI (the mode-acceleration form's static part) to
    # the dynamic lag 2 zeta (f / f1) = 4e-4 and the start transient (f / f1)^2 = 1e-4 of the
    # amplitude: tolerance 1e-3
    f1 = bt.first_bending_frequency(EI, MU, L)
    times = np.linspace(0.0, 50.0 / f1, 4001)
    moments = 1e-3 * 0.5 * (1.0 - np.cos(2 * math.pi * f1 / 100.0 * times))
    beta = 2 * 0.02 / (2 * math.pi * f1)
    theta = bt.end_moment_tip_rotation(EI, MU, L, beta, times, moments)
    np.testing.assert_allclose(theta, moments * L / EI, rtol=0, atol=1e-3 * 1e-3 * L / EI)
    assert np.max(np.abs(theta - moments * L / EI)) > 1e-5 * 1e-3 * L / EI  # it is a dynamic solution


def test_small_triangle_follows_the_modal_solution():
    # 1 % of the paper's amplitude (linear drive, small deflections) against the 30-mode solution
    # of the Euler-Bernoulli cantilever under the end moment EI kappa(t).  Measured 5.9e-5 of the
    # largest angle at n = 4 (the generalized-alpha step's floor, shared with the beam and ANCF
    # elements at h = 1e-4, plus the rotary inertia the closed form leaves out), 1.2e-4 at n = 3:
    # tolerances 1.5e-4 and 3e-4
    for n, tol in ((4, 1.5e-4), (3, 3e-4)):
        act = REF_A.actuator(PiezoDrive(Triangle(5.0, 10.0, 0.5)), n_cells=n, cell="ritz")
        r = simulate(act, 0.5)
        moments = act.bending_stiffness * act.curvature_per_strain * r["actuator.strain"]
        ref = bt.end_moment_tip_rotation(act.bending_stiffness, act.mass_per_length, act.length,
                                         act.stiffness_damping_factor, r["time"], moments)
        assert np.max(np.abs(r["actuator.tip_angle"] - ref)) <= tol * np.max(np.abs(ref))


def test_papers_run_agrees_with_32_beam_elements():
    # the paper's drive (triangle -500 ... 1500 V, 1 s, Preisach operator in the step) on the paper's
    # actuator: ritz (n = 4) against 32 geometrically exact elements.  Measured differences: tip
    # angle 1.9e-5 of its largest value, tip x and y 3.0e-5 of the largest deflection (4.7e-7 m),
    # the size of the 32 elements' own dynamic error (5e-5 of the tip angle on the small triangle);
    # the mass matrix follows kappa to 0.005 rad (without it the angle would differ by 2e-4 rad).
    # Tolerance 1e-4.
    runs = {}
    for cell, n in (("ritz", 4), ("beam", 32)):
        drive = PiezoDrive(Triangle(500.0, 1000.0, 1.0), hysteresis=paper_strain_preisach())
        with warnings.catch_warnings():
            warnings.simplefilter("error", RuntimeWarning)  # in particular no dynamic-rotation warning
            runs[cell] = simulate(REF_A.actuator(drive, n_cells=n, cell=cell), 1.0)
    a, b = runs["ritz"], runs["beam"]
    assert a.n_rows == b.n_rows == 10001
    np.testing.assert_array_equal(a["actuator.strain"], b["actuator.strain"])
    deflection = np.max(np.abs(b["actuator.tip_y"]))
    for name, scale in (("actuator.tip_x", deflection), ("actuator.tip_y", deflection), ("actuator.tip_angle", np.max(np.abs(b["actuator.tip_angle"])))):
        assert np.max(np.abs(a[name] - b[name])) <= 1e-4 * scale, name


def test_fast_voltage_step_warns_about_the_dynamic_rotation_and_a_slow_ramp_does_not():
    # 0 -> 1500 V in 1 ms (a step for the 36 Hz bender): the tip overshoots the arc by ~0.28 rad,
    # far beyond the linearisation about the quasi-static arc; over 50 ms the deviation is 0.02 rad
    act = REF_A.actuator(PiezoDrive(PiecewiseLinear([0.0, 1e-3], [0.0, 1500.0])), n_cells=4, cell="ritz")
    with pytest.warns(RuntimeWarning, match=r"deviates by up to 0\.2\d* rad.*cell='beam'"):
        simulate(act, 0.1)
    act = REF_A.actuator(PiezoDrive(PiecewiseLinear([0.0, 0.05], [0.0, 1500.0])), n_cells=4, cell="ritz")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        r = simulate(act, 0.1)
    delta = rb.dynamic_rotation(r["actuator.tip_angle"], r["actuator.strain"], act.curvature_per_strain, act.length)
    assert 0.005 < delta < rb.DYNAMIC_ROTATION_LIMIT


@pytest.mark.parametrize("call", ["solve_static", "simulate", "eigenfrequencies"])
def test_tip_force_is_refused(call):
    act = REF_A.actuator(PiezoDrive(500.0), n_cells=3, cell="ritz")
    run = {"solve_static": lambda: solve_static(act, tip_force=(0.0, -0.2)),
           "simulate": lambda: simulate(act, 1e-3, tip_force=(0.0, -0.2)),
           "eigenfrequencies": lambda: eigenfrequencies(act, n=1, tip_force=(0.0, -0.2))}[call]
    with pytest.raises(ValueError, match=r"tip_force must be \(0, 0\) for cell='ritz', got \(0\.0, -0\.2\).*'beam'"):
        run()


@pytest.mark.parametrize("path", ["offsets", "user_function"])
def test_other_stroke_paths_are_refused(path):
    act = fast_triangle_actuator("ritz", None)
    with pytest.raises(ValueError, match=f"stroke_path must be 'prestep' for the ritz cell.*{path}"):
        run_actuator(act, 1e-3, 1e-4, (0.0, 0.0), None, stroke_path=path)


def test_in_step_hysteresis_equals_offline_replay_despite_rejected_steps():
    with warnings.catch_warnings():
        # the 20 Hz triangle excites the 36 Hz bender: the dynamic-rotation warning is expected
        warnings.simplefilter("ignore", RuntimeWarning)
        check_in_step_hysteresis_equals_offline_replay("ritz", REJECTING)
        H2 = paper_strain_preisach()
        with coarse_step_expected():
            r2 = simulate(fast_triangle_actuator("ritz", LeakyOperator(H2)), 0.1, step=2e-3, settings=REJECTING)
    assert np.max(np.abs(r2["actuator.strain"] - H2.apply(r2["actuator.voltage"]))) > 1e-6


@pytest.mark.parametrize("n_cells", [1, 8])
def test_run_starts_in_static_equilibrium(n_cells):
    r, _ = check_run_starts_in_static_equilibrium("ritz", n_cells, force=(0.0, 0.0))
    assert [c for c in r if c.startswith("actuator.cell_angle_")] == [f"actuator.cell_angle_{j + 1}" for j in range(n_cells)]


# ----------------------------------------------------------------------------- cases and mechanisms

def test_fig12_case_runs_with_ritz_from_the_command_line(tmp_path):
    # --set cell=ritz: 4 modes of the 87 mm bender, one 1 s period of the paper's triangle.  The
    # tip follows the arc of each row's free strain up to the dynamic part excited by the
    # triangle's corners (measured 1.2 % of the largest deflection; the 36 Hz bender is driven at
    # 1 Hz): within 2 %
    from _cli_helpers import cli
    from exudyn_atcm.io import read_csv

    proc = cli(["run", "paper_bending_actuator", "--set", "cell=ritz", "--set", "n_cells=4", "--set",
                "cell_length=0.02175", "--set", "cycles=1", "--set", "animation=false", "--set", "record_every=0",
                "--out", "out"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    data = read_csv(tmp_path / "out" / "paper_bending_actuator.csv")
    assert [c for c in data.names if c.startswith("actuator.cell_angle_")] == [f"actuator.cell_angle_{j}" for j in (1, 2, 3, 4)]
    g = REF_A
    y_arc = np.array([float(bt.arc_point(_composite_kappa(g, s), g.length)[1]) if s != 0.0 else 0.0
                      for s in data["actuator.strain"]])
    assert np.max(np.abs(data["actuator.tip_y"] - y_arc)) <= 2e-2 * np.max(np.abs(y_arc))


def test_cases_and_mechanisms_that_need_tip_loads_or_cells_refuse_ritz():
    from exudyn_atcm.casework import CaseError, load_case
    from exudyn_atcm.model.materials import Layer
    from exudyn_atcm.mechanism import Bender

    from _cli_helpers import CASES

    # the stiffness comparison loads the tip (compliance run): ritz is not among its choices
    with pytest.raises((CaseError, ValueError), match="cell must be one of six-bar, rigid, beam, ancf, rod, got 'ritz'"):
        load_case(CASES / "stiffness_comparison.py").run({"cell": "ritz", "n_voltages": 2})
    # in a mechanism a ritz bender is a cantilever only: a joint at its tip is refused by the cell itself
    from exudyn_atcm import Link, Mechanism, MechanismError, solve_static

    b = Bender("b", width=1e-2, passive=Layer(0.2e-3, 70e9, 1550.0), active=Layer(0.3e-3, 30.336e9, 5440.0),
               length=0.03, n_cells=2, drive=PiezoDrive(300.0), cell="ritz")
    lever = Link("lever", {"A": (0.03, 0.0), "E": (0.05, 0.0)}, mass=2e-4, inertia=1e-8)
    with pytest.raises(MechanismError, match=r"bender 'b': the ritz cell joins a mechanism as a cantilever only .*"
                                             r"got its tip joined to other parts; use cell='beam'"):
        solve_static(Mechanism("m").add(b, lever).ground(b.base).weld(b.tip, lever.point("A")))
    with pytest.raises(MechanismError, match=r"'push' acts at b.tip of bender 'b': the ritz cell refuses tip loads"):
        solve_static(Mechanism("m").add(b).ground(b.base).force(b.tip, (0.0, -0.01), name="push"))
