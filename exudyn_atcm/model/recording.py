"""Which accepted solver steps are recorded: the recording interval ``record_every``.

A run of 2 s at 1e-4 s has 20001 instants; plots and most analyses need far fewer.
:class:`RecordingSchedule` decides per accepted step whether it is stored, so memory and
output files shrink while the solver (and the hysteresis memory, committed on every accepted
step) is unchanged.  Used by :func:`exudyn_atcm.solve.simulation.simulate`; any other solve path can
use it the same way.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np
from .._checks import shown

__all__ = ["RecordingSchedule", "recording_schedule"]


class RecordingSchedule:
    """Record every ``steps``-th accepted step, or the first step at or after each multiple of ``interval`` [s].

    The first instant (``t = 0``) is always recorded, and :meth:`last` tells whether the last
    accepted step still has to be added (so the end of a run, or of an interrupted run, is
    always in the record).

    Parameters
    ----------
    steps : int, optional
        Record every ``steps``-th accepted step (>= 1).
    interval : float, optional
        Recording interval [s] (> 0).  Exactly one of ``steps`` and ``interval`` is given.
    step : float
        The solver step [s], for round-off tolerances and the description.
    """

    def __init__(self, *, steps: int | None = None, interval: float | None = None, step: float) -> None:
        if (steps is None) == (interval is None):
            raise ValueError("give exactly one of steps and interval")
        self.steps = steps
        self.interval = interval
        self.step = step
        self._count = 0
        self._next_time = 0.0
        self._last_recorded: float | None = None

    @property
    def every_step(self) -> bool:
        """True when every accepted step is recorded."""
        return self.steps == 1 or (self.interval is not None and self.interval <= self.step * (1 + 1e-9))

    @property
    def even(self) -> bool:
        """True when the records are evenly spaced: every ``n``-th step, or an interval that is a whole number of
        steps (within 1e-9 of it)."""
        if self.steps is not None or self.every_step:
            return True
        ratio = self.interval / self.step
        return abs(ratio - round(ratio)) <= 1e-9 * ratio

    def describe(self) -> str:
        """``"every step"``, ``"every 10 steps"`` or ``"every 0.001 s"`` (for metadata); an interval that is not a
        whole number of steps says how far apart the records are (``"the first step at or after every 0.0007 s
        (steps of 0.0005 s: records 0.0005 or 0.001 s apart)"``)."""
        if self.every_step:
            return "every step"
        if self.steps is not None:
            return f"every {self.steps} steps"
        if not self.even:
            low = math.floor(self.interval / self.step) * self.step
            return (f"the first step at or after every {self.interval:.6g} s (steps of {self.step:.6g} s: records "
                    f"{low:.6g} or {low + self.step:.6g} s apart)")
        return f"every {self.interval:.6g} s"

    def take(self, t: float) -> bool:
        """Whether the accepted step ending at ``t`` [s] is recorded (call once per accepted step, in order)."""
        count = self._count
        self._count += 1
        if self.steps is not None:
            keep = count % self.steps == 0
        else:
            keep = t >= self._next_time - 1e-6 * self.step
            if keep:
                # next multiple of the interval strictly after t
                k = math.floor(t / self.interval + 1e-6 * self.step / self.interval) + 1
                self._next_time = k * self.interval
        if keep:
            self._last_recorded = t
        return keep

    def last(self, t: float) -> bool:
        """Whether the last accepted step (at ``t``) still has to be recorded to close the record."""
        return self._last_recorded is None or t > self._last_recorded


def recording_schedule(record_every: Any, step: float) -> RecordingSchedule:
    """The schedule for a ``record_every`` argument.

    Parameters
    ----------
    record_every : None, int or float
        ``None`` or ``0`` (``0.0``): every accepted step.  An ``int`` (Python or numpy integer)
        ``n >= 1``: every ``n``-th accepted step.  A ``float`` > 0: an interval in seconds (the
        first accepted step at or after each multiple is recorded; a multiple of ``step`` gives
        evenly spaced records; an interval up to the step records every step).  Zero means
        every step in Python as on the command line (``--set record_every=0`` of the cases).
    step : float
        The solver step [s].

    Raises
    ------
    ValueError
        For anything else (a negative or non-finite value, a bool, a string), naming the value.
    """
    allowed = "None or 0 (every step), an int number of steps >= 1 or a float interval [s] > 0"
    if record_every is None:
        return RecordingSchedule(steps=1, step=step)
    if isinstance(record_every, (bool, np.bool_)):
        raise ValueError(f"record_every must be {allowed}, got {shown(record_every)}")
    if isinstance(record_every, (numbers.Real, np.integer, np.floating)) and record_every == 0:
        return RecordingSchedule(steps=1, step=step)
    if isinstance(record_every, (numbers.Integral, np.integer)):
        if record_every < 1:
            raise ValueError(f"record_every as a number of steps must be >= 1 (or 0: every step), got {shown(record_every)}")
        return RecordingSchedule(steps=int(record_every), step=step)
    if isinstance(record_every, (numbers.Real, np.floating)):
        value = float(record_every)
        if not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"record_every as an interval must be a finite time > 0 [s] (or 0: every step), "
                             f"got {shown(record_every)}")
        return RecordingSchedule(interval=value, step=step)
    raise ValueError(f"record_every must be {allowed}, got {shown(record_every)}")
