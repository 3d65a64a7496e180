"""Plots of hysteresis loops and unit-tagged time series, saved as PNG (no display needed).

All functions write one PNG file atomically and return its path; axes are labelled
``quantity [unit]`` and small SI quantities are shown with a prefix (e.g. stroke in µm).
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .style import axis_label, display_scale, new_figure, save_figure
from ..io.result import Result

__all__ = ["Curve", "plot_loops", "plot_time_series", "plot_relays"]


@dataclass
class Curve:
    """One line of a plot: x and y values, legend label and matplotlib style keywords."""

    x: Sequence[float] | np.ndarray
    y: Sequence[float] | np.ndarray
    label: str = ""
    style: Mapping[str, object] = field(default_factory=dict)


def plot_loops(
    path: str | os.PathLike,
    curves: Sequence[Curve],
    *,
    x_name: str = "voltage",
    x_unit: str = "V",
    y_name: str = "stroke",
    y_unit: str = "m",
    points: Sequence[tuple[float, float, str]] = (),
    title: str = "",
) -> Path:
    """Input-output (X-Y) plot of one or more hysteresis loops.

    Parameters
    ----------
    path : str or os.PathLike
        PNG file to write.
    curves : sequence of Curve
        Loops, in SI units (x in ``x_unit``, y in ``y_unit``).
    x_name, x_unit, y_name, y_unit : str
        Axis quantities and SI units.
    points : sequence of (x, y, label)
        Marked points (e.g. the precision points of the continuous model).
    title : str
        Figure title.
    """
    fig, (ax,) = new_figure(1, height=4.2)
    all_y = np.concatenate([np.asarray(c.y, dtype=float) for c in curves] + [np.array([p[1] for p in points], dtype=float)])
    factor, unit = display_scale(all_y, y_unit)
    for curve in curves:
        ax.plot(np.asarray(curve.x, dtype=float), factor * np.asarray(curve.y, dtype=float), label=curve.label, **dict(curve.style))
    for x, y, label in points:
        ax.plot([x], [factor * y], "o", color="black", markersize=4)
        ax.annotate(label, (x, factor * y), textcoords="offset points", xytext=(5, -10), fontsize=8)
    ax.set_xlabel(axis_label(x_name, x_unit))
    ax.set_ylabel(axis_label(y_name, unit))
    if title:
        ax.set_title(title)
    if any(c.label for c in curves):
        ax.legend(loc="upper left")
    return save_figure(fig, path)


def plot_time_series(
    path: str | os.PathLike,
    result: Result,
    groups: Sequence[Sequence[str]],
    *,
    time: str = "time",
    labels: Mapping[str, str] | None = None,
    title: str = "",
) -> Path:
    """Time series of a :class:`~exudyn_atcm.io.result.Result`, one panel per group of series.

    Parameters
    ----------
    path : str or os.PathLike
        PNG file to write.
    result : Result
        The series, with their units.
    groups : sequence of sequence of str
        Series names per panel; the series of one panel must share a unit.
    time : str
        Name of the time series [s].
    labels : mapping, optional
        Legend label per series name (default: the name).
    title : str
        Figure title.
    """
    labels = dict(labels or {})
    fig, axes = new_figure(len(groups), sharex=True, height=2.2 * len(groups) + 0.6)
    t = result[time]
    for ax, names in zip(axes, groups):
        units = {result.unit(n) for n in names}
        if len(units) != 1:
            raise ValueError(f"groups: the series {list(names)} of one panel must share a unit, got {sorted(units)}")
        unit = units.pop()
        factor, shown = display_scale(np.concatenate([result[n] for n in names]), unit)
        for name in names:
            ax.plot(t, factor * result[name], label=labels.get(name, name))
        ax.set_ylabel(axis_label(_common_name(names), shown))
        if len(names) > 1:
            ax.legend(loc="best")
    axes[-1].set_xlabel(axis_label(time, result.unit(time)))
    if title:
        axes[0].set_title(title)
    return save_figure(fig, path)


def _common_name(names: Sequence[str]) -> str:
    """``stroke`` for ``stroke`` and ``stroke_rounded``; ``value`` if the names share nothing."""
    if len(names) == 1:
        return names[0]
    prefix = os.path.commonprefix(list(names)).rstrip("_")
    return prefix or "value"


def plot_relays(
    path: str | os.PathLike,
    alpha: Sequence[float],
    beta: Sequence[float],
    *,
    u_min: float,
    u_max: float,
    unit: str = "V",
    title: str = "",
) -> Path:
    """Relays of a discrete Preisach model as points on the Preisach plane (beta, alpha).

    Parameters
    ----------
    path : str or os.PathLike
        PNG file to write.
    alpha, beta : sequence of float
        Switch-on and switch-off thresholds, in ``unit``.
    u_min, u_max : float
        Input range drawn as the Preisach triangle.
    """
    fig, (ax,) = new_figure(1, width=4.6, height=4.2)
    ax.plot([u_min, u_max, u_min, u_min], [u_min, u_max, u_max, u_min], color="0.5", linewidth=1.0, label="Preisach triangle")
    ax.plot(np.asarray(beta, dtype=float), np.asarray(alpha, dtype=float), "s", label="relays")
    for i, (a, b) in enumerate(zip(alpha, beta), start=1):
        ax.annotate(str(i), (b, a), textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax.set_xlabel(axis_label("switch-off threshold beta", unit))
    ax.set_ylabel(axis_label("switch-on threshold alpha", unit))
    ax.set_aspect("equal")
    if title:
        ax.set_title(title)
    ax.legend(loc="lower right")
    return save_figure(fig, path)
