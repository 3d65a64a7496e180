"""``cell="rod"``: the geometrically exact rotation-field rod in assumed modes (issue 15, part 1).

The mathematics (:mod:`exudyn_atcm.theory.rotation_rod` and its compiled kernels) against
independent constructions: scipy's adaptive quadrature of the position integral, the kinetic
energy of finite-difference velocities, Lagrange's equations for the quadratic velocity vector
(finite differences of the mass matrix) and the ``ritz`` cell's double-integral mass on the arc.
The Exudyn model against the exact arc, Bisshopp & Drucker's elastica, the shooting solution of a
curved cantilever with a lever under a dead load (large deflection), the clamped-free beam's
f1, beam elements about bent and loaded states, the rigid four-bar's loop closure, the
hysteresis operator applied offline (the last two with the other cells in test_mechanism_solve.py, and
a user's own solve after ``add_to`` in test_cells.py).
"""

from __future__ import annotations

import math
import pathlib
import sys
import warnings

import numpy as np
import pytest
from scipy.integrate import quad

import exudyn_atcm as atcm
from exudyn_atcm import Bender, Layer, Link, Mechanism, PiezoDrive, eigenfrequencies, simulate, solve_static
from exudyn_atcm import theory as bt
from exudyn_atcm.casework import load_case
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.theory import ritz_beam, rod_kernels
from exudyn_atcm.theory import rotation_rod as rr

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from test_mechanism_solve import four_bar  # noqa: E402

CASES = pathlib.Path(__file__).resolve().parents[1] / "cases"
CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W = 28e-3
L = 0.06
MU, RHO_I = 0.2, 1.5e-8  # kg/m, kg m: the order of the paper's laminate
#: a large-rotation state of 4 modes [rad]: tip at 1.1 rad, an S-shaped part
Q = np.array([1.1, -0.4, 0.25, -0.1])
QD = np.array([3.0, -2.0, 1.5, 0.7])


def rod(name="b", n_cells=4, drive=None, length=L, **kw):
    return Bender(name, width=W, passive=CFC, active=MFC, length=length, n_cells=n_cells,
                  drive=drive if drive is not None else PiezoDrive(0.0), cell="rod", **kw)


def cantilever(b, force=(0.0, 0.0)):
    m = Mechanism("cantilever").add(b).ground(b.base)
    if force != (0.0, 0.0):
        m.force(b.tip, force)
    return m


def _theta(q, s, length=L):
    return float(ritz_beam.rotation_shapes(len(q), [s / length])[0] @ q)


def _position(q, s, length=L):
    """r(s) by scipy's adaptive quadrature of (cos theta, sin theta)."""
    return np.array([quad(lambda u: math.cos(_theta(q, u, length)), 0.0, s, epsabs=1e-15, epsrel=1e-13)[0],
                     quad(lambda u: math.sin(_theta(q, u, length)), 0.0, s, epsabs=1e-15, epsrel=1e-13)[0]])


# ----------------------------------------------------------------------------- the mathematics

def test_integration_matrix_is_exact_for_polynomials_below_its_order():
    xi, w, s = rr.quadrature(12)
    for m in range(12):
        np.testing.assert_allclose(s @ xi**m, xi ** (m + 1) / (m + 1), rtol=0, atol=1e-14)
        assert w @ xi**m == pytest.approx(1.0 / (m + 1), abs=1e-15)
    with pytest.raises(ValueError, match="n_points must be an integer >= 2, got 1"):
        rr.quadrature(1)


def test_tip_pose_is_the_integral_of_the_rotation_field():
    shapes = rr.rod_shapes(4, L)
    x, y, theta = rr.tip_pose(shapes, Q)
    ref = _position(Q, L)
    assert (x, y) == pytest.approx(tuple(ref), abs=1e-13 * L)
    assert theta == pytest.approx(_theta(Q, L), abs=1e-15)
    # the compiled kernel on a base at the origin with Phi = 0: z = (X, Y, Phi, q)
    z = np.concatenate([[0.0, 0.0, 0.0], Q])
    kx, ky, kth, jac = rod_kernels.tip_pose(z, shapes.phi_hat, shapes.weights, L, shapes.phi_hat_tip)
    assert (kx, ky, kth) == pytest.approx((x, y, theta), abs=1e-16)
    # the Jacobian rows against central differences of the adaptive quadrature; the base's columns:
    # a translation moves the tip with it, a base rotation turns it about the base point
    for i in range(4):
        e = np.zeros(4)
        e[i] = 1e-6
        fd = (_position(Q + e, L) - _position(Q - e, L)) / 2e-6
        np.testing.assert_allclose(jac[:, 3 + i], fd, rtol=0, atol=1e-9 * L)
    np.testing.assert_allclose(jac[:, :3], [[1.0, 0.0, -y], [0.0, 1.0, x]], rtol=0, atol=1e-15)


