"""The actuator plots draw a result read from a file written by hand in mm, ms and kV in SI.

``read_csv`` keeps a file's units as written; the plots' axes are labelled in SI (``voltage U [V]``, ``tip
deflection y [mm]`` from metres), so 1.5 kV was drawn as 1.5 V and 2 mm as 2000 mm.  Reference: the file's
numbers times the units' factors, read back from the plotted line.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

import exudyn_atcm as atcm  # noqa: E402
from exudyn_atcm.plots import plot_tip_vs_voltage  # noqa: E402


def test_a_hand_written_file_in_kv_and_mm_is_drawn_in_volts_and_millimetres(tmp_path):
    path = tmp_path / "h.csv"
    path.write_text("time [ms],actuator.voltage [kV],actuator.tip_y [mm],actuator.tip_x [mm]\n"
                    "0,0,0,40\n50,1.5,2,40\n")
    r = atcm.read_csv(path)
    assert r.unit("actuator.voltage") == "kV"  # the file's units, kept by read_csv
    fig = plot_tip_vs_voltage(r)
    x, y = fig.axes[0].lines[0].get_data()
    np.testing.assert_allclose(x, [0.0, 1500.0])  # V
    np.testing.assert_allclose(y, [0.0, 2.0])  # mm on the axis, from 2e-3 m
