"""``step_error``: the time-step error of a run, estimated by halving the step.

The truth the estimate is checked against is the same model integrated with a 32 times
smaller step (its own step error is 1/1024 of the examined run's, second order).  System: the
compliant four-bar case (4 beam cells, the paper's Preisach loop, a 0.5 s triangle whose kink at
0.25 s starts a lightly damped ringing: the error that decides the step in mechanisms).
"""

from __future__ import annotations

import importlib.util
import math
import pathlib
import warnings

import numpy as np
import pytest

from exudyn_atcm import AccuracyWarning, BendingActuator, Layer, PiezoDrive, simulate, step_error
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.solve.step_error import _common_rows

CASES = pathlib.Path(__file__).resolve().parents[1] / "cases"
CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
STEP = 5e-4  # s
T_END = 0.5  # s
TRACKED = ("coupler.P_x", "coupler.P_y", "crank.tip_angle", "rocker.angle")


def _case_module():
    spec = importlib.util.spec_from_file_location("compliant_four_bar_step_error", CASES / "compliant_four_bar.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


CASE = _case_module()


def four_bar(period: float = 0.5, n_cells: int = 4):
    p = CASE.CASE.resolve({"n_cells": n_cells, "cell": "beam"})
    return CASE.build_mechanism(p, paper_strain_preisach(), Triangle(500.0, 1000.0, period))


@pytest.fixture(scope="module")
def report():
    return step_error(four_bar(), T_END, step=STEP)


@pytest.fixture(scope="module")
def truth():
    return simulate(four_bar(), T_END, step=STEP / 32)


def test_estimate_equals_the_error_against_a_32_times_finer_run(report, truth):
    coarse = simulate(four_bar(), T_END, step=STEP)
    rows = _common_rows([coarse, truth], [STEP, STEP / 32])
    assert len(rows[0]) == round(T_END / STEP) + 1
    for name in TRACKED:
        true_error = float(np.max(np.abs(coarse[name][rows[0]] - truth[name][rows[1]])))
        column = report.columns[name]
        # Richardson's estimate is exact to O(h^2) of the error itself; measured 0.2 %
        assert column.error == pytest.approx(true_error, rel=0.02), name
        assert column.order == pytest.approx(2.0, abs=0.1), name
        assert column.relative == pytest.approx(column.error / np.ptp(report.finest[name]), rel=1e-12)
    # the error is real: about 1e-3 of the range at this step (the benchmark's path error 1.3e-3)
    assert 5e-4 < report.columns["coupler.P_x"].relative < 3e-3


def test_extrapolated_result_is_far_more_accurate_than_the_finest_run(report, truth):
    ex = report.extrapolated
    assert ex.names == report.finest.names and ex.unit("coupler.P_x") == "m"
    assert ex.n_rows == report.compared == round(T_END / STEP) + 1
    assert ex.info["extrapolated_from_steps"] == pytest.approx([STEP / 2, STEP / 4])
    rows = _common_rows([ex, truth], [STEP, STEP / 32])
    fine_rows = _common_rows([report.finest, truth], [STEP / 4, STEP / 32])
    for name in TRACKED:
        span = np.ptp(truth[name])
        extrapolated = float(np.max(np.abs(ex[name][rows[0]] - truth[name][rows[1]]))) / span
        finest = float(np.max(np.abs(report.finest[name][fine_rows[0]] - truth[name][fine_rows[1]]))) / span
        # the h^2 term cancels: measured 2.7e-6 ... 3.8e-6 against 5.7e-5 ... 1.0e-4 for the run at step/4
        # (the truth's own step error is about 1e-6 of the range: 1/1024 of 1e-3)
        assert extrapolated < finest / 10, name
        assert extrapolated < 1e-5, name
    # the voltage is the same program in every run: extrapolation leaves it as it is
    program = Triangle(500.0, 1000.0, 0.5)
    np.testing.assert_allclose(ex["crank.voltage"], [program(t) for t in ex["time"]], rtol=0, atol=1e-9)


def test_suggested_step_meets_its_target_against_the_finer_run(report, truth):
    target = 4e-4
    suggested = report.suggested_step(target, columns=TRACKED)
    assert suggested < STEP
    n = math.ceil(T_END / suggested)
    run = simulate(four_bar(), T_END, step=T_END / n)
    t = np.asarray(run["time"])
    for name in TRACKED:
        reference = np.interp(t, truth["time"], truth[name])  # interpolation error < 1e-6 of the range here
        relative = float(np.max(np.abs(run[name] - reference))) / np.ptp(truth[name])
        assert relative <= target * 1.05, name
    # and the law it came from: a quarter of the error at half the step
    worst = report.worst(TRACKED)
    assert report.suggested_step(worst.relative / 4, columns=TRACKED) == pytest.approx(STEP / 2, rel=1e-12)


def test_summary_is_the_motion_and_the_table_names_the_worst(report):
    units = {c.unit for n, c in report.columns.items() if n in report.summary}
    assert units <= {"m", "rad"}
    assert "crank.voltage" in report.columns and "crank.voltage" not in report.summary
    # the voltage program is sampled identically at the common instants: no step error
    assert report.columns["crank.voltage"].relative < 1e-9
    text = str(report)
    assert report.worst().name in text.splitlines()[-1]
    assert report.to_dict()["columns"]["coupler.P_x"]["unit"] == "m"


def test_a_reversal_between_the_steps_of_every_run_is_flagged():
    # the triangle's peak at 0.10015 s lies between the steps of all three runs, missed by 0.3, 0.4 and
    # 0.2 of their steps: the Preisach memory keeps a reversal that is off by O(h), not O(h^2)
    with pytest.warns(AccuracyWarning, match=r"fall more slowly than h\^1.5"):
        flagged = step_error(four_bar(period=0.2003), 0.2, step=STEP)
    assert flagged.worst().order < 1.5
    # the same program with its peak on the grid: second order, no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", AccuracyWarning)
        clean = step_error(four_bar(period=0.2), 0.2, step=STEP)
    assert clean.columns["coupler.P_x"].order == pytest.approx(2.0, abs=0.15)


def test_lone_actuator_with_a_tip_force_and_without_the_order_check():
    actuator = BendingActuator(3, 29e-3, 28e-3, CFC, MFC, PiezoDrive(Triangle(500.0, 1000.0, 0.1)), cell="beam")
    report = step_error(actuator, 0.05, step=1e-3, check_order=False, tip_force=(0.0, -0.01), columns=["actuator.tip_y"])
    assert report.summary == ["actuator.tip_y"]
    assert math.isnan(report.columns["actuator.tip_y"].order)  # no third run
    assert report.extrapolated is None  # two runs: nothing to check the order of an extrapolation against
    assert report.finest.info["step [s]"] == pytest.approx(5e-4)
    assert report.worst().name == "actuator.tip_y"


@pytest.mark.parametrize("kwargs, match", [
    ({"t_end": -1.0}, "t_end must be > 0"),
    ({"step": 0.0}, "step must be > 0"),
    ({"step": 1.0}, "step must be <= t_end"),
    ({"columns": "tip_y"}, "sequence of column names"),
    ({"columns": []}, "at least one result column"),
    ({"columns": ["tip_z"]}, r"no such result column \['tip_z'\]"),
])
def test_bad_arguments_are_refused_naming_them(kwargs, match):
    actuator = BendingActuator(3, 29e-3, 28e-3, CFC, MFC, PiezoDrive(Triangle(500.0, 1000.0, 0.1)), cell="beam")
    args = {"t_end": 0.02, "step": 1e-3, **kwargs}
    with pytest.raises(ValueError, match=match):
        step_error(actuator, args.pop("t_end"), **args)


def test_bad_target_is_refused(report):
    with pytest.raises(ValueError, match="target must be > 0"):
        report.suggested_step(0.0)
    with pytest.raises(ValueError, match="no such result column"):
        report.worst(["nope"])


def test_step_is_keyword_only_and_the_positional_form_warns_for_one_release():
    # issue 30, part 6: step_error(system, t_end, *, step=...) like simulate; the old positional call
    # runs the same steps (so the same estimate, to the bit) with an AtcmDeprecationWarning
    import inspect

    from exudyn_atcm import AtcmDeprecationWarning

    params = inspect.signature(step_error).parameters
    assert params["step"].kind is inspect.Parameter.KEYWORD_ONLY
    actuator = BendingActuator(3, 29e-3, 28e-3, CFC, MFC, PiezoDrive(Triangle(500.0, 1000.0, 0.1)), cell="beam")
    new = step_error(actuator, 0.02, step=2e-3, check_order=False)
    with pytest.warns(AtcmDeprecationWarning, match=r"step_error\(\): pass step= by keyword"):
        old = step_error(actuator, 0.02, 2e-3, check_order=False)
    assert old.step == new.step == 2e-3
    np.testing.assert_array_equal(old.finest["actuator.tip_angle"], new.finest["actuator.tip_angle"])
    with pytest.raises(TypeError, match="multiple values for argument 'step'"):
        step_error(actuator, 0.02, 2e-3, step=1e-3)
    with pytest.raises(TypeError, match="extra positional arguments"):
        step_error(actuator, 0.02, 2e-3, True)


def test_a_run_that_does_not_move_has_no_relative_error_and_no_order_warning():
    # the drive switched to 1000 V at t = 0 and held: the run starts in that equilibrium and stays there.  The
    # columns' ranges are round-off (the tip's angle: 4e-11 rad), against which the runs' round-off differences
    # were "8.8e-2 of its range" at an "order 0.77", with a warning and a suggested step of 1e-4 s for 1e-3
    # (until 2026-11-29).  Reference: the static equilibrium, where every run stays (solve_static)
    from exudyn_atcm import solve_static
    from exudyn_atcm.model.signals import Steps
    actuator = BendingActuator(3, 29e-3, 28e-3, CFC, MFC, PiezoDrive(Steps([0.0], [1000.0])), cell="rod")
    with warnings.catch_warnings():
        warnings.simplefilter("error", AccuracyWarning)
        report = step_error(actuator, 0.05, step=1e-3)
    assert all(math.isnan(report.columns[name].relative) for name in report.summary)
    with pytest.raises(ValueError, match="none of the columns varies"):
        report.worst()
    static = solve_static(actuator, voltage=1000.0)
    assert np.max(np.abs(report.finest["actuator.tip_y"] - static["actuator.tip_y"][-1])) < 1e-9 * 0.087  # round-off
