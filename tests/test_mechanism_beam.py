"""Mechanism benders with ``cell="beam"`` (geometrically exact beam elements), each against an
independent reference.

References: the lone actuator's beam cell (``BendingActuator(cell="beam")``, its own builder);
one bender of the summed length; the rigid four-bar's loop closure (circle intersection); the
exact S-blade (two arcs) of the parallel guide; the closed form of an arc followed by a
straight segment; Hooke's law and the axial rigidity; Euler-Bernoulli's cantilever
compliance ``L³/(3 EI)``; the hysteresis operator applied offline to the recorded voltages.

Discretisation facts used for the tolerances (derived in the docs' cells section, measured here):
a beam element integrates its strains at the midpoint, so under free curvature ``kappa`` its
chord has length ``L_c`` and the angle of the mean node rotation: the nodes lie on the arc's
inscribed polygon with chords ``L_c``, exactly as the rigid chain's joints, an end error of
order ``(kappa L_c)²/24`` (second order in the cell length).  Under a tip force its node
rotations are exact and the deflection is the trapezoidal rule over them: the compliance is
``L³/(3 EI) (1 - 1/(4 N²))`` plus the shear compliance ``L/(a1 + a2)``.
"""

from __future__ import annotations

import math
import pathlib
import sys

import exudyn as exu
import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.plots.mechanism import plot_mechanism
from exudyn_atcm import (Bender, BendingActuator, Layer, Link, Mechanism, MechanismError, PiezoDrive, Segment,
                         eigenfrequencies, simulate, solve_static, static_sweep)
from exudyn_atcm import theory as bt
from exudyn_atcm.casework import load_case
from exudyn_atcm.mbs import solver_settings
from exudyn_atcm.plots.mechanism_shapes import mechanism_shape
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import Triangle

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from test_mechanism_solve import four_bar, rigid_coupler_point  # noqa: E402  (the rigid-cell tests' mechanism)

CASES = pathlib.Path(__file__).resolve().parents[1] / "cases"
CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W = 28e-3


def beam(name="b", drive=None, n_cells=3, length=0.087, **kw):
    return Bender(name, width=W, passive=CFC, active=MFC, length=length, n_cells=n_cells,
                  drive=drive if drive is not None else PiezoDrive(500.0), cell="beam", **kw)


def cantilever(b, force=(0.0, 0.0)):
    m = Mechanism("cantilever").add(b).ground(b.base)
    if force != (0.0, 0.0):
        m.force(b.tip, force)
    return m


# ----------------------------------------------------------------------------- one bender == BendingActuator(cell="beam")

@pytest.mark.parametrize("force", [(0.0, 0.0), (0.01, -0.05), (-0.02, 0.3)])
def test_one_beam_bender_equals_the_beam_actuator_statics_and_eigenfrequencies(force):
    """The same equations (same elements, clamp and end torque EI kappa): equal to round-off."""
    drive = PiezoDrive(800.0)
    act = BendingActuator(4, 0.087 / 4, W, CFC, MFC, drive, cell="beam")
    ref = solve_static(act, tip_force=force)
    m = cantilever(beam(drive=drive, n_cells=4), force)
    r = solve_static(m)
    for name in ("tip_x", "tip_y", "tip_angle", "cell_angle_1", "cell_angle_4"):
        assert r[f"b.{name}"][0] == pytest.approx(ref[f"actuator.{name}"][0], abs=1e-12), name
    # the clamp's three coordinate constraints hold the base node to round-off
    assert abs(r["b.base_x"][0]) < 1e-15 and abs(r["b.base_angle"][0]) < 1e-15
    assert abs(r["b.tip_y"][0]) > 1e-3
    # about the undeformed pose and about the bent equilibrium (with the tip load)
    np.testing.assert_allclose(eigenfrequencies(m, n=3), eigenfrequencies(act, n=3), rtol=1e-10)
    np.testing.assert_allclose(eigenfrequencies(m, n=3, voltage=800.0),
                               eigenfrequencies(act, n=3, voltage=800.0, tip_force=force), rtol=1e-7)


