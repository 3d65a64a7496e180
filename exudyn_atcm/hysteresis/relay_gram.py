"""The relay grid of the Preisach fits and the Gram matrices of its least-squares problems.

:func:`relay_grid` lays the relays of an ``n_levels`` grid over an input range;
:func:`relay_gram` and :func:`cell_gram` accumulate the normal equations of a record over the
relays (discrete fit) or the grid cells (Everett fit), chunk by chunk, each distinct relay
state once with its count.  Used by :mod:`exudyn_atcm.hysteresis.identification`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .nnls import nnls_gram
from .staircase import StaircasePreisach

__all__ = ["relay_grid", "refined_relays", "smoothness_matrix", "relay_gram", "CellFractions", "cell_gram", "chunked_gram",
           "nnls_normal"]


def relay_grid(u_lo: float, u_hi: float, n_levels: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Relays of a regular grid on the Preisach triangle.

    The input range is cut into ``n_levels`` cells of width ``h``; the thresholds sit at the
    cell centres ``v_k = u_lo + (k + 1/2) h``.  One relay per pair ``alpha = v_i >= beta = v_j``:
    ``n_levels (n_levels + 1) / 2`` relays, those on the diagonal (``alpha == beta``) giving the
    reversible part.

    Returns
    -------
    alpha, beta : numpy.ndarray
        Thresholds of each relay.
    index : numpy.ndarray
        ``(i, j)`` grid indices of each relay, shape ``(n_relays, 2)``.
    """
    h = (u_hi - u_lo) / n_levels
    levels = u_lo + (np.arange(n_levels) + 0.5) * h
    i, j = np.tril_indices(n_levels)
    return levels[i], levels[j], np.column_stack([i, j])


