"""Checks made before and around a time integration: step size, time grid, run time, Ctrl-C.

Every function here is independent of Exudyn and of the model type, so any solve path (the
bending actuator's :func:`~exudyn_atcm.solve.simulation.simulate`, a mechanism) can call them:

* :func:`time_grid` -- the step actually used for ``t_end`` (warns when the requested step
  does not divide the run; from :mod:`exudyn_atcm.solve.time_grid`, with :func:`snap_time`);
* :func:`check_step_against_program` -- refuses a step that cannot resolve the voltage
  program, warns when it resolves it only coarsely;
* :func:`check_step_against_frequency` -- warns when the step resolves the first
  eigenfrequency too coarsely;
* :func:`estimate_run_time` / :func:`warn_if_long` -- a predicted wall time from steps x a
  measured cost per step for the cell type and number of cells;
* :class:`InterruptGuard` -- turns Ctrl-C inside a solver hook into a clean stop.

Thresholds and why
------------------
A voltage program's *feature* is the shortest interval between its corners (see
:meth:`exudyn_atcm.model.signals.Signal.shortest_feature`): the ramp of a triangle (half a period),
half a sine period, the dwell of a step program, the shortest stretch between reversals or
marked kinks of a piecewise-linear program (a densely sampled smooth curve is judged by its
extrema, not by its sampling interval).  The solver samples the program once per step, so with ``n`` steps per feature a
peak of a ramp can be missed by up to ``1/(2n)`` of the ramp's swing, and a sine peak by
``1 - cos(pi/(2n))`` of its amplitude:

* :data:`MIN_STEPS_PER_FEATURE` = 4: below it the run is refused (a ramp's peak missed by more
  than 12.5 % of its swing, reversals of the hysteresis input lost or moved by a quarter of a
  feature; the Fig. 12 case with ``step = 1`` s samples -500 V three times and shows a flat
  response);
* :data:`COMFORTABLE_STEPS_PER_FEATURE` = 20: below it a warning (peak error up to 2.5 % of a
  ramp's swing, 0.3 % of a sine amplitude).

A piecewise-linear program whose corners all lie on the step grid is exempt: the solver then
samples it exactly at every corner, and its input is the program itself
(:func:`corners_on_grid`; e.g. a feedforward program tabulated at a controller's sample time
that is a multiple of the step, whose inverse-hysteresis jumps at reversals last one sample).

The other way round, a program whose shortest feature lasts more than
:data:`SLOW_PROGRAM_FACTOR` = 100 times the run gives a warning: the run then sees at most 1 %
of a ramp's swing (2 % of a triangle's amplitude), which is what a period or ramp time written in
milliseconds against a run in seconds does (``Triangle(500, 1000, 500)`` for 500 ms, run 2 s).

Against the first eigenfrequency ``f1``: generalized-alpha (spectral radius 0.8) damps a mode
resolved by few steps per period and lengthens its period, so vibrations of the first bending
mode are lost.  Below :data:`MIN_STEPS_PER_MODE_PERIOD` = 10 steps per ``1/f1`` a warning
(period error of the trapezoidal family ~ (pi/n)^2/12, 8 % at 10 steps; fine for a
quasi-static answer, wrong for the dynamics).
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np

from ..cells import CELL_KINDS, CellKind, cell_kind
from .interrupts import InterruptGuard, SimulationInterrupted, WallClock, is_interrupt
from ..mechanism.build_cost import LARGE_MODEL_BYTES, build_detail
from .drive_cost import drive_share
from .long_runs import is_announced, long_run_message
from ..errors import AccuracyWarning, InputRangeWarning, RunCostWarning
from .time_grid import SUGGESTION_COUNTS, TimeGrid, dividing_steps, snap_time, snap_times, time_grid

__all__ = [
    "MIN_STEPS_PER_FEATURE", "COMFORTABLE_STEPS_PER_FEATURE", "MIN_STEPS_PER_MODE_PERIOD", "SLOW_PROGRAM_FACTOR",
    "LONG_RUN_SECONDS", "COST_PER_STEP", "TimeGrid", "time_grid", "snap_time", "snap_times",
    "check_step_against_program", "check_record_interval", "program_feature", "MIN_RECORDS_PER_FEATURE",
    "corners_on_grid", "check_step_against_frequency", "estimate_run_time", "warn_if_long", "dividing_steps",
    "SUGGESTION_COUNTS",
    "InterruptGuard", "SimulationInterrupted", "WallClock", "is_interrupt",
]

#: Fewest solver steps per feature of the voltage program; fewer are refused (see module notes).
MIN_STEPS_PER_FEATURE = 4
#: Fewer steps per feature than this give a warning (see module notes).
COMFORTABLE_STEPS_PER_FEATURE = 20
#: A program whose shortest feature (before ``t_end``) lasts more than this many runs gives a
#: warning (see module notes).
SLOW_PROGRAM_FACTOR = 100.0
#: Fewer steps per period of the first eigenfrequency than this give a warning.
MIN_STEPS_PER_MODE_PERIOD = 10
#: Fewer recorded instants per feature of the voltage program than this give a warning: the
#: record (and extremes or crossings computed from it) can miss a ramp's peak by up to
#: ``1/(2n)`` of its swing, 5 % at 10.
MIN_RECORDS_PER_FEATURE = 10
#: A run predicted to take longer than this [s] of wall time is announced with a warning.
LONG_RUN_SECONDS = 60.0

#: Measured wall time of the time integration per accepted step [s], by cell name, as
#: ``(a, b, c)``: a run of ``n`` cells and ``k`` steps takes about ``k * (a + b n + c n^2)``;
#: each kind's own measured
#: :attr:`~exudyn_atcm.cells.CellKind.cost_per_step` (``benchmarks/bench_run_cost.py``).
#: (``COST_PER_STEP`` is a module attribute read from the registry when asked.)
_LIVE = {"COST_PER_STEP": lambda: {name: kind.cost_per_step for name, kind in CELL_KINDS.items()
                                   if kind.cost_per_step is not None}}
# ------------------------------------------------------------------------------ step checks

def _step_used(step: float | TimeGrid) -> tuple[float, str]:
    """The step used [s] and its text in messages (the requested step too, for a grid)."""
    if isinstance(step, TimeGrid):
        return step.step, step.describe()
    return step, f"step = {step:.6g} s"


def program_feature(program: Any, t_end: float) -> tuple[float, str] | None:
    """``(duration [s], description)`` of the program's shortest feature before ``t_end``.

    ``None`` for a program without ``shortest_feature`` (plain callables, constants) or without
    a feature before ``t_end``.
    """
    shortest = getattr(program, "shortest_feature", None)
    return shortest(t_end) if callable(shortest) else None


def check_step_against_program(program: Any, step: float | TimeGrid, t_end: float, *,
                               what: str = "the voltage program", stacklevel: int = 4) -> None:
    """Refuse or warn when ``step`` resolves the program's shortest feature too coarsely.

    Parameters
    ----------
    program : object
        A voltage program; checked only if it has ``shortest_feature(t_end)`` (every
        :mod:`exudyn_atcm.model.signals` object), which returns ``(duration [s], description)`` or
        ``None``.  Plain callables and constants are not checked.
    step : float or TimeGrid
        Step used [s], or the run's :class:`TimeGrid` (then the messages quote the step as
        given and the step used, see :meth:`TimeGrid.describe`).
    t_end : float
        End time of the run [s]; only features before it count.
    what : str
        How the program is named in messages.

    Raises
    ------
    ValueError
        With fewer than :data:`MIN_STEPS_PER_FEATURE` steps per feature: says what the step
        would do and which step is needed.

    Warns
    -----
    RuntimeWarning
        With fewer than :data:`COMFORTABLE_STEPS_PER_FEATURE` steps per feature, and when the
        shortest feature lasts more than :data:`SLOW_PROGRAM_FACTOR` times ``t_end`` (a period
        or ramp time in milliseconds?).
    """
    step, step_given = _step_used(step)
    feature = program_feature(program, t_end)
    if feature is None:
        return
    duration, description = feature
    if duration > SLOW_PROGRAM_FACTOR * t_end:
        warnings.warn(
            f"{what} hardly changes during the run: its shortest feature, {description}, lasts "
            f"{duration:.6g} s, {duration / t_end:.3g} times t_end = {t_end:.6g} s, so the run covers at most "
            f"{100.0 * t_end / duration:.2g} % of it. Times are in seconds: if the program's times or period are "
            "in milliseconds, divide them by 1000",
            InputRangeWarning,
            stacklevel=stacklevel,
        )
    if corners_on_grid(program, step, t_end):
        return  # sampled exactly at every corner and linear between: nothing to miss
    per_feature = duration / step
    if per_feature < MIN_STEPS_PER_FEATURE:
        raise ValueError(
            f"{step_given} is too coarse for {what}: its shortest feature, {description}, lasts "
            f"{duration:.6g} s, only {per_feature:.3g} steps; the solver would sample the program "
            f"{per_feature:.3g} times across it and miss its peaks and reversals (a flat or distorted "
            f"response). Use step <= {duration / MIN_STEPS_PER_FEATURE:.6g} s (at least "
            f"{MIN_STEPS_PER_FEATURE} steps per feature; {COMFORTABLE_STEPS_PER_FEATURE} recommended: "
            f"step <= {duration / COMFORTABLE_STEPS_PER_FEATURE:.6g} s)"
        )
    if per_feature < COMFORTABLE_STEPS_PER_FEATURE:
        warnings.warn(
            f"{step_given} resolves the shortest feature of {what}, {description} lasting "
            f"{duration:.6g} s, with only {per_feature:.3g} steps: peaks can be missed by up to "
            f"{50.0 / per_feature:.2g} % of a ramp's swing. For {COMFORTABLE_STEPS_PER_FEATURE} steps per "
            f"feature use step <= {duration / COMFORTABLE_STEPS_PER_FEATURE:.6g} s",
            AccuracyWarning,
            stacklevel=stacklevel,
        )


def check_record_interval(program: Any, schedule: Any, t_end: float, *, what: str = "the voltage program",
                          stacklevel: int = 4) -> None:
    """Warn when ``record_every`` keeps fewer than :data:`MIN_RECORDS_PER_FEATURE` instants per program feature.

    The solution is computed on every step whatever the recording interval, but the record
    (its files and plots, and any extreme, crossing or cycle figure computed from its columns)
    sees only the recorded instants: a coarse interval misses peaks and shifts crossings.
    :attr:`Result.every_step <exudyn_atcm.Result.every_step>` keeps every accepted step for such figures.

    Parameters
    ----------
    program : object
        The voltage program (checked if it has ``shortest_feature``, as for
        :func:`check_step_against_program`).
    schedule : RecordingSchedule or None
        The run's recording schedule (``None`` or every step: nothing to check).
    t_end : float
        End time of the run [s].
    what : str
        How the program is named in the message.

    Warns
    -----
    RuntimeWarning
        Naming the interval as given (seconds or steps), the feature, and the largest
        interval that keeps :data:`MIN_RECORDS_PER_FEATURE` instants per feature.
    """
    if schedule is None or schedule.every_step:
        return
    feature = program_feature(program, t_end)
    if feature is None:
        return
    duration, description = feature
    interval = schedule.interval if schedule.interval is not None else schedule.steps * schedule.step
    per_feature = duration / interval
    if per_feature < MIN_RECORDS_PER_FEATURE:
        given = (f"{schedule.interval!r} s" if schedule.interval is not None
                 else f"{schedule.steps} steps ({interval:.6g} s)")
        warnings.warn(
            f"record_every = {given} keeps only {per_feature:.3g} recorded instants across the shortest feature of "
            f"{what}, {description} lasting {duration:.6g} s: the solution is computed on every step, but the record "
            f"(its files and plots, and any extreme, crossing or cycle figure computed from its columns) can miss "
            f"peaks by up to {min(50.0 / per_feature, 100.0):.2g} % of a ramp's swing (result.every_step keeps every "
            f"accepted step for such figures). Record at most "
            f"{duration / MIN_RECORDS_PER_FEATURE:.6g} s apart (or every step)",
            AccuracyWarning,
            stacklevel=stacklevel,
        )


def corners_on_grid(program: Any, step: float, t_end: float) -> bool:
    """Whether every corner of a piecewise-linear ``program`` before ``t_end`` lies on the step grid.

    The solver samples the program at the grid times ``k * step``.  A program that is linear
    between corners lying on that grid is then sampled exactly at every corner (peaks and
    reversals included) and the solver's input is the program itself, however few steps a
    segment spans; only the dynamics' resolution remains (:func:`check_step_against_frequency`).
    Programs without ``corner_times(t_end)`` (:class:`~exudyn_atcm.model.signals.PiecewiseLinear`
    has it) return False.
    """
    corner_times = getattr(program, "corner_times", None)
    if not callable(corner_times):
        return False
    corners = np.asarray(corner_times(t_end), dtype=float)
    if corners.size == 0:
        return False
    k = np.round(corners / step)
    return bool(np.all(np.abs(corners - k * step) <= 1e-9 * max(step, 1e-300) + 1e-12 * np.abs(corners)))


def check_step_against_frequency(step: float | TimeGrid, frequency: float, *, what: str = "the first bending mode",
                                 stacklevel: int = 4) -> None:
    """Warn when ``step`` [s] gives fewer than :data:`MIN_STEPS_PER_MODE_PERIOD` steps per ``1/frequency``.

    Parameters
    ----------
    step : float or TimeGrid
        Step used [s], or the run's :class:`TimeGrid` (as in :func:`check_step_against_program`).
    frequency : float
        Eigenfrequency [Hz] (e.g. :attr:`BendingActuator.first_frequency_estimate`); not
        checked if not finite and positive.
    what : str
        How the mode is named in the message.
    """
    step, step_given = _step_used(step)
    if not (frequency > 0.0 and math.isfinite(frequency)):
        return
    period = 1.0 / frequency
    per_period = period / step
    if per_period < MIN_STEPS_PER_MODE_PERIOD:
        warnings.warn(
            f"{step_given} resolves {what} (f1 = {frequency:.4g} Hz, period {period:.4g} s) with "
            f"only {per_period:.3g} steps: generalized-alpha damps it numerically and lengthens its "
            f"period, so its vibrations are lost (acceptable for a quasi-static answer only). For the "
            f"dynamics use step <= {period / (2 * MIN_STEPS_PER_MODE_PERIOD):.4g} s",
            AccuracyWarning,
            stacklevel=stacklevel,
        )


# ------------------------------------------------------------------------------ run time

def estimate_run_time(cell: str | CellKind, n_cells: int, n_steps: int, extra_per_step: float = 0.0) -> float | None:
    """Predicted wall time [s] of a time integration from the cell kind's measured cost.

    ``n_steps * (a + b n_cells + c n_cells^2 + extra_per_step)`` with the kind's
    :attr:`~exudyn_atcm.cells.CellKind.cost_per_step` ``(a, b, c)`` and the drives' measured cost
    beyond the one the kind's cost includes (``extra_per_step`` [s],
    :func:`~exudyn_atcm.solve.drive_cost.extra_drive_cost`); ``None`` for a kind without measured
    costs.  ``cell`` is a kind or its name.
    """
    per_step = cell_kind(cell).estimate_step_cost(n_cells)
    return None if per_step is None else n_steps * (per_step + extra_per_step)


def warn_if_long(cell: str | CellKind, n_cells: int, n_steps: int, *, limit: float | None = None,
                 parts: str | None = None, extra_per_step: float = 0.0, build: tuple[float, float] = (0.0, 0.0),
                 stacklevel: int = 4) -> float | None:
    """Warn (``RuntimeWarning``) when :func:`estimate_run_time` exceeds ``limit`` [s]; returns the estimate.

    ``build`` is the wall time [s] and memory [bytes] of building the model
    (:func:`~exudyn_atcm.solve.build_cost.build_estimate`): the time is added to the estimate, and
    a model needing more than :data:`~exudyn_atcm.solve.build_cost.LARGE_MODEL_BYTES` is announced
    whatever its time.

    Quiet inside :func:`~exudyn_atcm.solve.long_runs.announced_up_front` (a run of several
    simulations announced as a whole by :class:`~exudyn_atcm.solve.run_plan.RunPlan`).

    ``limit`` defaults to :data:`LONG_RUN_SECONDS`.  ``parts`` describes the model in the
    message (default ``"{n_cells} {cell} cells"``; a mechanism counts the cells of all its
    benders and flexures and its links).
    """
    limit = LONG_RUN_SECONDS if limit is None else limit
    stepping = estimate_run_time(cell, n_cells, n_steps, extra_per_step)
    estimate = None if stepping is None else stepping + build[0]
    large = build[1] > LARGE_MODEL_BYTES
    if estimate is not None and (estimate > limit or large) and not is_announced():  # a plan announced the whole run
        detail = (f"{n_steps} steps of {parts or f'{n_cells} {cell_kind(cell).name} cells'} at "
                  f"~{stepping / max(n_steps, 1) * 1e6:.3g} µs per step, measured{drive_share(extra_per_step)}"
                  + (f"; {build_detail(*build)}" if build[0] > 0.1 * estimate or large else ""))
        warnings.warn(long_run_message(estimate, detail), RunCostWarning, stacklevel=stacklevel)
    return estimate


def __getattr__(name: str):
    # the registry's names, read when asked (kinds registered with exudyn_atcm.register_cell_kind included)
    if name in _LIVE:
        return _LIVE[name]()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
