"""What every time integration does before and after its solve, whatever the model.

Shared by the actuator path (:func:`exudyn_atcm.solve.simulation.simulate`) and the mechanism path
(:func:`exudyn_atcm.solve.mechanism_solve.simulate`), so that both give the same errors, warnings
and metadata:

* :func:`prepare_run` -- argument checks, the :class:`~exudyn_atcm.solve.run_checks.TimeGrid`
  (a step that does not divide ``t_end`` is warned about and the step used recorded) and
  the :class:`~exudyn_atcm.model.recording.RecordingSchedule` of ``record_every``;
* :func:`run_info` -- the solver statistics written into ``result.info``;
* :func:`report_controller` -- a controller's ``summary()`` in the info and a warning when
  its output was held at a limit.

No Exudyn import: the solve itself stays in the model's own module.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

from .._checks import positive_float, shown
from ..model.recording import RecordingSchedule, recording_schedule
from .run_checks import TimeGrid, time_grid
from ..errors import OutOfReachWarning, SetupWarning

__all__ = ["DEFAULT_STEP", "prepare_run", "run_info", "report_controller"]

#: Default time step of :func:`exudyn_atcm.simulate` [s] (measured: the tip converges to 2e-7 m
#: at 10 cells).
DEFAULT_STEP = 1e-4


def prepare_run(t_end: Any, step: Any, settings: Any, progress: Any,
                record_every: Any) -> tuple[float, TimeGrid, RecordingSchedule]:
    """Checked ``t_end`` [s], the time grid and the recording schedule of a time integration.

    Raises
    ------
    ValueError
        For a non-positive or non-finite ``t_end`` or ``step``, ``step > t_end``, ``settings``
        that is neither None, a callable nor a dict, a ``progress`` that is not callable, or a
        bad ``record_every`` (see :func:`~exudyn_atcm.model.recording.recording_schedule`).

    Warns
    -----
    RuntimeWarning
        When ``step`` does not divide ``t_end`` (see :func:`~exudyn_atcm.solve.run_checks.time_grid`).
    SetupWarning
        When ``record_every`` is an interval that is not a whole number of steps: the records are then not
        evenly spaced (the first step at or after each multiple of the interval is recorded).
    """
    t_end = positive_float("t_end", t_end)
    step = positive_float("step", step)
    if step > t_end:
        raise ValueError(f"step must be <= t_end = {t_end!r} s, got {shown(step)}")
    if settings is not None and not callable(settings) and not isinstance(settings, dict):
        raise ValueError(f"settings must be None, a callable or a dict of dotted names, got {shown(settings)}")
    if progress is not None and not callable(progress):
        raise ValueError(f"progress must be None or a callable progress(t, t_end), got {shown(progress)}")
    grid = time_grid(t_end, step, stacklevel=5)  # the caller of simulate
    schedule = recording_schedule(record_every, grid.step)
    if not schedule.even:
        warnings.warn(f"record_every = {schedule.interval!r} s is not a whole number of steps of {grid.step:.6g} s: the "
                      f"records are not evenly spaced ({schedule.describe()}; info 'recorded' says so). Give a "
                      f"multiple of the step (e.g. {multiple_of(grid.step, schedule.interval)!r} s) for evenly "
                      "spaced records", SetupWarning, stacklevel=5)
    return t_end, grid, schedule


def multiple_of(step: float, interval: float) -> float:
    """The whole multiple of ``step`` [s] nearest ``interval`` [s] (at least one step), written short."""
    multiple = max(round(interval / step), 1) * step
    return float(f"{multiple:.12g}")


def run_info(grid: TimeGrid, accepted: int, schedule: RecordingSchedule, stats: dict | None,
             **extra: Any) -> dict:
    """``result.info`` of a time integration: step used (and requested), step counts, recording.

    ``accepted`` counts accepted steps after the initial instant; ``stats`` are the solver
    statistics (``pre_step_calls``, ``newton_steps``, ``steps_sent_to_the_grid``: the steps
    redone to end on an instant of the run's grid after Exudyn reduced one,
    :class:`~exudyn_atcm.mbs.step_grid.GridKeeper`) or ``None`` when the solve was interrupted
    before returning them.
    """
    info: dict[str, Any] = {"solver": "generalized-alpha", "step [s]": grid.step, "accepted_steps": accepted,
                            "recorded": schedule.describe()}
    if grid.adjusted:
        info["step_requested [s]"] = grid.requested_step
    if stats is not None:
        info["attempted_steps"] = stats["pre_step_calls"]
        info["rejected_steps"] = max(stats["pre_step_calls"] - accepted, 0)
        info["newton_steps"] = stats["newton_steps"]
        if stats.get("steps_sent_to_the_grid"):  # Exudyn reduced a step; the steps passing over an instant were redone
            info["steps_sent_to_the_grid"] = stats["steps_sent_to_the_grid"]
    info.update(extra)
    return info


def report_controller(controller: Any, info: dict, what: str = "the controller", stacklevel: int = 4) -> None:
    """Put ``controller.summary()`` into ``info["controller"]``; warn if its output sat at a limit.

    ``what`` names the controller in the warning (e.g. ``"the controller of drive 'crank'"``).
    """
    summary: dict = controller.summary() if callable(getattr(controller, "summary", None)) else {}
    info["controller"] = summary
    limited = summary.get("limited_samples", 0)
    if limited:
        first, last = summary.get("first_error [m]", math.nan), summary.get("last_error [m]", math.nan)
        moved = summary.get("last_output [m]", math.nan) - summary.get("first_output [m]", math.nan)
        # mostly limited, and the output went the other way than the first error asked, by a tenth of it or more
        away = 2 * limited > summary.get("samples", 0) and moved * first < 0.0 and abs(moved) > 0.1 * abs(first)
        why = (f"; but the output moved away from the setpoint (|error| {abs(first):.3g} -> {abs(last):.3g} m), which "
               "a loop of the wrong sign does: the gains must all be <= 0 when a positive voltage lowers the measured "
               "output (e.g. a bender with active_side='left')" if away else "")
        warnings.warn(
            f"{what}'s output was at its limits {summary.get('output_limits [V]')} V in "
            f"{limited} of {summary.get('samples')} samples (largest excess "
            f"{summary.get('largest_excess [V]', float('nan')):.4g} V): the wanted deflection is "
            f"partly out of reach{why}",
            OutOfReachWarning,
            stacklevel=stacklevel,
        )

