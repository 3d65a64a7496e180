"""The cases that choose their time step for an accuracy (``paper_bending_actuator``, ``bender_with_lever``):
step 0 means "chosen for ``accuracy``", ``--set step=...`` fixes it, the JSON says which step and why."""

from __future__ import annotations

import json

import numpy as np
import pytest

from exudyn_atcm.casework import load_case

from _cli_helpers import CASES

#: Short runs (one 0.2 s period): the choice and its check are those of the defaults, at a fraction of the cost.
SHORT = {
    "paper_bending_actuator": {"cell": "rigid", "period": 0.2, "cycles": 1, "animation": False},
    "bender_with_lever": {"period": 0.2, "animation": False},
}
#: The position columns [m] compared with a fine reference, and the travel they are relative to.
POSITIONS = {
    "paper_bending_actuator": ("actuator.tip_x", "actuator.tip_y"),
    "bender_with_lever": ("bender.tip_x", "bender.tip_y", "lever.end_x", "lever.end_y"),
}


def _error_against(run, reference, names) -> float:
    """Largest difference of ``names`` at ``run``'s accepted steps against ``reference`` (a run at a step that divides
    the run's, so the instants coincide), relative to the largest range among them in the reference."""
    fine, coarse = reference.every_step, run.every_step
    rows = np.searchsorted(fine["time"], coarse["time"])
    assert np.allclose(fine["time"][rows], coarse["time"], rtol=0.0, atol=1e-12)
    travel = max(float(np.ptp(fine[n])) for n in names)
    return max(float(np.max(np.abs(coarse[n] - fine[n][rows]))) for n in names) / travel


@pytest.mark.parametrize("name", ["paper_bending_actuator", "bender_with_lever"])
def test_the_default_step_is_chosen_for_the_accuracy_and_meets_it(name):
    case = load_case(CASES / f"{name}.py")
    assert case.resolve({})["step"] == 0.0 and case.resolve({})["accuracy"] == 1e-3
    out = case.run(SHORT[name])
    step = out.notes["step [s]"]
    assert out.result.info["step [s]"] == step
    assert out.notes["step_choice"].startswith(f"step {step:.4g} s") and "probe at" in out.notes["step_choice"]
    assert step > 1e-4  # coarser than the former fixed step: the point of choosing it
    # the run's own error against a run at an eighth of its step (time-converged to ~1/40 of it: second order)
    reference = case.run({**SHORT[name], "step": step / 8})
    assert _error_against(out.result, reference.result, POSITIONS[name]) <= 1e-3


@pytest.mark.parametrize("name", ["paper_bending_actuator", "bender_with_lever"])
def test_a_given_step_is_used_and_said_so(name):
    case = load_case(CASES / f"{name}.py")
    out = case.run({**SHORT[name], "step": 1e-4})
    assert out.notes["step [s]"] == 1e-4 == out.result.info["step [s]"]
    assert out.notes["step_choice"] == "given (--set step=...)"
    assert "accuracy" not in out.result.info


@pytest.mark.parametrize("name", ["paper_bending_actuator", "bender_with_lever"])
def test_a_step_with_another_accuracy_is_refused(name):
    case = load_case(CASES / f"{name}.py")
    with pytest.raises(ValueError, match=r"give step or accuracy, not both: step=0.0001 s .* accuracy=0.0001"):
        case.run({**SHORT[name], "step": 1e-4, "accuracy": 1e-4})


def test_an_accuracy_out_of_range_is_refused_before_the_run():
    case = load_case(CASES / "bender_with_lever.py")
    with pytest.raises(ValueError, match=r"accuracy must be >= 1e-06 and <= 0.1, got 0.5"):
        case.resolve({"accuracy": 0.5})


def test_the_json_summary_holds_the_step_and_why(tmp_path):
    case = load_case(CASES / "bender_with_lever.py")
    out = case.run(SHORT["bender_with_lever"], out_dir=tmp_path, plot=False)
    record = json.loads((tmp_path / "bender_with_lever.json").read_text())
    assert record["notes"]["step [s]"] == out.result.info["step [s]"]
    assert record["notes"]["step_choice"] == out.result.info["step_choice"]
    assert record["parameters"]["accuracy"] == {"value": 1e-3, "unit": "-"}


def test_the_regression_benchmarks_pin_the_step_of_their_references():
    # their stored references were recorded at 1e-4 s: the benchmarks must not follow the accuracy choice
    for name, bench in (("bender_with_lever", "bender_with_lever"), ("paper_bending_actuator", "bending_actuator_fig12")):
        case = load_case(CASES / f"{name}.py")
        entry = next(b for b in case.benchmarks if b["id"] == bench)
        assert entry["parameters"]["step"] == 1e-4