def test_mass_matrix_is_the_kinetic_energy_of_the_exact_velocity():
    # T = 1/2 int (mu |r_dot|^2 + rho_I theta_dot^2) ds with r_dot(s) from central differences of
    # the quadrature positions along q_dot: 1/2 q_dot^T M q_dot for several directions
    shapes = rr.rod_shapes(4, L)
    m = rr.mass_matrix(shapes, Q, MU, RHO_I)
    np.testing.assert_allclose(m, m.T, rtol=0, atol=1e-18)
    s_nodes, s_weights = np.polynomial.legendre.leggauss(24)
    s_nodes, s_weights = 0.5 * L * (s_nodes + 1.0), 0.5 * L * s_weights
    rng = np.random.default_rng(1)
    for v in [QD, *rng.normal(size=(3, 4))]:
        h = 1e-6
        energy = 0.0
        for s, w in zip(s_nodes, s_weights):
            rdot = (_position(Q + h * v, s) - _position(Q - h * v, s)) / (2 * h)
            thdot = ritz_beam.rotation_shapes(4, [s / L])[0] @ v
            energy += 0.5 * w * (MU * rdot @ rdot + RHO_I * thdot**2)
        assert 0.5 * v @ m @ v == pytest.approx(energy, rel=1e-8)


def test_mass_matrix_on_the_arc_is_the_ritz_cells():
    # the ritz cell's M(kappa) (its own double-integral form, tested against nested integrals in
    # test_actuator_ritz) is this M at q = (kappa L, 0, ...)
    for kappa_l in (0.0, 0.36, 1.2):
        q = np.array([kappa_l, 0.0, 0.0])
        np.testing.assert_allclose(rr.mass_matrix(rr.rod_shapes(3, L), q, MU, RHO_I),
                                   ritz_beam.mass_matrix(3, L, MU, RHO_I, kappa_l / L), rtol=1e-12, atol=1e-22)


def test_quadratic_velocity_vector_follows_lagranges_equations():
    # g = M_dot q_dot - 1/2 d(q_dot^T M q_dot)/dq, with M_dot and the gradient by central differences
    shapes = rr.rod_shapes(4, L)
    g = rr.quadratic_velocity_vector(shapes, Q, QD, MU)
    h = 1e-6
    m_dot = (rr.mass_matrix(shapes, Q + h * QD, MU, RHO_I) - rr.mass_matrix(shapes, Q - h * QD, MU, RHO_I)) / (2 * h)
    grad = np.array([(QD @ rr.mass_matrix(shapes, Q + h * e, MU, RHO_I) @ QD
                      - QD @ rr.mass_matrix(shapes, Q - h * e, MU, RHO_I) @ QD) / (2 * h) for e in np.eye(4)])
    np.testing.assert_allclose(g, m_dot @ QD - 0.5 * grad, rtol=1e-6, atol=1e-9 * np.max(np.abs(g)))
    assert np.max(np.abs(g)) > 1e-3 * MU * L**3 * (QD @ QD)  # not trivially zero
    np.testing.assert_allclose(rr.quadratic_velocity_vector(shapes, Q, np.zeros(4), MU), 0.0, atol=0)


def _floating(z, z_dot):
    shapes = rr.rod_shapes(4, L)
    return rod_kernels.rod_matrices(z, z_dot, shapes.phi_hat, shapes.integration, shapes.weights, L, MU, RHO_I,
                                    shapes.phi_hat_tip)