def test_one_beam_bender_equals_the_beam_actuator_dynamics_with_hysteresis():
    """Trajectories with the Preisach loop in the step: the same equations, so the same numbers.
    The bender's length is the actuator's ``3 * 0.029`` (not ``0.087``, one ulp apart: through the
    damping factor and the cell length that ulp moved the tip angle by 1.4e-11 rad)."""
    H1, H2 = paper_strain_preisach(), paper_strain_preisach()
    program = Triangle(500.0, 1000.0, 0.05)
    act = BendingActuator(3, 0.029, W, CFC, MFC, PiezoDrive(program, hysteresis=H1), cell="beam")
    ref = simulate(act, 0.03, step=1e-3, tip_force=(0.0, -0.02))
    b = beam(drive=PiezoDrive(program, hysteresis=H2), length=act.length)
    r = simulate(cantilever(b, (0.0, -0.02)), 0.03, step=1e-3)
    np.testing.assert_array_equal(r["time"], ref["time"])
    for name in ("tip_x", "tip_y", "tip_angle", "cell_angle_2"):
        np.testing.assert_allclose(r[f"b.{name}"], ref[f"actuator.{name}"], rtol=0, atol=1e-15, err_msg=name)
    np.testing.assert_array_equal(r["b.strain"], ref["actuator.strain"])
    np.testing.assert_allclose(r["b.strain"], paper_strain_preisach().apply(r["b.voltage"]), rtol=0, atol=1e-15)
    assert np.ptp(r["b.tip_y"]) > 1e-3  # it moved


def test_static_sweep_of_a_beam_actuator_keeps_its_columns():
    """static_sweep of a BendingActuator(cell="beam") runs as a one-bender mechanism."""
    act = BendingActuator(4, 0.087 / 4, W, CFC, MFC, PiezoDrive(0.0, hysteresis=paper_strain_preisach()), cell="beam")
    volts = [0.0, 750.0, 1500.0, 750.0]
    r = static_sweep(act, volts, tip_force=(0.0, -0.01))
    assert r.names[:10] == ["point", "actuator.voltage", "actuator.strain", "actuator.stroke", "actuator.base_x",
                            "actuator.base_y", "actuator.tip_x", "actuator.tip_y", "actuator.base_angle",
                            "actuator.tip_angle"]
    np.testing.assert_allclose(r["actuator.strain"], paper_strain_preisach().apply(volts), rtol=0, atol=1e-15)
    single = solve_static(act, voltage=1500.0, tip_force=(0.0, -0.01))
    assert r["actuator.tip_y"][2] == pytest.approx(single["actuator.tip_y"][0], rel=1e-9)
    assert r["actuator.tip_y"][3] > r["actuator.tip_y"][1]  # descending branch above the ascending one


# ----------------------------------------------------------------------------- two benders == one

def test_two_beam_benders_welded_end_to_end_equal_one_of_the_summed_length():
    drive = PiezoDrive(1000.0)
    lc = 0.01
    one = cantilever(beam("one", drive=drive, n_cells=7, length=7 * lc), (0.0, -0.03))
    a = beam("a", drive=drive, n_cells=3, length=3 * lc)
    b = beam("b", drive=drive, n_cells=4, length=4 * lc, base=(3 * lc, 0.0))
    two = Mechanism("two").add(a, b).ground(a.base).weld(a.tip, b.base).force(b.tip, (0.0, -0.03))
    r1, r2 = solve_static(one), solve_static(two)
    for axis in ("x", "y"):
        assert r2[f"b.tip_{axis}"][0] == pytest.approx(r1[f"one.tip_{axis}"][0], abs=1e-12)
    assert r2["b.tip_angle"][0] == pytest.approx(r1["one.tip_angle"][0], abs=1e-12)
    assert r2["a.tip_angle"][0] == pytest.approx(r2["b.base_angle"][0], abs=1e-12)
    np.testing.assert_allclose([r2[f"a.cell_angle_{j}"][0] for j in (1, 2, 3)] +
                               [r2[f"b.cell_angle_{j}"][0] for j in (1, 2, 3, 4)],
                               [r1[f"one.cell_angle_{j}"][0] for j in range(1, 8)], rtol=0, atol=1e-12)
    # the weld is two coincident nodes held by constraints instead of one node: the same model in
    # other coordinates; the eigen solution (central differences of 1e-7, then a null-space
    # projection) agrees to 1e-7
    np.testing.assert_allclose(eigenfrequencies(two, n=3), eigenfrequencies(one, n=3), rtol=1e-7)


