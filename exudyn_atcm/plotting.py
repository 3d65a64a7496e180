"""PNG plots of a :class:`~exudyn_atcm.result.Result` (matplotlib, headless).

Figures are drawn with matplotlib's object interface on an Agg canvas, so importing or
calling this module never selects or opens a GUI backend.
"""

from __future__ import annotations

import os
from typing import Sequence

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure


def _save(fig: Figure, path: str) -> str:
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=120)
    return path


def chain_shape(result, row: int) -> tuple[np.ndarray, np.ndarray]:
    """Vertices [m] of the passive layer at recorded ``row``, from the per-cell angles.

    Each cell's passive layer is a straight bar of the cell length at its recorded angle,
    starting at the clamp (0, 0).
    """
    names = [n for n in result.names if n.startswith("cell_angle_")]
    if not names:
        raise ValueError("result has no cell_angle_* series to draw the shape from")
    try:
        cell_length = float(result.parameters["cell_length [m]"])
    except KeyError:
        raise ValueError("result.parameters lacks 'cell_length [m]'") from None
    angles = np.array([result[n][row] for n in sorted(names, key=lambda s: int(s.rsplit("_", 1)[1]))])
    x = np.concatenate([[0.0], np.cumsum(cell_length * np.cos(angles))])
    y = np.concatenate([[0.0], np.cumsum(cell_length * np.sin(angles))])
    return x, y


def plot_time_series(result, path: str) -> str:
    """Voltage, stroke and tip displacement over time."""
    t = result["time"]
    fig = Figure(figsize=(7, 7), constrained_layout=True)
    axes = fig.subplots(3, 1, sharex=True)
    axes[0].plot(t, result["voltage"], color="tab:blue")
    axes[0].set_ylabel("voltage U [V]")
    axes[1].plot(t, result["stroke"] * 1e6, color="tab:orange")
    axes[1].set_ylabel("cell stroke x_a [µm]")
    axes[2].plot(t, result["tip_y"] * 1e3, label="tip y", color="tab:green")
    axes[2].plot(t, (result["tip_x"] - result["tip_x"].max()) * 1e3, label="tip x - max(tip x)",
                 color="tab:red", linestyle="--")
    axes[2].set_ylabel("tip displacement [mm]")
    axes[2].set_xlabel("time t [s]")
    axes[2].legend(loc="best")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    return _save(fig, path)


def plot_tip_vs_voltage(result, path: str) -> str:
    """Tip deflection over voltage (the actuator's hysteresis loop)."""
    fig = Figure(figsize=(6, 4.5), constrained_layout=True)
    ax = fig.subplots()
    ax.plot(result["voltage"], result["tip_y"] * 1e3, color="tab:green")
    ax.set_xlabel("voltage U [V]")
    ax.set_ylabel("tip deflection y [mm]")
    ax.grid(True, alpha=0.3)
    return _save(fig, path)


def plot_shapes(result, path: str, rows: Sequence[int] | None = None) -> str:
    """Deformed shape of the passive layer at a few instants (default: 6 evenly spaced)."""
    n = result.n_rows
    if rows is None:
        rows = sorted(set(np.linspace(0, n - 1, min(6, n)).round().astype(int).tolist()))
    fig = Figure(figsize=(7, 4), constrained_layout=True)
    ax = fig.subplots()
    for row in rows:
        x, y = chain_shape(result, row)
        ax.plot(x * 1e3, y * 1e3, marker="o", markersize=3,
                label=f"t = {result['time'][row]:.3g} s, U = {result['voltage'][row]:.0f} V")
    ax.set_xlabel("x along the undeformed actuator [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small", loc="best")
    return _save(fig, path)


def plot_result(result, out_dir: str | os.PathLike, prefix: str = "") -> list[str]:
    """Write ``time_series.png``, ``tip_vs_voltage.png`` and ``shapes.png`` to ``out_dir``.

    Returns the paths written.
    """
    out_dir = os.fspath(out_dir)
    os.makedirs(out_dir, exist_ok=True)
    return [
        plot_time_series(result, os.path.join(out_dir, f"{prefix}time_series.png")),
        plot_tip_vs_voltage(result, os.path.join(out_dir, f"{prefix}tip_vs_voltage.png")),
        plot_shapes(result, os.path.join(out_dir, f"{prefix}shapes.png")),
    ]
