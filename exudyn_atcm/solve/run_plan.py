"""A run made of several simulations: one announcement up front, one progress display across them.

A case that runs several time integrations one after the other (``tip_tracking`` runs four
controllers over the same ``duration``) declares them before it starts, as
:class:`PlannedRun` entries (the system, ``t_end`` and step of each, or its own estimate), and
runs them inside the :class:`RunPlan`::

    with ctx.plan([PlannedRun(actuator, p.duration, p.step)] * 4) as plan:
        for k, voltage in enumerate(drives):
            results.append(simulate(build(voltage), p.duration, step=p.step, progress=plan.progress(k)))

The plan sums the estimates of :func:`~exudyn_atcm.solve.run_checks.estimate_run_time` (the
cell kind's measured cost per step) and, when the sum exceeds
:data:`~exudyn_atcm.solve.run_checks.LONG_RUN_SECONDS`, warns once, with the wording of a
single run's announcement (:func:`~exudyn_atcm.solve.long_runs.long_run_message`).  Inside the
``with`` block the single simulations do not announce themselves again.

:meth:`RunPlan.progress` gives simulation ``k`` a callback that reports the fraction of the
whole run: the simulations before it count with their estimated cost (their simulated time
when an estimate is missing).  A display with a ``stage(label, share, detail)`` method (the
:class:`~exudyn_atcm.io.progress.ProgressBar`) shows ``simulation 2/4`` and the simulated time of
that one; any other ``progress(t, t_end)`` callable receives the whole run's fraction as
``(share * T, T)`` with ``T`` the summed simulated time of all simulations.

The estimate counts the cells' measured solver cost per step, not a hysteresis operator or a
controller evaluated in every step (``tip_tracking``: 24 µs per step predicted, 70 to 140 µs
measured on a shared 2-core machine).  So inside the ``with`` block the plan also measures:
when simulation ``k`` starts reporting, the wall time since the block began is compared with
the prediction of the simulations before it; more than :data:`PACE_FACTOR` times the prediction,
with the rest then expected to take over the limit, gives one more warning with the remaining
time scaled by the measured ratio.
"""

from __future__ import annotations

import math
import warnings
from time import perf_counter
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Callable

from .._checks import shown
from ..errors import RunCostWarning
from ..io.progress import format_duration
from ..mechanism.assembly import Mechanism
from .long_runs import announced_up_front, long_run_message
from .mechanism_checks import cost_description, cost_parts
from .drive_cost import drive_share, extra_drive_cost
from ..mechanism.build_cost import build_estimate
from .run_checks import LONG_RUN_SECONDS, estimate_run_time, time_grid

__all__ = ["PlannedRun", "RunPlan", "estimate_simulation", "PACE_FACTOR"]

#: A plan whose finished simulations took more than this many times their prediction says so,
#: with the remaining ones' time scaled by the measured ratio (when that exceeds the limit).
PACE_FACTOR = 2.0


@dataclass(frozen=True)
class PlannedRun:
    """One simulation of a run: ``system`` integrated to ``t_end`` [s] with ``step`` [s].

    Parameters
    ----------
    system : BendingActuator or Mechanism, optional
        What is simulated (its cell kind and number of cells give the cost per step); ``None``
        with ``seconds``.
    t_end : float
        Simulated time [s] (> 0).
    step : float
        Time step [s] (> 0).
    seconds : float, optional
        The case's own estimate of the wall time [s], used instead of the cell kind's measured cost.
    label : str, optional
        Name in the progress display (default ``"simulation k/n"``).
    """

    system: Any = None
    t_end: float = 0.0
    step: float = 0.0
    seconds: float | None = None
    label: str = ""

    def __post_init__(self) -> None:
        for name in ("t_end", "step"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value > 0):
                raise ValueError(f"PlannedRun.{name} must be a positive time [s], got {shown(value)}")
        if self.step > self.t_end:
            raise ValueError(f"PlannedRun.step must be <= t_end = {self.t_end!r} s, got {self.step!r}")
        if self.seconds is not None and not (isinstance(self.seconds, (int, float)) and not isinstance(self.seconds, bool)
                                             and math.isfinite(self.seconds) and self.seconds >= 0.0):
            raise ValueError(f"PlannedRun.seconds must be None or a wall time >= 0 [s], got {self.seconds!r}")
        if self.system is None and self.seconds is None:
            raise ValueError("PlannedRun needs the system simulated (for its measured cost per step) or its own "
                             "estimate seconds=...")


