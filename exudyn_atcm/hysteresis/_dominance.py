"""Weighted 2-D dominance sums over relay thresholds: a fixed, small work per query.

For points ``(alpha[i], beta[i])`` with weights ``w[i]`` the structure answers

``K(a, b) = sum of w[i] with alpha[i] <= a and beta[i] >= b``

(the Everett-type function of a discrete Preisach model, Mayergoyz 2003) for any ``a`` and
``b`` (infinite ones included), whatever the points' layout, with one binary search in the
sorted ``alpha`` plus, per level, one binary search in sorted ``beta`` and one table
look-up (``O(log n)``, no loop in Python): two levels up to 2**22 table entries (about
16000 points), three above.

Layout (a blocked table).  The points are sorted by ``alpha``, so that ``alpha <= a`` is
the prefix of the first ``i = bisect_right(sorted alpha, a)`` points, and cut into nested
blocks of ``2**p1 > 2**p2 > ... > 2**p_m = 1`` points.  Level ``t`` holds, for every
boundary of a level-``t+1`` block and every rank ``l`` of ``b`` among the ``beta`` of the
enclosing level-``t`` block (level 0: all points), the weight of the points from the
level-``t`` block's start up to that boundary with ``beta >= b``.  ``K`` is the sum over the
levels of one entry each, a level being skipped when ``i`` falls on its block boundary.

Memory: ``(n / 2**p1 + 1)(n + 1) + n (2**p1 + 1)`` floats with two levels (``p1 ~ log2(n)/2``,
``O(n**1.5)``: 5.9 MB at 5000 points, 46 MB at 20000), ``O(n**(4/3))`` with three
(14 MB at 20000), plus about 32 bytes per point and level for the sorted threshold lists.  The tables are flat ``array.array('d')``: 8 bytes per entry, and
indexing returns a Python float without numpy's per-call overhead.
"""

from __future__ import annotations

from array import array
from bisect import bisect_left, bisect_right
from itertools import product
from typing import Callable

import numpy as np
from .._checks import shown

#: largest two-level table (entries); a larger point set gets three levels
TWO_LEVEL_ENTRIES = 1 << 22


def _entries(n_pad: int, shifts: tuple[int, ...]) -> int:
    """Table entries for block shifts ``shifts`` (decreasing, last 0) over ``n_pad`` points."""
    total = 0
    size = n_pad
    for level, sub in enumerate(shifts):
        rows = (n_pad >> sub) + (1 if level == 0 else 0)
        total += rows * (size + 1)
        size = 1 << sub
    return total


def _best_shifts(n: int, levels: int) -> tuple[int, ...]:
    """Block shifts ``(p1, ..., 0)`` for ``levels`` levels with the fewest table entries."""
    top = max(1, (n - 1).bit_length())
    best: tuple[int, tuple[int, ...]] | None = None
    for inner in product(range(top, -1, -1), repeat=levels - 1):
        shifts = (*inner, 0)
        if any(x <= y for x, y in zip(shifts, shifts[1:])):
            continue
        cost = _entries(_padded(n, shifts), shifts)
        if best is None or cost < best[0]:
            best = (cost, shifts)
    if best is None:  # too few points for that many levels
        return (0,)
    return best[1]


