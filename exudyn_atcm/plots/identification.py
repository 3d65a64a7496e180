"""Plots of an identified hysteresis model against the record: the loop and the time series."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._checks import hide_keywords, options_from_keywords
from .style import AxisLabels, axis_label, display_scale
from .target import figure_axes, finish, is_path, warn_path_form

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure

__all__ = ["plot_fit", "plot_fit_series", "plot_model_choice", "fitted_samples"]


def fitted_samples(fit: Any, n: int) -> np.ndarray:
    """Which of ``n`` samples a fit (a ``FitReport`` or a ``ModelChoice``) used: its ``fit_mask`` when it has one
    (interleaved held-out cycles), else the samples before ``n_fit``."""
    mask = getattr(fit, "fit_mask", None)
    if mask is not None and np.size(mask) == n:
        return np.asarray(mask, dtype=bool)
    return np.arange(n) < int(fit.n_fit)


def _only(values: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """``values`` with the samples outside ``keep`` as NaN (lines break between separate cycles)."""
    return np.where(keep, values, np.nan)


def _runs(keep: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) indices of each run of True in ``keep``."""
    edges = np.diff(np.concatenate([[0], keep.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1))


@hide_keywords
def plot_fit(
    report: Any,
    u: Any,
    y: Any,
    *legacy: Any,
    ax: Any = None,
    path: str | os.PathLike | None = None,
    labels: AxisLabels | None = None,
    title: str = "",
    **flat: str,
) -> Figure:
    """Measured against predicted output as input-output loops: the fitted and the held-out part.

    Parameters
    ----------
    report : FitReport
        The fit's report (its ``predicted`` series, ``n_fit`` and the linear model are used).
    u, y : array_like
        The record's input and measured output.
    ax : sequence of 2 matplotlib Axes, optional
        Draw into these panels instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    labels : AxisLabels, optional
        Input and output quantities with their SI units (default voltage [V] and displacement [m]).
        The earlier flat keywords ``input_name``, ``input_unit``, ``output_name``, ``output_unit``
        still work for one release (with an :class:`~exudyn_atcm.AtcmDeprecationWarning`).
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.  The time series with the error is :func:`plot_fit_series`.  The earlier
        ``plot_fit(loop_path, series_path, report, u, y, time=None, ...)``, which wrote both, still
        works for one release (with an :class:`~exudyn_atcm.AtcmDeprecationWarning`) and returns the
        two paths.
    """
    (labels,) = options_from_keywords("plot_fit", flat, labels=(AxisLabels, labels))
    if is_path(report):  # the earlier plot_fit(loop_path, series_path, report, u, y, time=None, ...)
        if path is not None or ax is not None or not 2 <= len(legacy) <= 3:
            raise TypeError("plot_fit(loop_path, series_path, report, u, y[, time]) is the earlier form; "
                            "now plot_fit(report, u, y, *, ax=None, path=None)")
        warn_path_form("plot_fit")
        loop_path, series_path, report, u, y, time = report, u, y, legacy[0], legacy[1], (*legacy[2:], None)[0]
        plot_fit(report, u, y, path=loop_path, labels=labels, title=title)
        plot_fit_series(report, u, y, time=time, path=series_path, labels=labels, title=title)
        return [Path(loop_path), Path(series_path)]
    if legacy:
        raise TypeError(f"plot_fit() got {len(legacy)} extra positional arguments (ax=, path=, ... are keywords)")
    u = np.asarray(u, dtype=float)
    y = np.asarray(y, dtype=float)
    p = np.asarray(report.predicted, dtype=float)
    linear = report.linear_model["a"] * u + report.linear_model["b"]
    fitted = fitted_samples(report, u.size)
    factor, unit = display_scale(y, labels.output_unit)

    fig, axes = figure_axes(ax, 1, 2, width=9.0, height=4.0)
    for axis, part, keep in ((axes[0], "fitted part", fitted), (axes[1], "held-out part", ~fitted)):
        if not keep.any():
            axis.set_visible(False)
            continue
        axis.plot(u[keep], factor * y[keep], ".", markersize=2, color="0.6", label="measured")
        axis.plot(_only(u, keep), factor * _only(p, keep), label="model", linewidth=1.0)
        axis.plot(_only(u, keep), factor * _only(linear, keep), "--", label="best linear model", linewidth=1.0)
        rms = report.model_errors["fit" if keep is fitted else "held_out"]["rms"]
        axis.set_title(f"{part}: model RMS {factor * rms:.3g} {unit}")
        axis.set_xlabel(axis_label(labels.input_name, labels.input_unit))
        axis.set_ylabel(axis_label(labels.output_name, unit))
        axis.legend(loc="upper left")
    if title:
        fig.suptitle(title)
    return finish(fig, path)


@hide_keywords
def plot_fit_series(
    report: Any,
    u: Any,
    y: Any,
    *,
    time: Any = None,
    ax: Any = None,
    path: str | os.PathLike | None = None,
    labels: AxisLabels | None = None,
    title: str = "",
    **flat: str,
) -> Figure:
    """Measured against predicted output over time, with the model's and the linear model's error.

    Parameters
    ----------
    report : FitReport
        The fit's report (its ``predicted`` series, ``n_fit`` and the linear model are used).
    u, y : array_like
        The record's input and measured output.
    time : array_like, optional
        Sample times [s]; default the sample index.
    ax : sequence of 3 matplotlib Axes, optional
        Draw into these panels instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    labels : AxisLabels, optional
        Input and output quantities with their SI units (default voltage [V] and displacement [m]).
        The earlier flat keywords ``input_name``, ``input_unit``, ``output_name``, ``output_unit``
        still work for one release (with an :class:`~exudyn_atcm.AtcmDeprecationWarning`).
    title : str
        Figure title prefix.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    (labels,) = options_from_keywords("plot_fit_series", flat, labels=(AxisLabels, labels))
    u = np.asarray(u, dtype=float)
    y = np.asarray(y, dtype=float)
    p = np.asarray(report.predicted, dtype=float)
    linear = report.linear_model["a"] * u + report.linear_model["b"]
    held_out = ~fitted_samples(report, u.size)
    factor, unit = display_scale(y, labels.output_unit)

    x = np.arange(u.size) if time is None else np.asarray(time, dtype=float)
    x_label = axis_label("sample", "-") if time is None else axis_label("time", "s")
    fig, axes = figure_axes(ax, 3, 1, width=8.0, height=7.0, sharex=True)
    axes[0].plot(x, u)
    axes[0].set_ylabel(axis_label(labels.input_name, labels.input_unit))
    axes[1].plot(x, factor * y, ".", markersize=2, color="0.6", label="measured")
    axes[1].plot(x, factor * p, label="model", linewidth=1.0)
    axes[1].set_ylabel(axis_label(labels.output_name, unit))
    axes[1].legend(loc="upper left")
    axes[2].plot(x, factor * (p - y), label="model - measured", linewidth=0.8)
    axes[2].plot(x, factor * (linear - y), label="linear - measured", linewidth=0.8, alpha=0.7)
    axes[2].set_ylabel(axis_label("error", unit))
    axes[2].set_xlabel(x_label)
    axes[2].legend(loc="upper left")
    for i, (first, last) in enumerate(_runs(held_out)):  # the held-out samples shaded (interleaved cycles too)
        for a in axes:
            a.axvspan(x[first], x[last], color="0.9", zorder=0, label="held out" if i == 0 and a is axes[1] else None)
    if held_out.any():
        axes[1].legend(loc="upper left")
    if title:
        axes[0].set_title(f"{title}: held-out samples shaded")
    return finish(fig, path)


def plot_model_choice(
    choice: Any,
    *legacy: Any,
    ax: Any = None,
    path: str | os.PathLike | None = None,
    input_name: str = "voltage",
    input_unit: str = "V",
    output_name: str = "displacement",
    title: str = "",
) -> Figure:
    """The ranked table of :func:`exudyn_atcm.hysteresis.identify` as a figure.

    Left: held-out RMS error of each fitted family [% of the output range] (the chosen one
    filled, the parameter count at each bar).  Right: the held-out part of the loop, measured
    against the predictions of the chosen model and the two others ranked first.

    Parameters
    ----------
    choice : ModelChoice
        The result of :func:`~exudyn_atcm.hysteresis.identify`.
    ax : sequence of 2 matplotlib Axes, optional
        Draw into these panels instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    input_name, input_unit, output_name : str
        Axis quantities (the output unit is the choice's).
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.  The earlier ``plot_model_choice(path, choice, ...)`` still works for one
        release (with an :class:`~exudyn_atcm.AtcmDeprecationWarning`) and returns the path.
    """
    if is_path(choice):  # the earlier plot_model_choice(path, choice, ...)
        if path is not None or len(legacy) != 1:
            raise TypeError("plot_model_choice(path, choice) is the earlier form; now plot_model_choice(choice, *, "
                            "ax=None, path=None)")
        warn_path_form("plot_model_choice")
        plot_model_choice(legacy[0], ax=ax, path=choice, input_name=input_name, input_unit=input_unit,
                          output_name=output_name, title=title)
        return Path(choice)
    if legacy:
        raise TypeError(f"plot_model_choice() got {len(legacy)} extra positional arguments")
    fitted = [c for c in choice.candidates if not c.failure]
    u = np.asarray(choice.input, dtype=float)
    y = np.asarray(choice.output, dtype=float)
    held_out = ~fitted_samples(choice, u.size)
    factor, unit = display_scale(y, choice.output_unit or "m")
    fig, axes = figure_axes(ax, 1, 2, width=11.0, height=4.2)
    ax = axes[0]
    names = [c.label for c in fitted][::-1]
    values = [c.held_out_rms_percent for c in fitted][::-1]
    colours = ["C0" if c is choice.chosen else "0.75" for c in fitted][::-1]
    bars = ax.barh(range(len(names)), values, color=colours)
    for bar, c in zip(bars, fitted[::-1]):
        ax.text(bar.get_width(), bar.get_y() + bar.get_height() / 2, f" {c.parameters} par.", va="center", fontsize=8)
    ax.set_yticks(range(len(names)))
    ax.set_yticklabels(names, fontsize=8)
    ax.set_xlabel(axis_label("held-out RMS error", "% of range"))
    ax.set_xlim(0.0, 1.25 * max(values))
    ax.set_title(f"chosen: {choice.chosen.label}", fontsize=9)
    ax = axes[1]
    ax.plot(u[held_out], factor * y[held_out], ".", markersize=2, color="0.6", label="measured")
    shown = [choice.chosen] + [c for c in fitted if c is not choice.chosen][:2]
    for c in shown:
        ax.plot(_only(u, held_out), factor * _only(np.asarray(c.report.predicted, dtype=float), held_out),
                linewidth=1.0, label=c.label)
    ax.set_xlabel(axis_label(input_name, input_unit))
    ax.set_ylabel(axis_label(output_name, unit))
    ax.set_title("held-out part", fontsize=9)
    ax.legend(loc="upper left", fontsize=8)
    if title:
        fig.suptitle(title)
    return finish(fig, path)