def estimate_simulation(system: Any, t_end: float, step: float) -> tuple[float | None, int, str, float]:
    """Predicted wall time [s] (``None`` without measured costs), steps, parts and the drives' extra cost per
    step [s] of one simulation.

    A :class:`~exudyn_atcm.BendingActuator` counts its cells, a
    :class:`~exudyn_atcm.Mechanism` its cells and bodies
    (:func:`~exudyn_atcm.solve.mechanism_checks.cost_parts`); both add what their drives cost beyond
    the one the cells' measured costs include (:func:`~exudyn_atcm.solve.drive_cost.extra_drive_cost`)
    and the build of the model (:func:`~exudyn_atcm.mechanism.build_cost.build_estimate`).
    """
    grid = time_grid(t_end, step, warn=False)
    n_steps = grid.n_steps
    if isinstance(system, Mechanism):
        cell, parts = cost_parts(system)
        extra = extra_drive_cost(system.drives.values(), grid.step)
        estimate = estimate_run_time(cell, parts, n_steps, extra)
        build = build_estimate(system)[0]
        return None if estimate is None else estimate + build, n_steps, cost_description(system), extra
    cell, n_cells = getattr(system, "cell", None), getattr(system, "n_cells", None)
    if cell is None or n_cells is None:
        raise ValueError(f"PlannedRun.system must be a BendingActuator or a Mechanism, got {type(system).__name__}")
    extra = extra_drive_cost([system.drive], grid.step)
    estimate = estimate_run_time(cell, n_cells, n_steps, extra)
    build = (cell.estimate_build(n_cells) or (0.0, 0.0))[0]
    return None if estimate is None else estimate + build, n_steps, f"{n_cells} {cell.name} cells", extra


