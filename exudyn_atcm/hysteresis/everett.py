"""A Preisach operator with a continuous output: a relay grid's weights spread over their cells.

A relay grid (:class:`DiscretePreisach`) gives a staircase output: every threshold crossed is
a jump.  A real piezo layer has a continuous density.  Spreading each grid cell's weight
evenly over the cell (over the whole square for cells off the diagonal, over the half below
the diagonal ``alpha = beta`` for diagonal cells, where relays need ``alpha >= beta``) gives a
non-negative, piecewise-constant Preisach density, whose Everett function (Mayergoyz 2003)

``K(a, b) = measure of the relays with alpha <= a and beta >= b``

is, for the off-diagonal cells, exactly the bilinear interpolation of its values on the grid
points, and for a diagonal cell of weight ``w`` ``w·max(s − r, 0)²`` (``s``, ``r`` the
positions of ``a``, ``b`` across the cell, clamped to ``[0, 1]``).  The operator evaluates
that ``K`` in the staircase memory (:mod:`exudyn_atcm.hysteresis.staircase`); its output is
continuous in the input.
"""

from __future__ import annotations

from bisect import bisect_right
from typing import Any

import numpy as np

from .._checks import finite_array, finite_float, same_length
from .families import FamilyFit, FitRequest, register_family
from .staircase import StaircasePreisach
from .identification import fit_discrete

__all__ = ["EverettPreisach"]


