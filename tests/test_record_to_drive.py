"""docs/examples/record_to_drive.py, the walkthrough of docs/identification.rst, runs and lands near the truth.

Its record is a known Prandtl-Ishlinskii strain operator measured as a displacement over 60 mm in
micrometres, with a 3 um offset and 0.05 um of noise: identified, converted, saved and loaded, the
model must drive a bender to the true actuator's tip within the identification's accuracy.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.hysteresis import IdentifyOptions, identify
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.strain_conversion import model_to_strain

EXAMPLE = Path(__file__).resolve().parents[1] / "docs" / "examples" / "record_to_drive.py"


def load_example():
    spec = importlib.util.spec_from_file_location("record_to_drive", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_walkthrough_drives_like_the_true_actuator(tmp_path):
    # pytest turns every package warning into an error: the walkthrough runs without one
    example = load_example()
    figures = example.main(tmp_path)
    # the truth is a PI operator: its family's held-out error is the noise's (0.05 um of an 81 um range:
    # 0.06 %), and the tip at 1200 V follows the truth's to that order (allowed 0.2 %)
    assert figures["held_out_rms_percent"] < 0.2
    assert figures["tip_error [-]"] < 2e-3
    assert (tmp_path / "patch_model.json").is_file()


def test_the_walkthrough_steps_are_each_needed(tmp_path):
    """Without the conversion the drive refuses the displacement model; the saved model is the same operator."""
    example = load_example()
    record = atcm.preprocess(atcm.read_record(example.write_the_record(tmp_path / "r.txt"),
                                              units={"time": "s", "input": "V", "output": "um"}),
                             offset_window=(0.0, 0.15))
    # the offset window recovers the sensor's 3 um to the noise's standard error (0.05 um / sqrt(301))
    offset = [p for p in record.processing if "offset" in p]
    assert offset and abs(float(offset[0].split("offset of ")[1].split(" m")[0]) - 3e-6) < 5 * 0.05e-6 / np.sqrt(301)
    model = identify(record).chosen.model
    with pytest.raises(ValueError, match="displacement"):
        PiezoDrive(0.0, hysteresis=model)
    strain_model = model_to_strain(model, gauge_length=example.GAUGE)
    loaded = atcm.load_model(strain_model.save(tmp_path / "m.json"))
    u = np.concatenate([np.linspace(0, 1400, 50), np.linspace(1400, 300, 30), np.linspace(300, 900, 20)])
    np.testing.assert_array_equal(loaded.apply(u), strain_model.apply(u))
    # against the true strain: within the fit's accuracy (0.2 % of the 1.4e-3 range)
    assert np.max(np.abs(loaded.apply(u) - example.the_actuator().apply(u))) < 2e-3 * 1.4e-3


def test_identify_keeps_the_notes_of_families_it_does_not_choose(tmp_path):
    """The equal-gain construction notes that the noise makes a level's branches cross; identify chooses the PI
    family and keeps that note on the equal-gain candidate (issued, it would ask the user to act on a model they
    do not use).  Asked for the equal-gain family alone, the note is the chosen model's and is issued."""
    example = load_example()
    record = atcm.preprocess(atcm.read_record(example.write_the_record(tmp_path / "r.txt"),
                                              units={"time": "s", "input": "V", "output": "um"}),
                             offset_window=(0.0, 0.15))
    choice = identify(record)
    equal_gain = next(c for c in choice.candidates if c.family == "equal_gain")
    assert choice.chosen.family == "prandtl_ishlinskii" and choice.chosen.notes == ()
    assert any(n.startswith("AccuracyWarning: from_loop:") for n in equal_gain.notes), equal_gain.notes
    assert equal_gain.to_dict()["notes"] == list(equal_gain.notes)
    with pytest.warns(atcm.AccuracyWarning, match=r"identify \(equal_gain .*, chosen\): from_loop:"):
        alone = identify(record, families=("equal_gain",), options=IdentifyOptions(linear_margin=0.0))
    assert alone.chosen.family == "equal_gain"
