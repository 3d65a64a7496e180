"""A static sweep's result draws its standard plots (its rows are points, not instants: no time series).

``static_sweep(actuator, ...).plot(dir)`` stopped with ``KeyError: no series 'time'`` (the audit of 2026-11-30);
only ``plot_tip_vs_voltage`` took it.  Reference: the sweep's own points, in the shapes' legend.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

from pathlib import Path  # noqa: E402

import exudyn_atcm as atcm  # noqa: E402
from exudyn_atcm.plots import plot_shapes  # noqa: E402

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)


def test_a_static_sweep_draws_its_loop_and_shapes(tmp_path):
    actuator = atcm.BendingActuator(3, 0.01, 0.01, CFC, MFC, atcm.PiezoDrive(0.0), cell="rigid")
    sweep = atcm.static_sweep(actuator, [0.0, 500.0, 1000.0, 500.0, 0.0])
    written = sweep.plot(tmp_path)
    assert [Path(p).name for p in written] == ["tip_vs_voltage.png", "shapes.png"]
    assert all(Path(p).stat().st_size > 0 for p in written)
    labels = [line.get_label() for line in plot_shapes(sweep).axes[0].lines]
    assert labels[0] == "point 0, U = 0 V" and labels[2] == "point 2, U = 1000 V"