def refined_relays(u_lo: float, u_hi: float, n_levels: int, weights: np.ndarray,
                   relays_per_cell: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Relays of an ``n_levels`` grid whose cell weights are spread evenly over their cells.

    Each cell of the coarse grid (:func:`relay_grid` order of ``weights``) is cut into
    ``k = relays_per_cell`` parts along each axis, and one relay sits at the centre of every
    part that lies in the Preisach triangle ``alpha >= beta``: the relay grid of ``k·n_levels``
    levels.  A relay's weight is the cell's weight times the share of the cell's area its part
    holds (as :class:`~exudyn_atcm.hysteresis.everett.EverettPreisach` spreads it: over the
    square off the diagonal, over the half below ``alpha = beta`` on it), so ``1/k²`` off the
    diagonal, and on a diagonal cell ``2/k²`` for a full square part and ``1/k²`` for a part the
    diagonal halves.  The relays switch exactly where the spread cells are fully on or off,
    so for inputs whose turning points lie on the fine grid's cell edges their output equals
    the spread grid's; in between it is a staircase with steps ``k`` times finer than the
    coarse grid's relays would give.

    Returns
    -------
    alpha, beta, weights : numpy.ndarray
        ``k·n (k·n + 1)/2`` relays.
    """
    k = int(relays_per_cell)
    alpha, beta, fine = relay_grid(u_lo, u_hi, n_levels * k)
    _, _, coarse = relay_grid(u_lo, u_hi, n_levels)
    cell = np.zeros((n_levels, n_levels))
    cell[coarse[:, 0], coarse[:, 1]] = weights
    ci, cj = fine[:, 0] // k, fine[:, 1] // k
    share = np.where((ci == cj) & (fine[:, 0] != fine[:, 1]), 2.0, 1.0) / k**2
    return alpha, beta, cell[ci, cj] * share


def smoothness_matrix(index: np.ndarray, n_levels: int) -> Any:
    """First differences between neighbouring grid cells (along alpha and along beta), sparse."""
    import scipy.sparse  # noqa: PLC0415 - lazy: scipy.sparse is slow to import
    position = -np.ones((n_levels, n_levels), dtype=int)
    position[index[:, 0], index[:, 1]] = np.arange(index.shape[0])
    first, second = [], []
    for di, dj in ((1, 0), (0, 1)):
        ni, nj = index[:, 0] + di, index[:, 1] + dj
        ok = (ni < n_levels) & (nj <= ni)
        first.append(np.flatnonzero(ok))
        second.append(position[ni[ok], nj[ok]])
    a = np.concatenate(first)
    b = np.concatenate(second)
    rows = np.arange(a.size)
    return scipy.sparse.csr_matrix(
        (np.r_[np.ones(a.size), -np.ones(a.size)], (np.r_[rows, rows], np.r_[a, b])),
        shape=(a.size, index.shape[0]))


def relay_gram(alpha: np.ndarray, beta: np.ndarray, u: np.ndarray, y: np.ndarray, start: int, stop: int,
               chunk: int = 2048, mask: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, int]:
    """Normal equations of ``y ≈ c + S w`` over samples ``start .. stop - 1`` (only those where
    ``mask`` is true, if given: the relay states still run over every sample).

    ``S[k, r]`` is the state of relay ``r`` after sample ``k`` of ``u`` from all relays off
    (relay rule of Mayergoyz 2003: on if ``u >= alpha``, else off if ``u <= beta``, else
    unchanged).  Returns ``S^T S``, ``S^T y``, the column sums of ``S``, ``sum(y)`` and the
    number of samples.  ``S`` is never stored whole: a record's relay states repeat (the same
    staircase memory is reached again and again), so each distinct row is kept once, as bits,
    with its count and the sum of its samples' outputs, and ``S^T S`` is accumulated from the
    distinct rows in chunks (exactly the same sums, a few hundred rows instead of thousands).
    """
    seen: dict[bytes, int] = {}
    packed: list[np.ndarray] = []
    counts: list[int] = []
    sums: list[float] = []
    state = np.zeros(alpha.size, dtype=bool)
    for k in range(stop):
        v = u[k]
        state = (v >= alpha) | (state & (v > beta))
        if k < start or (mask is not None and not mask[k]):
            continue
        bits = np.packbits(state)
        key = bits.tobytes()
        row = seen.get(key)
        if row is None:
            seen[key] = len(packed)
            packed.append(bits)
            counts.append(1)
            sums.append(float(y[k]))
        else:
            counts[row] += 1
            sums[row] += float(y[k])
    n_r = alpha.size
    gram = np.zeros((n_r, n_r))
    rhs = np.zeros(n_r)
    colsum = np.zeros(n_r)
    count_a = np.asarray(counts, dtype=float)
    sum_a = np.asarray(sums, dtype=float)
    for first in range(0, len(packed), chunk):
        block = np.unpackbits(np.asarray(packed[first:first + chunk]), axis=1, count=n_r).astype(float)
        c = count_a[first:first + chunk]
        gram += (block * c[:, None]).T @ block
        rhs += block.T @ sum_a[first:first + chunk]
        colsum += block.T @ c
    return (gram, rhs, colsum, *_row_totals(y, start, stop, mask))


def _row_totals(y: np.ndarray, start: int, stop: int, mask: np.ndarray | None) -> tuple[float, int]:
    """``sum(y)`` and the number of the rows used (``start .. stop - 1``, where ``mask`` is true)."""
    if mask is None:
        return float(np.sum(y[start:stop])), stop - start
    rows = mask[start:stop]
    return float(np.sum(y[start:stop][rows])), int(np.count_nonzero(rows))


class CellFractions(StaircasePreisach):
    """Vector-valued Preisach operator: the share of each grid cell's spread relays that is on.

    The output after each input is the vector ``F`` with ``EverettPreisach output = offset +
    weights · F`` (the Everett function is linear in the cell weights, so the staircase memory
    works on vectors as on numbers).
    """

    def __init__(self, edges: np.ndarray, index: np.ndarray) -> None:
        self._low = edges[:-1]
        self._width = np.diff(edges)
        self._i, self._j = index[:, 0], index[:, 1]
        self._diagonal = self._i == self._j
        self._y_reset = np.zeros(index.shape[0])
        super().__init__()

    def _k_rising(self, a: float, b: float) -> np.ndarray:
        s = np.clip((a - self._low) / self._width, 0.0, 1.0)
        r = np.clip((b - self._low) / self._width, 0.0, 1.0)
        off = s[self._i] * (1.0 - r[self._j])
        on_diagonal = np.maximum(s[self._i] - r[self._i], 0.0) ** 2
        return np.where(self._diagonal, on_diagonal, off)

    _k_falling = _k_rising


def cell_gram(edges: np.ndarray, index: np.ndarray, u: np.ndarray, y: np.ndarray, start: int, stop: int,
              chunk: int = 2048, mask: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, int]:
    """As :func:`relay_gram` for relays spread over their grid cells (see :class:`EverettPreisach`)."""
    fractions = CellFractions(edges, index)

    def rows():
        for k in range(stop):
            yield fractions.commit(float(u[k]))

    return chunked_gram(rows(), index.shape[0], y, start, stop, chunk, mask)


def chunked_gram(rows: Any, n_r: int, y: np.ndarray, start: int, stop: int, chunk: int,
                 mask: np.ndarray | None = None) -> tuple:
    gram = np.zeros((n_r, n_r))
    rhs = np.zeros(n_r)
    colsum = np.zeros(n_r)
    block = np.empty((chunk, n_r))
    block_y = np.empty(chunk)
    filled = 0

    def flush(count: int) -> None:
        s = block[:count]
        gram[:] += s.T @ s
        rhs[:] += s.T @ block_y[:count]
        colsum[:] += s.sum(axis=0)

    for k, state in enumerate(rows):
        if k >= start and (mask is None or mask[k]):
            block[filled] = state
            block_y[filled] = y[k]
            filled += 1
            if filled == chunk:
                flush(filled)
                filled = 0
    if filled:
        flush(filled)
    return (gram, rhs, colsum, *_row_totals(y, start, stop, mask))


def nnls_normal(gram: np.ndarray, rhs: np.ndarray, regulariser: Any) -> np.ndarray:
    """``argmin_{w >= 0} w^T (G + R) w - 2 b^T w`` by block principal pivoting (:mod:`.nnls`)."""
    import scipy.sparse  # noqa: PLC0415 - lazy: scipy.sparse is slow to import
    matrix = gram + (regulariser.toarray() if scipy.sparse.issparse(regulariser) else regulariser)
    ridge = 1e-10 * max(float(np.trace(matrix)) / matrix.shape[0], 1e-300)
    matrix[np.diag_indices_from(matrix)] += ridge
    weights, _ = nnls_gram(matrix, rhs)
    return weights