class RunPlan:
    """Several simulations announced as one run, with one progress display across them.

    Parameters
    ----------
    runs : sequence of PlannedRun
        The simulations, in the order they will run (at least one).
    progress : callable, optional
        The run's display: ``progress(t, t_end)``, and ``progress.stage(label, share, detail)``
        if it has one.
    limit : float, optional
        Announce when the summed estimate exceeds this [s] (default
        :data:`~exudyn_atcm.solve.run_checks.LONG_RUN_SECONDS`).

    Attributes
    ----------
    estimates : tuple of float or None
        Predicted wall time [s] of each simulation (``None``: no measured cost).
    estimate : float or None
        Their sum (``None`` when none is known; the known ones otherwise).
    announced : bool
        Whether the run was announced.

    Warns
    -----
    RuntimeWarning
        Once, on construction, when :attr:`estimate` exceeds ``limit``.
    """

    def __init__(self, runs: Sequence[PlannedRun], progress: Callable[[float, float], None] | None = None, *,
                 limit: float | None = None, stacklevel: int = 2) -> None:
        runs = list(runs)
        if not runs or not all(isinstance(r, PlannedRun) for r in runs):
            raise ValueError(f"runs must be a non-empty sequence of PlannedRun, got {shown(runs)}")
        if progress is not None and not callable(progress):
            raise ValueError(f"progress must be None or a callable progress(t, t_end), got {shown(progress)}")
        self.runs = tuple(runs)
        self._progress = progress
        details, estimates = [], []
        for run in runs:
            if run.seconds is not None:
                estimates.append(float(run.seconds))
                details.append("its own estimate")
                continue
            estimate, n_steps, parts, extra = estimate_simulation(run.system, run.t_end, run.step)
            estimates.append(estimate)
            per_step = "" if estimate is None else \
                f" at ~{estimate / max(n_steps, 1) * 1e6:.3g} µs per step, measured{drive_share(extra)}"
            details.append(f"{n_steps} steps of {parts}{per_step}")
        self.estimates = tuple(estimates)
        known = [e for e in estimates if e is not None]
        self.estimate = sum(known) if known else None
        full = len(known) == len(runs) and self.estimate > 0.0
        weights = estimates if full else [r.t_end for r in runs]
        total = float(sum(weights))
        self._before = [sum(weights[:k]) / total for k in range(len(runs))]
        self._share = [w / total for w in weights]
        self._simulated = float(sum(r.t_end for r in runs))
        limit = LONG_RUN_SECONDS if limit is None else float(limit)
        self.announced = self.estimate is not None and self.estimate > limit
        if self.announced:
            warnings.warn(long_run_message(self.estimate, self._describe(details, len(known))),
                          RunCostWarning, stacklevel=stacklevel)
        self._scope: Any = None
        self._limit = limit
        self._entered: float | None = None
        self._reported: set[int] = set()
        self.pace_warned = False

    def _describe(self, details: list[str], n_known: int) -> str:
        counts: dict[str, int] = {}
        for d in details:
            counts[d] = counts.get(d, 0) + 1
        parts = [d if n == 1 else f"{n} x {d}" for d, n in counts.items()]
        text = f"{len(details)} simulations: " + "; ".join(parts)
        if n_known < len(details):
            text += f"; {len(details) - n_known} without a measured cost, not counted"
        return text

    def __enter__(self) -> "RunPlan":
        self._scope = announced_up_front()
        self._scope.__enter__()
        self._entered = perf_counter()
        return self

    def _check_pace(self, k: int) -> None:
        """Simulation ``k`` started: compare the wall time so far with the prediction of those before it."""
        if k in self._reported:
            return
        self._reported.add(k)
        if k == 0 or self._entered is None or self.pace_warned or any(e is None for e in self.estimates):
            return
        predicted = float(sum(self.estimates[:k]))
        elapsed = perf_counter() - self._entered
        if predicted <= 0.0 or elapsed <= PACE_FACTOR * predicted:
            return
        ratio = elapsed / predicted
        remaining = ratio * float(sum(self.estimates[k:]))
        if remaining <= self._limit:
            return
        self.pace_warned = True
        n = len(self.runs)
        warnings.warn(
            f"the first {k} of {n} simulations took {format_duration(elapsed)}, {ratio:.2g} times their prediction of "
            f"{format_duration(predicted)} (the prediction counts the cells' solver cost only, not a hysteresis "
            f"operator or controller evaluated in every step); the remaining {n - k} are predicted to take about "
            f"{format_duration(remaining, rough=True)} more. Ctrl-C stops the run and keeps what was computed",
            RunCostWarning, stacklevel=4)

    def __exit__(self, *exc: Any) -> None:
        scope, self._scope = self._scope, None
        if scope is not None:
            scope.__exit__(*exc)

    def share_done(self, k: int, t: float, t_end: float) -> float:
        """Fraction of the whole run done when simulation ``k`` has reached ``t`` of ``t_end`` [s]."""
        if not 0 <= k < len(self.runs):
            raise ValueError(f"k must be the index of a planned simulation, 0 ... {len(self.runs) - 1}, got {shown(k)}")
        within = min(max(t / t_end, 0.0), 1.0) if t_end > 0.0 else 1.0
        return min(self._before[k] + self._share[k] * within, 1.0)

    def progress(self, k: int) -> Callable[[float, float], None]:
        """The ``progress(t, t_end)`` callback for simulation ``k`` (0-based), reporting the whole run."""
        share0 = self.share_done(k, 0.0, 1.0)  # checks k
        label = self.runs[k].label or f"simulation {k + 1}/{len(self.runs)}"
        display = self._progress
        stage = getattr(display, "stage", None)

        def report(t: float, t_end: float) -> None:
            self._check_pace(k)
            if display is None:
                return
            share = self.share_done(k, t, t_end) if t_end > 0.0 else share0
            if stage is not None:
                stage(label, share, f"t = {t:.4g} / {t_end:.4g} s")
            else:
                display(share * self._simulated, self._simulated)

        return report
