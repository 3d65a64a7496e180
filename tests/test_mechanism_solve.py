"""Issue 7, parts 2 and 5: solving mechanisms, each against an independent reference.

References: today's BendingActuator path (the old builder, kept), rigid-body kinematics
(rotation invariance, a welded rigid extension, the rigid four-bar's circle intersection),
mirror symmetry, and the hysteresis operator applied offline to the recorded voltages.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

from exudyn_atcm import (Bender, BendingActuator, Layer, Link, Mechanism, PiezoDrive, Segment, eigenfrequencies, simulate,
                         solve_static, static_sweep)
from exudyn_atcm import Result as atcm_result
from exudyn_atcm import read_csv as atcm_read_csv
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import Triangle

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W = 28e-3


def bender(name="b", drive=None, n_cells=3, length=0.087, **kw):
    return Bender(name, width=W, passive=CFC, active=MFC, length=length, n_cells=n_cells,
                  drive=drive if drive is not None else PiezoDrive(500.0), **{"cell": "rigid", **kw})


def cantilever(b, force=(0.0, 0.0)):
    m = Mechanism("cantilever").add(b).ground(b.base)
    if force != (0.0, 0.0):
        m.force(b.tip, force)
    return m


def rot(angle, v):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


# ----------------------------------------------------------------------------- one bender == BendingActuator

@pytest.mark.parametrize("cell", ["rigid", "six-bar"])
@pytest.mark.parametrize("force", [(0.0, 0.0), (0.01, -0.05), (-0.02, 0.3)])
def test_one_bender_mechanism_equals_bending_actuator_statics(force, cell):
    drive = PiezoDrive(800.0)
    act = BendingActuator(4, 0.087 / 4, W, CFC, MFC, drive, cell=cell)
    ref = solve_static(act, tip_force=force)
    r = solve_static(cantilever(bender(drive=drive, n_cells=4, cell=cell), force))
    for name in ("tip_x", "tip_y", "tip_angle", "strain", "cell_angle_4"):
        assert r[f"b.{name}"][0] == pytest.approx(ref[f"actuator.{name}"][0], abs=1e-9 * 0.087), name
    assert r["b.base_x"][0] == 0.0 and r["b.base_angle"][0] == 0.0


@pytest.mark.parametrize("cell", ["rigid", "six-bar"])
def test_one_bender_mechanism_equals_bending_actuator_dynamics_with_hysteresis(cell):
    H1, H2 = paper_strain_preisach(), paper_strain_preisach()
    program = Triangle(500.0, 1000.0, 0.05)
    act = BendingActuator(3, 0.029, W, CFC, MFC, PiezoDrive(program, hysteresis=H1), cell=cell)
    ref = simulate(act, 0.03, step=1e-3, tip_force=(0.0, -0.02))
    r = simulate(cantilever(bender(drive=PiezoDrive(program, hysteresis=H2), cell=cell), (0.0, -0.02)), 0.03,
                 step=1e-3)
    np.testing.assert_array_equal(r["time"], ref["time"])
    for name in ("tip_x", "tip_y", "tip_angle", "strain", "voltage"):
        np.testing.assert_allclose(r[f"b.{name}"], ref[f"actuator.{name}"], rtol=0, atol=1e-9 * 0.087, err_msg=name)
    assert np.ptp(r["b.tip_y"]) > 1e-3  # it moved


def test_rotated_and_shifted_bender_is_the_rigidly_moved_solution():
    """Rigid-motion invariance: base at (x0, y0), angle a; the force turned with it."""
    a, x0 = 0.7, np.array([0.01, -0.02])
    f = np.array([0.01, -0.05])
    ref = solve_static(cantilever(bender(), tuple(f)))
    r = solve_static(cantilever(bender(base=tuple(x0), angle=a), tuple(rot(a, f))))
    tip = x0 + rot(a, [ref["b.tip_x"][0], ref["b.tip_y"][0]])
    assert r["b.tip_x"][0] == pytest.approx(tip[0], abs=1e-9 * 0.087)
    assert r["b.tip_y"][0] == pytest.approx(tip[1], abs=1e-9 * 0.087)
    assert r["b.tip_angle"][0] == pytest.approx(a + ref["b.tip_angle"][0], abs=1e-9)


def test_left_active_side_mirrors_the_bender():
    right = solve_static(cantilever(bender(), (0.0, 0.01)))
    left = solve_static(cantilever(bender(active_side="left"), (0.0, -0.01)))
    assert left["b.tip_x"][0] == pytest.approx(right["b.tip_x"][0], abs=1e-12)
    assert left["b.tip_y"][0] == pytest.approx(-right["b.tip_y"][0], abs=1e-9 * 0.087)
    assert left["b.tip_angle"][0] == pytest.approx(-right["b.tip_angle"][0], abs=1e-9)
    assert abs(right["b.tip_y"][0]) > 1e-3


# ----------------------------------------------------------------------------- two benders == one

@pytest.mark.parametrize("cell", ["rigid", "six-bar"])
def test_two_benders_welded_end_to_end_equal_one_of_the_summed_length(cell):
    drive = PiezoDrive(1000.0)
    lc = 0.01
    one = cantilever(bender("one", drive=drive, n_cells=7, length=7 * lc, cell=cell), (0.0, -0.03))
    a = bender("a", drive=drive, n_cells=3, length=3 * lc, cell=cell)
    b = bender("b", drive=drive, n_cells=4, length=4 * lc, base=(3 * lc, 0.0), cell=cell)
    two = Mechanism("two").add(a, b).ground(a.base).weld(a.tip, b.base).force(b.tip, (0.0, -0.03))
    r1, r2 = solve_static(one), solve_static(two)
    for axis in ("x", "y"):
        assert r2[f"b.tip_{axis}"][0] == pytest.approx(r1[f"one.tip_{axis}"][0], abs=1e-9 * 0.07)
    assert r2["b.tip_angle"][0] == pytest.approx(r1["one.tip_angle"][0], abs=1e-9)
    # the joint between them is the inner joint of the long bender: a's tip = the long bender's 3rd joint
    assert r2["a.tip_angle"][0] == pytest.approx(r2["b.base_angle"][0], abs=1e-12)
    np.testing.assert_allclose([r2[f"a.cell_angle_{j}"][0] for j in (1, 2, 3)] +
                               [r2[f"b.cell_angle_{j}"][0] for j in (1, 2, 3, 4)],
                               [r1[f"one.cell_angle_{j}"][0] for j in range(1, 8)], rtol=0, atol=1e-9)
    f1 = eigenfrequencies(one, n=3)
    f2 = eigenfrequencies(two, n=3)
    # the same model in other coordinates (six-bar: the welded interface body's node sits elsewhere);
    # the dense eigen solution agrees to 1e-8
    np.testing.assert_allclose(f2, f1, rtol=1e-9 if cell == "rigid" else 1e-7)


# ----------------------------------------------------------------------------- link welded to a tip

def test_link_welded_to_bender_tip_is_carried_rigidly():
    a = 0.02
    b = bender(drive=PiezoDrive(1200.0))
    lever = Link("lever", {"A": (0.087, 0.0), "E": (0.087 + a, 0.0)}, mass=2e-4, inertia=1e-8)
    m = Mechanism().add(b, lever).ground(b.base).weld(b.tip, lever.point("A")).force("lever.E", (0.0, -0.01))
    r = solve_static(m)
    theta = r["b.tip_angle"][0]
    assert r["lever.E_x"][0] == pytest.approx(r["b.tip_x"][0] + a * math.cos(theta), abs=1e-9 * 0.1)
    assert r["lever.E_y"][0] == pytest.approx(r["b.tip_y"][0] + a * math.sin(theta), abs=1e-9 * 0.1)
    assert r["lever.angle"][0] == pytest.approx(theta, abs=1e-12)
    assert abs(theta) > 0.02


# ----------------------------------------------------------------------------- closed four-bar

def four_bar(drive, n_cells=6, cell="rigid"):
    crank = Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=n_cells, drive=drive,
                   angle=math.pi / 2, cell=cell)
    coupler = Link("coupler", {"A": (0.0, 0.03), "B": (0.04, 0.03), "P": (0.02, 0.05)}, mass=1e-4, inertia=1e-8)
    rocker = Link("rocker", {"B": (0.04, 0.03), "O": (0.04, 0.0)}, mass=1e-4, inertia=1e-8)
    m = Mechanism("four_bar").add(crank, coupler, rocker)
    m.ground(crank.base).pin(crank.tip, coupler.point("A")).pin("coupler.B", "rocker.B")
    return m.ground("rocker.O", joint="pin")


def rigid_coupler_point(a_pos):
    """Rigid four-bar closure: B on circles about A (|AB| = 0.04) and O = (0.04, 0) (|OB| = 0.03), the
    branch of the reference pose; P from the rigid coupler triangle."""
    o = np.array([0.04, 0.0])
    d = np.linalg.norm(o - a_pos)
    r0, r1 = 0.04, 0.03
    x = (d**2 + r0**2 - r1**2) / (2 * d)
    h = math.sqrt(r0**2 - x**2)
    u = (o - a_pos) / d
    n = np.array([-u[1], u[0]])
    b = a_pos + x * u + h * n  # left of A->O: the upper branch (reference B = (0.04, 0.03))
    e = (b - a_pos) / r0
    # P = A + 0.02 e + 0.02 e_perp (reference: A = (0, .03), B = (.04, .03), P = (.02, .05))
    return a_pos + 0.02 * e + 0.02 * np.array([-e[1], e[0]]), b


# incidental warnings: the loop closure is kinematics (any step, any voltage), so the run keeps a coarse
# step for the crank's 302 Hz mode and a -1500 ... 1500 V triangle (beyond the MFC's -500 V) for a large turn
@pytest.mark.filterwarnings("ignore:step = .* resolves the first bending mode:exudyn_atcm.errors.AccuracyWarning")
@pytest.mark.filterwarnings("ignore:drive 'crank'. the voltage program spans -1500:exudyn_atcm.errors.InputRangeWarning")
@pytest.mark.parametrize("cell", ["rigid", "six-bar", "rod"])
def test_closed_four_bar_coupler_point_follows_rigid_loop_closure(cell):
    m = four_bar(PiezoDrive(Triangle(0.0, 1500.0, 0.1)), cell=cell)
    r = simulate(m, 0.05, step=1e-3)
    assert r.info["accepted_steps"] == 50
    for i in range(0, r.n_rows, 7):
        a_pos = np.array([r["crank.tip_x"][i], r["crank.tip_y"][i]])
        p, b = rigid_coupler_point(a_pos)
        np.testing.assert_allclose([r["coupler.P_x"][i], r["coupler.P_y"][i]], p, rtol=0, atol=1e-6 * 0.05)
        np.testing.assert_allclose([r["rocker.B_x"][i], r["rocker.B_y"][i]], b, rtol=0, atol=1e-6 * 0.05)
    # the crank really turned the loop (the tip moved by millimetres)
    assert np.ptp(r["crank.tip_x"]) > 1e-3


# incidental warnings: the step is coarse on purpose (Newton must reject steps) and the check is exact
# (strain = operator applied offline) whatever the step resolves
@pytest.mark.filterwarnings("ignore:step = .* resolves the first bending mode:exudyn_atcm.errors.AccuracyWarning")
@pytest.mark.filterwarnings("ignore:step = .* resolves the shortest feature:exudyn_atcm.errors.AccuracyWarning")
@pytest.mark.parametrize("cell, iterations", [("rigid", 2), ("six-bar", 3), ("rod", 2)])
def test_hysteresis_exact_under_step_rejection_in_a_closed_loop(cell, iterations):
    H = paper_strain_preisach()
    m = four_bar(PiezoDrive(Triangle(500.0, 1000.0, 0.05), hysteresis=H), cell=cell)
    # so few Newton iterations that Exudyn rejects steps and repeats them with smaller ones
    r = simulate(m, 0.06, step=2e-3, settings={"timeIntegration.newton.maxIterations": iterations,
                                              "timeIntegration.newton.useModifiedNewton": False})
    assert r.info["rejected_steps"] > 0
    assert np.diff(r["time"]).min() < 2e-3 * 0.75
    np.testing.assert_allclose(r["crank.strain"], H.apply(r["crank.voltage"]), rtol=0, atol=1e-15)
    assert np.ptp(r["crank.strain"]) > 0.9 * (1.3793e-3 + 1.3793e-4)


def test_static_sweep_follows_the_hysteresis_and_matches_single_solves():
    H = paper_strain_preisach()
    b = bender(drive=PiezoDrive(0.0, hysteresis=H))
    volts = [0.0, 500.0, 1000.0, 1500.0, 1000.0, 500.0, 0.0]
    r = static_sweep(cantilever(b), volts)
    np.testing.assert_allclose(r["b.strain"], paper_strain_preisach().apply(volts), rtol=0, atol=1e-15)
    # on the first ascending branch each point equals a solve from the reset state
    for i in (1, 3):
        single = solve_static(cantilever(bender(drive=PiezoDrive(volts[i], hysteresis=paper_strain_preisach()))))
        assert r["b.tip_y"][i] == pytest.approx(single["b.tip_y"][0], rel=1e-7)
    # descending branch: more strain than ascending at the same voltage (the loop opens)
    assert r["b.tip_y"][4] > r["b.tip_y"][2] and r["b.tip_y"][5] > r["b.tip_y"][1]


def test_mechanism_refuses_tip_force_and_unknown_drive():
    m = cantilever(bender())
    with pytest.raises(ValueError, match="tip_force is for a BendingActuator"):
        solve_static(m, tip_force=(0.0, 1.0))
    with pytest.raises(ValueError, match="unknown drive 'c'"):
        solve_static(m, voltage={"c": 1.0})


def test_a_bad_voltage_is_refused_before_the_system_is_built(monkeypatch):
    from exudyn_atcm.mbs import builder

    def no_build(*args, **kwargs):
        raise AssertionError("built before the voltage was checked")

    monkeypatch.setattr(builder, "build", no_build)
    m = cantilever(bender())
    with pytest.raises(ValueError, match="unknown drive 'c'"):
        solve_static(m, voltage={"c": 1.0})
    with pytest.raises(ValueError, match="voltage"):
        solve_static(m, voltage=float("nan"))


# ----------------------------------------------------------------------------- segments, pinned ends

# incidental warning: -800 V (beyond the MFC's -500 V) makes the opposite curvature large; the polygon is exact
@pytest.mark.filterwarnings("ignore:drive 's.2'. the voltage program spans -800:exudyn_atcm.errors.InputRangeWarning")
def test_s_shaped_two_segment_bender_takes_the_stress_free_polygon():
    """No load: every joint takes its rest angle, so the chain is the polygon of the free rotations.

    Segment 1: 3 cells of 10 mm at +U, segment 2: 5 cells of 4 mm at -U (opposite curvature).  The
    clamp turns the first cell by half its free rotation, each inner joint by the two half cells it
    stands for, the tip interface by half the last cell's.
    """
    d1, d2 = PiezoDrive(800.0), PiezoDrive(-800.0)
    s = Bender("s", width=W, passive=CFC, active=MFC, segments=[Segment(0.03, 3, d1), Segment(0.02, 5, d2)],
               base=(0.01, 0.02), angle=0.3, cell="rigid")
    r = solve_static(Mechanism().add(s).ground(s.base))
    c = s.laminate.curvature_per_strain
    half = [0.5 * c * 0.01 * d1.linear_strain(800.0)] * 3 + [0.5 * c * 0.004 * d2.linear_strain(-800.0)] * 5
    lengths = [0.01] * 3 + [0.004] * 5
    phi, angles = 0.3 + half[0], []
    for j in range(8):
        angles.append(phi)
        if j < 7:
            phi += half[j] + half[j + 1]
    tip = np.array([0.01, 0.02]) + sum(L * np.array([math.cos(a), math.sin(a)]) for L, a in zip(lengths, angles))
    np.testing.assert_allclose([r[f"s.cell_angle_{j + 1}"][0] for j in range(8)], angles, rtol=0, atol=1e-12)
    assert r["s.tip_x"][0] == pytest.approx(tip[0], abs=1e-13)
    assert r["s.tip_y"][0] == pytest.approx(tip[1], abs=1e-13)
    assert r["s.tip_angle"][0] == pytest.approx(angles[-1] + half[-1], abs=1e-12)
    assert list(r["s.1.voltage"]) == [800.0] and list(r["s.2.voltage"]) == [-800.0]


def test_pinned_base_with_a_torsion_spring_adds_the_rigid_rotation():
    """Linear range: the pin spring k_p in series with the clamp turns the whole bender by F L / k_p."""
    f, k_p = 1e-4, 0.05
    clamped = solve_static(cantilever(bender(drive=PiezoDrive(0.0)), (0.0, f)))
    b = bender(drive=PiezoDrive(0.0))
    pinned = solve_static(Mechanism().add(b).ground(b.base, joint="pin", stiffness=k_p).force(b.tip, (0.0, f)))
    extra = f * 0.087 / k_p  # rotation at the base [rad], ~1.7e-4: second-order terms ~3e-8 relative
    assert pinned["b.base_angle"][0] == pytest.approx(extra, rel=1e-4)
    assert pinned["b.tip_y"][0] == pytest.approx(clamped["b.tip_y"][0] + extra * 0.087, rel=1e-4)


def test_stiff_pin_tends_to_the_weld():
    lever = Link("lever", {"A": (0.087, 0.0), "E": (0.107, 0.0)}, mass=2e-4, inertia=1e-8)

    def solve(how, **kw):
        b = bender(drive=PiezoDrive(1200.0))
        m = Mechanism().add(b, lever).ground(b.base).force("lever.E", (0.0, -0.01))
        getattr(m, how)(b.tip, "lever.A", **kw)
        return solve_static(m)

    welded = solve("weld")
    k_end = 2 * bender().laminate.bending_stiffness / 0.029
    pinned = solve("pin", stiffness=1e4 * k_end)
    # series springs k_end, k_p: the end joint is softer by k_end/k_p = 1e-4
    assert pinned["lever.E_y"][0] == pytest.approx(welded["lever.E_y"][0], rel=1e-4)
    assert pinned["b.tip_angle"][0] == pytest.approx(welded["b.tip_angle"][0], rel=1e-4)
    assert pinned["b.tip_angle"][0] != welded["b.tip_angle"][0]
    # a softer pin lets the lever turn against the bender's tip: rotation jump M/k_p at the joint
    soft = solve("pin", stiffness=0.01)
    moment = 0.01 * 0.02 * math.cos(soft["lever.angle"][0])  # force 0.01 N at 20 mm from the pin
    jump = soft["lever.angle"][0] - soft["b.tip_angle"][0]
    # Newton stops at 1e-8 N m of residual: 1e-6 rad on this 0.01 N m/rad pin
    assert jump == pytest.approx(-moment / 0.01, abs=2e-6)


@pytest.mark.parametrize("cell", ["rigid", "six-bar"])
def test_static_sweep_of_a_bending_actuator_keeps_its_columns(cell):
    """The actuator as a one-bender mechanism; ascending points equal solve_static from the reset state."""
    act = BendingActuator(4, 0.087 / 4, W, CFC, MFC, PiezoDrive(0.0, hysteresis=paper_strain_preisach()), cell=cell)
    volts = [0.0, 750.0, 1500.0, 750.0]
    r = static_sweep(act, volts, tip_force=(0.0, -0.01))
    assert r.names[:10] == ["point", "actuator.voltage", "actuator.strain", "actuator.stroke", "actuator.base_x",
                            "actuator.base_y", "actuator.tip_x", "actuator.tip_y", "actuator.base_angle",
                            "actuator.tip_angle"]
    assert r.unit("point") == "-" and r["point"].tolist() == [0.0, 1.0, 2.0, 3.0]
    np.testing.assert_allclose(r["actuator.strain"], paper_strain_preisach().apply(volts), rtol=0, atol=1e-15)
    single = solve_static(act, voltage=1500.0, tip_force=(0.0, -0.01))
    assert r["actuator.tip_y"][2] == pytest.approx(single["actuator.tip_y"][0], rel=1e-7)
    np.testing.assert_allclose(r["actuator.stroke"], r["actuator.strain"] * 0.087 / 4, rtol=1e-15)
    assert r["actuator.tip_y"][3] > r["actuator.tip_y"][1]  # descending branch above the ascending one


def test_result_plot_draws_a_mechanism_result_from_its_columns(tmp_path, monkeypatch):
    # issue 30: Result.plot() works for every result (it refused a mechanism's before); the drawn lines are
    # the result's own columns in the plots' units (mm), found by their component-named suffixes
    from exudyn_atcm.plots import mechanism_series

    figures = []
    save = mechanism_series.save_figure
    monkeypatch.setattr(mechanism_series, "save_figure", lambda fig, path: figures.append(fig) or save(fig, path))
    r = static_sweep(cantilever(bender()), [0.0, 500.0, 1500.0])
    written = r.plot(tmp_path, prefix="b_")
    assert [os.path.basename(p) for p in written] == ["b_time_series.png", "b_tip_vs_voltage.png",
                                                      "b_point_paths.png"]
    assert all(open(p, "rb").read(8) == b"\x89PNG\r\n\x1a\n" for p in written)
    volts, tips = figures[0].axes
    np.testing.assert_array_equal(volts.lines[0].get_ydata(), r["b.voltage"])
    np.testing.assert_array_equal(tips.lines[0].get_xdata(), r["point"])
    np.testing.assert_allclose(tips.lines[0].get_ydata(), r["b.tip_y"] * 1e3, rtol=1e-15)
    (loop,) = figures[1].axes[0].lines
    np.testing.assert_array_equal(loop.get_xdata(), [0.0, 500.0, 1500.0])
    paths = {line.get_label(): line for line in figures[2].axes[0].lines}
    assert set(paths) == {"b.base", "b.tip"}
    np.testing.assert_allclose(paths["b.tip"].get_xdata(), r["b.tip_x"] * 1e3, rtol=1e-15)
    with pytest.raises(ValueError, match="a lone actuator's .* or a mechanism's"):
        atcm_result({"time": [0.0], "q": [1.0]}, {"time": "s", "q": "m"}).plot(tmp_path)


# incidental warning: a 5-step run at 1 ms (coarse for the crank's 302 Hz mode) is enough for a file round trip
@pytest.mark.filterwarnings("ignore:step = .* resolves the first bending mode:exudyn_atcm.errors.AccuracyWarning")
def test_mechanism_result_round_trips_through_csv(tmp_path):
    r = simulate(four_bar(PiezoDrive(Triangle(750.0, 750.0, 0.1))), 0.005, step=1e-3)
    path = tmp_path / "four_bar.csv"
    r.to_csv(path)
    back = atcm_read_csv(path)
    assert back.names == r.names and back.unit("coupler.P_x") == "m" and back.unit("crank.voltage") == "V"
    for name in r.names:
        np.testing.assert_array_equal(back[name], r[name])
    assert back.parameters["crank.segment_1.n_cells"] in (6, "6")


def test_progress_reports_simulated_time_of_a_mechanism():
    seen = []
    simulate(cantilever(bender(drive=PiezoDrive(Triangle(750.0, 750.0, 0.1)))), 0.01, step=1e-3,
             progress=lambda t, t_end: seen.append((t, t_end)))
    assert seen[0] == (0.0, 0.01) and seen[-1][0] == pytest.approx(0.01) and len(seen) == 11
    with pytest.raises(ValueError, match="progress must be None or a callable"):
        simulate(cantilever(bender()), 0.01, progress=3)
