"""Strain sources: how a drive's free strain reaches each solver step.

:class:`InStepStrain` evaluates the drive's hysteresis operator inside the step: a trial from
the committed memory for every attempted step (``trial(t)``, cached per ``t``) and a commit
only for accepted steps (``commit(t)``, called from the post-step hook, which Exudyn calls for
accepted steps only).  An operator with ``time_dependent = True`` (creep and rate lags,
:class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`) gets the step's time as well:
``evaluate(u, t)`` from its committed time and state, ``commit(u, t)``.  :class:`TableStrain` is the paper's approach (its Fig. 9): the
hysteresis applied offline to the voltage program on a time grid, the motor following the
table.  Both are plain Python (no Exudyn); the actuator and the mechanism paths use them.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["InStepStrain", "TableStrain"]


class InStepStrain:
    """Strain source with the hysteresis operator evaluated in the solver step.

    ``trial(t)`` gives the strain for the step ending at ``t`` from the committed memory
    (cached per ``t``, so one evaluation per attempted step); ``commit(t)`` accepts the step.
    """

    def __init__(self, drive) -> None:
        self.drive = drive
        self.hysteresis = drive.hysteresis
        self._timed = bool(getattr(self.hysteresis, "time_dependent", False))
        self._t = None
        self._u = 0.0
        self._strain = 0.0
        self.evaluations = 0
        #: lowest and highest committed voltage [V] (for the range check after the run)
        self.u_low = math.inf
        self.u_high = -math.inf
        if self.hysteresis is not None:
            self.hysteresis.reset()

    def trial(self, t: float) -> float:
        """Free strain [-] for the step ending at ``t`` [s], from the committed memory (no side effect)."""
        if t != self._t:
            u = self.drive.voltage_at(t)
            if self.hysteresis is None:
                strain = self.drive.linear_strain(u)
            else:
                strain = float(self.hysteresis.evaluate(u, t) if self._timed else self.hysteresis.evaluate(u))
                self.evaluations += 1
            self._t, self._u, self._strain = t, u, strain
        return self._strain

    def commit(self, t: float) -> tuple[float, float]:
        """Accept the step ending at ``t`` [s]: commit the operator; returns (voltage [V], strain [-])."""
        # the voltage of the accepted step was computed for its trial (same t)
        u = self._u if t == self._t else self.drive.voltage_at(t)
        if u < self.u_low:
            self.u_low = u
        if u > self.u_high:
            self.u_high = u
        if self.hysteresis is None:
            strain = self.drive.linear_strain(u)
        else:
            strain = float(self.hysteresis.commit(u, t) if self._timed else self.hysteresis.commit(u))
        # the next trial at this t (none in normal operation) must see the new memory
        self._t = None
        return u, strain


class TableStrain:
    """Strain from a precomputed table of (time, voltage, strain), linearly interpolated.

    The paper's approach (its Fig. 9): the hysteresis is applied offline to the voltage
    program on a time grid and the motor follows the table.  Used by the benchmarks.
    """

    def __init__(self, times: np.ndarray, voltages: np.ndarray, strains: np.ndarray) -> None:
        self.times = np.asarray(times, dtype=float)
        self.voltages = np.asarray(voltages, dtype=float)
        self.strains = np.asarray(strains, dtype=float)
        self._t = None
        self._strain = 0.0
        self.u_low = float(self.voltages.min()) if self.voltages.size else math.inf
        self.u_high = float(self.voltages.max()) if self.voltages.size else -math.inf

    @classmethod
    def from_drive(cls, drive, t_end: float, step: float) -> "TableStrain":
        """The table of ``drive``'s program on the grid ``0, step, ..., t_end`` [s], hysteresis applied offline."""
        n = int(math.ceil(t_end / step - 1e-9))
        times = np.linspace(0.0, n * step, n + 1)
        volts = np.array([drive.voltage_at(t) for t in times])
        if drive.hysteresis is None:
            strains = drive.linear_strain(volts)
        elif getattr(drive.hysteresis, "time_dependent", False):
            strains = drive.hysteresis.apply(volts, times)
        else:
            strains = drive.hysteresis.apply(volts)
        return cls(times, volts, strains)

    def trial(self, t: float) -> float:
        """Free strain [-] at ``t`` [s], interpolated in the table."""
        if t != self._t:
            self._t = t
            self._strain = float(np.interp(t, self.times, self.strains))
        return self._strain

    def commit(self, t: float) -> tuple[float, float]:
        """(voltage [V], strain [-]) at ``t`` [s], interpolated in the table."""
        return float(np.interp(t, self.times, self.voltages)), float(np.interp(t, self.times, self.strains))