def test_rigid_and_beam_benders_welded_end_to_end_join_exactly():
    """A rigid-cell bender's tip welded to a beam bender's base: the beam's first node is the
    joint body; no load, so every part takes its free shape: the tip angle is kappa L in total."""
    drive = PiezoDrive(1000.0)
    a = Bender("a", width=W, passive=CFC, active=MFC, length=0.03, n_cells=3, drive=drive, cell="rigid")
    b = beam("b", drive=drive, n_cells=4, length=0.04, base=(0.03, 0.0))
    r = solve_static(Mechanism().add(a, b).ground(a.base).weld(a.tip, b.base))
    kappa = a.laminate.curvature_per_strain * drive.linear_strain(1000.0)
    # static Newton tolerance (relative 1e-10 of the first residual): ~1e-12 rad measured
    assert r["b.tip_angle"][0] == pytest.approx(kappa * 0.07, abs=1e-10)
    assert r["a.tip_angle"][0] == pytest.approx(r["b.base_angle"][0], abs=1e-12)
    assert r["a.tip_x"][0] == pytest.approx(r["b.base_x"][0], abs=1e-14)


# ----------------------------------------------------------------------------- closed four-bar

def test_closed_four_bar_with_a_beam_crank_follows_rigid_loop_closure():
    m = four_bar(PiezoDrive(Triangle(0.0, 1500.0, 0.1)), cell="beam")
    with pytest.warns(RuntimeWarning):  # coarse step for the bender's vibrations; voltage outside the rating
        r = simulate(m, 0.05, step=1e-3)
    assert r.info["accepted_steps"] == 50
    for i in range(0, r.n_rows, 7):
        a_pos = np.array([r["crank.tip_x"][i], r["crank.tip_y"][i]])
        p, b = rigid_coupler_point(a_pos)
        # links and pins are rigid: the closure holds to the Newton tolerance, whatever the cells
        np.testing.assert_allclose([r["coupler.P_x"][i], r["coupler.P_y"][i]], p, rtol=0, atol=1e-6 * 0.05)
        np.testing.assert_allclose([r["rocker.B_x"][i], r["rocker.B_y"][i]], b, rtol=0, atol=1e-6 * 0.05)
    assert np.ptp(r["crank.tip_x"]) > 1e-3
    # 7 nodes of 3 coordinates (the beam's axial and shear motion are coordinates too) + 2 links;
    # clamp 3, three pins 2 each
    dof = m.degrees_of_freedom()
    assert (dof.coordinates, dof.constraints, dof.dof) == (27, 9, 18)


def test_hysteresis_exact_under_step_rejection_with_a_beam_crank():
    H = paper_strain_preisach()
    m = four_bar(PiezoDrive(Triangle(500.0, 1000.0, 0.05), hysteresis=H), cell="beam")
    with pytest.warns(RuntimeWarning):
        r = simulate(m, 0.06, step=2e-3, settings={"timeIntegration.newton.maxIterations": 2,
                                                  "timeIntegration.newton.useModifiedNewton": False})
    assert r.info["rejected_steps"] > 0
    np.testing.assert_allclose(r["crank.strain"], H.apply(r["crank.voltage"]), rtol=0, atol=1e-15)
    assert np.ptp(r["crank.strain"]) > 0.9 * (1.3793e-3 + 1.3793e-4)


@pytest.fixture(scope="module")
def four_bar_case():
    return load_case(CASES / "compliant_four_bar.py")


def test_compliant_four_bar_case_with_beam_cells(four_bar_case):
    """The case's references do not depend on the cells (rigid links and PRBM pivots): they hold to
    the Newton tolerance; beam and rigid cells of 8 give one coupler path to the discretisation
    error, which is second order (measured: the paths' difference falls 4x per doubling)."""
    out = four_bar_case.run({"cell": "beam", "dynamic_period": 0.02, "step": 5e-4, "n_steps": 8})
    s = out.scalars
    assert s["reference_error"] < 1e-6 and s["reference_error_linear"] < 1e-6
    assert s["reference_error_dynamic"] < 1e-6
    assert s["coupler_travel"] > 1e-3
    assert out.parameters["cell"] == "beam"
    gaps = []
    for n in (4, 8):
        paths = [four_bar_case.run({"cell": c, "n_cells": n, "dynamic_period": 0.0, "n_steps": 8}).result
                 for c in ("rigid", "beam")]
        gaps.append(max(np.max(np.abs(paths[0][f"hysteresis.P_{a}"] - paths[1][f"hysteresis.P_{a}"])) for a in "xy"))
    assert 3.0 < gaps[0] / gaps[1] < 5.0  # both second order in the cell length
    assert gaps[1] < 1e-3 * s["coupler_travel"]


