"""PNG plots of a :class:`~exudyn_atcm.io.result.Result` (matplotlib, headless).

Figures are drawn with matplotlib's object interface on an Agg canvas, so importing or
calling this module never selects or opens a GUI backend.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from .._checks import shown
from ..io.atomic import make_directory
from ..io.units import si_scale
from ..mechanism.actuator import NAME
from .gif import save_gif
from .mechanism_series import plot_mechanism_series
from .style import new_figure
from .target import figure_axes, finish, legacy_path
from ..io.progress import report_task

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure

__all__ = ["plot_result", "plot_time_series", "plot_tip_vs_voltage", "plot_shapes", "chain_shape", "animate_actuator"]


def actuator_column(result, name: str) -> np.ndarray:
    """Column ``actuator.<name>`` of a lone actuator's result, or ``<name>`` of one read from a file
    written before 0.3.0 (whose columns were ``tip_y``, ``stroke``, ...; kept as written), in SI: a column in
    a known other unit (a file written by hand in ``[mm]``, ``[ms]``, ``[kV]``:
    :data:`~exudyn_atcm.io.units.SI_SCALE`) is converted, as the plots' axes are labelled in SI."""
    key = f"{NAME}.{name}" if f"{NAME}.{name}" in result else name
    values = result[key]
    scale = si_scale(result.unit(key))
    return values * scale[0] if scale is not None and scale[0] != 1.0 else values


def is_actuator_result(result) -> bool:
    """Whether ``result`` is a lone actuator's (``actuator.stroke`` and ``actuator.tip_y``; in a file
    written before 0.3.0 ``voltage`` and ``tip_y``)."""
    if f"{NAME}.stroke" in result:
        return f"{NAME}.tip_y" in result
    return "voltage" in result.names and "tip_y" in result.names


def chain_shape(result, row: int) -> tuple[np.ndarray, np.ndarray]:
    """Vertices [m] of the passive layer at recorded ``row``, from the per-cell angles.

    Each cell's passive layer is a straight bar of the cell length at its recorded angle,
    starting at the clamp (0, 0).
    """
    names = [n for n in result.names if n.startswith(f"{NAME}.cell_angle_")]
    names = names or [n for n in result.names if n.startswith("cell_angle_")]  # a file before 0.3.0
    if not names:
        raise ValueError(f"result has no {NAME}.cell_angle_* series to draw the shape from")
    try:
        cell_length = float(result.parameters["cell_length [m]"])
    except KeyError:
        raise ValueError("result.parameters lacks 'cell_length [m]'") from None
    angles = np.array([result[n][row] for n in sorted(names, key=lambda s: int(s.rsplit("_", 1)[1]))])
    x = np.concatenate([[0.0], np.cumsum(cell_length * np.cos(angles))])
    y = np.concatenate([[0.0], np.cumsum(cell_length * np.sin(angles))])
    return x, y


def plot_time_series(result, *legacy: Any, ax: Any = None, path: str | os.PathLike | None = None) -> Figure:
    """Voltage, stroke and tip displacement over time (three panels).

    Parameters
    ----------
    result : Result
        A lone actuator's run (``actuator.voltage`` [V], ``actuator.stroke`` [m],
        ``actuator.tip_x``/``actuator.tip_y`` [m]).
    ax : sequence of 3 matplotlib Axes, optional
        Draw into these panels instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.  (The earlier ``plot_time_series(result, path)`` still works for one
        release, with an :class:`~exudyn_atcm.AtcmDeprecationWarning`, and returns the path.)
    """
    if legacy:
        old, _ = legacy_path("plot_time_series", legacy, path)
        plot_time_series(result, ax=ax, path=old)
        return old
    t = result["time"]
    fig, axes = figure_axes(ax, 3, 1, width=7, height=7, sharex=True)
    axes[0].plot(t, actuator_column(result, "voltage"), color="tab:blue")
    axes[0].set_ylabel("voltage U [V]")
    axes[1].plot(t, actuator_column(result, "stroke") * 1e6, color="tab:orange")
    axes[1].set_ylabel("cell stroke x_a [µm]")
    tip_x = actuator_column(result, "tip_x")
    axes[2].plot(t, actuator_column(result, "tip_y") * 1e3, label="tip y", color="tab:green")
    axes[2].plot(t, (tip_x - tip_x.max()) * 1e3, label="tip x - max(tip x)",
                 color="tab:red", linestyle="--")
    axes[2].set_ylabel("tip displacement [mm]")
    axes[2].set_xlabel("time t [s]")
    axes[2].legend(loc="best")
    for a in axes:
        a.grid(True, alpha=0.3)
    return finish(fig, path)


