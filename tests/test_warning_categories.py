"""The package's warning categories (issue 17, part 2): every warning is an ``AtcmWarning`` of a
documented kind, the test suite turns them into errors, messages quote the step as given, and a
case run shows each distinct warning once.

References: the source itself (every ``warnings.warn`` call, read with ``ast``), the step
arithmetic ``t_end / ceil(t_end / step)`` (1 s / ceil(1 / 0.3) = 0.25 s; 1 s / ceil(1 / 0.03) =
1/34 s) and the triangle of Eq. 11 (ramps of half the period).
"""

from __future__ import annotations

import ast
import pathlib
import warnings

import numpy as np
import pytest

import exudyn_atcm
from exudyn_atcm import errors
from exudyn_atcm.casework import Case, CaseOutput, Parameter
from exudyn_atcm.io.result import Result
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.signals import Constant, Triangle
from exudyn_atcm.solve import simulate
from exudyn_atcm.solve.run_checks import check_step_against_frequency, time_grid

from _actuator_geometries import REF_A

PACKAGE = pathlib.Path(exudyn_atcm.__file__).resolve().parent
CATEGORIES = ("InputRangeWarning", "AccuracyWarning", "StabilityWarning", "OutOfReachWarning", "RunCostWarning",
              "SetupWarning", "SuspectFileWarning", "AtcmDeprecationWarning")


def _warn_calls():
    """(file:line, category name) of every ``warnings.warn(...)`` call in the package."""
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "warn"
                    and isinstance(node.func.value, ast.Name) and node.func.value.id == "warnings"):
                category = node.args[1] if len(node.args) > 1 else next(
                    (k.value for k in node.keywords if k.arg == "category"), None)
                name = category.id if isinstance(category, ast.Name) else ast.dump(category) if category else None
                yield f"{path.relative_to(PACKAGE)}:{node.lineno}", name


def test_every_package_warning_has_a_package_category():
    calls = list(_warn_calls())
    assert len(calls) >= 35  # about 40 calls when this was written: the scan finds them
    # two places issue warnings again that were caught with their own category (each checked where it is first
    # issued): identify, the chosen family's fit warnings; simulate(accuracy=), the chosen run's warnings
    passed_on = {"hysteresis/model_choice.py:": "category",
                 "solve/step_choice.py:": "Attribute(value=Name(id='w', ctx=Load()), attr='category', ctx=Load())"}
    wrong = [(where, name) for where, name in calls
             if name not in CATEGORIES and not any(where.startswith(f) and name == n for f, n in passed_on.items())]
    assert not wrong, wrong


def test_the_categories_are_exported_and_keep_the_old_ones():
    for name in CATEGORIES:
        cls = getattr(exudyn_atcm, name)
        assert cls is getattr(errors, name) and name in exudyn_atcm.__all__
        assert issubclass(cls, errors.AtcmWarning) and issubclass(cls, UserWarning)
    # filters and tests written for RuntimeWarning / DeprecationWarning keep working
    for name in CATEGORIES[:-1]:
        assert issubclass(getattr(errors, name), RuntimeWarning)
    assert issubclass(errors.AtcmDeprecationWarning, DeprecationWarning)
    # the old import path of SuspectFileWarning is the same class
    from exudyn_atcm.io.file_checks import SuspectFileWarning

    assert SuspectFileWarning is errors.SuspectFileWarning


def test_the_suite_turns_package_warnings_into_errors():
    # setup.cfg [tool:pytest] filterwarnings = error::exudyn_atcm.errors.AtcmWarning
    with pytest.raises(errors.AccuracyWarning, match="unexpected"):
        warnings.warn("unexpected", errors.AccuracyWarning)
    with pytest.warns(RuntimeWarning, match="not the package's"):  # a warning, not an error
        warnings.warn("a plain RuntimeWarning is not the package's", RuntimeWarning)


# ----------------------------------------------------------------------------- the step as given
def _triangle_actuator(period: float):
    return REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, period)), cell="rigid")


