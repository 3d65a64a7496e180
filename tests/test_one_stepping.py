"""Issue 30, part 2: one stepping and recording path, and solving a built system again.

``simulate``, ``solve_static``, ``static_sweep`` and ``add_to`` trial, commit and record through
one :class:`~exudyn_atcm.mbs.stepping.Stepping`; a :class:`~exudyn_atcm.BuiltSystem` solves one
build many times.  References: the values main (commit 8af9a9c, before the unification) gave for
the same calls (a refactoring pin: the unified path must reproduce them to solver round-off),
a plain play (backlash) operator written here and applied offline to the recorded voltages,
Exudyn's own count of accepted steps, and fresh builds.
"""

from __future__ import annotations

import math
import warnings

import exudyn as exu
import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.mbs import solver_runs, solver_settings
from exudyn_atcm.model import Triangle
from exudyn_atcm.model.parameter_sets import paper_strain_preisach

CFC = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)


class CountingPlay:
    """A play (backlash) operator, strain ``k * x`` with ``x`` the play of half-width ``r`` [V] from 0,
    counting its trial evaluations and commits (since the last reset, which every run does at its start)."""

    def __init__(self, k: float = 5e-7, r: float = 200.0) -> None:
        self.k, self.r = k, r
        self.reset()

    def reset(self) -> None:
        self.x = 0.0
        self.commits = 0
        self.evaluations = 0

    def _play(self, u: float) -> float:
        return min(max(self.x, u - self.r), u + self.r)

    def evaluate(self, u: float) -> float:
        self.evaluations += 1
        return self.k * self._play(u)

    def commit(self, u: float) -> float:
        self.x = self._play(u)
        self.commits += 1
        return self.k * self.x

    def apply(self, us) -> np.ndarray:
        return np.array([self.k * x for x in offline_play(us, self.r)])

    def checkpoint(self):
        return (self.x, self.commits, self.evaluations)

    def restore(self, state) -> None:
        self.x, self.commits, self.evaluations = state


def offline_play(us, r: float) -> list[float]:
    """The play operator applied to a whole voltage series from 0 (the independent reference)."""
    x, out = 0.0, []
    for u in us:
        x = min(max(x, u - r), u + r)
        out.append(x)
    return out


def four_bar(drive: atcm.PiezoDrive, spring: bool = False) -> atcm.Mechanism:
    """The README's four-bar with rigid cells (main's values were taken with them; optionally a spring, for a force
    column)."""
    crank = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=6, drive=drive,
                        angle=math.pi / 2, cell="rigid")
    coupler = atcm.Link("coupler", {"A": (0.0, 0.03), "B": (0.04, 0.03), "P": (0.02, 0.05)}, mass=1e-4, inertia=1e-8)
    rocker = atcm.Link("rocker", {"B": (0.04, 0.03), "O": (0.04, 0.0)}, mass=1e-4, inertia=1e-8)
    m = atcm.Mechanism("four_bar").add(crank, coupler, rocker)
    m.ground(crank.base)
    m.pin(crank.tip, coupler.point("A"))
    m.pin("coupler.B", "rocker.B")
    m.ground("rocker.O", joint="pin")
    if spring:
        m.spring("coupler.P", "rocker.O", 50.0)
    return m


def lone(drive: atcm.PiezoDrive, force=(0.0, -0.02), cell: str = "rigid") -> atcm.Mechanism:
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=4, drive=drive, cell=cell)
    m = atcm.Mechanism("lone").add(b).ground(b.base)
    m.force(b.tip, force)
    return m


def paper_drive() -> atcm.PiezoDrive:
    return atcm.PiezoDrive(Triangle(750.0, 750.0, 0.1), hysteresis=paper_strain_preisach())


# ----------------------------------------------------------------------------- the unified path reproduces main