# ----------------------------------------------------------------------------- parallel guide

@pytest.fixture(scope="module")
def guide_case():
    return load_case(CASES / "parallel_guide.py")


def test_parallel_guide_with_beam_cells_converges_to_the_s_blade_at_second_order(guide_case):
    """Exact S-blade reference; the beam's nodes lie on the arcs' inscribed polygon (chord L_c):
    ``translation_error_chain_polygon`` holds to the static tolerance, and the error against the
    exact S falls 4x per doubling of the cells (measured 8.6e-4, 2.2e-4, 5.4e-5 for 2, 4, 8)."""
    errors = []
    for n in (2, 4, 8):
        s = guide_case.run({"cell": "beam", "n_cells": n, "n_steps": 8}).scalars
        assert s["translation_error_chain_polygon"] < 1e-9
        assert s["rotation_max"] < 1e-12
        errors.append(s["translation_error"])
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    np.testing.assert_allclose(ratios, 4.0, rtol=0.02)
    # the polygon factor (kappa L_c)²/24 on the axial coordinate, at the largest voltage
    kappa = bt.free_curvature(70e9, 0.2e-3, 30.336e9, 0.3e-3, 10e-3, bt.piezo_strain(500.0))
    lc = 0.03 / 8
    translation = np.hypot(*np.subtract(bt.s_blade_end(kappa, 0.06), (0.06, 0.0)))
    assert errors[-1] == pytest.approx(0.06 * (kappa * lc) ** 2 / 24 / translation, rel=0.05)


# ----------------------------------------------------------------------------- segments

def test_driven_then_passive_segment_is_an_arc_then_a_straight_line():
    """Segment 1 driven (free curvature kappa over L1), segment 2 passive (L2): unloaded, the
    shape is an arc of angle kappa L1 continued by its tangent.  The end node's rotation is exact;
    the nodes of the arc lie on its inscribed polygon (chords L_c = L1/n1), which moves the
    tip by the factor (kappa L_c/2)/sin(kappa L_c/2) on the arc's chord."""
    L1, L2, n1, n2, u = 0.04, 0.03, 8, 3, 1200.0
    drive = PiezoDrive(u)
    b = Bender("s", width=W, passive=CFC, active=MFC, segments=[Segment(L1, n1, drive), Segment(L2, n2, None)],
               cell="beam")
    r = solve_static(Mechanism().add(b).ground(b.base))
    kappa = b.laminate.curvature_per_strain * drive.linear_strain(u)
    phi = kappa * L1
    arc = np.array([math.sin(phi), 1.0 - math.cos(phi)]) / kappa
    straight = L2 * np.array([math.cos(phi), math.sin(phi)])
    tip = np.array([r["s.tip_x"][0], r["s.tip_y"][0]])
    assert r["s.tip_angle"][0] == pytest.approx(phi, abs=1e-10)  # static Newton tolerance (~2e-12 measured)
    half = 0.5 * kappa * L1 / n1
    np.testing.assert_allclose(tip, arc * half / math.sin(half) + straight, rtol=0, atol=1e-11)
    # against the continuous shape: the polygon's error (kappa L_c)²/24 of the arc's chord
    np.testing.assert_allclose(tip, arc + straight, rtol=0, atol=1.1 * np.linalg.norm(arc) * (2 * half) ** 2 / 24)
    assert np.linalg.norm(tip - arc - straight) > 0.5 * np.linalg.norm(arc) * (2 * half) ** 2 / 24
    assert list(r["s.1.voltage"]) == [u] and "s.2.voltage" not in r.names


