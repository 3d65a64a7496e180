"""A voltage program given as samples (a feedforward table, a measured voltage): its features are its reversals.

A :class:`~exudyn_atcm.model.signals.PiecewiseLinear` program is a few breakpoints a user placed:
every reversal, hold and marked kink is a corner, and the run checks ask for several solver steps
(and recorded instants) between corners.  A program *tabulated* at a sample time is different: the
inverse of a hysteresis model turns a smooth wanted output into voltages that jump where a relay
switches and hold in between, so nearly every sample is a kink or a hold.  Counted as corners they
made the run checks demand several records per sample ("record_every keeps only 1 recorded instants
across the shortest feature" for the package's own feedforward program), although nothing happens
between two samples that a record could miss.

What a hysteresis operator responds to in such a program are its reversals: between two of them
the input moves one way, and a rate-independent operator's memory changes only at the extremes.
:class:`SampledProgram` is the same linear interpolation as ``PiecewiseLinear``, whose
:meth:`~SampledProgram.shortest_feature` is the shortest monotone stretch between reversals (a hold
inside a rise is part of the rise; a rise, a hold and a fall reverse once).  Its corners on the
step grid (:meth:`~exudyn_atcm.model.signals.PiecewiseLinear.corner_times`) still exempt it from the
step check, as for any piecewise-linear program.  :func:`~exudyn_atcm.model.feedforward.feedforward_program`
and :func:`~exudyn_atcm.model.feedforward.linear_program` return one.
"""

from __future__ import annotations

from typing import Any, Literal

import numpy as np

from .signals import PiecewiseLinear

__all__ = ["SampledProgram", "reversal_times"]


def reversal_times(times: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Times [s] where a piecewise-linear program starts moving against its previous direction.

    The direction of each segment is the sign of its slope; segments that hold (slope 0) keep the
    previous direction.  A reversal is the start of the first segment whose direction differs from
    the last moving segment before it (after a hold at the extreme: where the new direction starts).
    """
    sign = np.sign(np.diff(values))
    moving = np.flatnonzero(sign != 0.0)
    if moving.size < 2:
        return np.empty(0)
    turns = moving[1:][sign[moving[1:]] != sign[moving[:-1]]]
    return np.asarray(times, dtype=float)[turns]


class SampledProgram(PiecewiseLinear):
    """Voltages [V] sampled at ``times`` [s], linearly interpolated; its features are its reversals.

    Parameters
    ----------
    times : array_like
        Sample times [s], strictly increasing.
    values : array_like
        Voltages [V] at those times.
    outside : {"hold", "error"}, optional
        Outside ``[times[0], times[-1]]``: hold the end value (default) or raise ``ValueError``.

    Notes
    -----
    The run checks (:func:`~exudyn_atcm.solve.run_checks.check_step_against_program`,
    :func:`~exudyn_atcm.solve.run_checks.check_record_interval`) measure it by
    :meth:`shortest_feature`: the shortest stretch between reversals, not the sample spacing.
    """

    def __init__(self, times: Any, values: Any, outside: Literal["hold", "error"] = "hold") -> None:
        super().__init__(times, values, outside=outside)

    def shortest_feature(self, t_end: float | None = None) -> tuple[float, str] | None:
        """The shortest monotone stretch [s] between reversals (and the program's ends), and what it is.

        ``None`` for a program that never moves.  Only stretches that start before ``t_end``
        count.  A stretch is measured from one reversal (:func:`reversal_times`) to the next; the
        first from the first sample, the last to the last sample.
        """
        t, v = self.times, self.values
        if t.size < 2 or not np.any(np.diff(v) != 0.0):
            return None
        bounds = np.concatenate([[t[0]], reversal_times(t, v), [t[-1]]])
        stretches = np.diff(bounds)
        starts = bounds[:-1]
        if t_end is not None:
            keep = starts < t_end
            stretches, starts = stretches[keep], starts[keep]
        keep = stretches > 0.0
        stretches, starts = stretches[keep], starts[keep]
        if stretches.size == 0:
            return None
        k = int(np.argmin(stretches))
        return (float(stretches[k]),
                f"a monotone stretch of {float(stretches[k]):g} s from t = {float(starts[k]):g} s between reversals "
                "of the sampled program")