def plot_tip_vs_voltage(result, *legacy: Any, ax: Any = None, path: str | os.PathLike | None = None) -> Figure:
    """Tip deflection over voltage (the actuator's hysteresis loop).

    Parameters
    ----------
    result : Result
        A lone actuator's run (``actuator.voltage`` [V], ``actuator.tip_y`` [m]).
    ax : matplotlib Axes, optional
        Draw into this axes instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on (the earlier ``plot_tip_vs_voltage(result, path)`` returns the path,
        with an :class:`~exudyn_atcm.AtcmDeprecationWarning`, for one release).
    """
    if legacy:
        old, _ = legacy_path("plot_tip_vs_voltage", legacy, path)
        plot_tip_vs_voltage(result, ax=ax, path=old)
        return old
    fig, (axis,) = figure_axes(ax, 1, 1, width=6, height=4.5)
    axis.plot(actuator_column(result, "voltage"), actuator_column(result, "tip_y") * 1e3, color="tab:green")
    axis.set_xlabel("voltage U [V]")
    axis.set_ylabel("tip deflection y [mm]")
    axis.grid(True, alpha=0.3)
    return finish(fig, path)


def plot_shapes(result, *legacy: Any, ax: Any = None, path: str | os.PathLike | None = None,
                rows: Sequence[int] | None = None) -> Figure:
    """Deformed shape of the passive layer at a few instants.

    Parameters
    ----------
    result : Result
        A lone actuator's run (``actuator.cell_angle_*`` series, ``cell_length [m]`` in its parameters).
    ax : matplotlib Axes, optional
        Draw into this axes instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    rows : sequence of int, optional
        Recorded rows drawn (default: 6 evenly spaced).

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on (the earlier ``plot_shapes(result, path, rows)`` returns the path,
        with an :class:`~exudyn_atcm.AtcmDeprecationWarning`, for one release).
    """
    if legacy:
        old, rest = legacy_path("plot_shapes", legacy, path, extra=1)
        plot_shapes(result, ax=ax, path=old, rows=rest[0] if rest else rows)
        return old
    n = result.n_rows
    if rows is None:
        rows = sorted(set(np.linspace(0, n - 1, min(6, n)).round().astype(int).tolist()))
    fig, (axis,) = figure_axes(ax, 1, 1, width=7, height=4)
    voltage = actuator_column(result, "voltage")
    for row in rows:
        x, y = chain_shape(result, row)
        when = f"t = {result['time'][row]:.3g} s" if "time" in result.names else f"point {row}"  # a static sweep's
        axis.plot(x * 1e3, y * 1e3, marker="o", markersize=3, label=f"{when}, U = {voltage[row]:.0f} V")
    axis.set_xlabel("x along the undeformed actuator [mm]")
    axis.set_ylabel("y [mm]")
    axis.set_aspect("equal", adjustable="datalim")
    axis.grid(True, alpha=0.3)
    axis.legend(fontsize="small", loc="best")
    return finish(fig, path)


