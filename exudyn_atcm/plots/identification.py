"""Plots of an identified hysteresis model against the record: the loop and the time series."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from .style import axis_label, display_scale, new_figure, save_figure

__all__ = ["plot_fit", "plot_model_choice"]


def plot_fit(
    loop_path: str | os.PathLike,
    series_path: str | os.PathLike,
    report: Any,
    u: Any,
    y: Any,
    time: Any = None,
    *,
    input_name: str = "voltage",
    input_unit: str = "V",
    output_name: str = "displacement",
    output_unit: str = "m",
    title: str = "",
) -> list[Path]:
    """Measured against predicted output: input-output loop and time series with the error.

    Parameters
    ----------
    loop_path, series_path : str or os.PathLike
        PNG files to write.
    report : FitReport
        The fit's report (its ``predicted`` series, ``n_fit`` and the linear model are used).
    u, y : array_like
        The record's input and measured output.
    time : array_like, optional
        Sample times [s]; default the sample index.
    input_name, input_unit, output_name, output_unit : str
        Axis quantities and SI units.
    title : str
        Figure title prefix.

    Returns
    -------
    list of Path
        The two files written.
    """
    u = np.asarray(u, dtype=float)
    y = np.asarray(y, dtype=float)
    p = np.asarray(report.predicted, dtype=float)
    linear = report.linear_model["a"] * u + report.linear_model["b"]
    k = report.n_fit
    factor, unit = display_scale(y, output_unit)

    fig, axes = new_figure(1, 2, width=9.0, height=4.0)
    for ax, part, sl in ((axes[0], "fitted part", slice(0, k)), (axes[1], "held-out part", slice(k, None))):
        if u[sl].size == 0:
            ax.set_visible(False)
            continue
        ax.plot(u[sl], factor * y[sl], ".", markersize=2, color="0.6", label="measured")
        ax.plot(u[sl], factor * p[sl], label="model", linewidth=1.0)
        ax.plot(u[sl], factor * linear[sl], "--", label="best linear model", linewidth=1.0)
        rms = report.model_errors["fit" if sl.start == 0 else "held_out"]["rms"]
        ax.set_title(f"{part}: model RMS {factor * rms:.3g} {unit}")
        ax.set_xlabel(axis_label(input_name, input_unit))
        ax.set_ylabel(axis_label(output_name, unit))
        ax.legend(loc="upper left")
    if title:
        fig.suptitle(title)
    loop = save_figure(fig, loop_path)

    x = np.arange(u.size) if time is None else np.asarray(time, dtype=float)
    x_label = axis_label("sample", "-") if time is None else axis_label("time", "s")
    fig, axes = new_figure(3, 1, width=8.0, height=7.0, sharex=True)
    axes[0].plot(x, u)
    axes[0].set_ylabel(axis_label(input_name, input_unit))
    axes[1].plot(x, factor * y, ".", markersize=2, color="0.6", label="measured")
    axes[1].plot(x, factor * p, label="model", linewidth=1.0)
    axes[1].set_ylabel(axis_label(output_name, unit))
    axes[1].legend(loc="upper left")
    axes[2].plot(x, factor * (p - y), label="model - measured", linewidth=0.8)
    axes[2].plot(x, factor * (linear - y), label="linear - measured", linewidth=0.8, alpha=0.7)
    axes[2].set_ylabel(axis_label("error", unit))
    axes[2].set_xlabel(x_label)
    axes[2].legend(loc="upper left")
    if k < u.size:
        for ax in axes:
            ax.axvline(x[k], color="black", linewidth=0.8, linestyle=":")
    if title:
        axes[0].set_title(f"{title}: fitted | held out")
    series = save_figure(fig, series_path)
    return [loop, series]


def plot_model_choice(
    path: str | os.PathLike,
    choice: Any,
    *,
    input_name: str = "voltage",
    input_unit: str = "V",
    output_name: str = "displacement",
    title: str = "",
) -> Path:
    """The ranked table of :func:`exudyn_atcm.hysteresis.identify` as a figure.

    Left: held-out RMS error of each fitted family [% of the output range] (the chosen one
    filled, the parameter count at each bar).  Right: the held-out part of the loop, measured
    against the predictions of the chosen model and the two others ranked first.

    Parameters
    ----------
    path : str or os.PathLike
        PNG file to write.
    choice : ModelChoice
        The result of :func:`~exudyn_atcm.hysteresis.identify`.
    input_name, input_unit, output_name : str
        Axis quantities (the output unit is the choice's).
    title : str
        Figure title.

    Returns
    -------
    Path
        The file written.
    """
    fitted = [c for c in choice.candidates if not c.failure]
    u = np.asarray(choice.input, dtype=float)
    y = np.asarray(choice.output, dtype=float)
    k = choice.n_fit
    factor, unit = display_scale(y, choice.output_unit or "m")
    fig, axes = new_figure(1, 2, width=11.0, height=4.2)
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
    ax.plot(u[k:], factor * y[k:], ".", markersize=2, color="0.6", label="measured")
    shown = [choice.chosen] + [c for c in fitted if c is not choice.chosen][:2]
    for c in shown:
        ax.plot(u[k:], factor * np.asarray(c.report.predicted)[k:], linewidth=1.0, label=c.label)
    ax.set_xlabel(axis_label(input_name, input_unit))
    ax.set_ylabel(axis_label(output_name, unit))
    ax.set_title("held-out part", fontsize=9)
    ax.legend(loc="upper left", fontsize=8)
    if title:
        fig.suptitle(title)
    return save_figure(fig, path)