#: What main (8af9a9c, separate recorders) gave for the same calls; the unified path must give the same to
#: solver round-off (1e-12 m, 1e-15 strain: measured identical to the last bit when this test was written).
MAIN = {
    "fb_sim": {"coupler.P_x": [0.01991534461026432, 0.01979565627057528, 0.019659347814578853, 0.01950750921512848,
                               0.019341407773227754],
               "coupler.P_y": [0.049999861266691724, 0.0499991900111534, 0.04999775046462106, 0.04999530433252994,
                               0.04999161522047023],
               "crank.strain": [6.269592476489024e-05, 0.00015629549018267037, 0.0002604406367952877,
                                0.0003739995893757574, 0.0004961310414562218]},
    "fb_static": {"coupler.P_x": [0.01944062147041596], "coupler.P_y": [0.049993957347735186],
                  "crank.strain": [0.0004137931034482759]},
    "fb_sweep": {"coupler.P_x": [0.01991534461026432, 0.01964810059546818, 0.01932914667536223, 0.019329146675355107,
                                 0.019331384850079476],
                 "coupler.P_y": [0.049999861266691724, 0.04999760611134059, 0.0499913136855657, 0.04999131368556306,
                                 0.049991371456261105],
                 "crank.strain": [6.269592476489024e-05, 0.00026044063679528785, 0.0004961310414562236,
                                  0.0004961310414562236, 0.0004944782334753798]},
    "lone_static": {"b.tip_x": [0.08678786622339016], "b.tip_y": [0.005275572573720341],
                    "b.strain": [0.0004961310414562236]},
    "lone_sweep": {"b.tip_x": [0.08699887578833197, 0.0869088378573658, 0.08665344948119819, 0.08665344948118626],
                   "b.tip_y": [0.00036002639284722225, 0.0034519724930541385, 0.006745771149560383,
                               0.006745771149679743],
                   "b.strain": [6.269592476489024e-05, 0.0003351571006451153, 0.0006261783295168849,
                                0.0006261783295168849]},
    "lone_sim": {"b.tip_x": [0.08699887578833197, 0.08699563598446114, 0.08697326429816495, 0.08689098716024576,
                             0.08674592691404813],
                 "b.tip_y": [0.00036002639284722225, 0.0006424616029410284, 0.0017754221653051658,
                             0.003769929215524944, 0.005831817332429687],
                 "b.strain": [6.269592476489024e-05, 0.00015629549018267037, 0.0002604406367952877,
                              0.0003739995893757574, 0.0004961310414562218]},
}

CALLS = {
    "fb_sim": lambda: atcm.simulate(four_bar(paper_drive()), 0.02, step=1e-4),
    "fb_static": lambda: atcm.solve_static(four_bar(paper_drive()), voltage=500.0),
    "fb_sweep": lambda: atcm.static_sweep(four_bar(paper_drive()), [0.0, 300.0, 600.0, 300.0, 0.0]),
    "lone_static": lambda: atcm.solve_static(lone(paper_drive()), voltage=600.0),
    "lone_sweep": lambda: atcm.static_sweep(lone(paper_drive()), [0.0, 400.0, 750.0, 200.0]),
    "lone_sim": lambda: atcm.simulate(lone(paper_drive()), 0.02, step=1e-4),
}


@pytest.mark.parametrize("case", list(MAIN))
def test_unified_path_gives_mains_values(case):
    r = CALLS[case]()
    every = 50 if case.endswith("_sim") else 1  # the dynamic values were stored every 50th step
    if case.endswith("_sim"):
        assert len(r["time"]) == 201
    for column, values in MAIN[case].items():
        tol = 1e-15 if column.endswith("strain") else 1e-12
        np.testing.assert_allclose(r[column][::every], values, rtol=0, atol=tol, err_msg=f"{case} {column}")


# ----------------------------------------------------------------------------- add_to records what simulate records