def test_a_refused_step_is_quoted_as_given_with_the_step_used():
    # issue 17: step=0.3 was refused quoting 0.25 s, the step that divides t_end = 1 s
    act = _triangle_actuator(1.0)
    with pytest.warns(errors.AccuracyWarning, match=r"step = 0\.3 s does not divide t_end = 1\.0 s"):
        with pytest.raises(ValueError) as info:
            simulate(act, 1.0, step=0.3)
    message = str(info.value)
    # ramps of 0.5 s (half the period), 2 steps of 0.25 s each
    assert message.startswith("step = 0.3 s (used: 0.25 s, so that it divides t_end = 1 s) is too coarse")
    assert "lasts 0.5 s, only 2 steps" in message and "Use step <= 0.125 s" in message


def test_a_step_that_divides_the_run_is_quoted_alone():
    act = _triangle_actuator(1.0)
    with pytest.raises(ValueError, match=r"^step = 0\.25 s is too coarse"):
        simulate(act, 1.0, step=0.25)


def test_the_frequency_warning_quotes_the_step_as_given():
    grid = time_grid(1.0, 0.03, warn=False)
    assert grid.n_steps == 34 and grid.step == 1.0 / 34
    # f1 = 50 Hz: period 0.02 s, 0.68 steps of 1/34 s
    with pytest.warns(errors.AccuracyWarning) as record:
        check_step_against_frequency(grid, 50.0)
    (message,) = [str(w.message) for w in record]
    assert message.startswith("step = 0.03 s (used: 0.0294118 s, so that it divides t_end = 1 s) resolves "
                              "the first bending mode (f1 = 50 Hz, period 0.02 s) with only 0.68 steps")


def test_simulate_quotes_the_step_as_given_in_its_frequency_warning():
    act = REF_A.actuator(PiezoDrive(Constant(500.0)), cell="rigid")  # f1 = 35.97 Hz (beam theory)
    with pytest.warns(errors.AccuracyWarning) as record:
        simulate(act, 0.1, step=0.03)  # 4 steps of 0.025 s
    texts = [str(w.message) for w in record]
    assert any(t.startswith("step = 0.03 s does not divide t_end = 0.1 s") for t in texts), texts
    # the actuator is solved as its one-bender mechanism "actuator": the mechanism's words
    assert any(t.startswith("step = 0.03 s (used: 0.025 s, so that it divides t_end = 0.1 s) resolves the "
                            "first bending mode of bender 'actuator' (clamped-free estimate) (f1 = 35.97 Hz")
               for t in texts), texts
    assert len(texts) == 2


# ----------------------------------------------------------------------------- once per run
def _repeating_case() -> Case:
    def run(p, ctx):
        for _ in range(5):
            warnings.warn("the same note", errors.AccuracyWarning)  # one line, five times
        warnings.warn("the same  note", errors.AccuracyWarning)  # another line, same text up to spaces
        for k in range(2):
            warnings.warn(f"note {k}", errors.AccuracyWarning)  # two different texts
        warnings.warn("the same note", errors.SetupWarning)  # same text, other category
        return CaseOutput(Result({"x": np.array([1.0])}, {"x": "-"}), steps=1)

    return Case("repeating", "A case warning the same thing six times.", [Parameter("a", 1.0)], run)


def test_a_case_run_shows_each_distinct_warning_once():
    case = _repeating_case()
    with pytest.warns(errors.AtcmWarning) as record:
        with warnings.catch_warnings():
            warnings.simplefilter("always")  # the worst case: every call reaches the display
            case.run()
    shown = [(w.category, str(w.message)) for w in record]
    assert shown == [(errors.AccuracyWarning, "the same note"), (errors.AccuracyWarning, "note 0"),
                     (errors.AccuracyWarning, "note 1"), (errors.SetupWarning, "the same note")]


def test_an_error_filter_still_raises_in_a_case_run():
    with pytest.raises(errors.AccuracyWarning, match="the same note"):
        _repeating_case().run()