def test_s_shaped_beam_bender_takes_the_stress_free_polygon():
    d1, d2 = PiezoDrive(800.0), PiezoDrive(-800.0)
    s = Bender("s", width=W, passive=CFC, active=MFC, segments=[Segment(0.03, 3, d1), Segment(0.02, 5, d2)],
               base=(0.01, 0.02), angle=0.3, cell="beam")
    with pytest.warns(RuntimeWarning, match="drive 's.2'.*below the MFC's rated range"):
        r = solve_static(Mechanism().add(s).ground(s.base))
    c = s.laminate.curvature_per_strain
    k1, k2 = c * d1.linear_strain(800.0), c * d2.linear_strain(-800.0)
    # node rotations: kappa L_c per cell; a cell's chord at the mean rotation of its nodes
    rot = np.concatenate([[0.0], np.cumsum([k1 * 0.01] * 3 + [k2 * 0.004] * 5)])
    angles = 0.3 + 0.5 * (rot[:-1] + rot[1:])
    lengths = [0.01] * 3 + [0.004] * 5
    tip = np.array([0.01, 0.02]) + sum(L * np.array([math.cos(a), math.sin(a)]) for L, a in zip(lengths, angles))
    np.testing.assert_allclose([r[f"s.cell_angle_{j + 1}"][0] for j in range(8)], angles, rtol=0, atol=1e-12)
    np.testing.assert_allclose([r["s.tip_x"][0], r["s.tip_y"][0]], tip, rtol=0, atol=1e-13)
    assert r["s.tip_angle"][0] == pytest.approx(0.3 + rot[-1], abs=1e-12)


# ----------------------------------------------------------------------------- loads and joints at beam ends

@pytest.mark.parametrize("n", [2, 4])
def test_tip_force_compliance_is_euler_bernoulli_with_the_trapezoidal_rule(n):
    """Unpowered, tip force F: w = F L³/(3 EI) (1 - 1/(4 N²)) + F L/(a1 + a2) (shear), to the
    linearisation error (F L²/EI ~ 1e-4 rad here: relative 1e-8)."""
    f, L = 1e-4, 0.04
    b = Bender("b", width=10e-3, passive=CFC, active=MFC, length=L, n_cells=n, drive=PiezoDrive(0.0), cell="beam")
    r = solve_static(cantilever(b, (0.0, f)))
    ei = bt.composite_bending_stiffness(70e9, 0.2e-3, 30.336e9, 0.3e-3, 10e-3)
    ea = 10e-3 * (70e9 * 0.2e-3 + 30.336e9 * 0.3e-3)
    expected = f * L**3 / (3 * ei) * (1 - 1 / (4 * n * n)) + f * L / ea
    assert r["b.tip_y"][0] == pytest.approx(expected, rel=1e-6)


def test_slider_spring_at_a_guided_beam_tip_acts_in_parallel_with_the_beam():
    """Tip on a vertical slider (no rotation, x held) with a spring k to the ground: a clamped-guided
    beam and the spring in parallel.  Tip force F: w = F/(k + 1/C) with the guided beam's
    compliance C = L³/(12 EI) (1 - 1/N²) + L/(a1 + a2) (node rotations exact for the linear
    moment, deflection the trapezoidal rule over them; shear).  The slider holds x, so the arc's
    shortening stretches the stiff axis, a tension that stiffens the beam by ~ (a1 + a2) w²/EI:
    2.7e-4 at F = 20 mN (measured), 2e-7 at the 0.5 mN used here.  Driven (1000 V), the guided
    beam stays straight: a uniform free curvature is held by a constant guide moment EI kappa."""
    k, f, L, n = 20.0, 5e-4, 0.03, 4
    b = Bender("b", width=10e-3, passive=CFC, active=MFC, length=L, n_cells=n, drive=PiezoDrive(1000.0), cell="beam")
    m = Mechanism().add(b).ground(b.base).ground(b.tip, joint="slider", axis=(0.0, 1.0), stiffness=k)
    r = solve_static(m.force(b.tip, (0.0, f)))
    ei = bt.composite_bending_stiffness(70e9, 0.2e-3, 30.336e9, 0.3e-3, 10e-3)
    ea = 10e-3 * (70e9 * 0.2e-3 + 30.336e9 * 0.3e-3)
    c = L**3 / (12 * ei) * (1 - 1 / n**2) + L / ea
    assert r["b.tip_y"][0] == pytest.approx(f / (k + 1 / c), rel=1e-6)
    assert abs(r["b.tip_y"][0] - f * c) > 1e-3 * f * c  # the spring carries a measurable share
    assert r["b.tip_angle"][0] == pytest.approx(0.0, abs=1e-12)
    assert r["b.tip_x"][0] == pytest.approx(L, abs=1e-12)