def test_rod_on_a_moving_base_kinetic_energy_lagrange_and_tip_linearisation():
    """The compiled kernels, coordinates z = (X, Y, Phi, q): the base's point and rotation (the rod
    rides on them) and the modes.  M against the kinetic energy of finite-difference velocities
    (base moving and turning), g against Lagrange's equations, the tie's linearisation and the
    geometric stiffness against finite differences; the modes' block equals the clamped numpy
    reference (a rigid motion does not change it)."""
    shapes = rr.rod_shapes(4, L)
    z = np.concatenate([[0.01, -0.02, 0.7], Q])
    z_dot = np.concatenate([[0.3, -0.1, 2.0], QD])
    mass, force, x1, offset = _floating(z, z_dot)
    np.testing.assert_allclose(mass, mass.T, rtol=0, atol=1e-18)
    np.testing.assert_allclose(mass[3:, 3:], rr.mass_matrix(shapes, Q, MU, RHO_I), rtol=1e-13, atol=1e-22)

    s_nodes, s_weights = np.polynomial.legendre.leggauss(24)
    s_nodes, s_weights = 0.5 * L * (s_nodes + 1.0), 0.5 * L * s_weights

    def point(zz, s):
        """r(s) of the rod on the base zz[:3], by scipy's adaptive quadrature."""
        def th(u):
            return zz[2] + _theta(zz[3:], u)
        return zz[:2] + np.array([quad(lambda u: math.cos(th(u)), 0.0, s, epsabs=1e-15, epsrel=1e-13)[0],
                                  quad(lambda u: math.sin(th(u)), 0.0, s, epsabs=1e-15, epsrel=1e-13)[0]])

    h = 1e-6
    energy = 0.0
    for s, w in zip(s_nodes, s_weights):
        rdot = (point(z + h * z_dot, s) - point(z - h * z_dot, s)) / (2 * h)
        thdot = z_dot[2] + ritz_beam.rotation_shapes(4, [s / L])[0] @ z_dot[3:]
        energy += 0.5 * w * (MU * rdot @ rdot + RHO_I * thdot**2)
    assert 0.5 * z_dot @ mass @ z_dot == pytest.approx(energy, rel=1e-8)
    # Lagrange: g = M_dot z_dot - 1/2 d(z_dot^T M z_dot)/dz (the kernel's force is -g)
    m_dot = (_floating(z + h * z_dot, z_dot)[0] - _floating(z - h * z_dot, z_dot)[0]) / (2 * h)
    grad = np.array([(z_dot @ _floating(z + h * e, z_dot)[0] @ z_dot - z_dot @ _floating(z - h * e, z_dot)[0] @ z_dot)
                     / (2 * h) for e in np.eye(7)])
    g = m_dot @ z_dot - 0.5 * grad
    np.testing.assert_allclose(-force, g, rtol=0, atol=1e-6 * np.max(np.abs(g)))
    assert np.max(np.abs(g)) > 1e-3 * MU * L**3 * (z_dot @ z_dot)

    def tip(zz):
        x, y, angle, _ = rod_kernels.tip_pose(zz, shapes.phi_hat, shapes.weights, L, shapes.phi_hat_tip)
        return np.array([x, y, angle])

    ref = tip(z)
    assert ref[:2] == pytest.approx(point(z, L), abs=1e-13 * L)
    assert ref[2] == pytest.approx(z[2] + z[3], abs=1e-15)  # Phi + q_1
    # Exudyn's tie: x1 z - q_tip - offset = 0 holds at z, and x1 is the tip's Jacobian
    np.testing.assert_allclose(x1 @ z - offset, ref, rtol=0, atol=1e-15)
    lam = np.array([0.3, -1.1])
    kg = rod_kernels.geometric_stiffness(z, shapes.phi_hat, shapes.weights, L, lam[0], lam[1])
    for i in range(7):
        e = np.zeros(7)
        e[i] = 1e-6
        np.testing.assert_allclose(x1[:, i], (tip(z + e) - tip(z - e)) / 2e-6, rtol=0, atol=1e-9)
        # the geometric stiffness: the derivative of x1^T lam
        dx1 = (_floating(z + e, z_dot)[2] - _floating(z - e, z_dot)[2]) / 2e-6
        np.testing.assert_allclose(kg[:, i], dx1[:2].T @ lam, rtol=0, atol=1e-8)


# ----------------------------------------------------------------------------- statics

@pytest.mark.parametrize("n", [1, 3])
@pytest.mark.parametrize("voltage", [100.0, 1500.0])
def test_free_actuation_is_the_exact_arc_for_any_mode_count(n, voltage):
    b = rod(n_cells=n, drive=PiezoDrive(voltage))
    r = solve_static(cantilever(b))
    kappa = b.laminate.curvature_per_strain * b.segments[0].drive.linear_strain(voltage)
    # the static Newton tolerance: relative 1e-10 of the first residual, absolute 1e-12 EI/L
    assert r["b.tip_angle"][0] == pytest.approx(kappa * L, rel=1e-9)
    x, y = bt.arc_point(kappa, L)
    # the angle's tolerance moves the tip by ~L kappa L 1e-10
    assert r["b.tip_x"][0] == pytest.approx(x, abs=1e-10 * L)
    assert r["b.tip_y"][0] == pytest.approx(y, abs=1e-10 * L)
    angles = [r[f"b.cell_angle_{j + 1}"][0] for j in range(n)]
    np.testing.assert_allclose(angles, (np.arange(n) + 0.5) * kappa * L / n, rtol=1e-9)  # mean rotations


@pytest.mark.parametrize("alpha", [1.0, 2.0, 5.0])
def test_large_tip_force_matches_the_elastica(alpha):
    b = rod(n_cells=8)
    ei = b.laminate.bending_stiffness
    r = solve_static(cantilever(b, (0.0, alpha * ei / L**2)))
    y_ref, dx_ref = bt.ELASTICA_TIP_FORCE[alpha]
    # Bisshopp & Drucker's table has 5 digits
    assert r["b.tip_y"][0] / L == pytest.approx(y_ref, abs=1e-5)
    assert 1.0 - r["b.tip_x"][0] / L == pytest.approx(dx_ref, abs=1e-5)
    # the shooting solution (DOP853, relative tolerance 1e-12): the modes converge exponentially,
    # measured 2e-11 L (alpha = 1), 9e-11 L (alpha = 5, tip rotation 1.2 rad) at 8 modes
    ref = bt.curved_cantilever_end_load(0.0, ei, L, (0.0, alpha * ei / L**2))
    assert r["b.tip_x"][0] == pytest.approx(ref["tip_x"], abs=1e-9 * L)
    assert r["b.tip_y"][0] == pytest.approx(ref["tip_y"], abs=1e-9 * L)
    assert r["b.tip_angle"][0] == pytest.approx(ref["tip_angle"], abs=1e-8)


