"""Where a legend covers the least of what an animation draws in all its frames.

matplotlib's ``loc="best"`` looks at the data of the figure it draws; an animation's legend placed
so in its first frame can cover what later frames draw.  :func:`place_legend` tries the same
locations in the same order as ``"best"`` and scores each much as ``"best"`` does (the drawn
vertices inside the legend, plus the filled shapes it overlaps: the shapes themselves, where
``"best"`` takes their boxes), over the vertices and shapes of every frame at once.

May import: numpy, matplotlib's paths (where a legend is placed: a figure exists).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure
    from matplotlib.legend import Legend

__all__ = ["LOCATIONS", "place_legend"]

#: The location codes in the order matplotlib's ``loc="best"`` tries them (the first of equal scores wins).
LOCATIONS = tuple(range(1, 11))


def place_legend(fig: Figure, ax: Any, legend: Legend, points: np.ndarray, shapes: Sequence[np.ndarray] = ()) -> int:
    """Set ``legend`` to the location covering the fewest of ``points`` and ``shapes``; returns its code.

    ``points``: every vertex drawn in any frame, shape (n, 2), in ``ax``'s data coordinates;
    ``shapes``: the filled polygons of every frame (each (m, 2), data coordinates), each counted
    once where the legend's box overlaps it.  The figure must have been drawn once (its axes laid out): each location's box is the
    legend's extent there, its size and padding as matplotlib lays them out.
    """
    from matplotlib.path import Path  # noqa: PLC0415 - lazy: matplotlib is slow to import (loaded by now)

    renderer = fig.canvas.get_renderer()
    to_pixels = ax.transData.transform
    xy = to_pixels(np.asarray(points, dtype=float).reshape(-1, 2))
    polygons = [Path(to_pixels(np.asarray(s, dtype=float).reshape(-1, 2)), closed=True) for s in shapes if len(s) > 2]
    best, best_score = LOCATIONS[0], None
    for code in LOCATIONS:
        legend.set_loc(code)
        e = legend.get_window_extent(renderer)
        inside = (xy[:, 0] >= e.x0) & (xy[:, 0] <= e.x1) & (xy[:, 1] >= e.y0) & (xy[:, 1] <= e.y1)
        score = int(inside.sum()) + sum(polygon.intersects_bbox(e, filled=True) for polygon in polygons)
        if best_score is None or score < best_score:
            best, best_score = code, score
    legend.set_loc(best)
    return best
