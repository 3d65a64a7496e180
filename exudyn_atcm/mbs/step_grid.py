"""Keeping a time integration on its step grid after Exudyn reduced a step.

Exudyn's adaptive time step halves a step whose Newton iteration fails and, some steps later,
doubles it again (``timeIntegration.adaptiveStepRecoverySteps``, ``adaptiveStepIncrease``)
without regard to where the run's grid ``k h`` lies: from then on the run's steps end between
the grid's instants (measured: up to half a step off on a lone actuator whose Newton iterations
were capped), so the record's times are no longer the grid's, a voltage program's corners and
switches fall inside steps, and an accuracy check comparing two runs at their common instants
(:func:`~exudyn_atcm.solve.step_choice.position_error`) loses the rest of the run without a word.

:class:`GridKeeper` watches the attempted steps (:meth:`GridKeeper.watch`, from the run's pre-step
hook: one comparison a step) and, once Exudyn has reduced a step, installs a ``PostNewton``
function (around the system's own, whose error and recommendation it keeps) that refuses a step
passing over an instant of the grid: it returns an error above Exudyn's
``discontinuous.iterationTolerance`` and, as the recommended step size, the distance to that
instant divided into equal parts no longer than ``0.75 h_step`` (halvings of ``h`` where they
divide it: :func:`equal_part`); Exudyn repeats the step with
``min(0.75 h_step, recommended)`` (its ``ReduceStepSize``), so the next accepted steps end on the
instant (to round-off: a step that were the remainder itself would carry the drift of the times
summed so far into the following steps) and every ``k h`` is a step's end.  Steps shorter than
``h`` in between (Exudyn's own reductions) stay as they are.  A run whose steps are never reduced
runs without it (a Python call after every Newton solve would cost about 2 us a step).
"""

from __future__ import annotations

import math
from typing import Any, Callable

import exudyn as exu

__all__ = ["GRID_TOLERANCE", "SMALLEST_REMAINDER", "GridKeeper", "equal_part"]

#: distance [in steps] within which a time counts as an instant of the grid (sums of steps carry round-off)
GRID_TOLERANCE = 1e-6
#: shortest remainder [in steps] a step may leave before the next instant (a step ending closer is sent back: the
#: remainder could be below Exudyn's smallest step, 1e-4 of the step in the package's settings); a step starting
#: closer than this (never, as steps are kept from ending there) is not sent to the instant but let pass over it
SMALLEST_REMAINDER = 1e-3


def equal_part(distance: float, longest: float, step: float) -> float:
    """A step [s] that ``distance`` [s] is a whole number of, at most ``longest`` [s]: the longest ``step / 2^j``
    down to ``longest / 8`` that divides it (a start on the halved grid, as Exudyn's own halving and doubling
    leave it: the steps stay on it and the doubled ones grow back to ``step``), else ``distance`` divided into
    the fewest equal parts."""
    part = step
    while part > longest * (1.0 + GRID_TOLERANCE):
        part *= 0.5
    while part >= longest / 8.0:
        count = distance / part
        if round(count) >= 1 and abs(count - round(count)) <= 1e-6:
            return distance / round(count)
        part *= 0.5
    return distance / math.ceil(distance / longest - GRID_TOLERANCE)


class GridKeeper:
    """Keeps a time integration of ``mbs`` with ``settings`` on its grid ``startTime + k h``,
    ``h = (endTime - startTime) / numberOfSteps``; ``refused`` counts the steps sent back to an instant.

    Call :meth:`watch` in every pre-step hook and :meth:`restore` after the run (also after a failure).
    """

    def __init__(self, mbs, settings: Any) -> None:
        ti = settings.timeIntegration
        self.mbs, self.refused, self.installed = mbs, 0, False
        self.origin = float(ti.startTime)
        self.step = (float(ti.endTime) - self.origin) / max(1, int(ti.numberOfSteps))
        self.active = bool(ti.adaptiveStep) and self.step > 0.0
        self._error = 2.0 * float(ti.discontinuous.iterationTolerance)
        previous = mbs.GetPostNewtonUserFunction()
        self.previous: Callable | None = previous if callable(previous) else None
        sd, start = mbs.systemData, exu.ConfigurationType.StartOfStep
        self._start_time = lambda: sd.GetTime(start)
        self._last_attempt = -math.inf

    def watch(self, t: float) -> None:
        """Pre-step (``t``: the end of the step attempted): a step attempted again, shorter (Exudyn reduced a failed
        one: its end is not after the last attempt's), installs the keeper for the rest of the run.  One comparison
        a step until then."""
        if t <= self._last_attempt and self.active and not self.installed:
            self.installed = True
            self.mbs.SetPostNewtonUserFunction(self)
        self._last_attempt = t

    def restore(self) -> None:
        """Put the system's own ``PostNewton`` function back."""
        if self.installed:
            self.installed = False
            self.mbs.SetPostNewtonUserFunction(self.previous if self.previous is not None else 0)

    def __call__(self, mbs_, t: float) -> list[float]:
        error, recommended = self.previous(mbs_, t) if self.previous is not None else (0.0, -1.0)
        h, t0 = self.step, self._start_time()
        # the first instant of the grid after the step's start
        instant = self.origin + (math.floor((t0 - self.origin) / h + GRID_TOLERANCE) + 1) * h
        to_instant = instant - t0
        over = t > instant + GRID_TOLERANCE * h  # the step would pass over the instant
        short = GRID_TOLERANCE * h < instant - t < SMALLEST_REMAINDER * h  # or leave a remainder too short to step
        if (over or short) and to_instant >= SMALLEST_REMAINDER * h:
            self.refused += 1
            part = equal_part(to_instant, 0.75 * (t - t0), h)
            recommended = part if recommended < 0.0 else min(float(recommended), part)
            return [max(float(error), self._error), recommended]
        return [float(error), float(recommended)]