def test_pinned_base_with_a_torsion_spring_adds_the_rigid_rotation():
    f, k_p = 1e-4, 0.05
    clamped = solve_static(cantilever(beam(drive=PiezoDrive(0.0)), (0.0, f)))
    b = beam(drive=PiezoDrive(0.0))
    pinned = solve_static(Mechanism().add(b).ground(b.base, joint="pin", stiffness=k_p).force(b.tip, (0.0, f)))
    extra = f * 0.087 / k_p  # rotation at the base [rad], ~1.7e-4: second-order terms ~3e-8 relative
    assert pinned["b.base_angle"][0] == pytest.approx(extra, rel=1e-4)
    assert pinned["b.tip_y"][0] == pytest.approx(clamped["b.tip_y"][0] + extra * 0.087, rel=1e-4)


def test_follower_force_at_a_beam_tip_turns_with_the_tip_node():
    """A follower force turns with the tip node: its equilibrium is the equilibrium under the dead
    force turned by the tip's final rotation (the same equations; Newton tolerance)."""
    f = np.array([0.0, 0.5])
    b = beam(drive=PiezoDrive(0.0), n_cells=8)
    follow = solve_static(Mechanism().add(b).ground(b.base).force(b.tip, tuple(f), follower=True))
    theta = follow["b.tip_angle"][0]
    turned = np.array([math.cos(theta) * f[0] - math.sin(theta) * f[1], math.sin(theta) * f[0] + math.cos(theta) * f[1]])
    dead = solve_static(cantilever(beam(drive=PiezoDrive(0.0), n_cells=8), tuple(turned)))
    assert theta > 0.1  # a large rotation: the follower really turned
    assert dead["b.tip_angle"][0] == pytest.approx(theta, abs=1e-9)
    assert dead["b.tip_y"][0] == pytest.approx(follow["b.tip_y"][0], abs=1e-11)
    plain = solve_static(cantilever(beam(drive=PiezoDrive(0.0), n_cells=8), tuple(f)))
    assert plain["b.tip_angle"][0] < theta - 5e-4  # a dead force of the reference direction bends less (1e-3)


def test_stop_and_spring_at_a_beam_tip():
    """Tip pushed by its drive against a linear spring to the ground (a grasped object): for small
    deflections the force is the blocked-force law k w0/(1 + k C) with the free deflection w0 =
    kappa L²/2 of the beam and the compliance C of the tip (closed form above)."""
    L, n, k = 0.04, 8, 50.0
    b = Bender("b", width=10e-3, passive=CFC, active=MFC, length=L, n_cells=n, drive=PiezoDrive(200.0), cell="beam")
    anchor = Link("anchor", {"Q": (L, 0.01)}, mass=1e-3, inertia=1e-8)
    m = Mechanism().add(b, anchor).ground(b.base).ground("anchor.Q").spring(b.tip, "anchor.Q", k, name="object")
    r = solve_static(m)
    ei = b.laminate.bending_stiffness
    kappa = b.laminate.curvature_per_strain * b.segments[0].drive.linear_strain(200.0)
    w0 = kappa * L**2 / 2  # the beam's nodes' polygon moves the tip by (kappa L_c)²/24: 1e-6 relative here
    c = L**3 / (3 * ei) * (1 - 1 / (4 * n * n)) + L / b.laminate.axial_rigidity
    expected = -k * w0 / (1 + k * c)  # the tip rises towards the anchor: compression
    # geometric nonlinearity: kappa L ~ 0.02 rad, the force's x component and the arc shortening
    # enter at (kappa L)² ~ 4e-4
    assert r["object.force"][0] == pytest.approx(expected, rel=1e-3)
    # a stop instead: a wall at 0.2 w0 above the tip, stiff: the tip stops there
    b2 = Bender("b", width=10e-3, passive=CFC, active=MFC, length=L, n_cells=n, drive=PiezoDrive(200.0), cell="beam")
    wall = Mechanism().add(b2).ground(b2.base).stop(b2.tip, position=(L, 0.2 * w0), normal=(0.0, -1.0),
                                                    stiffness=1e6, name="wall")
    r2 = solve_static(wall)
    assert r2["b.tip_y"][0] == pytest.approx(0.2 * w0, rel=2e-3)
    force = (w0 - r2["b.tip_y"][0]) / c  # the wall's force bends the tip back by its compliance
    assert r2["wall.force"][0] == pytest.approx(force, rel=1e-3)


