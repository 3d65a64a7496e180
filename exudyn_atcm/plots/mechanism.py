"""Drawings and GIF animations of a planar mechanism from its description and a Result.

What is drawn, for every recorded instant (row) of a mechanism :class:`~exudyn_atcm.Result`:

* **benders**: the passive layer's mid-plane as the polyline of the cells (from the recorded
  base point and cell angles), the cell joints (beam cells: the nodes) as dots, and the active (MFC) layer as a
  second polyline offset by the layer distance ``e`` to the MFC side; the driven cells'
  active layer carries a motor mark, coloured per drive and named in the legend;
* **links**: a filled polygon through their named points (ordered around their centroid);
* **flexures**: the two rigid segments of the pseudo-rigid-body model with the pivot as an
  open circle, or the cell polyline of the ``"cells"`` model;
* **connections and loads**: each draws itself on a
  :class:`~exudyn_atcm.plots.canvas.MechanismCanvas` (its ``draw``): springs (grasped objects) as
  zigzags between their points, stops as hatched walls, ground connections as hatched symbols
  (weld: a wall behind the point; pin: a triangle; slider: a rail along the axis).

Deformation can be exaggerated: with ``scale = s`` every displacement from the reference
pose is multiplied by ``s`` (bender cells: their rotations, with the chain's closure gap to
the magnified tip displacement spread along it so welded parts stay attached), and the title
says so.  The
layer offset ``e`` (a fraction of a millimetre) is drawn enlarged to be visible; the legend
gives the factor.  Result columns used (``name [unit]`` convention of mechanism runs):
``{comp}.{point}_x``/``_y`` [m], ``{bender}.cell_angle_{j}`` [rad] (absolute angle of cell
``j``'s axis), ``{flexure}.base_angle`` [rad] (absolute angle of the flexure's base segment),
``{drive}.voltage`` [V].

The geometry comes from :mod:`exudyn_atcm.plots.mechanism_shapes` (its public names are
re-exported here).  Figures are made on the Agg canvas through :mod:`exudyn_atcm.plots.style`;
files are written atomically.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._checks import shown
from ..mechanism import Link, Mechanism
from .mechanism_shapes import (
    BenderShape,
    MechanismShape,
    result_column,
    order_around_centroid,
    actuator_as_mechanism,
    mechanism_shape,
    point_at,
)
from .canvas import MechanismCanvas
from .gif import save_gif
from .legend_place import place_legend
from .style import COLORS, axis_label, new_figure
from .target import figure_axes, finish, legacy_path

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure

__all__ = [
    "BenderShape",
    "MechanismShape",
    "mechanism_shape",
    "draw_mechanism",
    "plot_mechanism",
    "animate_mechanism",
    "plot_point_paths",
    "actuator_as_mechanism",
]

_MM = 1e3  # drawings in millimetres
_PASSIVE = "#404040"
_LINK = "#9ecae1"
_FLEXURE = "#6a3d9a"
_ACTIVE = "#E69F00"
#: motor marks per drive: the package colours without the active layer's
_DRIVE_COLORS = [c for c in COLORS if c.upper() != _ACTIVE]


# ----------------------------------------------------------------------------- drawing
def _draw_reference(ax, mechanism: Mechanism) -> None:
    """Draw the mechanism's reference pose on ``ax`` (axes in mm): benders straight and links as described,
    thin grey dashed lines below the grid."""
    for b in mechanism.benders:
        p = np.array([b.base_position, np.array(b.base_position) + b.length * b.direction])
        ax.plot(*(p * _MM).T, color="0.75", lw=1.0, ls="--", zorder=1)
    for comp in mechanism.components.values():
        if isinstance(comp, Link):
            poly = order_around_centroid(np.array(list(comp.points.values())))
            closed = np.vstack([poly, poly[:1]]) if len(poly) > 2 else poly
            ax.plot(*(closed * _MM).T, color="0.75", lw=1.0, ls="--", zorder=1)


def draw_mechanism(
    ax,
    mechanism: Mechanism,
    result,
    row: int,
    *,
    scale: float = 1.0,
    offset_scale: float | None = None,
    reference: bool = True,
    labels: bool = True,
    legend: bool = True,
) -> MechanismShape:
    """Draw the mechanism at recorded ``row`` on matplotlib axes ``ax`` (axes in mm).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Target axes.
    mechanism, result, row, scale
        As for :func:`mechanism_shape`.
    offset_scale : float, optional
        Magnification of the layer offset ``e``; default: drawn as 1 % of the mechanism's size
        (never reduced below the true offset).
    reference : bool, optional
        Also draw the reference pose (thin grey).
    labels : bool, optional
        Write link point names.
    legend : bool, optional
        Add a legend (layers, joints, drives, flexure pivots, springs).

    Returns
    -------
    MechanismShape
        The geometry drawn [m].
    """
    size = max(mechanism.size, 1e-12)
    if offset_scale is None:
        offsets = [b.laminate.layer_offset for b in mechanism.benders if b.active is not None]
        e = max(offsets, default=0.0)
        offset_scale = max(1.0, 0.01 * size / e) if e > 0 else 1.0
    shape = mechanism_shape(mechanism, result, row, scale=scale, offset_scale=offset_scale)
    if reference:
        _draw_reference(ax, mechanism)
    drive_colors: dict[str, str] = {}
    layer_label = f"active layer (offset e drawn ×{offset_scale:.3g})" if offset_scale != 1.0 else "active layer"
    first = True
    labelled: set[str] = set()
    for b in shape.benders:
        ax.plot(*(b.passive * _MM).T, color=_PASSIVE, lw=2.2, zorder=3, label="passive layer" if first else None)
        cell = getattr(mechanism.components.get(b.name), "cell", None)
        joints = cell.joint_label if cell is not None else "cell joints"
        ax.plot(*(b.passive * _MM).T, "o", color=_PASSIVE, ms=2.5, zorder=4,
                label=joints if joints not in labelled else None)
        labelled.add(joints)
        if b.active is not None:
            seg = b.active
            path = np.vstack([seg[:, 0], seg[-1:, 1]])
            ax.plot(*(path * _MM).T, color=_ACTIVE, lw=1.6, zorder=3, label=layer_label if first else None)
            for j, drive in enumerate(b.drives):
                if drive is None:
                    continue
                color = drive_colors.setdefault(drive, _DRIVE_COLORS[len(drive_colors) % len(_DRIVE_COLORS)])
                mid = 0.5 * (seg[j, 0] + seg[j, 1])
                ax.plot(*(mid * _MM), marker="D", ms=4.5, color=color, zorder=5,
                        label=f"motor, drive {drive}" if j == b.drives.index(drive) else None)
        first = False
    for name, poly in shape.links.items():
        if len(poly) > 2:
            ax.fill(*(poly * _MM).T, color=_LINK, alpha=0.7, ec="#08519c", lw=1.2, zorder=2)
        else:
            ax.plot(*(poly * _MM).T, color="#08519c", lw=4, solid_capstyle="round", zorder=2)
        if labels:
            points = shape.link_points[name]
            centre = np.mean(np.array(list(points.values())), axis=0)
            for pname, x in points.items():
                ax.plot(*(x * _MM), ".", color="#08519c", ms=4, zorder=6)
                # away from the link's centre, so the names of a link's points do not overlap
                away = np.asarray(x, float) - centre
                norm = float(np.hypot(*away))
                dx, dy = (away / norm) if norm > 1e-12 * max(size, 1e-12) else (0.7071, 0.7071)
                ax.annotate(f"{name}.{pname}", x * _MM, xytext=(6 * dx, 6 * dy), textcoords="offset points", fontsize=7,
                            ha="left" if dx > 0.3 else "right" if dx < -0.3 else "center",
                            va="bottom" if dy > 0.3 else "top" if dy < -0.3 else "center", zorder=7)
    for k, (name, line) in enumerate(shape.flexures.items()):
        ax.plot(*(line * _MM).T, color=_FLEXURE, lw=1.6, zorder=3, label="flexures" if k == 0 else None)
        if name in shape.pivots:
            ax.plot(*(shape.pivots[name] * _MM), "o", mfc="white", mec=_FLEXURE, ms=5, zorder=6,
                    label="flexure pivots (PRBM)" if k == 0 else None)
    canvas = MechanismCanvas(ax, mechanism, lambda ref: point_at(result, mechanism, str(ref), row, scale), size)
    for connection in mechanism.connections:  # each draws itself (ground joints, springs, stops, ...)
        connection.draw(canvas)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(axis_label("x", "mm"))
    ax.set_ylabel(axis_label("y", "mm"))
    if legend:
        ax.legend(loc="best", fontsize=7)
    return shape


def _scale_text(scale: float) -> str:
    return "true scale" if scale == 1.0 else f"displacements ×{scale:g}"


def _time_text(result, row: int) -> str:
    parts = []
    if "static" in str(result.info.get("solver", "")):
        parts.append(f"static point {row + 1} of {result.n_rows}")
    elif "time" in result:
        parts.append(f"t = {result['time'][row]:.4g} s")
    for name in result.names:
        if name.endswith(".voltage"):
            parts.append(f"U({name[: -len('.voltage')]}) = {result[name][row]:.0f} V")
    return ", ".join(parts)


def plot_mechanism(
    mechanism: Mechanism,
    result,
    *legacy: object,
    ax: object = None,
    path: str | os.PathLike | None = None,
    row: int = -1,
    scale: float = 1.0,
    title: str | None = None,
    trace: Sequence[str] = (),
) -> Figure:
    """The mechanism at one recorded instant, with optional point traces.

    Parameters
    ----------
    mechanism, result
        The description and a run of it.
    ax : matplotlib Axes, optional
        Draw into this axes instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    row : int, optional
        Recorded instant (default: the last).
    scale : float, optional
        Displacement magnification, stated in the title.
    title : str, optional
        Title (the deformation scale and time/voltages are appended).
    trace : sequence of str, optional
        Points ``"component.point"`` whose whole recorded path is drawn.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on (the earlier ``plot_mechanism(mechanism, result, path)`` returns the path,
        with an :class:`~exudyn_atcm.AtcmDeprecationWarning`, for one release).
    """
    if legacy:
        old, _ = legacy_path("plot_mechanism", legacy, path)
        plot_mechanism(mechanism, result, ax=ax, path=old, row=row, scale=scale, title=title, trace=trace)
        return Path(old)
    _check_scale(scale)
    fig, (ax,) = figure_axes(ax, 1, 1, width=7.0, height=5.5)
    _draw_traces(ax, mechanism, result, trace, scale, None)
    n = result.n_rows
    draw_mechanism(ax, mechanism, result, row, scale=scale)
    head = title or mechanism.name
    ax.set_title(f"{head} ({_scale_text(scale)})\n{_time_text(result, int(row) % n)}", fontsize=9)
    return finish(fig, path)



def _check_scale(scale: float) -> None:
    if isinstance(scale, bool) or not isinstance(scale, (int, float)) or not math.isfinite(scale) or scale <= 0:
        raise ValueError(f"scale must be a finite displacement magnification > 0, got {shown(scale)}")


def _draw_traces(ax, mechanism: Mechanism, result, trace: Sequence[str], scale: float, upto: int | None) -> list:
    lines = []
    for k, ref in enumerate(trace):
        component, point = str(ref).split(".")
        if component not in mechanism.components or point not in mechanism.components[component].points:
            raise ValueError(f"trace point {ref!r} is not a point of the mechanism")
        x0, y0 = mechanism.components[component].points[point]
        x = x0 + scale * (result_column(result, f"{ref}_x") - x0)
        y = y0 + scale * (result_column(result, f"{ref}_y") - y0)
        stop = None if upto is None else upto + 1
        (line,) = ax.plot(x[:stop] * _MM, y[:stop] * _MM, lw=1.0, color=COLORS[(k + 2) % len(COLORS)],
                          label=f"path of {ref}", zorder=2)
        lines.append((line, x, y))
    return lines


def animate_mechanism(
    mechanism: Mechanism,
    result,
    path: str | os.PathLike,
    *,
    frames: int = 60,
    fps: int = 15,
    scale: float = 1.0,
    trace: Sequence[str] = (),
    title: str | None = None,
) -> Path:
    """GIF animation of the moving mechanism (frames drawn on the Agg canvas, written atomically with Pillow).

    The grid, the reference pose and the axes are drawn once; each frame draws the mechanism, the
    traces, the title and the legend over them (:func:`~exudyn_atcm.plots.gif.save_gif`).  The legend
    stays in one place, the one that covers the least of all frames
    (:func:`~exudyn_atcm.plots.legend_place.place_legend`).

    Parameters
    ----------
    mechanism, result
        The description and a run of it.
    path : str or os.PathLike
        Target ``.gif`` in an existing directory.
    frames : int, optional
        Number of frames, evenly spaced over the recorded rows, ``>= 2``.
    fps : int, optional
        Frames per second, ``>= 1``.
    scale : float, optional
        Displacement magnification, stated in the title of every frame.
    trace : sequence of str, optional
        Points ``"component.point"`` whose path so far is drawn.
    title : str, optional
        Title prefix (default: the mechanism's name).
    """
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 2:
        raise ValueError(f"frames must be an integer >= 2, got {shown(frames)}")
    if isinstance(fps, bool) or not isinstance(fps, int) or fps < 1:
        raise ValueError(f"fps must be an integer >= 1, got {shown(fps)}")
    _check_scale(scale)
    target = os.fspath(path)
    directory = os.path.dirname(os.path.abspath(target))
    if not os.path.isdir(directory):
        raise ValueError(f"path must be in an existing directory, got {shown(target)}")
    rows = np.unique(np.linspace(0, result.n_rows - 1, frames).round().astype(int))
    # fixed limits from every frame's geometry (and the legend's place: where it covers the least of it)
    shapes = [mechanism_shape(mechanism, result, int(r), scale=scale) for r in rows]
    pts = np.concatenate([shape.all_points() for shape in shapes])
    pts = np.vstack([pts, np.array([p for c in mechanism.components.values() for p in c.points.values()])])
    filled = [poly * _MM for shape in shapes for poly in shape.links.values() if len(poly) > 2]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    margin = 0.12 * float(max(hi - lo))
    fig, (ax,) = new_figure(1, 1, width=6.4, height=5.2)
    fig.set_dpi(90)
    head = title or mechanism.name
    # what every frame shares, drawn once: grid, reference pose, limits and labels
    ax.grid(True, alpha=0.3)
    _draw_reference(ax, mechanism)
    xlim = ((lo[0] - margin) * _MM, (hi[0] + margin) * _MM)
    ylim = ((lo[1] - margin) * _MM, (hi[1] + margin) * _MM)
    drawn: list = []  # the artists of the last frame, but the legend

    def draw(k: int) -> list:
        for artist in drawn:
            artist.remove()
        before = set(ax.get_children())
        row = int(rows[k])
        _draw_traces(ax, mechanism, result, trace, scale, row)
        draw_mechanism(ax, mechanism, result, row, scale=scale, reference=False, labels=False, legend=k == 0)
        ax.set_xlim(*xlim)
        ax.set_ylim(*ylim)
        ax.set_aspect("equal", adjustable="box")
        ax.set_title(f"{head} ({_scale_text(scale)})\n{_time_text(result, row)}", fontsize=8)
        legend = ax.get_legend()
        if k == 0 and legend is not None:  # one place for every frame, chosen over all of them (laid out first)
            fig.canvas.draw()
            place_legend(fig, ax, legend, pts * _MM, filled)
        drawn[:] = [a for a in ax.get_children() if a not in before and a is not legend]
        return drawn + [ax.title] + ([legend] if legend is not None else [])

    def legend() -> list:
        found = ax.get_legend()
        return [found] if found is not None else []

    return save_gif(fig, draw, len(rows), target, fps=fps, above=legend)


def plot_point_paths(
    result,
    points: Sequence[str],
    *legacy: object,
    ax: object = None,
    path: str | os.PathLike | None = None,
    labels: Sequence[str] | None = None,
    others: Sequence[tuple[np.ndarray, np.ndarray, str]] = (),
    title: str | None = None,
) -> Figure:
    """The recorded paths of points (``y`` over ``x`` in mm).

    Parameters
    ----------
    result : Result
        A mechanism run.
    points : sequence of str
        Points ``"component.point"`` (their ``_x``/``_y`` columns are drawn).
    ax : matplotlib Axes, optional
        Draw into this axes instead of a new figure.
    path : str or os.PathLike, optional
        Also write the figure as a PNG file (atomically).
    labels : sequence of str, optional
        Legend labels (default: the point names).
    others : sequence of (x [m], y [m], label), optional
        Further paths (e.g. a reference or another run) drawn dashed.
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on (the earlier ``plot_point_paths(result, points, path)`` returns the path,
        with an :class:`~exudyn_atcm.AtcmDeprecationWarning`, for one release).
    """
    if legacy:
        old, _ = legacy_path("plot_point_paths", legacy, path)
        plot_point_paths(result, points, ax=ax, path=old, labels=labels, others=others, title=title)
        return Path(old)
    labels = list(labels) if labels is not None else list(points)
    if len(labels) != len(points):
        raise ValueError(f"labels must have one entry per point ({len(points)}), got {len(labels)}")
    fig, (ax,) = figure_axes(ax, 1, 1, width=6.4, height=4.8)
    for ref, label in zip(points, labels):
        ax.plot(result_column(result, f"{ref}_x") * _MM, result_column(result, f"{ref}_y") * _MM, lw=1.5, label=label)
    for x, y, label in others:
        ax.plot(np.asarray(x) * _MM, np.asarray(y) * _MM, ls="--", lw=1.2, label=label)
    ax.set_xlabel(axis_label("x", "mm"))
    ax.set_ylabel(axis_label("y", "mm"))
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(loc="best", fontsize=8)
    if title:
        ax.set_title(title)
    return finish(fig, path)
