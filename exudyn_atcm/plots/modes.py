"""Drawings of mode shapes (:func:`plot_modes`) over the deformed state they were taken about."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

import numpy as np

from .._checks import shown
from .style import axis_label
from .target import figure_axes, finish

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure

__all__ = ["plot_modes"]


def _components(points: tuple[str, ...]) -> dict[str, list[int]]:
    """Point indices per component, a bender's in the order base, cells, tip (a polyline along it)."""
    groups: dict[str, list[int]] = {}
    for i, name in enumerate(points):
        groups.setdefault(name.split(".")[0], []).append(i)
    out = {}
    for comp, idx in groups.items():
        names = [points[i].split(".", 1)[1] for i in idx]
        cells = sorted((i for i, n in zip(idx, names) if n.startswith("cell_")),
                       key=lambda i: int(points[i].rsplit("_", 1)[1]))
        if cells:
            base = [i for i, n in zip(idx, names) if n == "base"]
            tip = [i for i, n in zip(idx, names) if n == "tip"]
            others = [i for i, n in zip(idx, names) if n not in ("base", "tip") and not n.startswith("cell_")]
            out[comp] = base + cells + tip + others
        else:
            out[comp] = idx
    return out


def plot_modes(modes: Any, *, ax: Any = None, path: str | os.PathLike | None = None,
               amplitude: float = 0.1) -> Figure:
    """One panel per mode: the mechanism at the equilibrium (grey) and moved by the mode (coloured).

    Parameters
    ----------
    modes : Modes
        From :func:`exudyn_atcm.modes`.
    ax : Axes or sequence of Axes, optional
        One axes per mode to draw into (default: a new figure, one row of panels).
    path : str or path, optional
        Also write the figure as a PNG file.
    amplitude : float, optional
        The largest point displacement drawn, as a share of the mechanism's size (default 0.1): mode
        shapes have no amplitude of their own, so the drawing scales them.

    Returns
    -------
    matplotlib.figure.Figure
    """
    if not (isinstance(amplitude, (int, float)) and 0.0 < amplitude <= 1.0):
        raise ValueError(f"amplitude must be a share of the mechanism's size in (0, 1], got {shown(amplitude)}")
    n = len(modes.frequencies)
    fig, axes = figure_axes(ax, 1, n, width=max(4.0, 3.2 * n), height=3.4)
    pos = np.asarray(modes.positions)
    size = float(np.max(np.ptp(pos, axis=0))) if pos.shape[0] > 1 else 1.0
    size = size if size > 0.0 else 1.0
    groups = _components(modes.points)
    for j, a in enumerate(axes):
        moved = pos + amplitude * size * modes.shapes[j]
        for comp, idx in groups.items():
            a.plot(pos[idx, 0], pos[idx, 1], "-o", color="0.7", ms=2, lw=1)
            a.plot(moved[idx, 0], moved[idx, 1], "-o", ms=3, lw=1.5, label=comp if j == 0 else None)
        a.set_aspect("equal", adjustable="datalim")
        a.set_xlabel(axis_label("x", "m"))
        a.set_ylabel(axis_label("y", "m"))
        a.set_title(f"mode {j + 1}: {modes.frequencies[j]:.4g} Hz")
    if groups:
        axes[0].legend(fontsize="small")
    fig.suptitle(f"modes about {modes.state}", fontsize="medium")
    return finish(fig, path)
