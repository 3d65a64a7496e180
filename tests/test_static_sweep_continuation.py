"""Issue 31, part 2: a static sweep as one continuation.

``static_sweep(..., method="continuation")`` (the default) solves the points after the first as the
load steps of one Exudyn static solve continuing from the first equilibrium; ``method="points"``
solves each point as its own equilibrium in load steps (the sweep before the continuation).
References: the per-point path computed in the same test (both are Newton solutions of the same
equilibrium equations with the same tolerances, so they agree to the solver tolerance), a plain play
operator applied offline to the voltages (the hysteresis memory across reversals), forced failures
of the continuation at chosen points and forced misses of the stability proof inside the solve.
"""

from __future__ import annotations

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.mbs import solver_runs
from exudyn_atcm.mbs.stability import StabilityProbe
from exudyn_atcm.mbs.sweep_solve import PointsSolved
from exudyn_atcm.solve import sweep_continuation

from test_one_stepping import CountingPlay, four_bar, lone, offline_play, paper_drive

#: A voltage cycle with three reversals (750 V, -200 V, 600 V): the Preisach memory matters.
CYCLE = np.concatenate([np.linspace(0.0, 750.0, 8), np.linspace(750.0, -200.0, 9)[1:],
                        np.linspace(-200.0, 600.0, 8)[1:], np.linspace(600.0, 0.0, 6)[1:]])

MECHANISMS = {
    "four_bar_rigid": lambda drive: four_bar(drive),
    "lone_rigid": lambda drive: lone(drive),
    "lone_rod": lambda drive: lone(drive, cell="rod"),
}


def position_columns(r) -> list[str]:
    return [c for c in r.names if r.unit(c) == "m"]


@pytest.mark.parametrize("case", sorted(MECHANISMS))
def test_continuation_equals_the_point_by_point_sweep(case):
    make = MECHANISMS[case]
    points = atcm.static_sweep(make(paper_drive()), CYCLE, method="points")
    cont = atcm.static_sweep(make(paper_drive()), CYCLE)
    assert cont.info["sweep_method"] == "continuation"
    assert cont.info["fallback_points"] == ""  # every point after the first was continued
    assert cont.info["continued_points"] == len(CYCLE) - 1 and cont.info["methods"] == "static"
    assert points.names == cont.names and cont.n_rows == len(CYCLE)
    # the hysteresis is the same function of the voltage history either way: strains identical
    strain = [c for c in cont.names if c.endswith(".strain")]
    for c in strain:
        np.testing.assert_array_equal(cont[c], points[c])
    # Both solve the same equilibrium equations to the same Newton tolerances (absolute ~1e-12 EI/L):
    # positions agree far below 1e-9 m (measured: 1e-12 m or less); 1e-9 m is 1e-8 of the size.
    for c in position_columns(cont):
        np.testing.assert_allclose(cont[c], points[c], rtol=0.0, atol=1e-9, err_msg=c)
    assert cont.info["unstable_points"] == points.info["unstable_points"] == ""


def test_continuation_keeps_the_hysteresis_memory_across_reversals():
    play = CountingPlay(k=5e-7, r=200.0)
    r = atcm.static_sweep(lone(atcm.PiezoDrive(0.0, hysteresis=play)), CYCLE)
    expected = [5e-7 * x for x in offline_play(CYCLE, 200.0)]
    np.testing.assert_allclose(r["b.strain"], expected, rtol=1e-15, atol=0.0)


@pytest.mark.parametrize("cell", ["rigid", "rod", "six-bar"])
def test_stability_is_checked_at_every_point(monkeypatch, cell):
    # rigid and rod cells: the proof from the running solver's Jacobian inside the solve (the full check only where
    # that proof misses); six-bar cells (Exudyn's Jacobian is not their tangent): the full check of every point
    # after the solve
    checked = []
    check, in_solve = StabilityProbe.check, StabilityProbe.proved_in_solve

    def counting_check(self):
        checked.append("check")
        return check(self)

    def counting_in_solve(self, solver, *state):
        proved = in_solve(self, solver, *state)
        checked.append("in solve" if proved else "missed")
        return proved

    monkeypatch.setattr(StabilityProbe, "check", counting_check)
    monkeypatch.setattr(StabilityProbe, "proved_in_solve", counting_in_solve)
    atcm.static_sweep(lone(paper_drive(), cell=cell), CYCLE)
    assert len(checked) - checked.count("missed") >= len(CYCLE)
    assert ("in solve" in checked) == (cell != "six-bar")


