"""The drives' own cost in the run-time estimate (issue 17's caveat: a closed-loop run was predicted at
a third of its time).

Reference: an operator that sleeps a known time in every evaluation and commit, so one step of its
drive costs at least twice that sleep (``time.sleep`` sleeps at least the time asked).  The
estimate must carry it, the user's drive must come out untouched, and a drive shared by two
segments counts once.
"""

from __future__ import annotations

import time

import pytest

import exudyn_atcm as atcm
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.solve import drive_cost
from exudyn_atcm.solve.drive_cost import drive_step_cost, extra_drive_cost, reference_drive_cost
from exudyn_atcm.solve.run_checks import estimate_run_time
from exudyn_atcm.solve.run_plan import estimate_simulation

from _actuator_runs import WrappedOperator

SLEEP = 2e-3  # s per evaluation and per commit
CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)


class SlowOperator(WrappedOperator):
    """The paper's Preisach loop, sleeping ``SLEEP`` in every evaluation and commit."""

    def __init__(self) -> None:
        super().__init__(paper_strain_preisach())

    def evaluate(self, u):
        time.sleep(SLEEP)
        return self.inner.evaluate(u)

    def commit(self, u):
        time.sleep(SLEEP)
        return self.inner.commit(u)


def slow_actuator(n_cells=4):
    drive = atcm.PiezoDrive(atcm.signals.Triangle(500.0, 1000.0, 0.5), hysteresis=SlowOperator())
    return atcm.BendingActuator(n_cells, 0.087 / n_cells, 28e-3, CFC, MFC, drive, cell="rigid")


def test_a_slow_drive_is_in_the_estimate():
    act = slow_actuator()
    cost = drive_step_cost(act.drive, 1e-4)
    assert cost >= 2 * SLEEP  # one evaluation and one commit per step
    extra = extra_drive_cost([act.drive], 1e-4)
    assert extra == pytest.approx(cost - reference_drive_cost(1e-4), rel=0.5)
    estimate, n_steps, parts, extra = estimate_simulation(act, 0.1, 1e-4)
    assert n_steps == 1000 and parts == "4 rigid cells"
    assert estimate >= n_steps * 2 * SLEEP * 0.95  # the sleeps alone, minus the reference drive's few µs
    plain = estimate_run_time("rigid", 4, n_steps)
    assert plain < 0.1 < estimate  # the cells' cost alone would have said 1000 steps take a few 10 ms


def test_the_users_drive_is_not_touched():
    act = slow_actuator()
    act.drive.hysteresis.commit(1200.0)
    before = act.drive.hysteresis.checkpoint()
    drive_step_cost(act.drive, 1e-4)
    after = act.drive.hysteresis.checkpoint()
    assert repr(before) == repr(after)
    assert act.drive.hysteresis.inner.evaluate(300.0) == paper_strain_preisach().apply([0.0, 1200.0, 300.0])[-1]


class CopyRefusingOperator(WrappedOperator):
    """The paper's loop, failing when copied or pickled.  A deep copy reads every copied object's
    ``__dict__``, after which CPython 3.11 keeps that object's attributes in a dictionary instead of
    its inline storage: every step of the run that follows pays for it (+8 % of a ritz run's
    instructions, measured with callgrind).  The measurement must not copy the user's drive."""

    def __deepcopy__(self, memo):
        raise AssertionError("the user's operator was deep-copied")

    def __copy__(self):
        raise AssertionError("the user's operator was copied")

    def __reduce_ex__(self, protocol):
        raise AssertionError("the user's operator was pickled")


def test_the_drive_is_measured_in_place_and_put_back():
    operator = CopyRefusingOperator(paper_strain_preisach())
    pid = atcm.PIDController(2e5, sample_time=1e-3, setpoint=1e-3)
    drive = atcm.PiezoDrive(pid, hysteresis=operator)
    operator.commit(1200.0)
    pid.observe(0.0, 2e-4)
    memory = operator.checkpoint()
    assert drive_step_cost(drive, 1e-4) is not None  # a copy would have raised, and the cost been None
    assert repr(operator.checkpoint()) == repr(memory)
    assert operator.inner.evaluate(300.0) == paper_strain_preisach().apply([0.0, 1200.0, 300.0])[-1]
    assert pid.samples == 0 and pid.voltage_at(0.0) == 0.0  # reset, as every run starts it


def test_a_drive_shared_by_segments_counts_once_and_a_plain_drive_adds_nothing():
    drive = atcm.PiezoDrive(atcm.signals.Triangle(500.0, 1000.0, 0.5), hysteresis=SlowOperator())
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC,
                    segments=[atcm.Segment(0.04, 2, drive), atcm.Segment(0.04, 2, drive)], cell="rigid")
    mech = atcm.Mechanism("m").add(b).ground(b.base)
    shared = extra_drive_cost(mech.drives.values(), 1e-4)
    single = extra_drive_cost([drive], 1e-4)
    assert len(mech.drives) == 2
    assert shared == pytest.approx(single, rel=0.5) and shared < 1.5 * 2 * SLEEP * 1.5
    plain = atcm.PiezoDrive(atcm.signals.Triangle(500.0, 1000.0, 0.5), hysteresis=paper_strain_preisach())
    # the paper's drive is what the cells' measured costs include: at most timing noise beyond it
    assert extra_drive_cost([plain], 1e-4) < 50e-6


def test_a_drive_whose_program_fails_counts_as_the_reference_drive():
    def program(t):
        if t > 0.0:
            raise ZeroDivisionError("a program that fails after t = 0")
        return 0.0

    drive = atcm.PiezoDrive(program)
    assert drive_step_cost(drive, 1e-4) is None  # the estimate never stops a run: the run reports it
    assert extra_drive_cost([drive], 1e-4) == 0.0


def test_an_excess_within_the_noise_counts_as_the_reference(monkeypatch):
    """A drive measured up to NOISE_SHARE above the reference is the reference (a shared machine's
    timings of one drive differ by up to 1.4x); above it, the whole excess counts."""
    monkeypatch.setattr(drive_cost, "reference_drive_cost", lambda step: 10e-6)
    costs = {"like": 14e-6, "dear": 25e-6, "second": 10e-6}
    monkeypatch.setattr(drive_cost, "drive_step_cost", lambda drive, step: costs[drive])
    assert drive_cost.NOISE_SHARE == 0.5
    assert extra_drive_cost(["like"], 1e-4) == 0.0  # 4 µs over: noise
    assert extra_drive_cost(["dear"], 1e-4) == pytest.approx(15e-6)
    assert extra_drive_cost(["like", "second"], 1e-4) == pytest.approx(14e-6)  # a second drive is never noise
