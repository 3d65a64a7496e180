"""Reported results do not depend on how often a run is recorded (``record_every``).

Every accepted step goes through one preallocated recorder
(:class:`exudyn_atcm.mbs.step_record.StepRecord`); a thinned run keeps the light columns of
every accepted step in :attr:`Result.every_step <exudyn_atcm.Result.every_step>`, and the cases
compute their scalars from it.  The reference is the run that records every step: the solver
and the hysteresis memory do not see the recording interval, so the every-step columns of a
thinned run must equal it exactly (bit for bit), and so must every case scalar.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.casework import load_case
from exudyn_atcm.model import Triangle, paper_strain_preisach
from exudyn_atcm.mbs.step_record import StepRecord

from _cli_helpers import CASES

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
PERIOD = 0.02  # s
T_END = 0.05  # s: 501 steps of 1e-4 s, more than one block of the recorder in the tests below


def _actuator(cell="rigid"):
    return atcm.BendingActuator(3, 0.029, 28e-3, CFC, MFC,
                                atcm.PiezoDrive(Triangle(500.0, 1000.0, PERIOD),
                                                hysteresis=paper_strain_preisach()), cell=cell)


def _mechanism():
    b = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=3,
                    drive=atcm.PiezoDrive(Triangle(500.0, 1000.0, PERIOD), hysteresis=paper_strain_preisach()), cell="rigid")
    lever = atcm.Link("lever", {"A": (0.03, 0.0), "E": (0.05, 0.0)}, mass=2e-4, inertia=1e-8)
    post = atcm.Link("post", {"P": (0.05, -0.01)}, mass=1e-4, inertia=1e-9)
    mech = atcm.Mechanism("m").add(b, lever, post).ground(b.base).weld(b.tip, lever.point("A"))
    mech.ground(post.point("P"))
    mech.spring(lever.point("E"), post.point("P"), 20.0, damping=0.01, name="holder")
    return mech


def _thinned(build, record_every):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # coarse intervals warn: that is tested elsewhere
        return atcm.simulate(build(), T_END, step=1e-4, record_every=record_every)


@pytest.fixture(scope="module")
def actuator_full():
    return atcm.simulate(_actuator(), T_END, step=1e-4)


@pytest.fixture(scope="module")
def mechanism_full():
    return atcm.simulate(_mechanism(), T_END, step=1e-4)


def test_every_step_of_a_full_record_is_the_record_itself(actuator_full, mechanism_full):
    assert actuator_full.every_step is actuator_full
    assert mechanism_full.every_step is mechanism_full
    assert actuator_full.n_rows == mechanism_full.n_rows == 501


@pytest.mark.parametrize("record_every", [7, 0.003, 1.0])
def test_actuator_every_step_columns_equal_the_full_run(actuator_full, record_every):
    thin = _thinned(_actuator, record_every)
    assert thin.n_rows < actuator_full.n_rows
    every = thin.every_step
    assert every.names == ["time", "actuator.voltage", "actuator.strain", "actuator.stroke", "actuator.base_x",
                           "actuator.base_y", "actuator.tip_x", "actuator.tip_y", "actuator.base_angle",
                           "actuator.tip_angle"]
    for name in every:
        np.testing.assert_array_equal(every[name], actuator_full[name], err_msg=name)
    # the record itself: the scheduled rows plus the last, equal to the full run's rows
    rows = np.searchsorted(actuator_full["time"], thin["time"])
    for name in thin:
        np.testing.assert_array_equal(thin[name], actuator_full[name][rows], err_msg=name)
    assert thin["time"][-1] == actuator_full["time"][-1]


@pytest.mark.parametrize("record_every", [7, 1.0])
def test_mechanism_every_step_columns_equal_the_full_run(mechanism_full, record_every):
    thin = _thinned(_mechanism, record_every)
    every = thin.every_step
    assert every.n_rows == mechanism_full.n_rows
    assert "holder.force" in every and "lever.E_y" in every and "crank.tip_angle" in every
    assert not [n for n in every if "cell_angle" in n]  # the light columns: no cell angles
    for name in every:
        np.testing.assert_array_equal(every[name], mechanism_full[name], err_msg=name)
    rows = np.searchsorted(mechanism_full["time"], thin["time"])
    for name in thin:
        np.testing.assert_array_equal(thin[name], mechanism_full[name][rows], err_msg=name)


def test_the_issue_example_reports_the_every_step_scalars():
    """``--set record_every=10`` kept 2 instants and reported tip_y_max_last_cycle = -0.0015 m instead of 0.0157 m."""
    case = load_case(CASES / "paper_bending_actuator.py")
    outputs = {}
    for every in (0.0, 1e-3, 10.0):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # record_every=10 warns (tested elsewhere)
            outputs[every] = case.run({"cell": "rigid", "cycles": 1, "record_every": every, "animation": False})
    reference = outputs[0.0].scalars
    assert reference["tip_y_max_last_cycle"] > 0.015  # the peak of the cycle, not the end of the run
    for every in (1e-3, 10.0):
        assert outputs[every].scalars == reference, every
    assert outputs[10.0].result.n_rows == 2


def test_mechanism_case_scalars_do_not_depend_on_the_interval():
    case = load_case(CASES / "bender_with_lever.py")
    scalars = []
    for every in (0.0, 0.05):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            scalars.append(case.run({"record_every": every, "period": 0.2, "animation": False}).scalars)
    assert scalars[0] == scalars[1]


# ----------------------------------------------------------------------------- the recorder itself

def _record(block_rows, spill_bytes, every=3, reduce=True):
    blocks = []
    record = StepRecord(3, lambda t: round(t) % every == 0,
                        reduce=(lambda rows: rows[:, :2] * 2.0) if reduce else None,
                        on_block=lambda rows: blocks.append(len(rows)), block_rows=block_rows,
                        spill_bytes=spill_bytes)
    for k in range(11):
        row = record.begin(float(k))
        row[1:] = (10.0 * k, 100.0 * k)
        record.end(float(k))
    record.close()
    return record, blocks


@pytest.mark.parametrize("block_rows, spill_bytes", [(4, 1 << 30), (4, 0), (100, 1 << 30), (1, 0)])
def test_step_record_keeps_the_schedule_and_the_last_step(block_rows, spill_bytes):
    record, blocks = _record(block_rows, spill_bytes)
    kept = [0, 3, 6, 9, 10]  # every third step, plus the last one (10) that the schedule skipped
    expected = np.array([[k, 10 * k, 100 * k] for k in kept], dtype=float)
    np.testing.assert_array_equal(record.rows(), expected)
    assert record.spilled == (spill_bytes == 0)
    assert record.accepted == 11 and sum(blocks) == 11
    every = np.array([[2 * k, 20 * k] for k in range(11)], dtype=float)
    np.testing.assert_array_equal(record.every_step(), every)


def test_step_record_without_reduce_has_no_every_step_columns():
    record, _ = _record(4, 1 << 30, every=1, reduce=False)
    assert record.every_step() is None
    assert record.rows().shape == (11, 3)


def test_step_record_refuses_an_empty_row():
    with pytest.raises(ValueError, match="width and block_rows must be >= 1, got 0"):
        StepRecord(0, lambda t: True)
