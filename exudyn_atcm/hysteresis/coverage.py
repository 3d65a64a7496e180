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
make reversals).
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from ..errors import AccuracyWarning

__all__ = ["TriangleCoverage", "reversal_curves"]


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
    u : array_like
        The fitted input samples (from where the model's memory is known).
    u_lo, u_hi : float
        Input range of the grid.
    n_levels : int
        Grid cells along the input; the triangle has ``n (n + 1) / 2`` cells.
    """

    def __init__(self, u: Any, u_lo: float, u_hi: float, n_levels: int) -> None:
        if not (np.isfinite(u_lo) and np.isfinite(u_hi) and u_hi > u_lo):
            raise ValueError(f"u_lo, u_hi must be finite with u_hi > u_lo, got {u_lo!r}, {u_hi!r}")
        if isinstance(n_levels, bool) or not isinstance(n_levels, (int, np.integer)) or n_levels < 1:
            raise ValueError(f"n_levels must be an integer >= 1, got {n_levels!r}")
        self.u_lo, self.u_hi, self.n_levels = float(u_lo), float(u_hi), int(n_levels)
        self.seen = self.cells(u)

    def _index(self, v: float) -> int:
        k = int((v - self.u_lo) / (self.u_hi - self.u_lo) * self.n_levels)
        return min(max(k, 0), self.n_levels - 1)

    def cells(self, u: Any) -> np.ndarray:
        """Boolean ``(n, n)`` mask ``[i_alpha, j_beta]`` (``j <= i``) of the cells the reversal curves of ``u`` cross."""
        n = self.n_levels
        mask = np.zeros((n, n), dtype=bool)
        h = (self.u_hi - self.u_lo) / n
        for first, last, rising in reversal_curves(np.asarray(u, dtype=float), 0.5 * h):
            lo, hi = (first, last) if rising else (last, first)
            i_lo, i_hi = self._index(lo), self._index(hi)
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
        """Share of the cells crossed by the reversal curves of ``u`` that the training input never crossed."""
        visited = self.cells(u)
        total = int(visited.sum())
        return float((visited & ~self.seen).sum()) / total if total else 0.0

    def check(self, u: Any, threshold: float = 0.1, *, warn: bool = True) -> float:
        """Return :meth:`unseen_fraction` of ``u``; warn (``RuntimeWarning``) if it exceeds ``threshold``.

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
            warnings.warn(
                f"the input's reversal curves (its minor loops) cross {100 * share:.0f} % of Preisach-triangle cells "
                f"that the fitted record never crossed (it covered {100 * self.fraction:.1f} % of the triangle): the "
                "model's output there rests on the fit's prior, not on data; measure minor loops or FORCs there",
                AccuracyWarning, stacklevel=2)
        return share

    def to_dict(self) -> dict[str, Any]:
        """Summary for reports: grid, cells crossed, fraction."""
        n = self.n_levels
        return {"n_levels": n, "input_range": [self.u_lo, self.u_hi], "cells_crossed": int(self.seen.sum()),
                "cells_total": n * (n + 1) // 2, "fraction": self.fraction}