@pytest.mark.parametrize("angle", [0.3, math.pi / 2, -2.5])
def test_a_turned_and_moved_rod_is_the_same_rod(angle):
    """A rod whose base sits at (0.02, -0.01) turned by ``angle``, with its load turned alike, takes the
    same shape turned and moved (the absolute rotation holds the base's rotation: a reference angle
    that leaked into the coordinates' stiffness compensation once bent such rods by 1e-2 rad)."""
    c, s = math.cos(angle), math.sin(angle)
    drive = PiezoDrive(1000.0)
    f = np.array([0.1, 0.4])
    flat = solve_static(cantilever(rod(n_cells=6, drive=drive), tuple(f)))
    b = rod(n_cells=6, drive=drive, base=(0.02, -0.01), angle=angle)
    turned = solve_static(cantilever(b, (c * f[0] - s * f[1], s * f[0] + c * f[1])))
    x, y = flat["b.tip_x"][0], flat["b.tip_y"][0]
    # the static Newton tolerance (relative 1e-10) leaves ~1e-10 L
    assert turned["b.tip_x"][0] == pytest.approx(0.02 + c * x - s * y, abs=1e-10 * L)
    assert turned["b.tip_y"][0] == pytest.approx(-0.01 + s * x + c * y, abs=1e-10 * L)
    assert turned["b.tip_angle"][0] - angle == pytest.approx(flat["b.tip_angle"][0], abs=1e-9)
    assert flat["b.tip_angle"][0] > 0.2  # bent


def test_mode_convergence_under_a_large_tip_force_is_exponential():
    """alpha = F L^2/EI = 10 (tip rotation 1.43 rad): tip error against the shooting solution
    1.9e-5, 1.4e-6, 3.8e-9 and 1.9e-11 L at 4, 6, 8 and 12 modes (measured)."""
    ei = rod().laminate.bending_stiffness
    ref = bt.curved_cantilever_end_load(0.0, ei, L, (0.0, 10.0 * ei / L**2))
    errors = []
    for n in (4, 6, 8, 12):
        r = solve_static(cantilever(rod(n_cells=n), (0.0, 10.0 * ei / L**2)))
        errors.append(math.hypot(r["b.tip_x"][0] - ref["tip_x"], r["b.tip_y"][0] - ref["tip_y"]) / L)
    assert errors[0] < 1e-4 and errors[-1] < 1e-9
    assert all(later < earlier / 5 for earlier, later in zip(errors, errors[1:]))


