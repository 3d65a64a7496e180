"""From your record to a drive: read, give units, identify, convert to strain, save, drive.

A tutorial script (``docs/identification.rst``, "From your record to a drive"); the test suite
runs it (``tests/test_record_to_drive.py``).  It writes its files into the folder given as the
first argument (default: a temporary folder).

The record stands in for a measurement: a free MFC patch's elongation over a gauge length of
60 mm, measured in micrometres by a laser sensor, written as a header-less text file of three
columns (time, voltage, displacement), as many data loggers export.  Its excitation is the usual
identification signal: cycles from the lowest voltage with peaks growing cycle by cycle.  The
"actuator" is a known Prandtl-Ishlinskii strain operator, so the script can say how close each
step gets (a real record has no truth; its held-out error plays that part).
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm.hysteresis import PrandtlIshlinskii, identify
from exudyn_atcm.model.strain_conversion import model_to_strain

GAUGE = 0.06  # [m] the length over which the patch's elongation is measured
CFC = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)


def the_actuator() -> PrandtlIshlinskii:
    """The patch's true free strain [-] over voltage [V] (unknown in a real measurement)."""
    return PrandtlIshlinskii([0.0, 150.0, 375.0, 600.0], [1.5e-7, 2e-7, 1e-7, 5e-8],
                             4.6e-7).with_output_quantity("strain")


def write_the_record(path: Path) -> Path:
    """A header-less record: time [s], voltage [V], elongation [um]; 0.2 s of rest, then 5 growing cycles."""
    rate, period = 2000.0, 0.5
    peaks = [0.2, 0.4, 0.6, 0.8, 1.0]
    t = np.arange(int(round((0.2 + period * len(peaks)) * rate)) + 1) / rate
    cycle = np.clip(((t - 0.2) / period).astype(int), 0, len(peaks) - 1)
    u = np.where(t < 0.2, 0.0, np.take(peaks, cycle) * 750.0 * (1.0 - np.cos(2.0 * np.pi * (t - 0.2) / period)))
    noise = np.random.default_rng(1).normal(0.0, 0.05, t.size)  # the sensor's noise [um]
    y_um = 1e6 * GAUGE * the_actuator().apply(u) + 3.0 + noise  # 3 um: the sensor's offset
    np.savetxt(path, np.column_stack([t, u, y_um]), fmt="%.6g")
    return path


def main(folder: Path) -> dict[str, float]:
    folder.mkdir(parents=True, exist_ok=True)
    path = write_the_record(folder / "patch.txt")

    # 1. read it, saying what the header-less columns are (the output in micrometres: read as metres)
    record = atcm.read_record(path, units={"time": "s", "input": "V", "output": "um"})
    # 2. remove the sensor's offset: the mean over the rest before the excitation (the first 0.15 s)
    record = atcm.preprocess(record, offset_window=(0.0, 0.15))
    print(record.processing)

    # 3. identify: every family fitted, the held-out cycles lie inside the fitted input range
    choice = identify(record)
    print(choice)
    model = choice.chosen.model  # a displacement model [m]: a drive refuses it as it is

    # 4. convert it to the free strain the drive takes: elongation over the gauge length
    strain_model = model_to_strain(model, gauge_length=GAUGE)

    # 5. save it (JSON: the parameters, units, input range and fit settings), and load it back
    saved = strain_model.save(folder / "patch_model.json")
    loaded = atcm.load_model(saved)

    # 6. drive a bender with it: the static tip deflection at 1200 V, against the true actuator's
    def tip(hysteresis) -> float:
        bender = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=4, cell="rod",
                             drive=atcm.PiezoDrive(0.0, hysteresis=hysteresis))
        mechanism = atcm.Mechanism("lone").add(bender).ground(bender.base)
        return float(atcm.solve_static(mechanism, voltage=1200.0)["b.tip_y"][-1])

    tip_model, tip_truth = tip(loaded), tip(the_actuator())
    figures = {
        "held_out_rms_percent": float(choice.chosen.held_out_rms_percent),
        "tip_model [m]": tip_model,
        "tip_truth [m]": tip_truth,
        "tip_error [-]": abs(tip_model / tip_truth - 1.0),
    }
    print(f"chosen: {choice.chosen.family}; tip at 1200 V {tip_model:.6e} m, the true actuator's "
          f"{tip_truth:.6e} m ({100 * figures['tip_error [-]']:.2f} % apart)")
    return figures


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp(prefix="record_to_drive_")))
