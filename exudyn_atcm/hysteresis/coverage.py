"""Which part of the Preisach triangle a record's input has shown a model: :class:`TriangleCoverage`.

A Preisach model's output along a monotone input segment that starts at a reversal ``m`` (a
local minimum) and rises to ``M`` is the Everett function ``K(u, m)`` for ``u`` from ``m`` to
``M``; along a falling segment from a maximum ``M`` it is ``K(M, u)``.  A record therefore
measures the density on the *reversal curves* of its input: the vertical line ``β = m``,
``α ∈ [m, M]`` of every rising segment and the horizontal line ``α = M``, ``β ∈ [m, M]`` of
every falling one (the first-order reversal curves of a FORC measurement fill the triangle
with them).  Major loops alone show only the two edges ``β = u_min`` and ``α = u_max``; the
interior, where nested minor loops live, comes from the fit's prior.

:class:`TriangleCoverage` marks the cells of an ``n``-level grid over the fitted input range
that the reversal curves of the fitted samples cross, and :meth:`TriangleCoverage.check`
says (and warns) how much of another input's reversal curves lie outside them.  A reversal
counts once the input has moved back by more than half a cell (noise on the input does not
make reversals).  Inputs beyond the grid's range are unseen: the grid is extended by whole
cells of the same size to hold them, and every cell outside the fitted range counts as never
crossed (there the model saturates or extrapolates, it was not fitted there).
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from .._checks import shown
from ..errors import AccuracyWarning

__all__ = ["TriangleCoverage", "reversal_curves", "runs"]


def runs(u: Any, rows: Any, overlap: int = 0) -> list[np.ndarray]:
    """The contiguous stretches of ``u`` where the boolean ``rows`` is true, each with ``overlap``
    samples before it (so a stretch starts from the input it left off), as arrays."""
    u = np.asarray(u, dtype=float)
    flags = np.asarray(rows, dtype=bool)
    edges = np.flatnonzero(np.diff(np.r_[0, flags.astype(np.int8), 0]))
    return [u[max(a - overlap, 0):b] for a, b in zip(edges[::2], edges[1::2])]


def _pieces(u: Any) -> list[np.ndarray]:
    """An input as a list of stretches: one array, or a list of arrays (e.g. from :func:`runs`)."""
    if isinstance(u, (list, tuple)) and u and all(np.ndim(p) == 1 for p in u):
        return [np.asarray(p, dtype=float) for p in u]
    return [np.asarray(u, dtype=float)]


def reversal_curves(u: np.ndarray, tolerance: float) -> list[tuple[float, float, bool]]:
    """Monotone segments of ``u`` as ``(start, end, rising)``; a reversal needs a move back by more than ``tolerance``."""
    u = np.asarray(u, dtype=float)
    if u.size < 2:
        return []
    segments = []
    start = float(u[0])
    extreme = float(u[0])
    rising: bool | None = None
    for v in u[1:].tolist():
        if rising is None:
            if abs(v - start) > tolerance:
                rising = v > start
                extreme = v
            continue
        if (v > extreme) if rising else (v < extreme):
            extreme = v
        elif (extreme - v > tolerance) if rising else (v - extreme > tolerance):
            segments.append((start, extreme, rising))
            start, extreme, rising = extreme, v, not rising
    if rising is not None:
        segments.append((start, extreme, rising))
    return segments


class TriangleCoverage:
    """Grid cells of the Preisach triangle crossed by the reversal curves of a training input.

    Parameters
    ----------
    u : array_like or list of array_like
        The fitted input samples (from where the model's memory is known); a list for
        stretches of a record (e.g. interleaved cycles).
    u_lo, u_hi : float
        Input range of the grid.
    n_levels : int
        Grid cells along the input; the triangle has ``n (n + 1) / 2`` cells.
    """

    def __init__(self, u: Any, u_lo: float, u_hi: float, n_levels: int) -> None:
        if not (np.isfinite(u_lo) and np.isfinite(u_hi) and u_hi > u_lo):
            raise ValueError(f"u_lo, u_hi must be finite with u_hi > u_lo, got {shown(u_lo)}, {u_hi!r}")
        if isinstance(n_levels, bool) or not isinstance(n_levels, (int, np.integer)) or n_levels < 1:
            raise ValueError(f"n_levels must be an integer >= 1, got {shown(n_levels)}")
        self.u_lo, self.u_hi, self.n_levels = float(u_lo), float(u_hi), int(n_levels)
        self.seen = self.cells(u)

    def _extension(self, u: Any) -> tuple[int, int]:
        """Whole cells needed below and above the grid to hold every input of ``u``."""
        values = np.concatenate([p for p in _pieces(u) if p.size] or [np.zeros(0)])
        if not values.size:
            return 0, 0
        h = (self.u_hi - self.u_lo) / self.n_levels
        below = max(int(np.ceil((self.u_lo - float(values.min())) / h - 1e-9)), 0)
        above = max(int(np.ceil((float(values.max()) - self.u_hi) / h - 1e-9)), 0)
        return below, above

    def cells(self, u: Any, extension: tuple[int, int] = (0, 0)) -> np.ndarray:
        """Boolean mask ``[i_alpha, j_beta]`` (``j <= i``) of the cells the reversal curves of ``u`` cross.

        ``(n, n)`` over the grid, inputs beyond it in its edge cells; with ``extension =
        (below, above)`` over the grid extended by that many cells of the same size (the grid's
        own cells from index ``below``).
        """
        below, above = extension
        n = self.n_levels + below + above
        mask = np.zeros((n, n), dtype=bool)
        h = (self.u_hi - self.u_lo) / self.n_levels
        top = self.n_levels - 1

        def index(v: float) -> int:
            # the grid's own cells hold [u_lo, u_hi] with both ends; beyond, cells of the same size
            k = int(np.floor((v - self.u_lo) / h))
            if self.u_lo <= v <= self.u_hi:
                k = min(max(k, 0), top)
            return min(max(k + below, 0), n - 1)

        for piece in _pieces(u):
            for first, last, rising in reversal_curves(piece, 0.5 * h):
                lo, hi = (first, last) if rising else (last, first)
                i_lo, i_hi = index(lo), index(hi)
                if rising:  # K(u, m): beta = m fixed, alpha from m to M
                    mask[i_lo:i_hi + 1, i_lo] = True
                else:  # K(M, u): alpha = M fixed, beta from m to M
                    mask[i_hi, i_lo:i_hi + 1] = True
        return mask

    @property
    def fraction(self) -> float:
        """Share of the triangle's cells crossed by the training input's reversal curves."""
        n = self.n_levels
        return float(self.seen.sum()) / (n * (n + 1) // 2)

    def unseen_fraction(self, u: Any) -> float:
        """Share of the cells crossed by the reversal curves of ``u`` that the training input never crossed.

        ``u``: an input, or a list of stretches of one.  Cells beyond the grid's range count as
        never crossed.
        """
        below, above = self._extension(u)
        visited = self.cells(u, (below, above))
        seen = np.zeros_like(visited)
        n = self.n_levels
        seen[below:below + n, below:below + n] = self.seen
        total = int(visited.sum())
        return float((visited & ~seen).sum()) / total if total else 0.0

    def check(self, u: Any, threshold: float = 0.1, *, warn: bool = True) -> float:
        """Return :meth:`unseen_fraction` of ``u``; warn (``AccuracyWarning``) if it exceeds ``threshold``.

        Parameters
        ----------
        u : array_like
            Input the model is to be used with.
        threshold : float, optional
            Share of unseen cells tolerated without a warning (default 0.1).
        warn : bool, optional
            Set ``False`` to only compute the share.
        """
        share = self.unseen_fraction(u)
        if warn and share > threshold:
            values = np.concatenate([p for p in _pieces(u) if p.size] or [np.zeros(1)])
            low, high = float(values.min()), float(values.max())
            beyond = "" if self.u_lo <= low and high <= self.u_hi else (
                f"; the input spans {low:g} ... {high:g}, beyond the fitted input range {self.u_lo:g} ... {self.u_hi:g}, "
                "where the model extrapolates (those cells count as unseen)")
            warnings.warn(
                f"the input's reversal curves (its minor loops) cross {100 * share:.0f} % of Preisach-triangle cells "
                f"that the fitted record never crossed (it covered {100 * self.fraction:.1f} % of the triangle): the "
                f"model's output there rests on the fit's prior, not on data; measure minor loops or FORCs there{beyond}",
                AccuracyWarning, stacklevel=2)
        return share

    def to_dict(self) -> dict[str, Any]:
        """Summary for reports: grid, cells crossed, fraction."""
        n = self.n_levels
        return {"n_levels": n, "input_range": [self.u_lo, self.u_hi], "cells_crossed": int(self.seen.sum()),
                "cells_total": n * (n + 1) // 2, "fraction": self.fraction}