# ----------------------------------------------------------------------------- inside a user's system

def test_add_to_with_a_beam_bender_equals_the_package_simulate():
    program = Triangle(750.0, 750.0, 0.1)

    def mech():
        b = Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=6,
                   drive=PiezoDrive(program), cell="beam")
        lever = Link("lever", {"A": (0.03, 0.0), "E": (0.05, 0.0)}, mass=2e-4, inertia=1e-8)
        return Mechanism("m").add(b, lever).ground(b.base).weld(b.tip, lever.point("A"))

    with pytest.warns(RuntimeWarning, match="first bending mode"):  # quasi-static answer: enough here
        ref = simulate(mech(), 0.05, step=1e-3)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    h = atcm.add_to(mbs, mech())
    mbs.Assemble()
    settings = solver_settings.dynamic_settings(0.05, 1e-3)
    settings.solution.sensors.writePeriod = 1e-3
    # the beam's stiff axis: the same Newton tolerance floor as the package's runs
    assert h.newton_tolerance_floor == h.model.newton_tolerance_floor > 0.0
    settings.timeIntegration.newton.absoluteTolerance = max(settings.timeIntegration.newton.absoluteTolerance,
                                                            h.newton_tolerance_floor)
    mbs.SolveDynamic(settings)
    r = h.result()
    assert r.names == ref.names
    for name in ref.names:
        np.testing.assert_allclose(r[name], ref[name], rtol=0, atol=1e-12, err_msg=name)
    assert np.ptp(ref["lever.E_y"]) > 1e-3


def test_add_to_a_lone_beam_bender_gives_node_markers_for_user_joints():
    """A lone bender's free tip is its end node: a user's pin there and a spring to the ground."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    b = Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4, drive=PiezoDrive(0.0), cell="beam")
    h = atcm.add_to(mbs, b)
    ground = mbs.AddObject(exu.itemInterface.ObjectGround())
    mg = mbs.AddMarker(exu.itemInterface.MarkerBodyPosition(bodyNumber=ground, localPosition=[0.03, 0.0, 0.0]))
    mbs.AddObject(exu.itemInterface.ObjectJointRevolute2D(markerNumbers=[mg, h.position_marker(b.tip)]))
    assert mbs.GetMarker(h.marker(b.tip))["markerType"] == "NodeRigid"
    assert mbs.GetMarker(h.position_marker("b.tip"))["markerType"] == "NodePosition"
    # the body carrying the tip: the last beam element, whose second node sits at (0.03, 0)
    element = mbs.GetObject(h.body(b.tip))
    assert element["objectType"] == "BeamGeometricallyExact2D" and element["Vshow"]
    assert mbs.GetNode(element["nodeNumbers"][1])["referenceCoordinates"][0] == pytest.approx(0.03)
    assert "b.tip" in h.sensors and "b.base" not in h.sensors  # the clamped base is on the ground: no sensor
    mbs.Assemble()
    info = mbs.ComputeSystemDegreeOfFreedom(verbose=False)
    assert info["degreeOfFreedom"] == 3 * 5 - 3 - 2  # 5 nodes; clamp 3, pin 2
    # clamp_base=False: the base node is free (no interface body, no clamp)
    SC2 = exu.SystemContainer()
    mbs2 = SC2.AddSystem()
    atcm.add_to(mbs2, b, clamp_base=False)
    mbs2.Assemble()
    assert mbs2.ComputeSystemDegreeOfFreedom(verbose=False)["degreeOfFreedom"] == 3 * 5


# ----------------------------------------------------------------------------- drawing

def test_shape_of_a_beam_bender_runs_through_its_nodes(tmp_path):
    """The drawn polyline is built from the cell angles (mean node rotations) and L_c: it ends at
    the recorded tip node to the beam's axial strain (F/(a1 + a2) ~ 1e-7 here), and is drawn."""
    b = beam(drive=PiezoDrive(1200.0), n_cells=6)
    m = cantilever(b, (0.0, -0.02))
    r = solve_static(m)
    shape = mechanism_shape(m, r, 0)
    (bs,) = shape.benders
    assert bs.passive.shape == (7, 2) and bs.active.shape == (6, 2, 2)
    # chords differ from L_c by the shear strain F/(a1 + a2) ~ 9e-8: 8e-9 m at the tip
    gap = 0.02 * 0.087 / b.laminate.axial_rigidity
    np.testing.assert_allclose(bs.passive[-1], [r["b.tip_x"][0], r["b.tip_y"][0]], rtol=0, atol=1.5 * gap)
    path = tmp_path / "beam.png"
    plot_mechanism(m, r, path=path)
    assert path.stat().st_size > 1000


