"""Plots of a study table: a scalar against one parameter, and a heat map over two.

Both take the table returned by :func:`~exudyn_atcm.study.sweep` (a :class:`~exudyn_atcm.study.table.StudyTable`, or a DataFrame or structured
array) and write a PNG atomically through :mod:`exudyn_atcm.plots.style`.  Failed runs
(NaN scalars) are left out of lines and shown as blank cells in heat maps.  When further
parameters vary, only the rows at the first value of each of them are plotted (the title
says which).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..plots.style import axis_label, display_scale, new_figure, save_figure
from .table import column, unit_of

__all__ = ["plot_scalar", "plot_heatmap", "plot_study"]


def _values(table: Any, name: str) -> np.ndarray:
    values = column(table, name)
    return values.astype(float) if values.dtype.kind in "biuf" else values


def _select(table: Any, keep: Sequence[str], others: Sequence[str]) -> tuple[np.ndarray, str]:
    """Rows at the first value of every parameter in ``others``; a note for the title."""
    n = len(column(table, keep[0]))
    mask = np.ones(n, dtype=bool)
    notes = []
    for name in others:
        values = column(table, name)
        first = values[0]
        mask &= values == first
        notes.append(f"{name} = {first:g}" if isinstance(first, (float, np.floating)) else f"{name} = {first}")
    return mask, ", ".join(notes)


def plot_scalar(
    table: Any,
    scalar: str,
    x: str,
    path: str | os.PathLike,
    *,
    by: str | None = None,
    others: Sequence[str] = (),
    lines: bool = True,
) -> Path:
    """Line plot of ``scalar`` against parameter ``x``, one line per value of ``by``.

    Parameters
    ----------
    table : StudyTable
        A study table.
    scalar, x, by : str
        Column names (with or without the ``[unit]``).
    path : str or os.PathLike
        PNG file to write.
    others : sequence of str
        Further varied parameters, held at their first value.
    lines : bool
        Join the points (grids); ``False`` draws markers only (sampled studies).
    """
    mask, note = _select(table, [x], [n for n in others if n not in (x, by)])
    xs = _values(table, x)[mask]
    ys = _values(table, scalar)[mask].astype(float)
    x_factor, x_unit = display_scale(xs, unit_of(table, x)) if xs.dtype.kind == "f" else (1.0, unit_of(table, x))
    y_factor, y_unit = display_scale(ys, unit_of(table, scalar))
    fig, (ax,) = new_figure(1, height=3.8)
    groups = [None] if by is None else list(dict.fromkeys(column(table, by)[mask].tolist()))
    for group in groups:
        sel = np.ones(xs.size, dtype=bool) if group is None else column(table, by)[mask] == group
        order = np.argsort(xs[sel], kind="stable")
        label = None if group is None else f"{by} = {group:g} {unit_of(table, by)}" if isinstance(group, float) else f"{by} = {group}"
        ax.plot(xs[sel][order] * x_factor if xs.dtype.kind == "f" else xs[sel][order], ys[sel][order] * y_factor, "o-" if lines else "o", markersize=3, label=label)
    ax.set_xlabel(axis_label(x, x_unit))
    ax.set_ylabel(axis_label(scalar, y_unit))
    ax.set_title(scalar + (f" ({note})" if note else ""))
    if by is not None:
        ax.legend(loc="best")
    return save_figure(fig, path)


def plot_heatmap(
    table: Any,
    scalar: str,
    x: str,
    y: str,
    path: str | os.PathLike,
    *,
    others: Sequence[str] = (),
) -> Path:
    """Heat map of ``scalar`` over parameters ``x`` and ``y``.

    A full grid is drawn as cells (``pcolormesh``); scattered points (sampled studies) as
    coloured markers.  Axes are labelled with units, the colour bar with the scalar's.
    """
    mask, note = _select(table, [x, y], [n for n in others if n not in (x, y)])
    xs = _values(table, x)[mask].astype(float)
    ys = _values(table, y)[mask].astype(float)
    zs = _values(table, scalar)[mask].astype(float)
    x_factor, x_unit = display_scale(xs, unit_of(table, x))
    y_factor, y_unit = display_scale(ys, unit_of(table, y))
    z_factor, z_unit = display_scale(zs, unit_of(table, scalar))
    ux, uy = np.unique(xs), np.unique(ys)
    fig, (ax,) = new_figure(1, height=4.2)
    if ux.size * uy.size == xs.size and ux.size > 1 and uy.size > 1:
        grid = np.full((uy.size, ux.size), np.nan)
        grid[np.searchsorted(uy, ys), np.searchsorted(ux, xs)] = zs
        mesh = ax.pcolormesh(_edges(ux) * x_factor, _edges(uy) * y_factor, np.ma.masked_invalid(grid * z_factor), shading="flat")
    else:
        mesh = ax.scatter(xs * x_factor, ys * y_factor, c=zs * z_factor, s=36)
    bar = fig.colorbar(mesh, ax=ax)
    bar.set_label(axis_label(scalar, z_unit))
    ax.set_xlabel(axis_label(x, x_unit))
    ax.set_ylabel(axis_label(y, y_unit))
    ax.set_title(scalar + (f" ({note})" if note else ""))
    return save_figure(fig, path)


def _edges(centres: np.ndarray) -> np.ndarray:
    mid = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[centres[0] - (mid[0] - centres[0])], mid, [centres[-1] + (centres[-1] - mid[-1])]])


def plot_study(
    table: Any, varied: Sequence[str], scalars: Sequence[str], out_dir: str | os.PathLike, prefix: str, *, grid: bool = True
) -> list[Path]:
    """The standard plots of a study; returns the files.

    For each scalar: a line plot against the first numeric varied parameter (one line per
    value of the second varied parameter; markers only and no grouping for a sampled
    study, ``grid=False``) and, with two or more numeric varied parameters, a heat map over
    the first two.
    """
    out = Path(out_dir)
    files: list[Path] = []
    numeric = [n for n in varied if column(table, n).dtype.kind in "iuf"]
    if not varied:
        return files
    for scalar in scalars:
        if not np.isfinite(_values(table, scalar).astype(float)).any():
            continue
        x = numeric[0] if numeric else varied[0]
        by = next((n for n in varied if n != x), None) if grid else None
        files.append(plot_scalar(table, scalar, x, out / f"{prefix}{scalar}_vs_{x}.png", by=by,
                                 others=varied if grid else (), lines=grid))
        if len(numeric) >= 2:
            files.append(plot_heatmap(table, scalar, numeric[0], numeric[1], out / f"{prefix}{scalar}_map.png",
                                      others=varied if grid else ()))
    return files
