"""Plot style and hysteresis plots: Agg-only PNG files with labelled axes and units."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.plots.hysteresis import Curve, plot_loops, plot_relays, plot_time_series
from exudyn_atcm.plots.style import axis_label, display_scale, new_figure, save_figure
from exudyn_atcm.io.result import Result

PNG = b"\x89PNG\r\n\x1a\n"


def test_display_scale_picks_readable_prefixes():
    assert display_scale([4e-5, -4e-6], "m") == (1e6, "µm")
    assert display_scale([0.0155], "m") == (1e3, "mm")
    assert display_scale([0.0216], "m V") == (1e3, "mm V")
    assert display_scale([1500.0], "V") == (1.0, "V")
    assert display_scale([2.0], "m") == (1.0, "m")
    assert axis_label("stroke", "µm") == "stroke [µm]"


def test_save_figure_is_atomic_png(tmp_path):
    fig, (ax,) = new_figure()
    ax.plot([0, 1], [0, 1])
    path = save_figure(fig, tmp_path / "a.png")
    assert path.read_bytes()[:8] == PNG
    assert [p.name for p in tmp_path.iterdir()] == ["a.png"]
    with pytest.raises(ValueError, match="existing directory"):
        save_figure(fig, tmp_path / "missing" / "a.png")


def test_loop_time_and_relay_plots(tmp_path):
    u = np.linspace(-500, 1500, 50)
    loop = tmp_path / "loop.png"
    plot_loops([Curve(u, 2e-8 * (u + 500)), Curve(u, 2.2e-8 * (u + 500), "b", {"linestyle": "--"})], path=loop,
               points=[(500.0, 12e-6, "x_m1")])
    t = np.linspace(0, 1, 50)
    r = Result({"time": t, "voltage": u, "stroke": 1e-6 * t, "stroke_rounded": 1.1e-6 * t}, {"time": "s", "voltage": "V", "stroke": "m", "stroke_rounded": "m"})
    series, relays = tmp_path / "t.png", tmp_path / "r.png"
    plot_time_series(r, [["voltage"], ["stroke", "stroke_rounded"]], path=series)
    plot_relays([0.0, 500.0], [-300.0, 100.0], path=relays, u_min=-500.0, u_max=1500.0)
    for path in (loop, series, relays):
        assert path.read_bytes()[:8] == PNG
    with pytest.raises(ValueError, match="share a unit"):
        plot_time_series(r, [["voltage", "stroke"]], path=tmp_path / "bad.png")