# ----------------------------------------------------------------------------- refused input

def test_an_ancf_bender_joined_at_its_tip_is_refused_by_the_cell():
    b = beam().__class__("x", width=W, passive=CFC, active=MFC, length=0.03, n_cells=2, cell="ancf",
                         drive=PiezoDrive(300.0))
    lever = Link("lever", {"A": (0.03, 0.0), "E": (0.05, 0.0)}, mass=2e-4, inertia=1e-8)
    with pytest.raises(MechanismError, match=r"bender 'x': the ancf cell joins a mechanism as a cantilever only "
                                             r".*got its tip joined to other parts; use cell='beam'"):
        solve_static(Mechanism("m").add(b, lever).ground(b.base).pin(b.tip, lever.point("A")))


@pytest.mark.parametrize("cell", ["ancf", "ritz"])
def test_static_sweep_of_any_actuator_cell_equals_solve_static_per_voltage(cell):
    # every cell joins the one builder, so static_sweep takes them all; without hysteresis each sweep
    # point (continued from the previous one) is the equilibrium solve_static finds from the reference pose
    act = BendingActuator(4, 0.087 / 4, W, CFC, MFC, PiezoDrive(0.0), cell=cell)
    volts = [0.0, 500.0, 1500.0, 200.0]
    r = static_sweep(act, volts)
    for i, v in enumerate(volts):
        s = solve_static(act, voltage=v)
        # positions to 1e-10 of the length, the angle to the same 1e-10 (a rotation error e moves the tip by
        # e * length: the position tolerance over the length; it was 1e-10 * 0.087 rad, which the continuation
        # sweep misses for ancf cells by 1.7e-11 rad, a tip displacement of 1.5e-12 m)
        for name, tol in (("actuator.tip_x", 1e-10 * 0.087), ("actuator.tip_y", 1e-10 * 0.087), ("actuator.tip_angle", 1e-10)):
            assert r[name][i] == pytest.approx(s[name][0], abs=tol), (name, v)
    assert r["actuator.tip_y"][2] > 0.01  # it bent


def test_bad_case_cell_is_refused(guide_case):
    with pytest.raises(ValueError, match="cell must be one of rigid, six-bar, beam, rod, got 'beams'"):
        guide_case.run({"cell": "beams"})


def test_a_passive_beam_strip_is_a_flexure():
    """active=None with cell="beam": a passive strip under a tip force, Euler-Bernoulli (+ trapezoid)."""
    f, L, n = 1e-5, 0.02, 4
    strip = Bender("strip", width=10e-3, passive=CFC, length=L, n_cells=n, cell="beam")
    r = solve_static(cantilever(strip, (0.0, f)))
    ei = 70e9 * 10e-3 * 0.2e-3**3 / 12
    expected = f * L**3 / (3 * ei) * (1 - 1 / (4 * n * n)) + f * L / (70e9 * 10e-3 * 0.2e-3)
    assert r["strip.tip_y"][0] == pytest.approx(expected, rel=1e-5)
    with pytest.raises(MechanismError, match="six-bar"):
        solve_static(cantilever(Bender("s6", width=10e-3, passive=CFC, length=L, n_cells=n, cell="six-bar")))
