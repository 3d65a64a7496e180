"""The identification case on the shipped synthetic record (its noise level is known from the file header)."""

from __future__ import annotations

import warnings

import json

import numpy as np
import pytest

from exudyn_atcm.casework import load_case
from exudyn_atcm.io.measurements import read_record
from exudyn_atcm.model.reference_record import REFERENCE, reference_samples

from _cli_helpers import CASES, run

NOISE = 0.4e-6  # m, the standard deviation written in the record's header


def test_shipped_record_is_what_its_header_says():
    path = CASES / "data" / "preisach_record.csv"
    header = [line for line in path.read_text().splitlines() if line.startswith("#")]
    assert any("NOT a measurement" in line for line in header)
    assert any("standard deviation 4e-07 m" in line for line in header)
    record = read_record(path, time="time", input="voltage", output="displacement")
    assert record.units == {"time": "s", "input": "V", "output": "m"}
    t, u, clean, noisy = reference_samples()
    np.testing.assert_allclose(record.input, u, atol=1e-6)
    np.testing.assert_allclose(record.output, noisy, rtol=1e-6, atol=1e-12)
    # the noise really has the stated level
    assert np.std(record.output - clean) == pytest.approx(NOISE, rel=0.05)
    assert REFERENCE["noise [m]"] == NOISE


def test_identify_and_predict_meets_the_noise_goal(tmp_path):
    proc = run([str(CASES / "identify_and_predict.py"), "--out", "out"], tmp_path)
    assert "warning" not in proc.stderr.lower(), proc.stderr  # a case must not warn on its defaults
    assert proc.returncode == 0, proc.stderr
    out = tmp_path / "out"
    record = json.loads((out / "identify_and_predict.json").read_text())
    s = {k: v["value"] for k, v in record["scalars"].items()}
    # goal of the issue: held-out RMS error within 1.5x the noise level
    assert s["held_out_rms_per_noise"] <= 1.5
    assert s["held_out_rms_relay_grid"] <= 1.5 * NOISE  # the bare relay grid (staircase) too
    # a model error cannot make the RMS error smaller than the noise itself (noise and model
    # error are independent): anything well below 1x would mean a fit to the noise
    assert s["held_out_rms_per_noise"] > 0.9
    assert s["held_out_rms_preisach"] == pytest.approx(s["held_out_rms_per_noise"] * NOISE, rel=1e-9)
    # the variable-gain Preisach fit beats the linear model and the constrained models clearly
    assert s["held_out_rms_linear"] > 5 * s["held_out_rms_preisach"]
    assert s["held_out_rms_equal_gain"] > s["held_out_rms_preisach"]
    report = json.loads((out / "identify_and_predict_fit_report.json").read_text())
    assert report["model_errors"]["held_out"]["rms"] == pytest.approx(s["held_out_rms_preisach"], rel=1e-12)
    assert sorted(p.name for p in out.glob("*.png")) == ["identify_and_predict_loop.png", "identify_and_predict_model_choice.png",
                                                         "identify_and_predict_time.png"]
    # the model-choice table (hysteresis.identify, issue 16): printed, in the notes, its figure above;
    # on this record (a non-PI Preisach density) the spread-cell grid is chosen, within 1.5x the noise
    choice = record["notes"]["model_choice"]
    assert choice["chosen"] == "everett" and "* chosen: everett" in proc.stdout
    assert s["chosen_held_out_rms_percent"] == pytest.approx(100 * s["held_out_rms_preisach"] / choice["output_range"], rel=1e-9)
    assert [c["family"] for c in choice["candidates"]][:2] == ["everett", "discrete"]