def run_add_to(mech: atcm.Mechanism, t_end: float, step: float, user_settings: dict | None = None):
    """``add_to`` into a fresh system and the user's own solve with the package's dynamic settings."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    handle = atcm.add_to(mbs, mech)
    mbs.Assemble()
    settings = solver_settings.dynamic_settings(t_end, step)
    solver_settings.apply_user_settings(settings, user_settings)
    solver = exu.MainSolverImplicitSecondOrder()
    solver.SolveSystem(mbs, settings)
    return handle.result(), solver


def test_add_to_records_the_columns_and_values_of_simulate():
    # no free bender end (add_to's interface bodies change nothing) and strain 0 at t = 0 (simulate's static
    # pre-solve does nothing): both solve the same system from the same state with the same settings
    play_a, play_b = CountingPlay(), CountingPlay()
    program = Triangle(750.0, 750.0, 0.02)
    ours = atcm.simulate(four_bar(atcm.PiezoDrive(program, hysteresis=play_a), spring=True), 0.01, step=1e-4)
    theirs, _ = run_add_to(four_bar(atcm.PiezoDrive(program, hysteresis=play_b), spring=True), 0.01, 1e-4)
    assert list(theirs) == list(ours)
    assert "spring_1.force" in ours and "crank.cell_angle_6" in ours
    assert [theirs.unit(c) for c in theirs] == [ours.unit(c) for c in ours]
    for column in ours:
        # the same solver on the same system: equal to round-off (angles and positions ~1e-2)
        np.testing.assert_allclose(theirs[column], ours[column], rtol=0, atol=1e-13, err_msg=column)
    # the recorded strain is the play applied offline to the recorded voltages (committed in order, once each)
    for r in (ours, theirs):
        np.testing.assert_allclose(r["crank.strain"], 5e-7 * np.array(offline_play(r["crank.voltage"], 200.0)),
                                   rtol=0, atol=1e-18)


# ----------------------------------------------------------------------------- one commit per accepted step

JUMPS = {"timeIntegration.newton.maxIterations": 3, "timeIntegration.newton.useModifiedNewton": False}


def jumping_program(t: float) -> float:
    return 1500.0 * (t > 0.0021) - 1500.0 * (t > 0.0071)


@pytest.mark.filterwarnings("ignore::exudyn_atcm.errors.AtcmWarning")  # a 1500 V jump on a 1 ms step, on purpose
def test_simulate_commits_once_per_accepted_step(monkeypatch):
    made = []
    solver_class = exu.MainSolverImplicitSecondOrder

    def capture():
        made.append(solver_class())
        return made[-1]

    monkeypatch.setattr(solver_runs.exu, "MainSolverImplicitSecondOrder", capture)
    play = CountingPlay(k=1e-6)
    r = atcm.simulate(four_bar(atcm.PiezoDrive(jumping_program, hysteresis=play)), 0.01, step=1e-3, settings=JUMPS)
    it = made[-1].it
    accepted = it.currentStepIndex - 1  # Exudyn's index of the step after the last one accepted, counted from 1
    assert r.info["rejected_steps"] > 0  # Newton failed on the jumps: steps were repeated smaller
    assert accepted > 10 and play.evaluations > play.commits
    # one commit per accepted step and one for the initial state (Exudyn's post step at t = 0)
    assert play.commits == accepted + 1 == len(r["time"])
    np.testing.assert_allclose(r["crank.strain"], 1e-6 * np.array(offline_play(r["crank.voltage"], 200.0)),
                               rtol=0, atol=1e-18)


@pytest.mark.filterwarnings("ignore::exudyn_atcm.errors.AtcmWarning")  # as above
def test_add_to_commits_once_per_accepted_step():
    play = CountingPlay(k=1e-6)
    r, solver = run_add_to(four_bar(atcm.PiezoDrive(jumping_program, hysteresis=play)), 0.01, 1e-3, JUMPS)
    accepted = solver.it.currentStepIndex - 1
    assert accepted > 10 and r["time"][-1] == pytest.approx(0.01)
    assert play.evaluations > play.commits  # trials of steps Exudyn rejected (one trial per attempted time)
    assert play.commits == accepted + 1 == len(r["time"])
    np.testing.assert_allclose(r["crank.strain"], 1e-6 * np.array(offline_play(r["crank.voltage"], 200.0)),
                               rtol=0, atol=1e-18)


# ----------------------------------------------------------------------------- a built system solved again

def assert_same(a: atcm.Result, b: atcm.Result) -> None:
    assert list(a) == list(b)
    for column in b:
        np.testing.assert_allclose(a[column], b[column], rtol=0, atol=1e-13, err_msg=column)


@pytest.mark.parametrize("make", [lambda: four_bar(paper_drive()), lambda: lone(paper_drive()),
                                  # cells with state of their own between steps (the rod's linearisation, the
                                  # six-bar's motors, the beam's nodes)
                                  lambda: lone(paper_drive(), cell="rod"), lambda: lone(paper_drive(), cell="six-bar"),
                                  lambda: lone(paper_drive(), cell="beam")],
                         ids=["four_bar", "lone", "lone_rod", "lone_six_bar", "lone_beam"])
def test_resolve_without_rebuilding_equals_a_fresh_build(make):
    built = atcm.BuiltSystem(make())
    # every kind of solve, in an order that leaves each one's state for the next (deformed, hysteresis committed)
    assert_same(built.static_sweep([0.0, 300.0, 600.0]), atcm.static_sweep(make(), [0.0, 300.0, 600.0]))
    assert_same(built.solve_static(500.0), atcm.solve_static(make(), voltage=500.0))
    assert_same(built.simulate(0.01, step=1e-4), atcm.simulate(make(), 0.01, step=1e-4))
    assert_same(built.solve_static(200.0), atcm.solve_static(make(), voltage=200.0))
    assert_same(built.simulate(0.005, step=5e-5), atcm.simulate(make(), 0.005, step=5e-5))
    assert built.builds == 1


def test_a_changed_mechanism_is_built_again():
    mech = lone(paper_drive())
    built = atcm.BuiltSystem(mech)
    before = built.solve_static(500.0)
    mech.force("b.tip", (0.0, 0.05), name="extra")
    after = built.solve_static(500.0)
    assert built.builds == 2
    fresh = lone(paper_drive())
    fresh.force("b.tip", (0.0, 0.05), name="extra")
    assert_same(after, atcm.solve_static(fresh, voltage=500.0))
    assert after["b.tip_y"][0] > before["b.tip_y"][0] + 1e-4  # the extra upward load is in


def test_built_system_refuses_what_is_not_a_mechanism():
    with pytest.raises(ValueError, match=r"mechanism must be a Mechanism, got str"):
        atcm.BuiltSystem("four_bar")


def test_the_old_step_record_path_warns():
    import importlib
    import sys

    sys.modules.pop("exudyn_atcm.solve.step_record", None)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        old = importlib.import_module("exudyn_atcm.solve.step_record")
    from exudyn_atcm.mbs.step_record import StepRecord

    assert old.StepRecord is StepRecord
    assert any("exudyn_atcm.mbs.step_record" in str(w.message) for w in caught)


def test_built_system_warnings_point_at_the_callers_line():
    # as for simulate (tests/test_mechanism_run_checks.py): the step does not divide t_end, is coarse for the
    # program, and the program goes beyond the rating; each warning names this file's line, not the package's
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=3, cell="rigid",
                    drive=atcm.PiezoDrive(Triangle(1000.0, 1000.0, 0.02)))
    built = atcm.BuiltSystem(atcm.Mechanism("lone").add(b).ground(b.base))
    with pytest.warns(RuntimeWarning) as record:
        built.simulate(0.01, step=3e-3)
    assert len(record) == 3 and {w.filename for w in record} == {__file__}
