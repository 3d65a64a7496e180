"""Discrete Preisach model: non-ideal relays with gains in parallel (the paper's Figs. 13-15)."""

from __future__ import annotations

from bisect import bisect_left, bisect_right
from itertools import accumulate
from typing import Any

import numpy as np

from .._checks import finite_array, finite_float, same_length, shown
from ..physical_bounds import check_element_count
from ._dominance import DominanceSums
from .families import FamilyFit, FitRequest, register_family
from .fit_report import make_report
from .staircase import StaircasePreisach
from .identification import fit_discrete
from .loop_identification import identify_from_loop


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
    * ``kernel == "dominance"``: otherwise (many scattered thresholds), weighted dominance
      sums over the thresholds in a blocked table (``exudyn_atcm.hysteresis._dominance``,
      ``O(n**1.5)`` memory, ``O(n**(4/3))`` for larger sets): every step three or four
      binary searches and two or three table look-ups, whatever the input.

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
        Largest Everett table (number of float cells) built for a non-monotone relay set;
        beyond it the ``"dominance"`` kernel is used (``0``: always, for a non-monotone set).

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
        check_element_count("len(alpha)", alpha_a.size, "relays")
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
            raise ValueError(f"max_table_entries must be an integer >= 0, got {shown(max_table_entries)}")
        self.max_table_entries = int(max_table_entries)

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
            self.kernel = "dominance"
            self._dominance = DominanceSums(alpha_a, beta_a, weights_a)
            self._k_rising = self._k_falling = self._dominance.query  # type: ignore[method-assign]
        ties: dict[float, float] = {}
        for a, b, w in zip(alpha_a.tolist(), beta_a.tolist(), weights_a.tolist()):
            if a == b:
                ties[a] = ties.get(a, 0.0) + w
        self._ties = ties
        self._has_ties = bool(ties)
        super().__init__()

    @property
    def saturation_range(self) -> tuple[float, float]:
        """``(min beta, max alpha)``: below it every relay is off, above it every relay is on."""
        return (self._beta_low, self._alpha_sorted[-1])

    @property
    def n_relays(self) -> int:
        """Number of relays."""
        return len(self._alpha_sorted)

    @classmethod
    def from_loop(
        cls,
        u: Any,
        y: Any,
        n: int,
        *,
        reversal_tolerance: float = 0.0,
        coverage: float = 0.9,
        report: bool = False,
        output_unit: str = "",
        levels: str = "paper",
        fit_mask: Any = None,
        output_quantity: str | None = None,
    ) -> Any:
        """Identify ``n`` equal-gain relays from a measured major loop (the paper's Eq. 12).

        The gain is ``Δy = (y_max − y_min)/n``.  Relay ``i = 1 … n`` sits at level
        ``y_i = y_min + i·Δy`` (``levels="paper"``, the default) or
        ``y_i = y_min + (i − ½)·Δy`` (``levels="centred"``): its switch-on threshold is where the
        ascending branch crosses ``y_i`` (the right-hand crossing), its switch-off threshold
        where the descending branch does (the left-hand crossing), both by linear interpolation
        between samples.

        What the level rule does to the error on the loop: the model's output is the staircase
        ``y_min + Δy·(relays on)``.  With the paper's levels a relay switches when the branch
        has reached the *top* of its step (and switches back once the descending branch is
        below it), so on both branches the staircase lies below the measured output and the
        error is spread evenly over ``[0, Δy)``: RMS ``Δy/√3``, largest ``Δy``, a mean offset
        of ``−Δy/2``.  With centred levels a relay
        switches at the *middle* of its step, so the staircase rounds the branch to the nearest
        step: error in ``[−Δy/2, Δy/2)``, RMS ``Δy/√12`` (half the paper's), largest ``Δy/2``,
        no mean offset; the model's range is the same (all relays off: ``y_min``, all on:
        ``y_max``).  Half the relays thus give the paper construction's error.

        The rule for measured records (several cycles, noise):

        1. The input is cut at its reversals into monotone segments; a reversal counts once
           the input has moved back by more than ``reversal_tolerance`` × its range (0: every
           reversal; use about twice the input's noise for measured voltages).
        2. Only segments spanning at least ``coverage`` × the input range are major-loop
           branches (minor loops and a partial first rise are left out).
        3. Per direction, the samples of all those segments are pooled and sorted by input,
           and the branch is their least-squares non-decreasing fit (isotonic regression): an
           average over the cycles which crosses every level exactly once, however often the
           noise crosses it.  On clean, monotone branches it is the data itself, so a single
           clean loop gives exactly the paper's construction.
        4. ``y_min``, ``y_max`` are the extremes of the two averaged branches.  A level an
           averaged branch never reaches gets the switch at that branch's end input (its
           highest input for switch-on, its lowest for switch-off); a level where the averaged
           branches cross (switch-on below switch-off) by no more than ``reversal_tolerance`` ×
           the input range gets both thresholds at their mean.  Both are said in a
           ``RuntimeWarning`` and in the report's notes; a larger crossing is an error.

        Parameters
        ----------
        u, y : array_like
            Samples of the loop(s) in time order (input, output).
        n : int
            Number of relays, ``>= 1``.
        reversal_tolerance : float, optional
            Fraction of the input range a reversal must exceed (default 0).
        coverage : float, optional
            Fraction of the input range a segment must span to count as a branch (default 0.9).
        report : bool, optional
            Also return a :class:`~exudyn_atcm.hysteresis.fit_report.FitReport` of the model on
            the record.
        output_unit : str, optional
            Unit of ``y`` for the report.
        levels : {"paper", "centred"}, optional
            Switching level of each relay within its gain step (see above); default the
            paper's.
        fit_mask : array_like of bool, optional
            Only the monotone segments within the samples where it is true are branches (the
            others are held out in the report).
        output_quantity : str, optional
            What ``y`` is; default from ``output_unit`` (a length: ``"displacement"``).

        Returns
        -------
        DiscretePreisach or (DiscretePreisach, FitReport)
            The model's ``fitted_range`` is the record's (or masked samples') input range.

        Raises
        ------
        ValueError
            For empty, non-finite or mismatched data, ``n < 1``, a record without a branch in
            each direction spanning ``coverage`` of the range, a constant output, or branches
            that cross by more than the tolerance (not a hysteresis loop).
        """
        return identify_from_loop(cls, u, y, n, reversal_tolerance=reversal_tolerance, coverage=coverage,
                                  report=report, output_unit=output_unit, levels=levels, fit_mask=fit_mask,
                                  output_quantity=output_quantity)

    @classmethod
    def fit(
        cls,
        u: Any,
        y: Any,
        n_levels: int,
        *,
        smoothing: float = 1e-3,
        n_fit: int | None = None,
        input_range: tuple[float, float] | None = None,
        output_unit: str = "",
        prior: str = "pi",
        prior_weight: float | None = None,
        cv_folds: int = 5,
        relays_per_cell: int = 1,
        fit_mask: Any = None,
        output_quantity: str | None = None,
    ) -> tuple["DiscretePreisach", Any]:
        """Variable gains: relay weights on a Preisach grid by non-negative least squares.

        The input range of the fitted samples (or ``input_range``) is cut into ``n_levels``
        cells; one relay sits at every pair of cell centres ``alpha >= beta``
        (``n_levels (n_levels + 1)/2`` relays, the diagonal ones giving the reversible part).
        The relay states along the record follow from the input alone, so the output is
        linear in the weights: ``y ≈ c + S w``.  The weights ``w >= 0`` (a non-negative
        Preisach density keeps the operator monotone, so its inverse exists) and the offset
        ``c`` minimise

        ``|| c + S w - y ||² + λ || D w ||²``,

        with ``D`` the differences between neighbouring grid cells (smoothness of the density)
        and ``λ = smoothing · trace(SᵀS)/trace(DᵀD)`` (centred ``S``), solved with SciPy's NNLS
        on the Cholesky factor of the normal equations.  Any input history identifies the
        density where the history explores the Preisach plane: major loops only the
        neighbourhood of the boundary, minor loops and first-order reversal curves (see
        :class:`exudyn_atcm.model.signals.ForcProgram`) the interior; so a model fitted on records
        with minor loops predicts minor loops whose outputs change right after a reversal
        (sloped), unlike the equal-gain construction of :meth:`from_loop`.

        Parameters
        ----------
        u, y : array_like
            Input and output samples in time order (at least 10).
        n_levels : int
            Grid cells along the input, ``>= 2``.
        smoothing : float, optional
            Dimensionless regularisation weight, ``>= 0`` (default 1e-3).
        n_fit : int, optional
            Fit the first ``n_fit`` samples, predict the rest (held out).  Default: all.
        input_range : (float, float), optional
            Input range of the grid; default the range of the fitted samples.  A range that
            does not hold every fitted input is refused (the model would saturate where the
            data go on).
        output_unit : str, optional
            Unit of ``y`` (``"m"``, ``"-"``, ...); kept as the model's ``output_unit``.
        prior : {"pi", "smooth"}, optional
            What fills the part of the Preisach triangle the record does not show
            (:mod:`exudyn_atcm.hysteresis.priors`): ``"pi"`` (default) smoothness along the lines
            ``α − β = const``, the structure of a Prandtl-Ishlinskii operator, so a record of
            major loops predicts nested minor loops (tested: 0.5 % of the range where the smooth
            prior gives 3.7 %; on a measured record with nested minor loops 0.50 % against
            1.78 %, on major loops alone both 0.14 %), plus the ``smoothing``; ``"smooth"``
            only the ``smoothing`` (the default before issue 28).
        prior_weight : float, optional
            Strength of the ``"pi"`` prior (relative, like ``smoothing``); default: chosen by
            ``cv_folds``-fold cross-validation on the fitted samples (the strongest within one
            standard error of the best; the table is in the report's ``settings``).
        cv_folds : int, optional
            Blocks of the cross-validation (default 5).
        relays_per_cell : int, optional
            ``1`` (default): one relay per grid cell, weights fitted to the relays' staircase.
            ``k > 1``: the weights are fitted with each spread evenly over its cell (the
            density of :meth:`EverettPreisach.fit <exudyn_atcm.hysteresis.EverettPreisach.fit>`,
            same least squares) and realised as ``k × k`` relays per cell, the relay grid of
            ``k·n_levels`` levels (:func:`~exudyn_atcm.hysteresis.relay_gram.refined_relays`).
            The staircase's steps shrink ``k`` times at the same number of fitted weights and
            the same fit time; an operator step still costs ``O(log n)``.  What it buys on
            nested minor loops predicted from major loops (``prior="pi"``, 30 levels, 0.3 % noise;
            ``tests/test_minor_loop_prior.py``), held-out RMS in % of the range: on a non-PI
            truth 1.3 with ``k = 1``, 0.65 with ``k = 4``, 0.61 with ``k = 8``, against 0.59
            for the spread grid itself; on a PI truth 1.08, 0.39, 0.35 against 0.30 for the
            PI fit.  ``k = 8`` keeps the relay grid within 1.2 times the package's best model
            on both.
        fit_mask : array_like of bool, optional
            Fit the samples where it is true (one entry per sample; e.g. every other cycle),
            predict the others; instead of ``n_fit``.  The model runs over the whole record.
        output_quantity : str, optional
            What ``y`` is (``"strain"``, ``"displacement"``, ...); default from the unit (a length
            unit: ``"displacement"``; otherwise not stated).

        Returns
        -------
        (DiscretePreisach, FitReport)
            The model (reset state: all relays off; its ``fitted_range`` the fitted inputs'
            range, its ``fit_info`` what the fit did) and its errors on the fitted and held-out
            parts against the best linear model, in % of the whole record's output range.

        Raises
        ------
        ValueError
            For fewer than 10 samples, non-finite values, different lengths, a constant input
            or output, ``n_levels < 2``, a negative ``smoothing``, an ``input_range`` that cuts the
            fitted samples, or a record whose input never comes down to the grid's lowest
            threshold (the memory at its start is unknown).

        Notes
        -----
        Samples before the input first comes down to the lowest threshold are left out: until
        then the relays' states depend on the history before the record.
        """
        return fit_discrete(cls, u, y, n_levels, smoothing=smoothing, n_fit=n_fit, input_range=input_range,
                            output_unit=output_unit, prior=prior, prior_weight=prior_weight, cv_folds=cv_folds,
                            relays_per_cell=relays_per_cell, fit_mask=fit_mask, output_quantity=output_quantity)

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

    def _tie(self, u: float) -> float:
        return self._ties.get(u, 0.0)

    def __repr__(self) -> str:
        return f"DiscretePreisach(n_relays={self.n_relays}, offset={self.offset!r}, kernel={self.kernel!r})"


