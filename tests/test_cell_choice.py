"""Cell kinds and counts left to the package (``n_cells="auto"``, ``cell="auto"``), chosen for a run's accuracy.

The validation runs the chosen mechanism against a spatially and temporally converged reference: ten
modes of the rod (the count converges by an order of magnitude per mode: 4.7e-3, 2.8e-4, 1.7e-5 in
the first frequency at 2, 3, 4 modes, ``benchmarks/bench_rod_vs_ritz.py``) at a quarter of the chosen
step.  The discretisation's own error is measured as the chosen count against ten modes of the same
kind at the same step, so the time error cancels.
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.errors import AccuracyWarning
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import Sine, Steps, Triangle
from exudyn_atcm.solve import cell_choice
from exudyn_atcm.solve.cell_choice import SPACE_SHARE, choose_cells, frequency_error_share
from exudyn_atcm.solve.step_choice import position_error

from _spinning_threads import HAS_PROC, ticks_after

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from readme_systems import CFC, MFC, readme_four_bar  # noqa: E402 - the README's materials and four-bar


def four_bar(n_cells, cell="rod", program=None) -> atcm.Mechanism:
    """The README's four-bar (``benchmarks/readme_systems.py``), its crank driven by a triangle 0 -> 1500 -> 0 V of
    period 0.1 s."""
    return readme_four_bar(Triangle(750.0, 750.0, 0.1) if program is None else program, n_cells=n_cells, cell=cell)


def cantilever(n_cells, cell="rod", tip_force=None, program=None) -> atcm.Mechanism:
    """The paper's actuator as a cantilever bender with the paper's Preisach operator (a 0.5 s triangle)."""
    program = Triangle(750.0, 750.0, 0.5) if program is None else program
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=n_cells, cell=cell,
                    drive=atcm.PiezoDrive(program, hysteresis=paper_strain_preisach()))
    m = atcm.Mechanism("lone").add(b).ground(b.base)
    if tip_force is not None:
        m.force(b.tip, tip_force)
    return m


# ---------------------------------------------------------------------- the open choices
def test_a_bender_leaving_its_cells_open_is_refused_by_every_analysis_but_an_accuracy_run():
    m = four_bar("auto")
    for call in (lambda: atcm.simulate(m, 0.01), lambda: atcm.static_sweep(m, [0.0, 100.0]),
                 lambda: atcm.eigenfrequencies(m, n=1), lambda: atcm.solve_static(m)):
        with pytest.raises(atcm.MechanismError, match=r"bender 'crank' has no cell count yet.*n_cells='auto'.*"
                                                      r"simulate\(\.\.\., accuracy=\.\.\.\).*choose_cells"):
            call()
    open_kind = four_bar(4, cell="auto")
    with pytest.raises(atcm.MechanismError, match="bender 'crank' has no cell kind yet.*cell='auto'"):
        atcm.simulate(open_kind, 0.01)


def test_an_open_bender_says_so_in_its_parameters_and_repr():
    b = four_bar("auto", cell="auto").components["crank"]
    assert b.open_choices == ("cell", "n_cells")
    assert "cell='auto'" in repr(b) and "n_cells='auto'" in repr(b)
    p = b.parameters()
    assert p["crank.cell"] == "auto" and p["crank.segment_1.n_cells"] == "auto"
    with pytest.raises(atcm.MechanismError, match="cell count"):
        b.cell_lengths  # noqa: B018
    with pytest.raises(atcm.MechanismError, match="left to the package"):
        b.segments[0].cell_length  # noqa: B018


def test_segments_may_leave_their_counts_open_and_take_the_same_count():
    segments = [atcm.Segment(0.02, "auto", atcm.PiezoDrive(Triangle(500.0, 500.0, 0.1))), atcm.Segment(0.01, 3)]
    b = atcm.Bender("b", width=1e-2, passive=CFC, active=MFC, segments=segments)
    assert b.open_choices == ("n_cells",)
    m = atcm.Mechanism("two").add(b).ground(b.base)
    choice = choose_cells(m, 0.1, 1e-2)
    n = choice.cells["b"][1]
    assert [s.n_cells for s in choice.mechanism.components["b"].segments] == [n, 3]
    with pytest.raises(ValueError, match="n_cells"):
        atcm.Segment(0.02, "many")


def test_choose_cells_refuses_bad_input_and_leaves_a_fixed_mechanism_alone():
    with pytest.raises(ValueError, match="mechanism: expected an exudyn_atcm Mechanism"):
        choose_cells("four-bar", 0.1)
    with pytest.raises(ValueError, match="t_end"):
        choose_cells(four_bar("auto"), -1.0)
    with pytest.raises(ValueError, match="accuracy"):
        choose_cells(four_bar("auto"), 0.1, accuracy=0.5)
    fixed = four_bar(3)
    choice = choose_cells(fixed, 0.1)
    assert choice.mechanism is fixed and choice.cells == {}


def test_the_open_mechanism_is_not_changed_by_the_choice():
    m = four_bar("auto", cell="auto")
    choice = choose_cells(m, 0.1, 1e-2)
    assert m.components["crank"].open_choices == ("cell", "n_cells")
    crank = choice.mechanism.components["crank"]
    assert crank.open_choices == () and crank.n_cells == choice.cells["crank"][1]
    assert crank is not m.components["crank"] and choice.mechanism.connections == m.connections


# ---------------------------------------------------------------------- the kind
def test_the_kind_is_ritz_for_a_cantilever_and_rod_where_ritz_is_refused():
    assert choose_cells(cantilever("auto", "auto"), 0.1, 1e-2).cells["b"][0] == "ritz"
    # ritz takes no tip load, and joins a mechanism as a cantilever only
    assert choose_cells(cantilever("auto", "auto", tip_force=(0.0, -0.02)), 0.1, 1e-2).cells["b"][0] == "rod"
    assert choose_cells(four_bar("auto", "auto"), 0.1, 1e-2).cells["crank"][0] == "rod"


def test_a_cantilever_of_two_segments_takes_rod_cells():
    # ritz models one uniform segment (refused at the build): the open kind falls to rod
    segments = [atcm.Segment(0.05, "auto", atcm.PiezoDrive(Triangle(750.0, 750.0, 0.2))), atcm.Segment(0.037, "auto")]
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, segments=segments, cell="auto")
    choice = choose_cells(atcm.Mechanism("two").add(b).ground(b.base), 0.2, 1e-2)
    assert choice.cells["b"][0] == "rod"


def test_an_open_kind_with_a_fixed_count_keeps_the_count():
    choice = choose_cells(cantilever(5, "auto"), 0.1)
    assert choice.cells == {"b": ("ritz", 5)} and "ritz cells, the cheapest kind" in choice.line


# ---------------------------------------------------------------------- the count against converged runs
def two_segments(n_cells, cell="rod") -> atcm.Mechanism:
    """The paper's laminate as a cantilever of two segments, each with its own drive (a triangle and a sine of
    another period), under a tip load."""
    segments = [atcm.Segment(0.05, n_cells, atcm.PiezoDrive(Triangle(750.0, 750.0, 0.2))),
                atcm.Segment(0.037, n_cells, atcm.PiezoDrive(Sine(500.0, 500.0, 0.1)))]
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, segments=segments, cell=cell)
    return atcm.Mechanism("two").add(b).ground(b.base).force(b.tip, (0.0, -0.02))


@pytest.mark.parametrize("make, t_end, accuracy", [
    (lambda n, c: four_bar(n, c), 0.2, 1e-3),
    (lambda n, c: cantilever(n, c), 0.5, 1e-2),
    (two_segments, 0.2, 1e-2),
], ids=["four-bar, triangle, 1e-3", "cantilever with hysteresis, triangle, 1e-2", "two segments, tip load, 1e-2"])
def test_a_run_with_open_cells_is_within_the_target_of_the_converged_solution(make, t_end, accuracy):
    with warnings.catch_warnings():
        warnings.simplefilter("error", AccuracyWarning)  # neither the cells nor the step may miss
        result = atcm.simulate(make("auto", "auto"), t_end, accuracy=accuracy)
    info = result.info["accuracy"]
    h = info["step [s]"]
    (name, chosen), = info["cells"].items()
    n, kind = int(chosen.split()[0]), chosen.split()[1]
    assert result.info["cell_choice"].startswith(f"bender '{name}': {n} {kind} modes for {SPACE_SHARE * accuracy:g}")
    # the step takes what twice the cells' estimate leaves, at least 0.7 of the target
    assert info["target"] == accuracy
    assert info["step_target"] == pytest.approx(max(1 - SPACE_SHARE, 1 - 2 * info["cells_estimated_error"] / accuracy)
                                                * accuracy)
    assert result.parameters[f"{name}.segment_1.n_cells"] == n
    assert result.parameters.get(f"{name}.segment_2.n_cells", n) == n
    reference = atcm.simulate(make(10, "rod"), t_end, step=h / 4)
    assert position_error(reference, result, h) <= accuracy
    # the discretisation alone (the same step: its error cancels) within its share, and the estimate close to it:
    # the difference to the next count is about the count's error where each mode cuts it by 10x or more (measured
    # 1.04x and 1.07x of it on the first two, 1.49x on the two segments, whose two drives excite more than the
    # lowest mode); an estimate, so it may fall below the error, but not by much
    spatial = position_error(atcm.simulate(make(10, kind), t_end, step=h), atcm.simulate(make(n, kind), t_end, step=h),
                             h)
    assert spatial <= SPACE_SHARE * accuracy
    assert 0.7 * spatial <= info["cells_estimated_error"] <= 2.0 * spatial


def test_the_largest_count_tried_is_taken_with_a_warning_when_it_is_not_checked(monkeypatch):
    monkeypatch.setattr(cell_choice, "MODAL_COUNTS", (2, 3))
    with pytest.warns(AccuracyWarning, match=r"'crank' at the largest count tried, 3, not checked"):
        choice = choose_cells(four_bar("auto"), 0.2, 1e-5)
    assert choice.cells == {"crank": ("rod", 3)} and "not checked" in choice.line


# ---------------------------------------------------------------------- the stand-in's frequency error
def test_a_frequency_error_shifts_the_ringing_of_a_voltage_step_by_the_closed_form():
    """A unit step of the strain at ``t0`` rings as ``1 - cos(omega (t - t0))`` undamped; at ``omega (1 + d)``
    the difference is ``cos(omega tau) - cos(omega (1 + d) tau)``, its largest value up to ``t_end`` taken on a
    fine grid (under the envelope ``2 sin(omega d T / 2)``, ``T = t_end - t0``).  The function samples the strain
    40 times a period (the step a ramp over one sample) and takes the largest difference at the samples: within
    1 % of it."""
    m = cantilever(3, "rod", program=Steps([0.0, 0.01], [0.0, 1000.0]))
    f, t_end, d = 36.0, 0.2, 0.01
    got = frequency_error_share(m, t_end, f, d, 0.0)
    omega, tau = 2.0 * math.pi * f, np.linspace(0.0, t_end - 0.01, 200_001)
    expected = float(np.max(np.abs(np.cos(omega * tau) - np.cos(omega * (1.0 + d) * tau))))
    assert expected <= 2.0 * math.sin(omega * d * (t_end - 0.01) / 2.0)  # the envelope
    assert got == pytest.approx(expected, rel=0.01)
    assert frequency_error_share(m, t_end, f, 0.0, 0.0) == 0.0
    # a drive whose strain does not change (a constant program): the run starts at rest in its equilibrium and
    # nothing excites the mode; a load given as a function of time does: then the phase drift 2 pi f t_end d
    held = cantilever(3, "rod", program=Steps([0.0], [1000.0]))
    assert frequency_error_share(held, t_end, f, d, 0.0) == 0.0
    held.force("b.tip", lambda t: (0.0, -0.01 * min(t / 0.01, 1.0)))
    assert frequency_error_share(held, t_end, f, d, 0.0) == pytest.approx(2.0 * math.pi * f * t_end * d)


def test_a_display_with_stages_is_told_each_count_tried():
    class Display:
        def __init__(self):
            self.stages = []

        def __call__(self, t, t_end):
            pass

        def stage(self, label, share, detail):
            self.stages.append((label, detail))

    display = Display()
    result = atcm.simulate(four_bar("auto"), 0.05, accuracy=1e-2, progress=display)
    tried = [detail for label, detail in display.stages if label == "cell choice"]
    n = result.parameters["crank.segment_1.n_cells"]
    assert tried[0].startswith("'crank': 2 rod modes") and tried[-1].startswith(f"'crank': {n + 1} rod modes")
    assert len(tried) == n  # 2 ... n + 1: each count against the next


@pytest.mark.parametrize("tip_force", [None, (0.0, -0.02)], ids=["unloaded", "tip load"])
def test_the_run_takes_the_chosen_counts_build_and_gives_the_plain_runs_result(monkeypatch, tip_force):
    # one build per count measured (its eigenvalue analysis and its static poses share it); the run takes the chosen
    # count's build (the kind's trial build aside), put back in its built state: it equals a plain run at the chosen step from a fresh build of the
    # fixed mechanism to round-off
    from exudyn_atcm.mbs import builder
    calls = []
    build = builder.build
    monkeypatch.setattr(builder, "build", lambda *a, **k: calls.append(1) or build(*a, **k))
    run = atcm.simulate(cantilever("auto", "auto", tip_force=tip_force), 0.1, accuracy=1e-2)
    (kind, n), = [tuple(v.split()[::-1]) for v in run.info["accuracy"]["cells"].values()]
    # counts 2 ... n + 1, and unloaded the trial build that finds ritz possible (a tip load refuses it before)
    assert len(calls) == int(n) - 2 + 2 + (tip_force is None)
    monkeypatch.setattr(builder, "build", build)
    plain = atcm.simulate(cantilever(int(n), kind, tip_force=tip_force), 0.1, step=run.info["step [s]"])
    for name in plain.names:
        assert np.allclose(run[name], plain[name], rtol=1e-10, atol=1e-13)


def test_a_chain_of_rigid_cells_doubles_its_count_and_meets_the_target():
    # chains converge at second order: counts 4, 8, 16, ... and the difference to the next count scaled by
    # Richardson's 1 / (1 - 2^-2); the reference for the cells alone is four times the count (1/16 of the error left)
    with warnings.catch_warnings():
        warnings.simplefilter("error", AccuracyWarning)
        result = atcm.simulate(four_bar("auto", "rigid"), 0.2, accuracy=1e-2)
    info = result.info["accuracy"]
    h, n = info["step [s]"], int(info["cells"]["crank"].split()[0])
    assert n in cell_choice.CHAIN_COUNTS and "rigid cells for 0.003 of the travel" in result.info["cell_choice"]
    assert position_error(atcm.simulate(four_bar(10, "rod"), 0.2, step=h / 4), result, h) <= 1e-2
    spatial = position_error(atcm.simulate(four_bar(4 * n, "rigid"), 0.2, step=h),
                             atcm.simulate(four_bar(n, "rigid"), 0.2, step=h), h)
    assert spatial <= SPACE_SHARE * 1e-2
    assert 0.7 * spatial <= info["cells_estimated_error"] <= 2.0 * spatial


@pytest.mark.skipif(not HAS_PROC, reason="reads the threads' CPU time from Linux's /proc")
def test_the_choice_leaves_no_blas_thread_spinning():
    # OpenBLAS's workers spin about 0.1 s of CPU after a threaded product (a tenth of a core taken from a parallel
    # study's other worker); the stand-in's small block products run on one thread.  Measured before: 13 ticks
    threadpoolctl = pytest.importorskip("threadpoolctl")
    if all(lib["num_threads"] <= 1 for lib in threadpoolctl.threadpool_info() if lib["user_api"] == "blas"):
        pytest.skip("a single-threaded BLAS: nothing can spin")
    m = four_bar("auto", program=Triangle(750.0, 750.0, 0.5))
    assert ticks_after(lambda: choose_cells(m, 0.5, 1e-3)) <= 2  # clock ticks of 10 ms: what may be taken by chance


def loaded_strip(n_cells, cell="rigid") -> atcm.Mechanism:
    """A passive strip (no drive) under a tip load."""
    b = atcm.Bender("s", width=5e-3, passive=CFC, length=0.03, n_cells=n_cells, cell=cell)
    return atcm.Mechanism("strip").add(b).ground(b.base).force(b.tip, (0.0, -0.01))


def test_a_loaded_strip_without_a_drive_compares_its_pose_with_its_deflection():
    # one static pose (no drive) has no travel: its difference to the next count is taken relative to its
    # deflection from the reference pose.  Rigid cells under a tip load: the tip's deflection converges as n^-2,
    # so the static estimate of count n is 4/3 of its difference to 2n; measured against four times the count
    # from static solves, extrapolated (Richardson: the error of n is 16/15 of its difference to 4n)
    choice = choose_cells(loaded_strip("auto"), 0.05, 1e-2)
    n = choice.cells["s"][1]
    static = [t[2] for t in choice.tried if t[0] == n][0]  # its difference to 2n, relative to the deflection
    tip = {k: atcm.solve_static(loaded_strip(k))["s.tip_y"][-1] for k in (n, 4 * n)}
    error = 16.0 / 15.0 * abs(tip[n] - tip[4 * n]) / abs(tip[4 * n])
    assert error > 0.0 and 0.7 * error <= 4.0 / 3.0 * static <= 1.5 * error
    assert "static poses by 0 of" not in choice.line


def test_a_straight_column_whose_poses_do_not_move_takes_the_smallest_count_and_says_why():
    # a rod cantilever under an axial load below Euler's (stable) and no drive: every count's equilibrium is the
    # straight reference pose (the rod is inextensible), so the poses differ between counts by round-off only
    # (1e-17 m: taken for an error of 1 and 5 times that "travel" until 2026-11-29, which drove the count to 4).
    # Nothing excites the lowest mode either: the exact run is the reference pose at rest, which the run with the
    # chosen count reproduces
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells="auto", cell="rod",
                    drive=atcm.PiezoDrive(0.0))
    p_cr = math.pi**2 * b.laminate.bending_stiffness / (4.0 * 0.03**2)
    column = atcm.Mechanism("column").add(b).ground(b.base)
    column.force(b.tip, (-0.5 * p_cr, 0.0))
    choice = choose_cells(column, 0.05, 1e-3)
    assert choice.cells["b"] == ("rod", cell_choice.MODAL_COUNTS[0])
    assert choice.tried[0][2] == 0.0 and choice.estimated_error == 0.0
    assert "the static poses do not move" in choice.line and "nothing in the run excites that mode" in choice.line
    with warnings.catch_warnings():
        warnings.simplefilter("error", AccuracyWarning)
        result = atcm.simulate(column, 0.05, accuracy=1e-3)
    assert np.max(np.abs(result["b.tip_y"])) < 1e-12 and np.max(np.abs(result["b.tip_x"] - 0.03)) < 1e-12