@pytest.mark.parametrize("alpha, n", [(5.0, 2), (10.0, 2), (5.0, 3), (10.0, 3), (5.0, 4)])
def test_left_out_mode_estimate_follows_the_true_error_against_the_elastica(alpha, n):
    """The hierarchical estimate (one Newton step of the rod with one more mode, from the tip force's work on
    the new mode) against the true tip error from the shooting solution: measured 1.00-1.02 at 2 and 3 modes,
    0.88 (5 EI/L^2) at 4 modes (more left-out modes contribute as the error falls to 1e-5 L; the first
    left-out mode alone, the kept modes held, gave 0.93-1.04 and 0.61)."""
    b = rod(n_cells=n)
    ei = b.laminate.bending_stiffness
    force = (0.0, alpha * ei / L**2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", atcm.AccuracyWarning)  # the warning itself: the next test
        r = solve_static(cantilever(b, force))
    ref = bt.curved_cantilever_end_load(0.0, ei, L, force)
    true = math.hypot(r["b.tip_x"][0] - ref["tip_x"], r["b.tip_y"][0] - ref["tip_y"])
    # the modes from the cells' mean rotations (G q), independent of the package's internals
    q = np.linalg.solve(ritz_beam.segment_rotation_matrix(n, n), [r[f"b.cell_angle_{j + 1}"][0] for j in range(n)])
    estimate = rr.truncation_error(rr.rod_shapes(n, L), ei, 0.0, q, force)
    assert (0.85 if n < 4 else 0.4) < estimate / true < 1.15


def test_too_few_modes_for_the_tip_force_are_warned_about_in_solves_and_sweeps():
    ei = rod().laminate.bending_stiffness
    force = (0.0, 5.0 * ei / L**2)  # tip turned by 1.2 rad: 2 modes miss the tip by 7.4e-3 L, 4 modes by 1.6e-5 L
    with pytest.warns(atcm.AccuracyWarning, match=r"rod bender 'b' with 2 modes is too coarse .* about 0.000[34]\d* m"):
        solve_static(cantilever(rod(n_cells=2), force))
    with warnings.catch_warnings():
        warnings.simplefilter("error", atcm.AccuracyWarning)
        solve_static(cantilever(rod(n_cells=4), force))
    # a sweep warns once, with its worst point; eigenfrequencies about the loaded state too
    with pytest.warns(atcm.AccuracyWarning, match="too coarse") as record:
        atcm.static_sweep(cantilever(rod(n_cells=2), force), [0.0, 100.0, 200.0])
    assert sum("too coarse" in str(w.message) for w in record) == 1
    with pytest.warns(atcm.AccuracyWarning, match="too coarse"):
        eigenfrequencies(cantilever(rod(n_cells=2), force), n=1, voltage=0.0)
    # a segmented rod names its modes per segment
    seg = Bender("s", width=W, passive=CFC, active=MFC, cell="rod",
                 segments=[atcm.Segment(0.03, 1, PiezoDrive(0.0)), atcm.Segment(0.03, 1, None)])
    with pytest.warns(atcm.AccuracyWarning, match=r"modes 1 \+ 1 \(per segment\)"):
        solve_static(Mechanism().add(seg).ground(seg.base).force(seg.tip, force))


def _follower_elastica(ei, length, force, guess_angle, guess_curvature):
    """Kirchhoff's rod clamped at the origin under a follower end force (``force`` in the reference pose, turned
    by the tip's rotation): shooting on the base curvature and the tip rotation (DOP853, relative 1e-12)."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import root

    def shoot(u):
        k, angle = u
        c, s = math.cos(angle), math.sin(angle)
        fx, fy = c * force[0] - s * force[1], s * force[0] + c * force[1]
        return solve_ivp(lambda _s, y: [y[1], (math.sin(y[0]) * fx - math.cos(y[0]) * fy) / ei, math.cos(y[0]),
                                        math.sin(y[0])], (0.0, length), [0.0, k, 0.0, 0.0], method="DOP853",
                         rtol=1e-12, atol=1e-14).y[:, -1]

    solution = root(lambda u: (lambda e: [e[1] * length, e[0] - u[1]])(shoot(u)), [guess_curvature, guess_angle],
                    tol=1e-13)
    assert solution.success
    end = shoot(solution.x)
    return end[2], end[3], end[0]


@pytest.mark.parametrize("alpha, n", [(5.0, 2), (5.0, 3), (10.0, 3), (10.0, 4), (30.0, 4), (30.0, 6), (30.0, 8)])
def test_left_out_mode_estimate_follows_the_true_error_of_a_follower_force(alpha, n):
    """The estimate (one Newton step of the rod with one more mode, with the follower force's turning in its
    tangent) against the follower elastica (shooting, started from a 24-mode rod): measured 0.95-1.45 of the
    true tip error (the larger at 30 EI/L^2 with 2-3 modes, errors of 0.1-0.5 L), 0.84 at 6 modes and
    30 EI/L^2; the first left-out mode alone, the kept modes held (the estimate before), gave 0.15-0.5."""
    ei = rod().laminate.bending_stiffness
    force = (0.0, alpha * ei / L**2)
    fine = solve_static(Mechanism().add(rod(n_cells=24)).ground("b.base").force("b.tip", force, follower=True))
    x, y, angle = _follower_elastica(ei, L, force, fine["b.tip_angle"][0], 48.0 * fine["b.cell_angle_1"][0] / L)
    assert math.hypot(fine["b.tip_x"][0] - x, fine["b.tip_y"][0] - y) < 1e-9 * L  # 24 modes: converged
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", atcm.AccuracyWarning)  # the warning itself: the next test
        r = solve_static(Mechanism().add(rod(n_cells=n)).ground("b.base").force("b.tip", force, follower=True))
    true = math.hypot(r["b.tip_x"][0] - x, r["b.tip_y"][0] - y)
    q = np.linalg.solve(ritz_beam.segment_rotation_matrix(n, n), [r[f"b.cell_angle_{j + 1}"][0] for j in range(n)])
    theta = r["b.tip_angle"][0]
    turned = (-math.sin(theta) * force[1], math.cos(theta) * force[1])
    estimate = rr.truncation_error(rr.rod_shapes(n, L), ei, 0.0, q, turned, follower_force=turned)
    assert 0.8 < estimate / true < 1.5, estimate / true


def test_too_few_modes_for_a_follower_force_are_warned_about():
    """6 modes under a follower force of 30 EI/L^2 miss the tip by 3.8e-3 L (the elastica, previous test): warned
    (on main the estimate, 0.15 of it, passed silently); 8 modes miss it by 4.3e-4 L: no warning."""
    ei = rod().laminate.bending_stiffness
    force = (0.0, 30.0 * ei / L**2)
    with pytest.warns(atcm.AccuracyWarning, match=r"rod bender 'b' with 6 modes is too coarse .* 0\.003\d* of its length"):
        solve_static(Mechanism().add(rod(n_cells=6)).ground("b.base").force("b.tip", force, follower=True))
    with warnings.catch_warnings():
        warnings.simplefilter("error", atcm.AccuracyWarning)
        solve_static(Mechanism().add(rod(n_cells=8)).ground("b.base").force("b.tip", force, follower=True))


def test_follower_force_at_a_rod_tip_turns_with_the_tip():
    """A follower force turns with the tip node: its equilibrium is the equilibrium under the dead
    force turned by the tip's final rotation (the same equations; Newton tolerance)."""
    f = np.array([0.0, 2.0])
    follow = solve_static(Mechanism().add(rod()).ground("b.base").force("b.tip", tuple(f), follower=True))
    theta = follow["b.tip_angle"][0]
    turned = np.array([math.cos(theta) * f[0] - math.sin(theta) * f[1], math.sin(theta) * f[0] + math.cos(theta) * f[1]])
    dead = solve_static(cantilever(rod(), tuple(turned)))
    assert theta > 0.1  # a large rotation: the follower really turned
    assert dead["b.tip_angle"][0] == pytest.approx(theta, abs=1e-9)
    assert dead["b.tip_y"][0] == pytest.approx(follow["b.tip_y"][0], abs=1e-11)
    plain = solve_static(cantilever(rod(), tuple(f)))
    assert plain["b.tip_angle"][0] < theta - 5e-4  # a dead force of the reference direction bends less


def test_curved_rod_with_a_lever_under_a_dead_load_matches_the_shooting_solution():
    """Lever on the tip (a rigid link welded there), free curvature and a dead force at the
    lever's end: the large-deflection equilibrium of Kirchhoff's rod (shooting, scipy)."""
    drive = PiezoDrive(1500.0)
    b = rod(n_cells=6, drive=drive)
    lever = Link("lever", {"A": (L, 0.0), "P": (L + 0.02, 0.0)}, mass=1e-4, inertia=1e-8)
    ei = b.laminate.bending_stiffness
    force = (0.3 * ei / L**2, -1.5 * ei / L**2)
    m = Mechanism().add(b, lever).ground(b.base).weld(b.tip, lever.point("A")).force("lever.P", force)
    r = solve_static(m)
    kappa = b.laminate.curvature_per_strain * drive.linear_strain(1500.0)
    ref = bt.curved_cantilever_end_load(kappa, ei, L, force, (0.02, 0.0))
    assert abs(ref["tip_angle"]) > 0.5  # large rotation
    for key in ("tip_x", "tip_y"):
        assert r[f"b.{key}"][0] == pytest.approx(ref[key], abs=1e-7 * L), key
    assert r["b.tip_angle"][0] == pytest.approx(ref["tip_angle"], abs=1e-7)
    assert r["lever.P_x"][0] == pytest.approx(ref["point_x"], abs=1e-7 * L)
    assert r["lever.P_y"][0] == pytest.approx(ref["point_y"], abs=1e-7 * L)


def test_tip_pinned_to_a_slider_block_with_a_spring_matches_the_shooting_solution():
    """Clamped base, tip pinned to a block that slides along the x axis against a spring k: under the
    free curvature the guide pushes the tip back to y = 0 and the spring takes the shortening.
    Reference: the curved cantilever's shooting solution with the end force (Fx, Fy) that gives
    tip_y = 0 and Fx = -k (tip_x - L) (scipy's root)."""
    from scipy.optimize import root

    k, drive = 20.0, PiezoDrive(1500.0)
    b = rod(n_cells=6, drive=drive)
    block = Link("block", {"A": (L, 0.0)}, mass=1e-4, inertia=1e-9)
    m = Mechanism().add(b, block).ground(b.base).pin(b.tip, "block.A")
    r = solve_static(m.ground("block.A", joint="slider", axis=(1.0, 0.0), stiffness=k))
    ei = b.laminate.bending_stiffness
    kappa = b.laminate.curvature_per_strain * drive.linear_strain(1500.0)

    def residual(f):
        end = bt.curved_cantilever_end_load(kappa, ei, L, (f[0], f[1]))
        return [end["tip_y"] / L, (f[0] + k * (end["tip_x"] - L)) * L**2 / ei]

    force = root(residual, [0.0, -2.0 * ei * kappa / L], tol=1e-14).x
    ref = bt.curved_cantilever_end_load(kappa, ei, L, tuple(force))
    assert L - ref["tip_x"] > 1e-5  # the spring is compressed by the arc's shortening
    assert r["b.tip_x"][0] == pytest.approx(ref["tip_x"], abs=1e-12)
    assert r["b.tip_y"][0] == pytest.approx(0.0, abs=1e-14)
    assert r["b.tip_angle"][0] == pytest.approx(ref["tip_angle"], abs=1e-9)


# ----------------------------------------------------------------------------- eigenfrequencies

def test_clamped_free_f1_converges_to_the_beams():
    b = rod(n_cells=2)
    f1 = bt.first_bending_frequency(b.laminate.bending_stiffness, b.laminate.mass_per_length, L)
    errors = [eigenfrequencies(cantilever(rod(n_cells=n)), n=1)[0] / f1 - 1 for n in (2, 3, 4, 6)]
    # Rayleigh-Ritz from above in the modes (+0.47 %, +0.028 % at 2 and 3); the rotary inertia
    # lowers f1 by ~(h/L)^2 ~ 2e-5 (the Euler-Bernoulli f1 leaves it out)
    assert errors[0] > errors[1] > errors[2]
    assert abs(errors[-1]) < 5e-5


def test_frequencies_about_a_bent_and_loaded_state_equal_beam_elements():
    # the tie's geometric stiffness (the tip force turning with the rod) enters the tangent: a tip
    # force 2 EI/L^2 against the bending raises f1 by 18 %, and the rod follows beam
    # elements.  The beam's error is second order (from above): Richardson's extrapolation of 32 and
    # 64 elements; what remains is the beam's axial and shear compliance (the rod is inextensible
    # and shear-rigid): measured 1.8e-5 (f1) and 1.4e-4 (f2)
    drive = PiezoDrive(1500.0)

    def frequencies(cell, n, loaded=True):
        b = Bender("b", width=W, passive=CFC, active=MFC, length=L, n_cells=n, drive=drive, cell=cell)
        force = (0.0, -2.0 * b.laminate.bending_stiffness / L**2) if loaded else (0.0, 0.0)
        return eigenfrequencies(cantilever(b, force), n=2, voltage=1500.0)

    rod_f = frequencies("rod", 8)
    assert rod_f[0] / frequencies("rod", 8, loaded=False)[0] - 1 > 0.15  # +18 %
    f32, f64 = frequencies("beam", 32), frequencies("beam", 64)
    beam_f = f64 + (f64 - f32) / 3.0
    assert rod_f[0] == pytest.approx(beam_f[0], rel=5e-5)
    assert rod_f[1] == pytest.approx(beam_f[1], rel=3e-4)


# ----------------------------------------------------------------------------- mechanisms and dynamics

def test_a_rod_crank_has_few_coordinates():
    # the loop closure and the hysteresis under step rejection of a rod crank are checked with the
    # other cells' (tests/test_mechanism_solve.py); here its size: the base node's 3 coordinates, 3
    # modes, the tip node's 3 and 2 links; the base's clamp 3, the tie 3, three pins 2 each
    dof = four_bar(PiezoDrive(0.0), n_cells=3, cell="rod").degrees_of_freedom()
    assert (dof.coordinates, dof.constraints, dof.dof) == (15, 12, 3)


def test_dynamic_four_bar_path_equals_fine_beam_elements():
    """The closed four-bar in motion (a fast triangle that excites its vibrations): a 4-mode rod
    crank and a 64-element beam crank give one coupler path (the beam's O(1/N^2) error at 64
    elements is ~1e-5 of the travel; measured difference 1e-5)."""
    paths = {}
    for cell, n in (("rod", 4), ("beam", 64)):
        m = four_bar(PiezoDrive(Triangle(500.0, 1000.0, 0.02)), n_cells=n, cell=cell)
        r = simulate(m, 0.02, step=1e-4)
        paths[cell] = np.column_stack([r["coupler.P_x"], r["coupler.P_y"]])
    travel = np.max(np.linalg.norm(paths["beam"] - paths["beam"][0], axis=1))
    assert travel > 1e-3
    assert np.max(np.linalg.norm(paths["rod"] - paths["beam"], axis=1)) < 1e-4 * travel


@pytest.mark.parametrize("cell", ["rod", "ritz"])
def test_a_setting_that_would_freeze_a_rewritten_mass_matrix_is_refused(cell):
    # both cells rewrite their mass matrix during a run: Exudyn must re-read it every step
    drive = PiezoDrive(Triangle(500.0, 1000.0, 0.02))
    if cell == "rod":
        system, name = cantilever(rod(n_cells=3, drive=drive)), "b"
    else:
        system, name = atcm.BendingActuator(3, L / 3, W, CFC, MFC, drive, cell="ritz"), "actuator"
    with pytest.raises(ValueError, match=rf"reuseConstantMassMatrix = True would keep the mass matrix of bender\(s\) \['{name}'\]"):
        simulate(system, 0.002, step=1e-4, settings={"timeIntegration.reuseConstantMassMatrix": True})
    simulate(system, 0.002, step=1e-4, settings={"timeIntegration.reuseConstantMassMatrix": False})


def test_compliant_four_bar_case_with_rod_cells():
    case = load_case(CASES / "compliant_four_bar.py")
    out = case.run({"cell": "rod", "n_cells": 4, "dynamic_period": 0.02, "step": 5e-4, "n_steps": 8})
    s = out.scalars
    # the references do not depend on the cells (rigid links and PRBM pivots): Newton tolerance
    assert s["reference_error"] < 1e-6 and s["reference_error_linear"] < 1e-6
    assert s["reference_error_dynamic"] < 1e-6
    assert s["coupler_travel"] > 1e-3


def test_rod_updates_wait_for_the_users_assemble():
    # after add_to the user assembles later: writing strains before that changes nothing and reads no
    # coordinates (the rod's ODE2 indices do not exist yet); after Assemble the first write linearises
    import exudyn as exu

    mbs = exu.SystemContainer().AddSystem()
    handle = atcm.add_to(mbs, cantilever(rod(n_cells=3, drive=PiezoDrive(1500.0))))
    handle.model.set_strains(np.array([1e-3]))  # before Assemble: must not read the (absent) coordinates
    mbs.Assemble()
    handle.model.set_strains(np.array([1e-3]))
    assert np.all(np.isfinite(mbs.systemData.GetODE2Coordinates()))


def test_two_rods_welded_end_to_end_equal_one_of_the_summed_length():
    """The second rod rides on the first one's tip (its base node welded there): the same elastica as one
    rod of the summed length, under actuation and a tip force, to the modes' accuracy (measured 1e-12 m
    and 4e-11 rad with 6 + 6 against 8 modes); the lowest eigenfrequencies agree as well (f1 to 4e-12,
    f2 to 7e-9, f3 to 3e-6, converging with the modes)."""
    drive = PiezoDrive(1000.0)
    one = cantilever(rod("one", n_cells=8, drive=drive, length=0.07), (0.0, -0.5))
    a = rod("a", n_cells=6, drive=drive, length=0.03)
    b = rod("b", n_cells=6, drive=drive, length=0.04, base=(0.03, 0.0))
    two = Mechanism("two").add(a, b).ground(a.base).weld(a.tip, b.base).force(b.tip, (0.0, -0.5))
    r1, r2 = solve_static(one), solve_static(two)
    assert r1["one.tip_angle"][0] > 0.05  # bent
    for axis in ("x", "y"):
        assert r2[f"b.tip_{axis}"][0] == pytest.approx(r1[f"one.tip_{axis}"][0], abs=1e-10 * 0.07)
    assert r2["b.tip_angle"][0] == pytest.approx(r1["one.tip_angle"][0], abs=1e-9)
    assert r2["a.tip_angle"][0] == pytest.approx(r2["b.base_angle"][0], abs=1e-12)
    ratio = eigenfrequencies(two, n=3) / eigenfrequencies(one, n=3) - 1.0
    assert np.all(np.abs(ratio) < [1e-9, 1e-7, 1e-5]), ratio


def test_pinned_base_with_a_torsion_spring_adds_the_rigid_rotation():
    f, k_p = 1e-4, 0.05
    clamped = solve_static(cantilever(rod(), (0.0, f)))
    b = rod()
    pinned = solve_static(Mechanism().add(b).ground(b.base, joint="pin", stiffness=k_p).force(b.tip, (0.0, f)))
    extra = f * L / k_p  # rotation at the base [rad], 1.2e-4: second-order terms ~1e-8 relative
    assert pinned["b.base_angle"][0] == pytest.approx(extra, rel=1e-6)
    assert pinned["b.tip_y"][0] == pytest.approx(clamped["b.tip_y"][0] + extra * L, rel=1e-6)


def test_rod_refuses_mass_damping():
    # (segmented benders: tests/test_mechanism_rod_segments.py)
    # its mass matrix is not a set of rigid bodies: mass-proportional damping is refused, not approximated
    with pytest.raises(ValueError, match="which the 'rod' cell cannot realise exactly"):
        rod(damping=atcm.RayleighDamping(alpha=2.0))


def test_the_ties_force_is_its_algebraic_coordinates_and_a_repeated_linearisation_writes_the_same_items():
    """The rod reads its tie's force as the tie's algebraic coordinates (a slice of the system's, instead of Exudyn's
    Force output, about 10 us inside a solve): equal to the output to the bit on a loaded, bent rod.  And the
    linearisation for an eigenvalue or stability analysis, skipped when the items hold the one at exactly that
    state, leaves them as a fresh one at that state would: the same Exudyn system Jacobian and mass matrix."""
    import exudyn as exu
    from exudyn_atcm.mbs.solver_jacobian import SolverJacobian
    from exudyn_atcm.solve import mechanism_solve

    made, linearisations = [], [0]
    original, kernel = mechanism_solve.stability_probe, rod_kernels.linearisation

    def keep(mech, model):
        made.append(original(mech, model))
        return made[-1]

    def counted(*args):
        linearisations[0] += 1
        return kernel(*args)

    mechanism_solve.stability_probe, rod_kernels.linearisation = keep, counted  # the rod takes its kernel at build
    try:
        b = rod(n_cells=4, drive=PiezoDrive(1200.0))
        ei = b.laminate.bending_stiffness
        solve_static(cantilever(b, force=(0.4 * ei / L**2, -1.2 * ei / L**2)))
    finally:
        mechanism_solve.stability_probe, rod_kernels.linearisation = original, kernel
    model = made[-1].model
    mbs, sd = model.mbs, model.mbs.systemData
    ties = [i for i in range(sd.NumberOfObjects()) if mbs.GetObject(i)["objectType"] == "ConnectorCoordinateVector"]
    assert len(ties) == 1
    force = np.array(mbs.GetObjectOutput(ties[0], exu.OutputVariableType.Force))
    multipliers = np.array(sd.GetAECoordinates())[list(sd.GetObjectLTGAE(ties[0]))]
    assert np.linalg.norm(force) > 0.1 * ei / L**2  # loaded
    np.testing.assert_array_equal(force, multipliers)
    jacobian = SolverJacobian(mbs)
    model.before_linearisation()  # writes the linearisation at this state (the solve's last pass may not have)
    first = jacobian.system()
    before = linearisations[0]
    model.before_linearisation()  # the same state: skipped
    assert linearisations[0] == before
    again = jacobian.system()
    for key in ("M", "K", "Cq"):
        np.testing.assert_array_equal(first[key], again[key], err_msg=key)
