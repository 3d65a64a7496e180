"""A thinned mechanism record closes with the last accepted step.

The mechanism path writes every accepted step's state into a preallocated block in the
post-step hook (:class:`exudyn_atcm.mbs.step_record.StepRecord`), so the last accepted step
is at hand when the run ends however it ends.  An earlier version read that state after the
solve instead; the first tests keep what was measured then about what Exudyn 1.13 leaves
behind after each way a run can end (a fact about Exudyn that any code reading the state
after a run relies on), against the coordinates copied in the post-step hook of the last
accepted step:

* normal end, a post-step hook returning False, a Newton failure at the minimum step: the
  current state is the last accepted one;
* a pre-step hook returning False (Ctrl-C caught there): Exudyn still computes that step and
  calls the post-step hook, so the current state is one step further; the state at the start
  of the last step (``StartOfStep``) is the last accepted one;
* an exception inside a user function during the Newton iteration (Ctrl-C landing in a stop's
  force function): the current state is an iterate; ``StartOfStep`` is the last accepted one.

The other tests compare each way of ending a thinned run against the every-step run of the
same mechanism (the same steps; every column, spring and stop forces included).
"""

from __future__ import annotations

import numpy as np
import pytest
import exudyn as exu

from exudyn_atcm import Bender, Layer, Mechanism, PiezoDrive, simulate
from exudyn_atcm.mbs import builder as mb
from exudyn_atcm.mbs import loads as mbs_loads
from exudyn_atcm.mbs import solver_runs as runs
from exudyn_atcm.mbs import solver_settings
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.solve.run_checks import SimulationInterrupted
from exudyn_atcm.model.signals import Triangle

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W = 28e-3
T_END, STEP = 0.01, 1e-4
#: the run is stopped during the step ending at t = 0.0046 s: the last accepted step is k = 45
#: (t = 0.0045 s), which record_every = 7 skips (records at k = 0, 7, ..., 42)
T_STOP, LAST = 0.00455, 45


def _mechanism(program, cell="rigid") -> Mechanism:
    """Two cantilevers joined at their tips by a damped spring; bender 'a' presses on a damped stop.

    Bender 'a' bends up by ~1 mm within the run and meets the wall at y = 0.2 mm: the stop's
    force and the spring's damping force (velocity dependent) are non-zero at the end.
    """
    a = Bender("a", width=W, passive=CFC, active=MFC, length=0.087, n_cells=3, cell=cell,
               drive=PiezoDrive(program, hysteresis=paper_strain_preisach()))
    b = Bender("b", width=W, passive=CFC, active=MFC, length=0.087, n_cells=3, cell=cell,
               drive=PiezoDrive(0.0), base=(0.0, 0.02))
    mech = Mechanism("pair").add(a, b).ground(a.base).ground(b.base)
    mech.spring(a.tip, b.tip, 50.0, damping=0.05, name="link")
    mech.stop(a.tip, position=(0.087, 2e-4), normal=(0.0, -1.0), stiffness=2e3, damping=0.5, name="wall")
    return mech


def _triangle():
    return Triangle(500.0, 1000.0, 0.02)


def _assert_row_equals(partial, full, row):
    assert list(partial) == list(full)
    for name in full:
        # the same accepted steps in the same order: identical numbers, not only close ones
        assert partial[name][-1] == full[name][row], name


@pytest.fixture(scope="module")
def full_run():
    return simulate(_mechanism(_triangle()), T_END, step=STEP)


# ----------------------------------------------------------------------------- Exudyn's state after a run

def _model(cell):
    b = Bender("a", width=W, passive=CFC, active=MFC, length=0.087, n_cells=3, drive=PiezoDrive(0.0), cell=cell)
    mech = Mechanism("m").add(b).ground(b.base)
    mech.stop(b.tip, position=(0.087, -1.0), normal=(0.0, 1.0), stiffness=1e3, name="wall")  # never touched
    model = mb.build(mech)
    model.ramp_loads, model.load_factor = False, 1.0
    return model


@pytest.mark.parametrize("cell", ["rigid", "six-bar"])
@pytest.mark.parametrize("ending", ["normal", "post_false", "pre_false", "newton_failure", "exception_in_newton"])
def test_exudyn_state_after_the_run(cell, ending):
    model = _model(cell)
    settings = solver_settings.dynamic_settings(T_END, STEP)
    seen = {"accepted": 0, "t": None, "q": None, "stop": False}

    def strain(t):
        if ending == "newton_failure" and t > 0.005:
            return 0.5  # a motor stroke jump no step can follow
        return 1e-3 * min(t / 0.005, 1.0)

    def pre(t):
        model.set_strains(np.array([strain(t)]))
        if ending == "pre_false" and seen["accepted"] >= 40:
            return False
        return None

    def post(t):
        seen["accepted"] += 1
        seen["t"], seen["q"] = t, np.array(model.coordinates())
        if seen["accepted"] >= 40:
            seen["stop"] = True
        if ending == "post_false" and seen["stop"]:
            return False
        return None

    if ending == "exception_in_newton":
        calls = {"n": 0}

        def raising(mbs, t, item, displacement, velocity, k, d, offset):
            if seen["stop"]:
                calls["n"] += 1
                if calls["n"] >= 3:  # the third evaluation of the step: inside its Newton iteration
                    raise KeyboardInterrupt
            return [0.0, 0.0, 0.0]

        model.mbs.SetObjectParameter(model.spring_items["wall"], "springForceUserFunction", raising)
    if ending == "newton_failure":
        settings.timeIntegration.minimumStepSize = STEP / 8  # fail after three halvings
    failed = None
    try:
        runs.run_dynamic(model, settings, pre, post)
    except runs.ExudynFailure as exc:
        failed = exc
    current = np.array(model.coordinates())
    start = np.array(model.mbs.systemData.GetODE2Coordinates(configuration=exu.ConfigurationType.StartOfStep))
    last = seen["q"]
    if ending == "normal":
        assert failed is None and seen["t"] == pytest.approx(T_END)
        np.testing.assert_array_equal(current, last)
    elif ending == "post_false":
        assert failed is None and seen["accepted"] == 40
        np.testing.assert_array_equal(current, last)
    elif ending == "newton_failure":
        assert failed is not None and 0.005 < failed.time < T_END
        np.testing.assert_array_equal(current, last)
    elif ending == "pre_false":
        # Exudyn completed the step whose pre-step said stop and called the post-step hook for
        # it: a caller that refuses that step finds it in the current state (next test)
        assert failed is None and seen["accepted"] == 41
        np.testing.assert_array_equal(current, last)
    else:
        assert failed is not None and "KeyboardInterrupt" in str(failed)
        assert np.max(np.abs(current - last)) > 1e-6  # a Newton iterate (or predictor), not the last step
        np.testing.assert_array_equal(start, last)