def animate_actuator(result, path: str | os.PathLike, frames: int = 60, fps: int = 15) -> str:
    """GIF animation of the deformed actuator with its tip trace and the voltage.

    Parameters
    ----------
    result : Result
        A lone actuator's run (``actuator.cell_angle_*`` series, ``cell_length [m]`` in its parameters).
    path : str or os.PathLike
        Target ``.gif`` file (written atomically).
    frames : int, optional
        Number of frames, evenly spaced over the recorded time, ``>= 2``.
    fps : int, optional
        Frames per second of the GIF, ``>= 1``.
    """
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 2:
        raise ValueError(f"frames must be an integer >= 2, got {shown(frames)}")
    if isinstance(fps, bool) or not isinstance(fps, int) or fps < 1:
        raise ValueError(f"fps must be an integer >= 1, got {shown(fps)}")
    rows = np.unique(np.linspace(0, result.n_rows - 1, frames).round().astype(int))
    shapes = [chain_shape(result, int(row)) for row in rows]
    xs = np.concatenate([x for x, _ in shapes]) * 1e3
    ys = np.concatenate([y for _, y in shapes]) * 1e3
    fig, (ax,) = new_figure(1, 1, width=6, height=4)
    ax.set_xlim(xs.min() - 5, xs.max() + 5)
    margin = 0.1 * max(ys.max() - ys.min(), 1.0)
    ax.set_ylim(ys.min() - margin, ys.max() + margin)
    ax.set_xlabel("x along the undeformed actuator [mm]")
    ax.set_ylabel("y [mm]")
    (trace,) = ax.plot([], [], color="0.6", lw=1, label="tip path")
    (chain,) = ax.plot([], [], "o-", color="tab:blue", lw=2, ms=4, label="passive layer")
    label = ax.text(0.02, 0.95, "", transform=ax.transAxes, va="top")
    legend = ax.legend(loc="lower right", fontsize="small")
    tip_x, tip_y = actuator_column(result, "tip_x") * 1e3, actuator_column(result, "tip_y") * 1e3
    voltage = actuator_column(result, "voltage")

    def draw(k: int):
        x, y = shapes[k]
        chain.set_data(x * 1e3, y * 1e3)
        trace.set_data(tip_x[: rows[k] + 1], tip_y[: rows[k] + 1])
        label.set_text(f"t = {result['time'][rows[k]]:.3f} s   U = {voltage[rows[k]]:.0f} V")
        return chain, trace, label, legend  # the legend stays above the chain

    total = len(shapes)
    save_gif(fig, draw, total, path, fps=fps)  # reports the frames to the active progress display
    return os.fspath(path)


def plot_result(result, out_dir: str | os.PathLike, prefix: str = "") -> list[str]:
    """Write the standard plots of any result to ``out_dir``; returns the paths written.

    A lone actuator's result (``actuator.stroke``, ``actuator.tip_y``, ...; or a file of one written
    before 0.3.0, ``stroke``, ``tip_y``, ...): ``time_series.png`` (not for a static sweep's, whose rows are points),
    ``tip_vs_voltage.png`` and ``shapes.png``.  A
    mechanism's result (columns ``{drive}.voltage``, ``{component}.tip_y``, ``{component}.{point}_x``):
    :func:`~exudyn_atcm.plots.mechanism_series.plot_mechanism_series` (voltages and tips over time or
    sweep point, each driven bender's loop, the recorded points' paths); to draw the mechanism itself,
    :func:`exudyn_atcm.plots.mechanism.plot_mechanism` with its description.
    """
    if not is_actuator_result(result):
        return plot_mechanism_series(result, out_dir, prefix)
    out_dir = os.fspath(out_dir)
    make_directory(out_dir, "plot directory")
    jobs = [
        (plot_time_series, "time_series.png"),
        (plot_tip_vs_voltage, "tip_vs_voltage.png"),
        (plot_shapes, "shapes.png"),
    ]
    if "time" not in result.names:  # a static sweep's (its rows are points, not instants): no time series
        jobs = jobs[1:]
    written = []
    report_task("plots", 0, len(jobs))
    for k, (draw, name) in enumerate(jobs, start=1):
        target = os.path.join(out_dir, f"{prefix}{name}")
        draw(result, path=target)
        written.append(target)
        report_task("plots", k, len(jobs))
    return written
