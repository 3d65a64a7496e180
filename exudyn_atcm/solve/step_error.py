"""How large is the time-step error of a run?  ``step_error`` measures it by halving the step.

The time integration (generalized-alpha, :func:`~exudyn_atcm.simulate`) is second-order
accurate for every cell kind (each declares its order, :attr:`exudyn_atcm.cells.CellKind.time_order`;
the ``rod`` cell reaches 2 since issue 29, measured against an exact integration of its modes): a
run with step ``h`` differs from the exact solution of the same model by about ``C(t) h^p``.  Runs
at ``h`` and ``h/2`` therefore differ by about ``(1 - 2^-p) C h^p``, and the error of the run at
``h`` is about ``2^p / (2^p - 1)`` of that difference (Richardson's estimate; 4/3 for ``p = 2``),
with ``p`` the lowest order among the system's cells (:func:`time_orders`).  A third run at
``h/4`` checks the order: the differences should fall by about ``2^p`` per halving.  They fall more
slowly when the error is not smooth in ``h``: a voltage program whose corners fall between
steps, steps reduced after Newton failures, or a difference at the level of the Newton
tolerance (then the step error is negligible anyway).

In mechanisms the step, not the bender model, often decides the accuracy: a lightly damped
vibration started at a corner of the voltage program rings through the run, and the
integrator's period error (about ``(ω h)²/12``) shifts its phase.  The compliant four-bar of
the benchmark (``benchmarks/bench_mechanisms.py --targets``) with rod benders misses
its path by 2.4-2.7e-4, 7.3-7.7e-4 and 1.2e-3 of its travel at steps 2.5e-4, 4e-4 and 5e-4 s,
with 3, 4 or 8 modes alike: the step alone decides whether it reaches 1e-3.
``step_error`` tells a user the same for their own design before a study runs it thousands of
times.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from functools import reduce
from typing import Any, Callable, Sequence

import numpy as np

from .._checks import positive_float, shown
from ..cells import CellKind
from ..errors import AccuracyWarning, AtcmDeprecationWarning
from ..io.result import Result
from .keywords import keyword_signature, legacy_positional
from .run_checks import time_grid
from .run_setup import DEFAULT_STEP
from .simulation import simulate
from .step_choice import STILL_TRAVEL

__all__ = ["step_error", "StepError", "ColumnStepError", "richardson", "time_orders", "NOMINAL_ORDER",
           "MOTION_UNITS"]

#: Order of accuracy of the time integration (generalized-alpha) of the parts that are no cells (links,
#: flexures, springs: Exudyn's own items) and of a system without cells.
NOMINAL_ORDER = 2.0
#: Units of the columns summarised by default (positions and angles: the motion).
MOTION_UNITS = ("m", "rad")
#: Observed orders more than this below the assumed order give an :class:`~exudyn_atcm.AccuracyWarning`.
ORDER_SLACK = 0.5
#: Observed orders below this give the warning when the assumed order is 2 (``2 - ORDER_SLACK``).
MIN_ORDER = NOMINAL_ORDER - ORDER_SLACK
#: Differences below this share of a column's range are round-off and Newton tolerance, not step error.
NOISE = 1e-8


def richardson(changes: Sequence[float], noise: float, order: float = NOMINAL_ORDER) -> tuple[float, float]:
    """Richardson's estimate from the changes between runs at ``h``, ``h/2`` (and ``h/4``).

    ``changes``: ``|x_h - x_{h/2}|`` (and ``|x_{h/2} - x_{h/4}|``).  Returns the estimated error of
    the run at ``h``, ``changes[0] * 2^p / (2^p - 1)`` with ``p`` = ``order`` (the integration's
    order, default :data:`NOMINAL_ORDER`), and the observed order ``log2(changes[0] / changes[1])``
    (``nan`` without the second change or when the first is not above ``noise``, round-off and
    Newton tolerance in the caller's units).
    """
    if not order > 0.0:
        raise ValueError(f"order must be a positive order of accuracy, got {shown(order)}")
    factor = 2.0 ** order / (2.0 ** order - 1.0)
    order = math.nan
    if len(changes) > 1 and changes[0] > noise and changes[1] > 0.0:
        order = math.log2(changes[0] / changes[1])
    return factor * changes[0], order


@dataclass(frozen=True)
class ColumnStepError:
    """The step error of one result column.

    Attributes
    ----------
    name, unit : str
        The column and its unit.
    difference : float
        Largest difference between the runs at ``step`` and ``step/2`` [unit] (at the instants
        both recorded).
    error : float
        Estimated largest error of the run at ``step`` [unit]: ``difference`` x ``2^p / (2^p - 1)``
        (4/3 for the order ``p = 2`` of every cell kind, :attr:`StepError.order`).
    relative : float
        ``error`` / the column's range over the finest run [-] (``nan`` for a constant column, and for a
        position or angle whose range is within ``STILL_TRAVEL`` (1e-9) of the mechanism's extent or of
        a radian: round-off, not motion).
    order : float
        Observed order ``log2(difference / difference of step/2 against step/4)``; ``nan`` without
        the third run or when the differences are round-off.
    """

    name: str
    unit: str
    difference: float
    error: float
    relative: float
    order: float


@dataclass(frozen=True)
class StepError:
    """The result of :func:`step_error`: per column, the estimated error of a run at :attr:`step`.

    Attributes
    ----------
    step : float
        The step examined [s] (the one used: adjusted to divide ``t_end``, as :func:`simulate` does).
    t_end : float
        Length of the runs [s].
    columns : dict of str to ColumnStepError
        Every result column but ``time``.
    summary : list of str
        The columns :meth:`worst` and :meth:`suggested_step` look at by default.
    finest : Result
        The run at the finest step (``step/4``, or ``step/2`` without the order check).
    compared : int
        Instants compared (the coarse run's recorded instants that all runs recorded).
    order : float
        The order ``p`` the estimates assume: the lowest :attr:`~exudyn_atcm.cells.CellKind.time_order`
        among the system's cells (2 for every cell kind).
    cell_orders : dict of str to float
        That order per cell kind in the system (``{"rod": 2.0}``).
    extrapolated : Result or None
        Richardson's extrapolation of the two finest runs to step zero at the compared instants,
        ``x_{h/4} + (x_{h/4} - x_{h/2}) / (2^p - 1)`` in every column: the error of order ``p`` cancels, so
        where the observed order is about 2 this is more accurate than :attr:`finest` (on the
        compliant four-bar at step 5e-4 s, 25-30 times; ``tests/test_step_error.py``).  Where
        the order is not 2 (the :class:`~exudyn_atcm.AccuracyWarning` of :func:`step_error`) it
        is no better than :attr:`finest`.  ``None`` without the order check.
    """

    step: float
    t_end: float
    columns: dict[str, ColumnStepError]
    summary: list[str]
    finest: Result = field(repr=False)
    compared: int = 0
    extrapolated: Result | None = field(default=None, repr=False)
    order: float = NOMINAL_ORDER
    cell_orders: dict[str, float] = field(default_factory=dict)

    def _chosen(self, columns: Sequence[str] | None) -> list[ColumnStepError]:
        names = self.summary if columns is None else list(columns)
        unknown = [n for n in names if n not in self.columns]
        if unknown:
            raise ValueError(f"columns: no such result column {unknown}; available: {', '.join(self.columns)}")
        return [self.columns[n] for n in names]

    def worst(self, columns: Sequence[str] | None = None) -> ColumnStepError:
        """The column with the largest relative error (default: among :attr:`summary`)."""
        chosen = [c for c in self._chosen(columns) if math.isfinite(c.relative)]
        if not chosen:
            raise ValueError("none of the columns varies during the run: there is no relative error to compare")
        return max(chosen, key=lambda c: c.relative)

    def suggested_step(self, target: float, columns: Sequence[str] | None = None) -> float:
        """Largest step [s] whose estimated relative error is ``target`` [-] in every chosen column.

        From the law ``error ~ h^p`` (``p`` = :attr:`order`, 2 for every cell kind) through the
        measured error at :attr:`step`.
        Below :attr:`step` that is an interpolation of a measured law; above it an
        extrapolation: check the suggested step with :func:`step_error` before relying on it
        (a coarser step may no longer resolve the voltage program or the lowest mode).
        """
        target = positive_float("target", target)
        worst = self.worst(columns)
        if worst.relative == 0.0:
            return math.inf
        return self.step * (target / worst.relative) ** (1.0 / self.order)

    def to_dict(self) -> dict[str, Any]:
        """Plain numbers for JSON: the step, and per column its unit, difference, error, relative error and order."""
        return {"step [s]": self.step, "t_end [s]": self.t_end, "compared": self.compared, "summary": list(self.summary),
                "order": self.order, "cell_orders": dict(self.cell_orders),
                "columns": {n: {"unit": c.unit, "difference": c.difference, "error": c.error,
                                "relative": c.relative, "order": c.order} for n, c in self.columns.items()}}

    def __str__(self) -> str:
        cells = ", ".join(f"{name} {p:g}" for name, p in self.cell_orders.items()) or "none"
        lines = [f"time-step error of a run at step {self.step:.6g} s over {self.t_end:.6g} s "
                 f"({self.compared} instants compared)",
                 f"estimates assume order {self.order:g} (time integration order per cell kind: {cells})",
                 f"{'column':>28} | {'unit':>4} | {'estimated error':>15} | {'of its range':>12} | {'order':>5}"]
        lines.append("-" * len(lines[-1]))
        for c in self.columns.values():
            marker = " *" if c.name in self.summary else ""
            lines.append(f"{c.name:>28} | {c.unit:>4} | {c.error:>15.3e} | {c.relative:>12.2e} | "
                         f"{c.order:>5.2f}{marker}")
        if any(math.isfinite(self.columns[n].relative) for n in self.summary):
            worst = self.worst()
            lines.append(f"* summarised (worst: {worst.name}, {worst.relative:.2e} of its range)")
        else:
            lines.append("* summarised (none varies)")
        return "\n".join(lines)


def time_orders(system: Any) -> dict[str, float]:
    """Order of the time integration per cell kind in ``system`` (:attr:`~exudyn_atcm.cells.CellKind.time_order`).

    ``system``: a :class:`~exudyn_atcm.BendingActuator` (its ``cell``) or a
    :class:`~exudyn_atcm.Mechanism` (its benders' and cell-model flexures' cells); ``{}`` for anything
    else (links, pseudo-rigid-body flexures and springs are Exudyn's own items, order
    :data:`NOMINAL_ORDER`).
    """
    kinds = [getattr(system, "cell", None)] + [getattr(b, "cell", None) for b in getattr(system, "benders", ())]
    return {kind.name: float(kind.time_order) for kind in kinds if isinstance(kind, CellKind)}


def _grid_rows(times: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Grid indices ``k`` (``t = k step``) of the recorded instants on the grid, and their rows."""
    k = np.rint(times / step)
    on = np.abs(times - k * step) <= 1e-6 * step
    return k[on].astype(np.int64), np.flatnonzero(on)


def _common_rows(results: list[Result], steps: list[float]) -> list[np.ndarray]:
    """Rows of every run at the coarse grid's instants that all runs recorded (same order)."""
    keyed = []
    for result, step in zip(results, steps):
        k, rows = _grid_rows(np.asarray(result["time"], dtype=float), step)
        factor = int(round(steps[0] / step))
        on_coarse = k % factor == 0
        keyed.append((k[on_coarse] // factor, rows[on_coarse]))
    common = reduce(np.intersect1d, [k for k, _ in keyed])
    return [rows[np.searchsorted(k, common)] for k, rows in keyed]


@keyword_signature
def step_error(system: Any, t_end: float, *legacy: Any, step: float = DEFAULT_STEP, check_order: bool = True,
               columns: Sequence[str] | None = None, tip_force: tuple[float, float] = (0.0, 0.0),
               settings: Callable[[Any], None] | dict | None = None) -> StepError:
    """Estimate the time-step error of :func:`~exudyn_atcm.simulate` at ``step`` by running at smaller steps.

    Runs ``system`` for ``t_end`` at ``step``, ``step/2`` and (``check_order``) ``step/4``, and
    compares every result column at the instants all runs recorded.  The error of the run at
    ``step`` is estimated as ``2^p / (2^p - 1)`` of its largest difference from the run at
    ``step/2`` (``p``: the lowest time-integration order of the system's cells, 2 for every cell
    kind, so 4/3; :attr:`StepError.order` and :attr:`StepError.cell_orders` name them); the third
    run measures the order that estimate assumes.

    Parameters
    ----------
    system : BendingActuator or Mechanism
        What :func:`~exudyn_atcm.simulate` runs (its voltage program, loads and hysteresis).
    t_end : float
        Length of the runs [s], > 0.
    step : float, optional
        The step to examine [s] (default 1e-4).  A step that does not divide ``t_end`` is
        adjusted as :func:`~exudyn_atcm.simulate` does (with its warning).
    check_order : bool, optional
        Run ``step/4`` too and report the observed order (default True; the three runs cost
        about 7 runs at ``step``, the two without it about 3).
    columns : sequence of str, optional
        The columns :meth:`StepError.worst` and :meth:`StepError.suggested_step` look at by
        default (default: every column in metres or radians, the motion).
    tip_force : (float, float), optional
        A lone actuator's tip force [N], as for :func:`~exudyn_atcm.simulate`.
    settings : callable or dict, optional
        Solver adjustments, as for :func:`~exudyn_atcm.simulate` (the same for every run).

    Returns
    -------
    StepError
        Per column: the difference, the estimated error [the column's unit], the error over the
        column's range and the observed order; ``print(report)`` gives the table,
        ``report.suggested_step(1e-3)`` the step for a relative error of 1e-3,
        ``report.extrapolated`` the two finest runs extrapolated to step zero.

    Raises
    ------
    ValueError
        For a bad ``t_end``, ``step`` or ``columns``, or runs that share fewer than two
        recorded instants.

    Warns
    -----
    AccuracyWarning
        When the differences of a summarised column fall more slowly than ``h^(p - 0.5)``
        (``h^1.5``): the error is not smooth in the step (a voltage program's corners between
        steps, step reductions) and the estimate, which assumes ``h^p``, may be too small.

    Examples
    --------
    >>> report = step_error(mechanism, 0.5, step=5e-4)            # doctest: +SKIP
    >>> print(report)                                             # doctest: +SKIP
    >>> report.suggested_step(1e-3)                               # doctest: +SKIP

    ``step`` is keyword-only, as for :func:`~exudyn_atcm.simulate`; the positional form of earlier
    releases (``step_error(system, t_end, 1e-4)``) still works for one release with an
    :class:`~exudyn_atcm.AtcmDeprecationWarning`.
    """
    if legacy:  # the positional step of earlier releases, for one more release
        (step,) = legacy_positional("step_error", legacy, {"step": step}, {"step": DEFAULT_STEP}).values()
    t_end = positive_float("t_end", t_end)
    step = positive_float("step", step)
    if step > t_end:
        raise ValueError(f"step must be <= t_end = {t_end!r} s, got {shown(step)}")
    used = time_grid(t_end, step, stacklevel=3).step
    steps = [used, used / 2.0] + ([used / 4.0] if check_order else [])
    if isinstance(columns, str):
        raise ValueError(f"columns must be a sequence of column names, got the string {columns!r}")
    if columns is not None and len(columns) == 0:
        raise ValueError("columns must name at least one result column (None: every column in m or rad), got []")
    runs = [simulate(system, t_end, step=used, tip_force=tip_force, settings=settings)]
    names = [n for n in runs[0].names if n != "time"]
    if columns is None:
        summary = [n for n in names if runs[0].unit(n) in MOTION_UNITS] or names
    else:
        old = runs[0].old_names  # a lone actuator's names before 0.3.0 ("tip_y"), for one release
        for n in columns:
            if n in old:
                warnings.warn(f"columns: series {n!r} is now named {old[n]!r}; the old name goes away in the next "
                              "release", AtcmDeprecationWarning, stacklevel=2)
        summary = [old.get(n, n) for n in columns]
        unknown = [n for n in summary if n not in names]
        if unknown:  # before the finer (dearer) runs
            raise ValueError(f"columns: no such result column {unknown}; available: {', '.join(names)}")
    cell_orders = time_orders(system)
    order = min(cell_orders.values(), default=NOMINAL_ORDER)
    runs += [simulate(system, t_end, step=h, tip_force=tip_force, settings=settings) for h in steps[1:]]
    rows = _common_rows(runs, steps)
    compared = len(rows[0])
    if compared < 2:
        raise ValueError(f"the runs at steps {steps} s share {compared} recorded instants; a run whose steps were "
                         "reduced everywhere (Newton failures) cannot be compared: use a smaller step")
    finest = runs[-1]
    # what a position's or an angle's range is compared with to tell motion from round-off: the mechanism's extent
    # (the largest magnitude of a position column) [m], a whole angle [rad]
    extent = max((float(np.max(np.abs(finest[c]), initial=0.0)) for c in finest.names if finest.unit(c) == "m"),
                 default=0.0)
    scales = {"m": extent, "rad": 1.0}
    out: dict[str, ColumnStepError] = {}
    for name in names:
        values = [np.asarray(run[name], dtype=float)[r] for run, r in zip(runs, rows)]
        differences = [float(np.max(np.abs(a - b))) for a, b in zip(values, values[1:])]
        span = float(np.ptp(finest[name])) if finest.n_rows else 0.0
        if span <= STILL_TRAVEL * scales.get(finest.unit(name), 0.0):
            span = 0.0  # a column that does not move: its range is round-off, no scale for an error
        error, observed = richardson(differences, NOISE * span if span > 0.0 else math.inf, order)
        relative = error / span if span > 0.0 else math.nan
        out[name] = ColumnStepError(name, finest.unit(name), differences[0], error, relative, observed)
    lowest = order - ORDER_SLACK
    slow = [c for c in (out[n] for n in summary) if math.isfinite(c.order) and c.order < lowest]
    if slow:
        slow.sort(key=lambda c: c.order)
        listed = ", ".join(f"{c.name} (order {c.order:.2f})" for c in slow[:3])
        if len(slow) > 3:
            listed += f" and {len(slow) - 3} more columns"
        warnings.warn(
            f"step_error: the differences of {listed} fall more slowly than h^{lowest:g} from step {used:.6g} s to "
            f"{steps[-1]:.6g} s, not as h^{order:g} (the order of the cells' time integration): the error is not smooth "
            "in the step (a voltage program whose corners fall between steps, steps reduced after Newton failures, a "
            f"stop), and the estimate, which assumes h^{order:g}, may be too small. Compare the finest run (report.finest) with a run at a step whose grid holds the "
            "program's corners", AccuracyWarning, stacklevel=2)
    return StepError(used, t_end, out, summary, finest, compared,
                     _extrapolated(runs[1:], rows[1:], steps[1:], order) if check_order else None, order, cell_orders)


def _extrapolated(runs: list[Result], rows: list[np.ndarray], steps: list[float], order: float) -> Result:
    """Richardson's extrapolation of the runs at ``h`` and ``h/2`` (order ``order``) at their common ``rows``."""
    finer = runs[-1]
    series = {}
    for name in finer.names:
        coarse, fine = (np.asarray(run[name], dtype=float)[r] for run, r in zip(runs, rows))
        series[name] = fine if name == "time" else fine + (fine - coarse) / (2.0 ** order - 1.0)
    info = dict(finer.info, extrapolated_from_steps=list(steps), extrapolation=f"Richardson, order {order:g}")
    return Result(series, finer.units, finer.parameters, info)