def test_tip_tracking_feedforward_plus_pid_beats_linear_inversion_tenfold():
    with warnings.catch_warnings():  # a case must not warn on its defaults
        warnings.simplefilter("error", RuntimeWarning)
        out = load_case(CASES / "tip_tracking.py").run()
    s = {k: (v[0] if isinstance(v, tuple) else v) for k, v in out.scalars.items()}
    # goal of the issue: feedforward + PID at least 10x smaller RMS error than linear inversion
    assert s["rms_error_linear"] >= 10 * s["rms_error_pid_feedforward"]
    # each ingredient alone helps: compensation and feedback both beat linear inversion
    assert s["rms_error_feedforward"] < s["rms_error_linear"]
    assert s["rms_error_pid"] < s["rms_error_linear"]
    assert s["rms_error_pid_feedforward"] < min(s["rms_error_feedforward"], s["rms_error_pid"])
    # the linear inversion's error is the hysteresis: a sizeable part of the ~9 mm swing
    assert s["rms_error_linear"] > 0.3e-3
    assert out.notes["feedforward_program"]["clipped_samples"] == 0
    assert out.notes["controller_pid_feedforward"]["limited_samples"] == 0


# ----------------------------------------------------------------------------- a growing-amplitude record
PLAY_RADII = np.array([0.0, 100.0, 250.0, 400.0])  # V
PLAY_WEIGHTS = np.array([1.0, 1.5, 1.0, 0.5]) * 1e-9  # m/V
PLAY_LINEAR = 2e-9  # m/V
PLAY_NOISE = 2e-9  # m


def play_record(path):
    """Five raised-cosine cycles from 0 V growing to 1000 V (the usual identification excitation), through a
    Prandtl-Ishlinskii operator (plays of the radii above from zero memory plus a linear term) with noise, in µm."""
    t = np.arange(2701) / 1000.0
    cycle = np.clip(((t - 0.2) / 0.5).astype(int), 0, 4)
    u = np.where(t < 0.2, 0.0, np.linspace(0.2, 1.0, 5)[cycle] * 500.0 * (1.0 - np.cos(2.0 * np.pi * (t - 0.2) / 0.5)))
    z = np.zeros(PLAY_RADII.size)
    y = np.empty_like(u)
    for k, x in enumerate(u):
        z = np.maximum(x - PLAY_RADII, np.minimum(x + PLAY_RADII, z))
        y[k] = PLAY_LINEAR * x + PLAY_WEIGHTS @ z
    y += np.random.default_rng(0).normal(0.0, PLAY_NOISE, u.size)
    np.savetxt(path, np.c_[t, u, y * 1e6], delimiter=",", header="time [s],voltage [V],displacement [um]", comments="")


def test_a_growing_amplitude_record_is_identified_on_interleaved_cycles(tmp_path):
    """Eq. 12's equal-gain relays need a whole major loop, which a growing record has only at its end: the
    family is left out with its reason (the case stopped with an AttributeError on it); ``split=cycles``
    holds out whole cycles inside the fitted range, where the Prandtl-Ishlinskii fit recovers the operator
    that made the record to its noise."""
    record = tmp_path / "growing.csv"
    play_record(record)
    case = load_case(CASES / "identify_and_predict.py")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the time split extrapolates (warned): its numbers are not the point here
        by_time = case.run({"record": str(record), "n_levels": 20}, plot=False)
    assert "equal_gain" in by_time.notes["not_fitted"]
    assert "descending" in by_time.notes["not_fitted"]["equal_gain"]
    assert "held_out_rms_equal_gain" not in by_time.scalars and "equal_gain_eq12" not in by_time.notes
    assert by_time.notes["main_model"] == "everett"
    by_cycles = case.run({"record": str(record), "n_levels": 20, "split": "cycles"}, plot=False)
    fitted = by_cycles.result["fitted"]
    assert 0 < fitted.sum() < fitted.size and np.any(np.diff(fitted) > 0)  # held-out cycles between fitted ones
    held_out_pi = by_cycles.scalars["held_out_rms_prandtl_ishlinskii"]
    assert PLAY_NOISE * 0.9 < held_out_pi < PLAY_NOISE * 1.5  # the generating operator's error is the noise
    assert by_cycles.notes["model_choice"]["chosen"] == "prandtl_ishlinskii"


def test_a_fraction_with_a_split_that_chooses_itself_is_refused():
    case = load_case(CASES / "identify_and_predict.py")
    with pytest.raises(ValueError, match=r"split_fraction applies to split='time' only, got split_fraction=0.5"):
        case.run({"split": "cycles", "split_fraction": 0.5}, plot=False)