class EverettPreisach(StaircasePreisach):
    """Preisach operator from a relay grid with each cell's weight spread over the cell.

    Parameters
    ----------
    edges : array_like
        Cell edges of the input grid (input units), strictly increasing, ``n + 1`` values.
    alpha, beta, weights : array_like
        Relays with thresholds at cell centres (as from
        :func:`exudyn_atcm.hysteresis.identification.relay_grid` over ``edges[0] … edges[-1]``)
        and non-negative weights (output units).
    offset : float, optional
        Output with all relays off.

    Notes
    -----
    Initial state (after :meth:`reset`): all relays off, output ``offset``.  Outside
    ``[edges[0], edges[-1]]`` the output saturates.  Where the input crosses a cell, the output
    changes continuously instead of jumping at the cell's centre; at the cell edges it equals
    the relay grid's.
    """

    def __init__(self, edges: Any, alpha: Any, beta: Any, weights: Any, offset: float = 0.0) -> None:
        e = finite_array("edges", edges, min_length=2)
        if np.any(np.diff(e) <= 0.0):
            k = int(np.argmax(np.diff(e) <= 0.0)) + 1
            raise ValueError(f"edges must be strictly increasing, got edges[{k}] = {float(e[k])!r} after {float(e[k - 1])!r}")
        a = finite_array("alpha", alpha)
        b = finite_array("beta", beta)
        w = finite_array("weights", weights)
        same_length(("alpha", "beta", "weights"), (a, b, w))
        if (a < b).any():
            k = int(np.argmax(a < b))
            raise ValueError(f"alpha must be >= beta for every relay, got alpha[{k}] = {float(a[k])!r} < beta[{k}] = {float(b[k])!r}")
        if (w < 0).any():
            k = int(np.argmax(w < 0))
            raise ValueError(f"weights must be >= 0 (a non-negative density), got weights[{k}] = {float(w[k])!r}")
        ia = np.searchsorted(e, a) - 1
        ib = np.searchsorted(e, b) - 1
        outside = (ia < 0) | (ia >= e.size - 1) | (ib < 0) | (ib >= e.size - 1)
        if outside.any():
            k = int(np.argmax(outside))
            raise ValueError(
                f"every relay threshold must lie strictly inside the edges ({float(e[0])!r} ... {float(e[-1])!r}), "
                f"got alpha[{k}] = {float(a[k])!r}, beta[{k}] = {float(b[k])!r}"
            )
        n = e.size - 1
        diagonal = ia == ib
        cells = np.zeros((n, n))
        np.add.at(cells, (ia[~diagonal], ib[~diagonal]), w[~diagonal])
        # table[i, j] = K(edges[i], edges[j]) of the off-diagonal cells: cell (p, q) counts
        # fully when p < i and q >= j
        table = np.zeros((n + 1, n + 1))
        table[1:, :-1] = np.cumsum(np.cumsum(cells[:, ::-1], axis=1)[:, ::-1], axis=0)
        diag = np.zeros(n)
        np.add.at(diag, ia[diagonal], w[diagonal])
        self.edges = e.copy()
        self.alpha, self.beta, self.weights = a.copy(), b.copy(), w.copy()
        self.offset = finite_float("offset", offset)
        self.total_weight = float(w.sum())
        self._edges: list[float] = e.tolist()
        self._table: list[list[float]] = table.tolist()  # Python floats: the step's hot path indexes it
        self._diag: list[float] = diag.tolist()
        self._diag_prefix: list[float] = [0.0, *np.cumsum(diag).tolist()]
        self._y_reset = self.offset
        super().__init__()

    @property
    def saturation_range(self) -> tuple[float, float]:
        """``(edges[0], edges[-1])``: below it every relay is off, above it every relay is on."""
        return (self._edges[0], self._edges[-1])

    @classmethod
    def from_grid(cls, model: Any, u_lo: float, u_hi: float, n_levels: int) -> "EverettPreisach":
        """Spread the relays of a grid model (e.g. from :meth:`DiscretePreisach.fit`) over their cells.

        ``u_lo``, ``u_hi``, ``n_levels`` are the grid's (the fit report's ``settings``).
        """
        edges = np.linspace(finite_float("u_lo", u_lo), finite_float("u_hi", u_hi), int(n_levels) + 1)
        return cls(edges, model.alpha, model.beta, model.weights, offset=model.offset)

    @classmethod
    def fit(cls, u: Any, y: Any, n_levels: int, **options: Any) -> tuple["EverettPreisach", Any]:
        """Fit the cell weights of the spread grid to a record (non-negative least squares).

        The same procedure as :meth:`DiscretePreisach.fit
        <exudyn_atcm.hysteresis.DiscretePreisach.fit>` (same arguments: ``smoothing``,
        ``n_fit``, ``fit_mask``, ``input_range``, ``output_unit``, ``output_quantity``,
        ``prior`` (default ``"pi"``), ``prior_weight``, ``cv_folds``), with each relay's state replaced by the
        share of its cell that is switched on, so the identified operator is the one fitted
        (continuous output, no staircase error).  The samples before the input first comes
        down to the grid's lowest edge are left out (the memory is unknown until then).

        Returns
        -------
        (EverettPreisach, FitReport)
        """
        return fit_discrete(cls, u, y, n_levels, basis="cells", **options)

    def _k(self, a: float, b: float) -> float:
        edges = self._edges
        lo, hi = edges[0], edges[-1]
        a = lo if a < lo else hi if a > hi else a
        b = lo if b < lo else hi if b > hi else b
        if a <= b:
            return 0.0
        last = len(edges) - 2
        i = min(bisect_right(edges, a) - 1, last)
        j = min(bisect_right(edges, b) - 1, last)
        s = (a - edges[i]) / (edges[i + 1] - edges[i])
        r = (b - edges[j]) / (edges[j + 1] - edges[j])
        row, below = self._table[i], self._table[i + 1]
        k = (1 - s) * (1 - r) * row[j] + s * (1 - r) * below[j] + (1 - s) * r * row[j + 1] + s * r * below[j + 1]
        diag = self._diag
        if i == j:
            return float(k + diag[i] * (s - r) ** 2)
        return float(k + diag[j] * (1 - r) ** 2 + (self._diag_prefix[i] - self._diag_prefix[j + 1]) + diag[i] * s * s)

    def _k_rising(self, a: float, b: float) -> float:
        return self._k(a, b)

    _k_falling = _k_rising

    def __repr__(self) -> str:
        return (f"EverettPreisach(cells={len(self._edges) - 1}, range=({self._edges[0]!r}, {self._edges[-1]!r}), "
                f"offset={self.offset!r})")


def _fit_everett(request: FitRequest) -> FamilyFit:
    """The ``everett`` family: :meth:`EverettPreisach.fit` (grid, each weight spread over its cell)."""
    n_levels, prior = request.options.get("n_levels", 30), request.options.get("prior", "pi")
    model, report = EverettPreisach.fit(request.u, request.y, n_levels, smoothing=request.options.get("smoothing", 1e-3),
                                        prior=prior, **request.rows, **request.units)
    return FamilyFit(f"everett ({n_levels} levels, {prior})", model, report, n_levels * (n_levels + 1) // 2 + 1)


register_family("everett", _fit_everett, inverse="bisection", operator=EverettPreisach,
                description="relay grid with each weight spread over its cell (continuous output)")
