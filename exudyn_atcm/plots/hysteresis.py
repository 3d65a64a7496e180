"""Plots of hysteresis loops and unit-tagged time series, saved as PNG (no display needed).

Each function draws into a new figure or the caller's ``ax`` and returns the figure; with ``path`` it
also writes a PNG file atomically (:mod:`exudyn_atcm.plots.target`); axes are labelled
``quantity [unit]`` and small SI quantities are shown with a prefix (e.g. stroke in µm).
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .style import axis_label, display_scale
from .target import figure_axes, finish, is_path, warn_path_form
from ..io.result import Result

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure

__all__ = ["Curve", "plot_loops", "plot_time_series", "plot_relays"]


@dataclass
class Curve:
    """One line of a plot: x and y values, legend label and matplotlib style keywords."""

    x: Sequence[float] | np.ndarray
    y: Sequence[float] | np.ndarray
    label: str = ""
    style: Mapping[str, object] = field(default_factory=dict)


def plot_loops(
    curves: Sequence[Curve],
    *legacy: Any,
    ax: Any = None,
    path: str | os.PathLike | None = None,
    x_name: str = "voltage",
    x_unit: str = "V",
    y_name: str = "stroke",
    y_unit: str = "m",
    points: Sequence[tuple[float, float, str]] = (),
    title: str = "",
) -> Figure:
    """Input-output (X-Y) plot of one or more hysteresis loops.

    Parameters
    ----------
    curves : sequence of Curve
        Loops, in SI units (x in ``x_unit``, y in ``y_unit``).
    ax : matplotlib Axes, optional
        Draw into this axes instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    x_name, x_unit, y_name, y_unit : str
        Axis quantities and SI units.
    points : sequence of (x, y, label)
        Marked points (e.g. the precision points of the continuous model).
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.  The earlier ``plot_loops(path, curves, ...)`` still works for one
        release (with an :class:`~exudyn_atcm.AtcmDeprecationWarning`) and returns the path.
    """
    if is_path(curves):  # the earlier plot_loops(path, curves, ...)
        old, (curves,) = _shift("plot_loops", curves, legacy, 1, path)
        plot_loops(curves, ax=ax, path=old, x_name=x_name, x_unit=x_unit, y_name=y_name, y_unit=y_unit,
                   points=points, title=title)
        return Path(old)
    _no_extra("plot_loops", legacy)
    fig, (ax,) = figure_axes(ax, 1, height=4.2)
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
    return finish(fig, path)


def plot_time_series(
    result: Result,
    groups: Sequence[Sequence[str]],
    *legacy: Any,
    ax: Any = None,
    path: str | os.PathLike | None = None,
    time: str = "time",
    labels: Mapping[str, str] | None = None,
    title: str = "",
) -> Figure:
    """Time series of a :class:`~exudyn_atcm.io.result.Result`, one panel per group of series.

    Parameters
    ----------
    result : Result
        The series, with their units.
    groups : sequence of sequence of str
        Series names per panel; the series of one panel must share a unit.
    ax : sequence of matplotlib Axes, optional
        Draw into these panels (one per group) instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    time : str
        Name of the time series [s].
    labels : mapping, optional
        Legend label per series name (default: the name).
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.  The earlier ``plot_time_series(path, result, groups, ...)`` still works
        for one release (with an :class:`~exudyn_atcm.AtcmDeprecationWarning`) and returns the path.
    """
    if is_path(result):  # the earlier plot_time_series(path, result, groups, ...)
        old, (result, groups) = _shift("plot_time_series", result, (groups, *legacy), 2, path)
        plot_time_series(result, groups, ax=ax, path=old, time=time, labels=labels, title=title)
        return Path(old)
    _no_extra("plot_time_series", legacy)
    labels = dict(labels or {})
    fig, axes = figure_axes(ax, len(groups), sharex=True, height=2.2 * len(groups) + 0.6)
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
    return finish(fig, path)


def _common_name(names: Sequence[str]) -> str:
    """``stroke`` for ``stroke`` and ``stroke_rounded``; ``value`` if the names share nothing."""
    if len(names) == 1:
        return names[0]
    prefix = os.path.commonprefix(list(names)).rstrip("_")
    return prefix or "value"


def plot_relays(
    alpha: Sequence[float],
    beta: Sequence[float],
    *legacy: Any,
    ax: Any = None,
    path: str | os.PathLike | None = None,
    u_min: float,
    u_max: float,
    unit: str = "V",
    title: str = "",
) -> Figure:
    """Relays of a discrete Preisach model as points on the Preisach plane (beta, alpha).

    Parameters
    ----------
    alpha, beta : sequence of float
        Switch-on and switch-off thresholds, in ``unit``.
    ax : matplotlib Axes, optional
        Draw into this axes instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    u_min, u_max : float
        Input range drawn as the Preisach triangle.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.  The earlier ``plot_relays(path, alpha, beta, ...)`` still works for one
        release (with an :class:`~exudyn_atcm.AtcmDeprecationWarning`) and returns the path.
    """
    if is_path(alpha):  # the earlier plot_relays(path, alpha, beta, ...)
        old, (alpha, beta) = _shift("plot_relays", alpha, (beta, *legacy), 2, path)
        plot_relays(alpha, beta, ax=ax, path=old, u_min=u_min, u_max=u_max, unit=unit, title=title)
        return Path(old)
    _no_extra("plot_relays", legacy)
    fig, (ax,) = figure_axes(ax, 1, width=4.6, height=4.2)
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
    return finish(fig, path)


def _shift(function: str, old_path: Any, rest: tuple, count: int, path: Any) -> tuple[Any, tuple]:
    """The earlier signature's path and its ``count`` positional arguments after it, with the warning."""
    if path is not None:
        raise TypeError(f"{function}() got multiple values for argument 'path'")
    if len(rest) != count:
        raise TypeError(f"{function}() takes {count} positional arguments after the output path of the earlier "
                        f"signature, got {len(rest)}")
    warn_path_form(function, stacklevel=4)
    return old_path, tuple(rest)


def _no_extra(function: str, legacy: tuple) -> None:
    if legacy:
        raise TypeError(f"{function}() got {len(legacy)} extra positional arguments (everything after the data is "
                        "keyword-only: ax=, path=, ...)")