def failing_at(points: set[int]):
    """A stand-in for ``solve_points`` whose Newton iteration fails half-way to each point in ``points``: the
    real solve up to the point before, then the failure (the model left in that point's equilibrium, as the
    real one leaves it)."""
    original = sweep_continuation.solve_points

    def solve(model, strains, first, on_point, **kwargs):
        stop = min([k for k in points if k >= first], default=len(strains))
        failure = solver_runs.ExudynFailure("static Newton iteration did not converge", 0.5)
        if stop == first:
            return PointsSolved(first - 1, failure=failure)
        solved = original(model, strains[:stop], first, on_point, **kwargs)
        if solved.last == stop - 1 and stop < len(strains):
            return PointsSolved(solved.last, failure=failure)
        return solved

    return solve


@pytest.mark.parametrize("cell", ["six-bar", "rod"])
def test_a_failed_continuation_falls_back_to_its_own_equilibrium_and_continues(monkeypatch, cell):
    reference = atcm.static_sweep(lone(paper_drive(), cell=cell), CYCLE, method="points")
    failing = {3, 4, 11, len(CYCLE) - 1}
    monkeypatch.setattr(sweep_continuation, "solve_points", failing_at(failing))
    r = atcm.static_sweep(lone(paper_drive(), cell=cell), CYCLE)
    notes = r.info["fallback_points"].split(" | ")
    assert [int(n.split(":")[0]) for n in notes] == sorted(failing)
    assert r.info["continued_points"] == len(CYCLE) - 1 - len(failing)
    assert "continuation step failed at load factor 0.5" in notes[0] and "own equilibrium" in notes[0]
    assert r.n_rows == len(CYCLE) and list(r["point"]) == list(range(len(CYCLE)))
    # the same equilibria as the per-point sweep to the Newton tolerance (see above)
    for c in position_columns(r):
        np.testing.assert_allclose(r[c], reference[c], rtol=0.0, atol=1e-9, err_msg=c)


def test_a_solve_that_reaches_no_point_and_reports_no_failure_falls_back_instead_of_looping(monkeypatch):
    monkeypatch.setattr(sweep_continuation, "solve_points", lambda model, strains, first, on_point, **kw:
                        PointsSolved(first - 1))
    reference = atcm.static_sweep(lone(paper_drive(), cell="rod"), CYCLE[:6], method="points")
    r = atcm.static_sweep(lone(paper_drive(), cell="rod"), CYCLE[:6])
    notes = r.info["fallback_points"].split(" | ")
    assert len(notes) == 5 and all("the continuation reached no point" in n for n in notes)
    for c in position_columns(r):
        np.testing.assert_allclose(r[c], reference[c], rtol=0.0, atol=1e-12, err_msg=c)


def test_a_missed_proof_in_the_solve_is_checked_in_full_and_the_sweep_goes_on(monkeypatch):
    reference = atcm.static_sweep(lone(paper_drive(), cell="rod"), CYCLE)
    missed, calls = {5, 6, 20}, []
    original = StabilityProbe.proved_in_solve

    def missing(self, solver, *state):
        calls.append(1)
        return False if len(calls) in missed else original(self, solver, *state)

    full = []
    check = StabilityProbe.check

    def counting_check(self):
        full.append(1)
        return check(self)

    monkeypatch.setattr(StabilityProbe, "proved_in_solve", missing)
    monkeypatch.setattr(StabilityProbe, "check", counting_check)
    r = atcm.static_sweep(lone(paper_drive(), cell="rod"), CYCLE)
    # every miss stops the solve, its point is checked in full (stable) and kept, a new solve goes on
    assert len(full) >= len(missed) and r.info["fallback_points"] == "" and r.info["unstable_points"] == ""
    assert r.info["continued_points"] == len(CYCLE) - 1
    for c in position_columns(r):
        np.testing.assert_allclose(r[c], reference[c], rtol=0.0, atol=1e-12, err_msg=c)


def test_unknown_method_is_refused():
    with pytest.raises(ValueError, match=r"method: expected one of 'continuation', 'points', got 'newton'"):
        atcm.static_sweep(lone(paper_drive()), [0.0, 100.0], method="newton")


@pytest.mark.parametrize("cell", ["rigid", "six-bar"])
def test_a_bending_actuator_sweep_takes_the_method(cell):
    act = atcm.BendingActuator(4, 0.087 / 4, 28e-3, atcm.Layer(0.2e-3, 70e9, 1550.0),
                               atcm.Layer(0.3e-3, 30.336e9, 5440.0), paper_drive(), cell=cell)
    points = atcm.static_sweep(act, CYCLE, tip_force=(0.0, -0.01), method="points")
    cont = atcm.static_sweep(act, CYCLE, tip_force=(0.0, -0.01))
    assert cont.info["sweep_method"] == "continuation" and points.info["sweep_method"] == "points"
    # the same equilibria to the Newton tolerance (see above): 1e-9 m is 1e-8 of the length
    for c in ("actuator.tip_x", "actuator.tip_y"):
        np.testing.assert_allclose(cont[c], points[c], rtol=0.0, atol=1e-9, err_msg=c)