def _fit_equal_gain(request: FitRequest) -> FamilyFit:
    """The ``equal_gain`` family: :meth:`DiscretePreisach.from_loop` (the paper's Eq. 12)."""
    n_relays = request.options.get("n_relays", 20)
    levels = request.options.get("levels", "paper")
    rows = {} if request.contiguous else {"fit_mask": request.fit_mask}
    stop = request.n_fit if request.contiguous else request.u.size
    model, fitted = DiscretePreisach.from_loop(request.u[:stop], request.y[:stop], n_relays,
                                               reversal_tolerance=request.options.get("reversal_tolerance", 0.02),
                                               report=True, levels=levels, **rows, **request.units)
    low = np.flatnonzero(request.u <= float(model.beta.min()))
    report = make_report(model, request.u, request.y, request.n_fit if request.contiguous else request.u.size,
                         int(low[0]) if low.size else 0, "DiscretePreisach.from_loop", settings=fitted.settings,
                         notes=fitted.notes, output_unit=request.output_unit, fit_time=fitted.fit_time,
                         fit_mask=None if request.contiguous else request.fit_mask)
    return FamilyFit(f"equal_gain ({n_relays} relays, {levels})", model, report, 2 * n_relays + 2)


def _fit_grid(request: FitRequest) -> FamilyFit:
    """The ``discrete`` family: :meth:`DiscretePreisach.fit` on a relay grid."""
    n_levels, prior = request.options.get("n_levels", 30), request.options.get("prior", "pi")
    per_cell = request.options.get("relays_per_cell", 1)
    model, report = DiscretePreisach.fit(request.u, request.y, n_levels, smoothing=request.options.get("smoothing", 1e-3),
                                         prior=prior, relays_per_cell=per_cell, **request.rows, **request.units)
    refined = f", {per_cell}x{per_cell} relays per cell" if per_cell != 1 else ""
    return FamilyFit(f"discrete ({n_levels} levels, {prior}{refined})", model, report, n_levels * (n_levels + 1) // 2 + 1)


register_family("equal_gain", _fit_equal_gain, inverse="none (staircase)", operator=DiscretePreisach,
                description="equal-gain relays from one major loop (the paper's Eq. 12)")
register_family("discrete", _fit_grid, inverse="none (staircase)", operator=DiscretePreisach,
                description="relay grid, weights by regularised non-negative least squares")
