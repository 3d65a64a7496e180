"""The recorders read Exudyn's coordinates through one view taken before the run: that view must stay valid.

Both solve paths take ``mbs.systemData.GetODE2Coordinates(copy=False)`` once and copy from it
after every accepted step (a fresh call costs about 3 us per step).  That is right only while
Exudyn keeps the current coordinates in the same vector for the whole run, step reductions and
rejected steps included.  These tests measure it with Exudyn 1.13 against a fresh read in every
post-step hook; :func:`~exudyn_atcm.mbs.step_record.check_view` refuses a stale view after the run.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.mbs import solver_runs
from exudyn_atcm.model import Triangle, paper_strain_preisach
from exudyn_atcm.mbs.step_record import check_view

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
#: two full Newton iterations at most: steps are rejected and repeated at half the step
REJECTING = {"timeIntegration.newton.maxIterations": 2, "timeIntegration.newton.useModifiedNewton": False}


@pytest.fixture
def fresh_reads(monkeypatch):
    """Every post-step hook also compares a view taken before the run with a fresh copy."""
    seen = {"steps": 0, "stale": 0, "same_memory": True}
    original = solver_runs.run_dynamic

    def run(model, settings, pre_step, post_step):
        view = model.mbs.systemData.GetODE2Coordinates(copy=False)

        def post(t):
            fresh = model.mbs.systemData.GetODE2Coordinates()
            seen["steps"] += 1
            seen["stale"] += int(not np.array_equal(view, fresh))
            seen["same_memory"] &= np.shares_memory(view, model.mbs.systemData.GetODE2Coordinates(copy=False))
            return post_step(t)

        return original(model, settings, pre_step, post)

    monkeypatch.setattr(solver_runs, "run_dynamic", run)
    return seen


def _drive(period=0.01):
    return atcm.PiezoDrive(Triangle(500.0, 1000.0, period), hysteresis=paper_strain_preisach())


@pytest.mark.parametrize("cell", ["rigid", "six-bar", "beam", "ritz"])
def test_an_actuator_run_keeps_the_coordinate_vector_in_place(fresh_reads, cell):
    act = atcm.BendingActuator(3, 0.029, 28e-3, CFC, MFC, _drive(), cell=cell)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # a coarse step for the rejections
        r = atcm.simulate(act, 0.01, step=5e-4, settings=REJECTING)
    if cell in ("rigid", "six-bar"):  # measured: 3 and 23 rejected steps with these settings
        assert r.info["rejected_steps"] > 0
    assert fresh_reads["steps"] == r.info["accepted_steps"] + 1
    assert fresh_reads["stale"] == 0 and fresh_reads["same_memory"]


def test_a_mechanism_run_with_rejected_steps_keeps_the_coordinate_vector_in_place(fresh_reads):
    b = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=3, drive=_drive(0.04), cell="rigid")
    lever = atcm.Link("lever", {"A": (0.03, 0.0), "E": (0.05, 0.0)}, mass=2e-4, inertia=1e-8)
    mech = atcm.Mechanism("m").add(b, lever).ground(b.base).weld(b.tip, lever.point("A"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        r = atcm.simulate(mech, 0.04, step=2e-3, settings={**REJECTING, "timeIntegration.newton.maxIterations": 1})
    assert r.info["rejected_steps"] > 0
    assert fresh_reads["steps"] == r.info["accepted_steps"] + 1
    assert fresh_reads["stale"] == 0 and fresh_reads["same_memory"]


def test_a_stale_view_is_refused():
    exudyn_vector = np.zeros(4)
    with pytest.raises(RuntimeError, match="Exudyn moved its coordinate vector during the run"):
        check_view(np.zeros(4), exudyn_vector)
    check_view(exudyn_vector[:], exudyn_vector)  # a view of the same vector passes
