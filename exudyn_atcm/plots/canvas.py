"""The drawing surface handed to a connection's ``draw`` (:mod:`exudyn_atcm.mechanism.connection`).

Positions are in metres (drawn in millimetres); ``position`` gives a point at the drawn row
(displacements scaled as the drawing's), ``reference`` in the reference pose.  A label is put
in the legend once however many connections use it.
"""

from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np

from ..mechanism import Bender, Flexure, Mechanism, PointRef

__all__ = ["MechanismCanvas"]

_MM = 1e3


def zigzag(p: np.ndarray, q: np.ndarray, width: float, turns: int = 6) -> np.ndarray:
    """A zigzag line [m] from ``p`` to ``q`` of half-width ``width`` [m]."""
    d = q - p
    length = float(np.hypot(*d))
    if length == 0.0:
        return np.array([p, q])
    u = d / length
    n = np.array([-u[1], u[0]])
    s = np.concatenate([[0.0, 0.2], 0.2 + 0.6 * (np.arange(2 * turns) + 0.5) / (2 * turns), [0.8, 1.0]])
    amp = np.concatenate([[0.0, 0.0], np.where(np.arange(2 * turns) % 2 == 0, 1.0, -1.0), [0.0, 0.0]])
    return p + s[:, None] * d + (amp * width)[:, None] * n


class MechanismCanvas:
    """Matplotlib axes ``ax`` (in mm) with the positions of ``mechanism``'s points.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Target axes.
    mechanism : Mechanism
        The mechanism drawn.
    position : callable
        ``position(point)`` -> (x, y) [m] of a :class:`~exudyn_atcm.mechanism.PointRef` as drawn.
    size : float
        The mechanism's size [m] (symbols scale with it).
    """

    def __init__(self, ax: Any, mechanism: Mechanism, position: Callable[[PointRef], np.ndarray], size: float) -> None:
        self.ax = ax
        self.mechanism = mechanism
        self._position = position
        self.size = float(size)
        self._labels: set[str] = set()

    def position(self, point: PointRef) -> np.ndarray:
        """Position [m] of ``point`` as drawn (the drawn row, displacements scaled)."""
        return np.asarray(self._position(point), dtype=float)

    def reference(self, point: PointRef) -> np.ndarray:
        """Position [m] of ``point`` in the reference pose."""
        return self.mechanism.position(point)

    def inward(self, point: PointRef) -> np.ndarray:
        """Unit direction from ``point`` into its component (along a bender or flexure, to a link's centre)."""
        comp = self.mechanism.components[point.component]
        if isinstance(comp, (Bender, Flexure)):
            d = np.array([math.cos(comp.angle), math.sin(comp.angle)])
            d = d if point.point == "base" else -d
        else:
            d = np.array(comp.center_of_mass) - np.array(comp.points[point.point])
            d = d if np.hypot(*d) > 0 else np.array([1.0, 0.0])
        return d / np.hypot(*d)

    def _label(self, label: str | None) -> str | None:
        if label is None or label in self._labels:
            return None
        self._labels.add(label)
        return label

    def line(self, xy: Any, *, label: str | None = None, **style: Any) -> Any:
        """A polyline through the rows (x, y) [m] of ``xy``; matplotlib ``style``; ``label`` once in the legend."""
        xy = np.atleast_2d(np.asarray(xy, dtype=float))
        style.setdefault("zorder", 4)
        return self.ax.plot(*(xy * _MM).T, label=self._label(label), **style)[0]

    def zigzag(self, p: Any, q: Any, *, label: str | None = None, **style: Any) -> Any:
        """A spring's zigzag from ``p`` to ``q`` [m]."""
        style.setdefault("lw", 1.2)
        return self.line(zigzag(np.asarray(p, float), np.asarray(q, float), 0.012 * self.size), label=label, **style)

    def wall(self, center: Any, along: Any, length: float, behind: Any, **style: Any) -> None:
        """A ground wall [m] through ``center`` along ``along``, ``length`` long, hatched towards ``behind``."""
        along = np.asarray(along, float) / np.hypot(*along)
        behind = np.asarray(behind, float) / np.hypot(*behind)
        center = np.asarray(center, float)
        a, b = center - 0.5 * length * along, center + 0.5 * length * along
        self.ax.plot(*(np.array([a, b]) * _MM).T, color="k", lw=1.5, **style)
        for t in np.linspace(0.0, 1.0, 6):
            start = a + t * (b - a)
            end = start + 0.25 * length * (behind - 0.6 * along)
            self.ax.plot(*(np.array([start, end]) * _MM).T, color="k", lw=0.8)
