"""A Preisach operator with a rate lag, identified from records at several rates.

The model is the Hammerstein chain of :mod:`exudyn_atcm.hysteresis.dynamics`: an
:class:`~exudyn_atcm.hysteresis.everett.EverettPreisach` operator (any non-negative density on
the Preisach triangle, so loops that are not point-symmetric: a density that depends on
``α + β`` as well as ``α − β``), then an optional creep law known beforehand, then a
first-order lag ``1/(1 + T s)``, as one :class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`:

``y = L_T[ offset + Σ_c w_c F_c(u) ]``

with ``F_c`` the cell fractions along the input (:func:`~exudyn_atcm.hysteresis.lagged_basis.cell_fraction_columns`)
and ``L_T`` the linear block.  For a given ``T`` the output is linear in the cell weights and
the offset, so :func:`fit_rate_preisach` solves one regularised non-negative least-squares
problem per ``T`` (the block applied to every basis column; smoothness and the ``"pi"`` prior
along ``α − β`` of :mod:`exudyn_atcm.hysteresis.priors`, which fills the parts of the triangle
the records do not reach the way a Prandtl-Ishlinskii density would) and finds ``T`` by a
bounded scalar search over ``log T``.  The records at different rates separate the two: the
operator's loop is the same at every rate, the lag's phase grows with the rate.

Why a lag, not rate-dependent weights: see :class:`~exudyn_atcm.hysteresis.dynamics.RateLag`
(linear in the weights for each ``T``, an exact inverse, few parameters for a few rates).  The
fitted model runs in the solver step (``PiezoDrive(..., hysteresis=model)``) and has an inverse
for feedforward: :meth:`WithDynamics.inverse()
<exudyn_atcm.hysteresis.dynamics.WithDynamics.inverse>` (bisection on the Everett operator after
the lag block's exact inverse).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from .._checks import finite_float, positive_float, shown
from ..physical_bounds import check_element_count
from .creep import Creep
from .dynamics import LagSum, RateLag, WithDynamics
from .everett import EverettPreisach
from .fit_cost import FLOP_RATE, CostEstimate, check_cost
from .identification import MAX_FIT_LEVELS
from .lagged_basis import cell_fraction_columns, check_records, lagged_columns, record_rates
from .nnls import single_blas_thread
from .priors import PRIOR_STRENGTHS, along_lines_matrix, cross_validate_strength, solve_regularised
from .relay_gram import relay_grid, smoothness_matrix

__all__ = ["fit_rate_preisach", "rate_fit_cost", "MIN_RATE_RATIO", "KNOWN_MEMORY_TOLERANCE"]

#: Fastest over slowest record rate (:func:`~exudyn_atcm.hysteresis.lagged_basis.record_rates`)
#: below which the records cannot tell the lag from the loop.
MIN_RATE_RATIO = 1.5

#: The memory is taken as known from the first sample within this share of the input range of
#: the grid's lowest edge (the relays switched off there are all but a sliver of the lowest cell).
KNOWN_MEMORY_TOLERANCE = 0.01

#: Candidate values of ``T`` tried on a log grid before the bounded search refines the best.
SEARCH_POINTS = 13


def rate_fit_cost(n_levels: int, n_samples: int, n_lags: int, evaluations: int) -> CostEstimate:
    """Cost of :func:`fit_rate_preisach`: ``R = n(n + 1)/2`` cells, ``m`` samples.

    Memory: the cell fractions and the lagged design (two ``m × R`` arrays) and three ``R × R``
    arrays.  Time: the state sweep (as the Everett fit's), and per evaluated ``T`` the lag
    filters (about ``20 m R`` flops per lag), the Gram matrix (``2 m R²``) and the NNLS (``R³``).
    """
    cells = n_levels * (n_levels + 1) // 2
    m = max(int(n_samples), 1)
    memory = 3.0 * m * cells * 8.0 + 3.0 * cells**2 * 8.0
    per_t = (20.0 * m * cells * max(n_lags, 1) + 2.0 * m * cells**2 + cells**3) / FLOP_RATE
    seconds = m * (7e-5 + 5e-8 * cells) + evaluations * per_t
    return CostEstimate(seconds, memory, f"{cells} cells, {m} samples, about {evaluations} least-squares fits")


def _levels(value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 2 <= value <= MAX_FIT_LEVELS:
        raise ValueError(f"n_levels must be an integer in [2, {MAX_FIT_LEVELS}], got {shown(value)}")
    return int(value)


def _bounds(T_bounds: Any, recs: list) -> tuple[float, float]:
    if T_bounds is None:
        low = 0.1 * min(float(np.min(np.diff(t))) for t, _, _ in recs)
        return low, max(float(t[-1] - t[0]) for t, _, _ in recs)
    try:
        low, high = T_bounds
    except (TypeError, ValueError):
        raise ValueError(f"T_bounds must be a pair (low, high) [s], got {T_bounds!r}") from None
    low, high = finite_float("T_bounds[0]", low), finite_float("T_bounds[1]", high)
    if not 0.0 < low < high:
        raise ValueError(f"T_bounds must satisfy 0 < low < high [s], got {T_bounds!r}")
    return low, high


class _Problem:
    """The records' lagged least-squares problem (scaled output) for any lag block."""

    def __init__(self, recs: list, edges: np.ndarray, index: np.ndarray, starts: list, scale: float,
                 smoothing: float, n_levels: int) -> None:
        self.recs, self.starts, self.scale = recs, starts, scale
        self.columns = [cell_fraction_columns(u, edges, index) for _, u, _ in recs]
        self.targets = [y[k0:] / scale for (_, _, y), k0 in zip(recs, starts)]
        self.rest = np.zeros(index.shape[0])
        d = smoothness_matrix(index, n_levels)
        self.dtd = (d.T @ d).tocsr()
        p = along_lines_matrix(index, n_levels)
        self.ptp = (p.T @ p).tocsr()
        self.smoothing = smoothing

    def design(self, lags: LagSum) -> tuple[np.ndarray, np.ndarray, list[int]]:
        """Lagged cell-fraction rows of every record after its memory is known, stacked; the free columns
        (a constant, and for a record that does not start at the lowest input the free decay
        ``e^{−(t − t₀)/τ_j}`` of each lag from its unknown state at ``t₀``); the rows per record."""
        blocks, sizes, free = [], [], []
        for f, (t, _, _), k0 in zip(self.columns, self.recs, self.starts):
            blocks.append(lagged_columns(f, t, lags, self.rest)[k0:])
            sizes.append(t.size - k0)
            if k0 > 0:
                free.append((len(sizes) - 1, np.exp(-(t[k0:, None] - t[k0]) / lags.tau[None, :])))
        total = sum(sizes)
        offsets = np.concatenate([[0], np.cumsum(sizes)])
        extra = np.zeros((total, sum(e.shape[1] for _, e in free)))
        col = 0
        for i, e in free:
            extra[offsets[i]:offsets[i + 1], col:col + e.shape[1]] = e
            col += e.shape[1]
        return np.vstack(blocks), np.column_stack([np.ones(total), extra]), sizes

    def solve(self, lags: LagSum, strength: float) -> tuple[np.ndarray, float, list[np.ndarray]]:
        """Cell weights and the (lagged) offset for the scaled output, and the residuals per record.

        The free columns are projected out (for the constant alone: centring), the weights solved
        by the regularised NNLS, the free coefficients by least squares on what is left.
        """
        a, free, sizes = self.design(lags)
        y = np.concatenate(self.targets)
        q, _ = np.linalg.qr(free)
        a_p, y_p = a - q @ (q.T @ a), y - q @ (q.T @ y)
        with single_blas_thread():
            weights, _, _ = solve_regularised(a_p.T @ a_p, a_p.T @ y_p,
                                              [(self.smoothing, self.dtd), (strength, self.ptp)])
        fitted = a @ weights
        coef = np.linalg.lstsq(free, y - fitted, rcond=None)[0]
        residual = fitted + free @ coef - y
        return weights, float(coef[0]), np.split(residual, np.cumsum(sizes)[:-1])

    def cross_validate(self, lags: LagSum, folds: int) -> tuple[float, list]:
        """The ``"pi"`` prior's strength by ``folds``-fold cross-validation over contiguous blocks of the rows
        (the free columns projected out of all rows first)."""
        a, free, _ = self.design(lags)
        y = np.concatenate(self.targets)
        q, _ = np.linalg.qr(free)
        a, y = a - q @ (q.T @ a), y - q @ (q.T @ y)
        bounds = np.linspace(0, y.size, folds + 1).round().astype(int)
        stats = []
        for lo, hi in zip(bounds[:-1], bounds[1:]):
            b, yb = a[lo:hi], y[lo:hi]
            stats.append((b.T @ b, b.T @ yb, b.sum(axis=0), float(yb.sum()), float(hi - lo), float(yb @ yb)))
        with single_blas_thread():
            return cross_validate_strength(stats, self.dtd, self.smoothing, self.ptp)

    def cost(self, lags: LagSum, strength: float) -> float:
        return float(sum(np.sum(r**2) for r in self.solve(lags, strength)[2]))


def _off_creep(creep: Creep | None, T: float) -> float:
    """A searched ``T`` moved by 1e-6 relative off a creep time constant (a double pole has no lag sum)."""
    if creep is not None and np.any(np.abs(creep.tau - T) <= 1e-9 * T):
        return T * (1.0 + 1e-6)
    return T


def _series(creep: Creep | None, T: float) -> LagSum:
    """The block ``creep`` then ``RateLag(T)`` (``T`` off the creep's time constants)."""
    return LagSum.series(creep, RateLag(_off_creep(creep, T)))


def _search(problem: _Problem, creep: Creep | None, strength: float, low: float, high: float) -> tuple[float, list]:
    """``T`` minimising the squared residuals: the best of a log grid, refined by a bounded Brent search."""
    from scipy.optimize import minimize_scalar  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    grid = np.geomspace(low, high, SEARCH_POINTS)
    costs = [problem.cost(_series(creep, float(T)), strength) for T in grid]
    table = [{"T": float(T), "cost": c} for T, c in zip(grid, costs)]
    k = int(np.argmin(costs))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    best = minimize_scalar(lambda lt: problem.cost(_series(creep, float(np.exp(lt))), strength),
                           bounds=(math.log(lo), math.log(hi)), method="bounded", options={"xatol": 1e-4})
    T = float(np.exp(best.x))
    if costs[k] < float(best.fun):
        T = float(grid[k])
    return T, table


def fit_rate_preisach(records: Any, n_levels: int, *, creep: Creep | None = None, T: float | None = None,
                      T_bounds: tuple[float, float] | None = None, smoothing: float = 1e-3,
                      prior_weight: float | None = None, cv_folds: int = 5, output_unit: str = "",
                      output_quantity: str | None = None) -> tuple[WithDynamics, dict]:
    """Everett (Preisach) operator and rate lag ``T`` (after a given creep law) from records at several rates.

    Parameters
    ----------
    records : sequence of (t, u, y)
        Records [s, input units, output units], each starting from rest at the lowest input: the
        device held at (or driven down to) the grid's lowest edge, so every relay is off, and the
        lags at rest; e.g. sine, triangle or growing-amplitude cycles at a few rates.  At least
        two records whose rates differ by :data:`MIN_RATE_RATIO` (one is enough with ``T`` given).
        Samples before a record first comes within :data:`KNOWN_MEMORY_TOLERANCE` of the lowest
        edge are left out of the least squares (the operator's memory is unknown there), and the
        lags' states at that sample are fitted as free (their free decay ``e^{−(t − t₀)/τ_j}`` is
        one more least-squares column per lag, not a weight of the model).
    n_levels : int
        Grid levels over the input range of all records, ``2 ... 100``; ``n(n + 1)/2`` cells.
    creep : Creep, optional
        A creep law known beforehand (e.g. :func:`~exudyn_atcm.hysteresis.dynamics_fit.creep_from_step`), kept fixed.
    T : float, optional
        The lag's time constant [s], if known: then no search.
    T_bounds : (float, float), optional
        Search range of ``T`` [s]; default from a tenth of the shortest sample spacing to the
        longest record.
    smoothing : float, optional
        Weight of the smoothness between neighbouring cells (as in :meth:`EverettPreisach.fit`).
    prior_weight : float, optional
        Strength of the ``"pi"`` prior; default chosen by ``cv_folds``-fold cross-validation (at
        the ``T`` found with the strength 0.01; the search is then repeated around it).
    cv_folds : int, optional
        Blocks of the cross-validation, ``>= 2``.
    output_unit : str, optional
        Unit of ``y`` (e.g. ``""`` for strain, ``"m"``), kept as the model's ``output_unit``.
    output_quantity : str, optional
        What ``y`` is (``"strain"``, ``"displacement"``, ...), kept as the model's ``output_quantity``.

    Returns
    -------
    (WithDynamics, dict)
        ``WithDynamics(EverettPreisach, creep, RateLag(T))`` with ``fitted_range``,
        ``output_unit``, ``output_quantity`` and ``fit_info`` set, and that ``fit_info``:
        ``T``, ``rms`` and ``rms_rate_independent`` (the same operator fitted without the lag)
        per record [output units], ``fit_start`` per record, ``rates`` [1/s], ``prior_weight``,
        ``cross_validation``, ``search``, ``notes``, ``fit_time`` [s].

    Raises
    ------
    ValueError
        For malformed records, a single record or records at one rate when ``T`` is searched, a
        record that never comes down to the lowest input, ``n_levels`` outside ``2 ... 100``,
        bounds that are not ``0 < low < high``, ``T <= 0``, a ``creep`` that is not a
        :class:`~exudyn_atcm.hysteresis.creep.Creep` or a constant output.
    """
    started = time.perf_counter()
    searched = T is None
    recs = check_records(records, minimum=2 if searched else 1)
    n = _levels(n_levels)
    check_element_count(f"n_levels={n}", n * (n + 1) // 2, "cells")
    if creep is not None and not isinstance(creep, Creep):
        raise ValueError(f"creep must be a Creep or None, got {type(creep).__name__}")
    rates = record_rates(recs)
    if searched:
        ratio = float(rates.max() / rates.min())
        if ratio < MIN_RATE_RATIO:
            raise ValueError(
                f"records: their rates {', '.join(f'{r:.4g}' for r in rates)} 1/s (mean |du/dt| over twice the input "
                f"range) differ by {ratio:.3g}x, less than {MIN_RATE_RATIO}x: records at one rate cannot tell the lag "
                "from the loop; add a record at another rate or give T")
        _bounds(T_bounds, recs)
    else:
        T = positive_float("T", T)
        LagSum.series(creep, RateLag(T))  # refuses a T equal to a creep time constant
    smoothing = finite_float("smoothing", smoothing)
    if smoothing < 0.0:
        raise ValueError(f"smoothing must be >= 0, got {shown(smoothing)}")
    if prior_weight is not None:
        prior_weight = finite_float("prior_weight", prior_weight)
        if prior_weight < 0.0:
            raise ValueError(f"prior_weight must be >= 0, got {shown(prior_weight)}")
    elif isinstance(cv_folds, bool) or not isinstance(cv_folds, (int, np.integer)) or cv_folds < 2:
        raise ValueError(f"cv_folds must be an integer >= 2, got {shown(cv_folds)}")
    u_lo = min(float(u.min()) for _, u, _ in recs)
    u_hi = max(float(u.max()) for _, u, _ in recs)
    known = u_lo + KNOWN_MEMORY_TOLERANCE * (u_hi - u_lo)
    starts, notes = [], []
    for i, (_, u, _) in enumerate(recs):
        hits = np.flatnonzero(u <= known)
        if not hits.size:
            raise ValueError(f"records[{i}] never comes down to the lowest input {u_lo!r} of the records "
                             f"(its lowest is {float(u.min())!r}): its memory is never known; start every record at "
                             "the lowest input")
        starts.append(int(hits[0]))
        if hits[0] > 0:
            notes.append(f"records[{i}]: samples 0..{int(hits[0]) - 1} left out (the memory is unknown until the input "
                         f"first comes down to {u_lo!r}); the lags' states there are fitted as free")
    if sum(u.size - k0 for (_, u, _), k0 in zip(recs, starts)) < 10:
        raise ValueError("records: fewer than 10 samples remain after the memory is known")
    fitted_y = np.concatenate([y[k0:] for (_, _, y), k0 in zip(recs, starts)])
    scale = float(np.ptp(fitted_y))
    if scale == 0.0:
        raise ValueError(f"records: the output must vary, got a constant {float(fitted_y[0])!r}")
    n_lags = (0 if creep is None else creep.tau.size) + 1
    evaluations = (2 * (SEARCH_POINTS + 20) + 5 * len(PRIOR_STRENGTHS)) if searched else 2 + 5 * len(PRIOR_STRENGTHS)
    check_cost("fit_rate_preisach", rate_fit_cost(n, fitted_y.size, n_lags, evaluations),
               "use fewer levels (n_levels) or decimate the records")
    alpha, beta, index = relay_grid(u_lo, u_hi, n)
    edges = np.linspace(u_lo, u_hi, n + 1)
    problem = _Problem(recs, edges, index, starts, scale, smoothing, n)
    search: list = []
    cv_table: list | None = None
    strength = 1e-2 if prior_weight is None else prior_weight
    if searched:
        low, high = _bounds(T_bounds, recs)
        T, search = _search(problem, creep, strength, low, high)
    if prior_weight is None:
        strength, cv_table = problem.cross_validate(_series(creep, T), cv_folds)
        for row in cv_table:
            row["cv_rms"] *= scale
            row["cv_mse_se"] *= scale**2
        if searched and strength != 1e-2:
            T, search = _search(problem, creep, strength, max(low, T / 3.0), min(high, 3.0 * T))
    T = _off_creep(creep, T)
    lags = LagSum.series(creep, RateLag(T))
    weights, c, residuals = problem.solve(lags, strength)
    plain = problem.solve(LagSum.series(creep, None), strength)[2]
    operator = EverettPreisach(edges, alpha, beta, weights * scale, offset=c * scale / lags.static_gain)
    model = WithDynamics(operator, creep, RateLag(T))
    info = {
        "T": T,
        "rms": [scale * float(np.sqrt(np.mean(r**2))) for r in residuals],
        "rms_rate_independent": [scale * float(np.sqrt(np.mean(r**2))) for r in plain],
        "fit_start": starts,
        "rates": rates.tolist(),
        "n_levels": n,
        "input_range": [u_lo, u_hi],
        "smoothing": smoothing,
        "prior_weight": strength,
        "cross_validation": None if cv_table is None else {"folds": cv_folds, "table": cv_table,
                                                            "rule": "strongest within one standard error"},
        "search": search,
        "notes": notes,
        "fit_time": time.perf_counter() - started,
    }
    for target in (operator, model):
        target.fitted_range = (u_lo, u_hi)
        target.output_unit = output_unit
        target.output_quantity = output_quantity
        target.fit_info = info
    return model, info