class DominanceSums:
    """Static weighted dominance sums ``K(a, b)`` of points ``(alpha, beta)``.

    Parameters
    ----------
    alpha, beta : numpy.ndarray
        Finite coordinates of the points, shape ``(n,)``, ``n >= 1``, any order; ties and
        duplicate points are allowed, ``beta <= alpha`` is not required.
    weights : numpy.ndarray
        Finite weights, shape ``(n,)``.
    levels : int, optional
        2 or 3; by default 2 while the tables hold at most :data:`TWO_LEVEL_ENTRIES`
        entries, else 3 (less memory, one more binary search per query).

    Attributes
    ----------
    query : callable
        ``query(a, b) -> float``: the weight of the points with ``alpha <= a`` and
        ``beta >= b`` (``a``, ``b`` real or infinite).  A plain function, no ``self``, for the lowest call
        overhead in CPython.
    shifts : tuple of int
        Block sizes ``2**p`` of the levels below the top, largest first (the last is 1).
    nbytes : int
        Memory held by the tables (8 bytes per entry) and the sorted threshold lists (about
        32 bytes per entry), bytes.
    """

    query: Callable[[float, float], float]

    def __init__(self, alpha: np.ndarray, beta: np.ndarray, weights: np.ndarray, levels: int | None = None) -> None:
        alpha = np.asarray(alpha, dtype=float)
        beta = np.asarray(beta, dtype=float)
        weights = np.asarray(weights, dtype=float)
        n = alpha.size
        if n < 1 or alpha.shape != (n,) or beta.shape != (n,) or weights.shape != (n,):
            raise ValueError(
                "alpha, beta, weights must be 1-D arrays of one length >= 1, got shapes "
                f"{alpha.shape}, {beta.shape}, {weights.shape}"
            )
        if levels is None:
            shifts = _best_shifts(n, 2)
            if _entries(_padded(n, shifts), shifts) > TWO_LEVEL_ENTRIES:
                shifts = _best_shifts(n, 3)
        elif levels in (2, 3):
            shifts = _best_shifts(n, levels)
        else:
            raise ValueError(f"levels must be 2, 3 or None (automatic), got {shown(levels)}")
        n_pad = _padded(n, shifts)

        order = np.argsort(alpha, kind="stable")
        b_by_a = np.full(n_pad, np.inf)  # padding points: beta = +inf, weight 0, never counted
        b_by_a[:n] = beta[order]
        w_by_a = np.zeros(n_pad)
        w_by_a[:n] = weights[order]

        tables: list[array] = []
        sorted_betas: list[list[list[float]]] = []
        size = n_pad
        for level, sub in enumerate(shifts):
            n_blocks = n_pad // size
            per_block = size >> sub  # level-(t+1) blocks in a level-t block
            blocks_b = b_by_a.reshape(n_blocks, size)
            # rank of each point's beta in its block (stable: equal betas get consecutive
            # ranks, so "beta >= b" is "rank >= bisect_left(block's sorted beta, b)")
            local_order = np.argsort(blocks_b, axis=1, kind="stable")
            local_rank = np.empty_like(local_order)
            np.put_along_axis(local_rank, local_order, np.arange(size)[None, :], axis=1)
            table = np.zeros((n_blocks, per_block + 1, size + 1))
            positions = np.arange(n_pad)
            # each point once: (its block, the sub-block boundary after it, its rank)
            table[positions // size, ((positions % size) >> sub) + 1, local_rank.ravel()] = w_by_a
            np.cumsum(table, axis=1, out=table)
            table = np.cumsum(table[:, :, ::-1], axis=2)[:, :, ::-1]
            if level > 0:
                table = table[:, :per_block, :]  # a whole block is a boundary of the level above
            tables.append(array("d", np.ascontiguousarray(table).tobytes()))
            sorted_betas.append(np.take_along_axis(blocks_b, local_order, axis=1).tolist())
            size = 1 << sub

        alpha_list: list[float] = alpha[order].tolist()
        self.shifts = shifts
        self.n_points = n
        self.nbytes = 8 * sum(len(t) for t in tables) + 32 * (n + len(shifts) * n_pad)
        self.query = _make_query(alpha_list, shifts, n_pad, tables, sorted_betas)


def _padded(n: int, shifts: tuple[int, ...]) -> int:
    size = 1 << shifts[0]
    return -(-n // size) * size


def _make_query(alpha_list, shifts, n_pad, tables, sorted_betas) -> Callable[[float, float], float]:
    """The query as a closure over local variables, unrolled for two or three levels."""
    t0 = tables[0]
    beta0 = sorted_betas[0][0]
    w0 = n_pad + 1
    if len(shifts) == 1:  # a single point: no block below the top

        def query1(a: float, b: float) -> float:
            return t0[bisect_right(alpha_list, a) * w0 + bisect_left(beta0, b)]

        return query1
    p1 = shifts[0]
    m1 = (1 << p1) - 1
    t1 = tables[1]
    beta1 = sorted_betas[1]
    w1 = (1 << p1) + 1
    if len(shifts) == 2:

        def query2(a: float, b: float) -> float:
            i = bisect_right(alpha_list, a)
            s = t0[(i >> p1) * w0 + bisect_left(beta0, b)]
            if i & m1:
                s += t1[i * w1 + bisect_left(beta1[i >> p1], b)]
            return s

        return query2
    p2 = shifts[1]
    m2 = (1 << p2) - 1
    t2 = tables[2]
    beta2 = sorted_betas[2]
    w2 = (1 << p2) + 1

    def query3(a: float, b: float) -> float:
        i = bisect_right(alpha_list, a)
        s = t0[(i >> p1) * w0 + bisect_left(beta0, b)]
        if i & m1:
            s += t1[(i >> p2) * w1 + bisect_left(beta1[i >> p1], b)]
            if i & m2:
                s += t2[i * w2 + bisect_left(beta2[i >> p2], b)]
        return s

    return query3
