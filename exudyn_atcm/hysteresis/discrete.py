"""Discrete Preisach model: non-ideal relays with gains in parallel (the paper's Figs. 13-15)."""

from __future__ import annotations

from bisect import bisect_left, bisect_right
from itertools import accumulate
from typing import Any

import numpy as np

from .._checks import finite_array, finite_float, positive_int, same_length
from .staircase import StaircasePreisach

_CACHE_SIZE = 256


class DiscretePreisach(StaircasePreisach):
    """``n`` non-ideal relays in parallel with gains.

    Relay ``i`` has output 1 once the input reaches ``u >= alpha[i]`` (switch-on) and 0 once
    ``u <= beta[i]`` with ``u < alpha[i]`` (switch-off), and keeps its state in between.  The
    operator's output is ``offset + sum(weights * states)``.

    The memory is the staircase of dominant input extrema (see
    :mod:`exudyn_atcm.hysteresis.staircase`), not the array of relay states, so a step costs
    ``O(log n)`` binary searches in the sorted thresholds plus prefix sums of the weights:

    * ``kernel == "prefix"``: the relays form a monotone family (sorted by ``alpha``, their
      ``beta`` is non-decreasing, as for every model identified by :meth:`from_loop`); prefix
      sums of the weights, ``O(n)`` memory, every step ``O(log n)``;
    * ``kernel == "table"``: any other relay set whose grid of distinct thresholds has at most
      ``max_table_entries`` cells (a Preisach grid of ``n`` relays has about ``n``): the Everett
      function tabulated on that grid, every step ``O(log n)``;
    * ``kernel == "rows"``: otherwise (many scattered thresholds), a step is ``O(log n)``
      except the first one after a new reversal point, which builds that point's prefix-sum
      row once (``O(n)``, vectorised; rows are cached).

    Parameters
    ----------
    alpha : array_like
        Switch-on thresholds (input units), shape ``(n,)``.
    beta : array_like
        Switch-off thresholds, shape ``(n,)``, ``beta[i] <= alpha[i]``.
    weights : array_like
        Gains (output units), shape ``(n,)``.
    offset : float, optional
        Output with all relays off.
    max_table_entries : int, optional
        Largest Everett table (number of float cells) built for a non-monotone relay set.

    Notes
    -----
    Initial state (after :meth:`reset`): all relays off, output ``offset``.
    """

    def __init__(
        self, alpha: Any, beta: Any, weights: Any, offset: float = 0.0, *, max_table_entries: int = 1 << 22
    ) -> None:
        alpha_a = finite_array("alpha", alpha)
        beta_a = finite_array("beta", beta)
        weights_a = finite_array("weights", weights)
        same_length(("alpha", "beta", "weights"), (alpha_a, beta_a, weights_a))
        bad = alpha_a < beta_a
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(
                f"alpha must be >= beta for every relay (switch-on at or above switch-off), got "
                f"alpha[{i}] = {float(alpha_a[i])!r} < beta[{i}] = {float(beta_a[i])!r}"
            )
        self.alpha = alpha_a.copy()
        self.beta = beta_a.copy()
        self.weights = weights_a.copy()
        self.offset = finite_float("offset", offset)
        self._y_reset = self.offset
        self._beta_low = float(beta_a.min())
        if isinstance(max_table_entries, bool) or not isinstance(max_table_entries, (int, np.integer)) or max_table_entries < 0:
            raise ValueError(f"max_table_entries must be an integer >= 0, got {max_table_entries!r}")

        order = np.lexsort((beta_a, alpha_a))  # by alpha, ties by beta
        self._alpha_sorted: list[float] = alpha_a[order].tolist()
        beta_by_alpha = beta_a[order]
        self.monotone = bool(np.all(np.diff(beta_by_alpha) >= 0.0))
        alpha_levels = np.unique(alpha_a)
        beta_levels = np.unique(beta_a)
        if self.monotone:
            self.kernel = "prefix"
            self._beta_sorted: list[float] = beta_by_alpha.tolist()
            self._prefix: list[float] = [0.0, *accumulate(weights_a[order].tolist())]
        elif (alpha_levels.size + 1) * (beta_levels.size + 1) <= max_table_entries:
            self.kernel = "table"
            self._alpha_levels: list[float] = alpha_levels.tolist()
            self._beta_levels: list[float] = beta_levels.tolist()
            counts = np.zeros((alpha_levels.size, beta_levels.size))
            np.add.at(
                counts,
                (np.searchsorted(alpha_levels, alpha_a), np.searchsorted(beta_levels, beta_a)),
                weights_a,
            )
            # table[i, j] = sum of weights with alpha among the i lowest levels and beta
            # among the levels from j upwards: the Everett function on the threshold grid.
            table = np.zeros((alpha_levels.size + 1, beta_levels.size + 1))
            table[1:, :-1] = np.cumsum(np.cumsum(counts[:, ::-1], axis=1)[:, ::-1], axis=0)
            self._table_item = table.item
            self._k_rising = self._k_falling = self._k_table  # type: ignore[method-assign]
        else:
            self.kernel = "rows"
            self._w_by_alpha = weights_a[order]
            self._beta_by_alpha = beta_by_alpha
            border = np.argsort(beta_a, kind="stable")
            self._beta_sorted = beta_a[border].tolist()
            self._w_by_beta = weights_a[border]
            self._alpha_by_beta = alpha_a[border]
            self._rows: dict[float, list[float]] = {}
            self._columns: dict[float, list[float]] = {}
            self._k_rising = self._k_row  # type: ignore[method-assign]
            self._k_falling = self._k_column  # type: ignore[method-assign]
        ties: dict[float, float] = {}
        for a, b, w in zip(alpha_a.tolist(), beta_a.tolist(), weights_a.tolist()):
            if a == b:
                ties[a] = ties.get(a, 0.0) + w
        self._ties = ties
        self._has_ties = bool(ties)
        super().__init__()

    @property
    def input_range(self) -> tuple[float, float]:
        """``(min beta, max alpha)``: below it every relay is off, above it every relay is on."""
        return (self._beta_low, self._alpha_sorted[-1])

    @property
    def n_relays(self) -> int:
        """Number of relays."""
        return len(self._alpha_sorted)

    @classmethod
    def from_loop(cls, u: Any, y: Any, n: int) -> "DiscretePreisach":
        """Identify ``n`` equal-gain relays from a measured major loop (the paper's Eq. 12).

        The gain is ``Δy = (y_max − y_min)/n``.  Relay ``i = 1 … n`` sits at level
        ``y_i = y_min + i·Δy``: its switch-on threshold is where the ascending branch crosses
        ``y_i`` (the right-hand crossing), its switch-off threshold where the descending branch
        does (the left-hand crossing), both by linear interpolation between samples.  On the
        loop itself the model's error is below one gain step ``Δy``.

        Parameters
        ----------
        u, y : array_like
            Samples of the loop in time order (input, output); the ascending branch is taken
            from the samples where ``u`` rises, the descending one from where it falls.
        n : int
            Number of relays, ``>= 1``.

        Raises
        ------
        ValueError
            For empty, non-finite or mismatched data, ``n < 1``, a loop without both branches,
            a branch that does not reach a level, or branches that cross (ascending above
            descending, which gives a relay with ``alpha < beta``).
        """
        u_a = finite_array("u", u, min_length=2)
        y_a = finite_array("y", y, min_length=2)
        same_length(("u", "y"), (u_a, y_a))
        n = positive_int("n", n)
        du = np.diff(u_a)
        rising = np.zeros(u_a.size, dtype=bool)
        falling = np.zeros(u_a.size, dtype=bool)
        rising[:-1] |= du > 0
        rising[1:] |= du > 0
        falling[:-1] |= du < 0
        falling[1:] |= du < 0
        if not rising.any() or not falling.any():
            missing = "ascending (rising u)" if not rising.any() else "descending (falling u)"
            raise ValueError(f"u, y must describe a loop with both branches; the {missing} branch is missing")
        y_min, y_max = float(y_a.min()), float(y_a.max())
        if y_max <= y_min:
            raise ValueError(f"y must vary over the loop, got a constant {y_min!r}")
        gain = (y_max - y_min) / n
        levels = y_min + gain * np.arange(1, n + 1)
        levels[-1] = y_max  # exact top level, free of round-off
        alpha = _crossings(u_a[rising], y_a[rising], levels, ascending=True)
        beta = _crossings(u_a[falling], y_a[falling], levels, ascending=False)
        bad = alpha < beta
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(
                f"u, y: the ascending branch lies above the descending one at level {float(levels[i])!r} "
                f"(ascending crossing u = {float(alpha[i])!r} < descending crossing u = {float(beta[i])!r}); "
                "not a hysteresis loop"
            )
        return cls(alpha, beta, np.full(n, gain), offset=y_min)

    # -- the function K -----------------------------------------------------------------
    def _k_rising(self, a: float, b: float) -> float:
        # "prefix" kernel: relays sorted by alpha have non-decreasing beta, so the relays with
        # alpha <= a are a prefix and those with beta >= b a suffix of one order.
        on = bisect_right(self._alpha_sorted, a)
        off = bisect_left(self._beta_sorted, b)
        return self._prefix[on] - self._prefix[off] if on > off else 0.0

    _k_falling = _k_rising

    def _k_table(self, a: float, b: float) -> float:
        return self._table_item(bisect_right(self._alpha_levels, a), bisect_left(self._beta_levels, b))

    def _k_row(self, a: float, b: float) -> float:
        row = self._rows.get(b)
        if row is None:
            row = self._cache(self._rows, b, np.cumsum(self._w_by_alpha * (self._beta_by_alpha >= b)))
        return row[bisect_right(self._alpha_sorted, a)]

    def _k_column(self, a: float, b: float) -> float:
        column = self._columns.get(a)
        if column is None:
            selected = self._w_by_beta * (self._alpha_by_beta <= a)
            column = self._cache(self._columns, a, np.cumsum(selected[::-1])[::-1], at_end=True)
        return column[bisect_left(self._beta_sorted, b)]

    @staticmethod
    def _cache(store: dict, key: float, sums: np.ndarray, at_end: bool = False) -> list[float]:
        values = sums.tolist()
        values = values + [0.0] if at_end else [0.0] + values
        if len(store) >= _CACHE_SIZE:
            store.clear()
        store[key] = values
        return values

    def _tie(self, u: float) -> float:
        return self._ties.get(u, 0.0)

    def __repr__(self) -> str:
        return f"DiscretePreisach(n_relays={self.n_relays}, offset={self.offset!r}, kernel={self.kernel!r})"


def _crossings(u: np.ndarray, y: np.ndarray, levels: np.ndarray, *, ascending: bool) -> np.ndarray:
    """Input at which a branch first reaches each level, walking the branch in its direction."""
    order = np.argsort(u, kind="stable")
    u, y = u[order], y[order]
    if not ascending:  # walk the descending branch from u_max downwards
        u, y = u[::-1], y[::-1]
    result = np.empty(levels.size)
    for j, level in enumerate(levels.tolist()):
        reached = y >= level if ascending else y <= level
        if not reached.any():
            kind = "ascending" if ascending else "descending"
            raise ValueError(f"u, y: the {kind} branch never reaches the level y = {level!r}")
        k = int(np.argmax(reached))
        if k == 0:
            result[j] = u[0]
        else:
            y0, y1 = y[k - 1], y[k]
            s = (level - y0) / (y1 - y0)
            result[j] = u[k - 1] + s * (u[k] - u[k - 1])
    return result