def test_exudyn_start_of_step_is_the_step_before_after_a_pre_step_stop():
    model = _model("rigid")
    states = []

    def pre(t):
        model.set_strains(np.array([1e-3 * min(t / 0.005, 1.0)]))
        return False if len(states) >= 40 else None

    def post(t):
        states.append((np.array(model.coordinates()), model.connector_forces()))

    runs.run_dynamic(model, solver_settings.dynamic_settings(T_END, STEP), pre, post)
    assert len(states) == 41  # the stop came from step 41's pre-step; Exudyn finished that step
    current = np.array(model.coordinates())
    np.testing.assert_array_equal(current, states[-1][0])
    assert np.max(np.abs(current - states[-2][0])) > 1e-6
    restore_start_of_step(model)
    np.testing.assert_array_equal(np.array(model.coordinates()), states[-2][0])


def restore_start_of_step(model) -> None:
    """Make Exudyn's state at the start of the last computed step the current state."""
    data = model.mbs.systemData
    state = data.GetSystemState(configuration=exu.ConfigurationType.StartOfStep)
    data.SetSystemState(systemStateList=state, configuration=exu.ConfigurationType.Current)


# ----------------------------------------------------------------------------- end to end

def test_normal_end_closes_the_record_with_the_last_step(full_run):
    thin = simulate(_mechanism(_triangle()), T_END, step=STEP, record_every=7)
    idx = list(range(0, 101, 7)) + [100]
    assert thin.n_rows == len(idx)
    assert abs(full_run["wall.force"][-1]) > 1e-3 and abs(full_run["link.force"][-1]) > 1e-4
    for name in full_run:
        np.testing.assert_array_equal(thin[name], full_run[name][idx], err_msg=name)


def test_interrupt_in_the_post_step_closes_with_the_last_accepted_step(full_run):
    def progress(t, t_end):
        if t >= T_STOP:
            raise KeyboardInterrupt

    with pytest.raises(SimulationInterrupted) as info:
        simulate(_mechanism(_triangle()), T_END, step=STEP, record_every=7, progress=progress)
    partial = info.value.result
    # the progress call of step 46 (t = 0.0046 s) raises, after the step was accepted and
    # committed: that step, skipped by the schedule, closes the record
    assert partial["time"][-1] == pytest.approx((LAST + 1) * STEP, abs=1e-15)
    assert info.value.time == partial["time"][-1]
    _assert_row_equals(partial, full_run, LAST + 1)


def test_interrupt_in_the_pre_step_closes_with_the_last_accepted_step(full_run):
    triangle = _triangle()

    def program(t):  # Ctrl-C while the voltage of the step ending at 0.0046 s is computed
        if t > T_STOP:
            raise KeyboardInterrupt
        return triangle(t)

    with pytest.raises(SimulationInterrupted) as info:
        simulate(_mechanism(program), T_END, step=STEP, record_every=7)
    partial = info.value.result
    # Exudyn computed one more step (with the previous step's strain) after the pre-step said
    # stop; the record still ends with step 45 as the every-step run has it
    assert partial["time"][-1] == pytest.approx(LAST * STEP, abs=1e-15)
    assert partial.n_rows == 7 + 1
    _assert_row_equals(partial, full_run, LAST)


def test_interrupt_inside_newton_closes_with_the_last_accepted_step(full_run, monkeypatch):
    original = mbs_loads._stop_force
    armed = {"on": False, "calls": 0}

    def stop_force(normal, stiffness, damping):
        force = original(normal, stiffness, damping)

        def interrupted(mbs, t, *args):
            if armed["on"]:
                armed["calls"] += 1
                if armed["calls"] == 3:  # one Ctrl-C, landing in the stop's force function in step 46's Newton iteration
                    raise KeyboardInterrupt
            return force(mbs, t, *args)

        return interrupted

    def progress(t, t_end):  # armed after step 45 was accepted and recorded as pending
        armed["on"] = armed["on"] or t >= LAST * STEP - 1e-12

    monkeypatch.setattr(mbs_loads, "_stop_force", stop_force)
    with pytest.raises(SimulationInterrupted) as info:
        simulate(_mechanism(_triangle()), T_END, step=STEP, record_every=7, progress=progress)
    partial = info.value.result
    # the third call falls in the Newton iteration of step 46 or 47 (the number of iterations
    # per step varies); either way the last accepted step is skipped by the schedule and
    # closes the record as the every-step run has it
    last = int(round(partial["time"][-1] / STEP))
    assert armed["calls"] >= 3 and last in (LAST, LAST + 1) and last % 7 != 0
    _assert_row_equals(partial, full_run, last)
