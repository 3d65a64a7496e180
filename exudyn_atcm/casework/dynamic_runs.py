"""A case's dynamic run at a given step, or at the step chosen for a stated accuracy.

A case with a ``step`` parameter [s] (0: chosen) and an ``accuracy`` parameter [-] (the largest
error of the recorded positions relative to their travel) runs through :func:`case_dynamic_run`:
a given step is used as it is; otherwise the step is chosen and checked by a probe run
(:func:`exudyn_atcm.solve.accurate_run`, as ``simulate(..., accuracy=...)``) on the grid of
:data:`STEP_GRID`, so that the solution and the case's scalars do not depend on the recording
interval.  :func:`step_notes` gives the step used and why, for the case's JSON notes.
"""

from __future__ import annotations

from typing import Any

from ..io.result import Result
from ..solve.simulation import simulate
from ..solve.step_choice import accurate_run

__all__ = ["STEP_GRID", "case_dynamic_run", "step_notes"]

#: Grid [s] that a chosen step divides, whatever the recording interval (records at a multiple of it
#: are evenly spaced).
STEP_GRID = 1e-3


def case_dynamic_run(system: Any, t_end: float, *, step: float, accuracy: float, default_accuracy: float,
                     record_every: float = 0.0, progress: Any = None) -> Result:
    """:func:`~exudyn_atcm.simulate` of ``system`` to ``t_end`` [s] at ``step`` [s], or (``step`` 0) at
    the step chosen for ``accuracy`` [-] and checked by a probe run.

    ``default_accuracy``: the case's default accuracy; a given step together with another
    accuracy is refused (one of them would be ignored).  ``record_every`` [s]: 0 records every step.

    Raises
    ------
    ValueError
        For a step together with an accuracy other than the default.
    """
    every = record_every if record_every > 0.0 else None
    if step > 0.0:
        if accuracy != default_accuracy:
            raise ValueError(f"give step or accuracy, not both: step={step!r} s fixes the step, accuracy={accuracy!r} "
                             f"chooses it (leave step at 0 to choose it for accuracy)")
        return simulate(system, t_end, step=step, progress=progress, record_every=every)

    def run_at(h: float, run_progress: Any, t_stop: float) -> Result:
        return simulate(system, t_stop, step=h, progress=run_progress, record_every=every)

    mechanism = system.as_mechanism((0.0, 0.0)) if hasattr(system, "as_mechanism") else system
    return accurate_run(run_at, mechanism, t_end, accuracy, progress, record_every=STEP_GRID)


def step_notes(result: Result) -> dict:
    """The step used [s] and why (``result.info["step_choice"]``, or that it was given), for the JSON's notes."""
    return {"step [s]": float(result.info["step [s]"]),
            "step_choice": result.info.get("step_choice", "given (--set step=...)")}
