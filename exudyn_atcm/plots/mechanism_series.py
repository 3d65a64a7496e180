"""The standard PNG plots of a mechanism's result (:meth:`exudyn_atcm.Result.plot` of any result).

A mechanism's columns carry their component's name (``crank.tip_y``, ``crank.voltage``,
``coupler.P_x``); these plots find them by their suffix, so they need no description of the
mechanism: every drive's voltage and every tip's deflection over time (or sweep point), every
driven bender's tip deflection over its own drive's voltage, and the path of every recorded point.
Figures are drawn on an Agg canvas (no GUI backend).
"""

from __future__ import annotations

import os

from ..io.atomic import make_directory
from ..io.progress import report_task
from .style import new_figure, save_figure

__all__ = ["plot_mechanism_series", "column_groups"]

_MM = 1e3


def column_groups(result) -> tuple[list[str], list[str], list[str]]:
    """Names of the drives (``{d}.voltage``), the components with a tip (``{c}.tip_y``) and the recorded
    points (``{c}.{p}`` with ``_x`` and ``_y`` in metres) of a mechanism's ``result``, in column order."""
    names = list(result)
    drives = [n[: -len(".voltage")] for n in names if n.endswith(".voltage")]
    tips = [n[: -len(".tip_y")] for n in names if n.endswith(".tip_y") and n[:-2] + "_x" in result]
    points = [n[:-2] for n in names if "." in n and n.endswith("_x") and n[:-2] + "_y" in result
              and result.unit(n) == "m" and result.unit(n[:-2] + "_y") == "m"]
    return drives, tips, points


def _abscissa(result) -> tuple[str, str]:
    if "time" in result:
        return "time", "time t [s]"
    if "point" in result:
        return "point", "sweep point [-]"
    raise ValueError(f"a mechanism's result has a 'time' or a 'point' column; this one has {', '.join(result)}")


def plot_mechanism_series(result, out_dir: str | os.PathLike, prefix: str = "") -> list[str]:
    """Write ``time_series.png``, ``tip_vs_voltage.png`` (if a component with a tip has a drive of its
    name) and ``point_paths.png`` of a mechanism's result to ``out_dir``; returns the paths written.

    ``time_series.png``: every drive's voltage [V] and every tip's deflection ``tip_y`` [mm] over
    ``time`` (a sweep: over its ``point`` index).  ``tip_vs_voltage.png``: the tip deflection of every
    bender driven by the drive of its own name over that voltage (its hysteresis loop).
    ``point_paths.png``: ``y`` over ``x`` [mm] of every recorded point.

    Raises
    ------
    ValueError
        For a result without ``time``/``point``, or without a drive's voltage or a point of a mechanism.
    """
    key, xlabel = _abscissa(result)
    drives, tips, points = column_groups(result)
    if not drives and not points:
        raise ValueError("plot_result draws a simulation result: a lone actuator's (actuator.voltage, actuator.stroke, ...) or a "
                         f"mechanism's ({{drive}}.voltage, {{component}}.tip_y, ...); this result has "
                         f"{', '.join(list(result)[:6])}")
    out_dir = os.fspath(out_dir)
    make_directory(out_dir, "plot directory")
    looped = [c for c in tips if c in drives]
    jobs = [("time_series.png", _time_series), ("tip_vs_voltage.png", _tip_vs_voltage) if looped else None,
            ("point_paths.png", _point_paths)]
    jobs = [job for job in jobs if job is not None]
    written = []
    report_task("plots", 0, len(jobs))
    for k, (name, draw) in enumerate(jobs, start=1):
        path = os.path.join(out_dir, f"{prefix}{name}")
        save_figure(draw(result, key, xlabel, drives, tips, points, looped), path)
        written.append(path)
        report_task("plots", k, len(jobs))
    return written


def _time_series(result, key, xlabel, drives, tips, points, looped):
    fig, axes = new_figure(2, 1, width=7, height=6, sharex=True)
    x = result[key]
    for d in drives:
        axes[0].plot(x, result[f"{d}.voltage"], marker="." if result.n_rows < 3 else None, label=d)
    axes[0].set_ylabel("voltage U [V]")
    for c in tips:
        axes[1].plot(x, result[f"{c}.tip_y"] * _MM, marker="." if result.n_rows < 3 else None, label=f"{c} tip y")
    axes[1].set_ylabel("tip y [mm]")
    axes[1].set_xlabel(xlabel)
    for ax in axes:
        ax.grid(True, alpha=0.3)
        if ax.lines:
            ax.legend(loc="best", fontsize="small")
    return fig


def _tip_vs_voltage(result, key, xlabel, drives, tips, points, looped):
    fig, (ax,) = new_figure(1, 1, width=6, height=4.5)
    for c in looped:
        ax.plot(result[f"{c}.voltage"], result[f"{c}.tip_y"] * _MM, marker="." if result.n_rows < 3 else None,
                label=c)
    ax.set_xlabel("voltage U [V]")
    ax.set_ylabel("tip deflection y [mm]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    return fig


def _point_paths(result, key, xlabel, drives, tips, points, looped):
    fig, (ax,) = new_figure(1, 1, width=6.4, height=4.8)
    for p in points:
        ax.plot(result[f"{p}_x"] * _MM, result[f"{p}_y"] * _MM, marker="." if result.n_rows < 3 else None, label=p)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    if points:
        ax.legend(loc="best", fontsize="small")
    return fig
