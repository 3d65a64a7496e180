"""Controllers that set the drive voltage during a simulation from the simulated tip deflection.

The controller protocol
-----------------------
A :class:`~exudyn_atcm.model.drive.PiezoDrive` accepts, in place of a voltage program, any object
with these methods (:class:`Controller` is the abstract base):

* ``voltage_at(t) -> float``: the voltage [V] for the solver step ending at ``t`` [s]; it must
  not change the controller's state (the solver may try a step several times);
* ``observe(t, tip_deflection) -> None``: called once per *accepted* step, after the
  hysteresis operator has been committed, with the step's time [s] and the tip deflection
  ``actuator.tip_y`` [m] of a lone actuator (in a mechanism: the value of the result column declared
  with :meth:`Mechanism.feedback <exudyn_atcm.Mechanism.feedback>`, e.g. ``"crank.tip_y"``);
  the controller updates its state here;
* ``reset() -> None``: called when a simulation starts;
* ``summary() -> dict`` (optional): written into ``result.info["controller"]``.

So within a run the voltage of a step comes from the controller, the hysteresis operator
turns it into free strain inside the step, and the controller sees the accepted deflection.
"""

from __future__ import annotations

import abc
import math
import warnings
from typing import Any, Callable, Union

from .._checks import finite_float, positive_float, shown
from ..errors import AccuracyWarning

__all__ = ["Controller", "PIDController"]

TimeFunction = Union[float, Callable[[float], float]]


def _time_function(name: str, value: Any) -> Callable[[float], float]:
    if callable(value):
        return value
    number = finite_float(name, value)
    return lambda t: number


class Controller(abc.ABC):
    """Base class of the drive-controller protocol (see the module documentation)."""

    @abc.abstractmethod
    def voltage_at(self, t: float) -> float:
        """Voltage [V] for the step ending at ``t`` [s]; no side effect."""

    @abc.abstractmethod
    def observe(self, t: float, tip_deflection: float) -> None:
        """Accepted step at ``t`` [s] with tip deflection [m]: update the controller."""

    @abc.abstractmethod
    def reset(self) -> None:
        """Initial state, at the start of a simulation."""

    def summary(self) -> dict:
        """What the controller did (for ``result.info``)."""
        return {}


class PIDController(Controller):
    r"""Discrete PID controller of the tip deflection with zero-order hold and a feedforward term.

    At the sample instants ``t_k = k·sample_time`` (the first accepted step at or after each)
    the error ``e_k = r(t_k) − y_k`` of the observed tip deflection ``y_k`` gives

    :math:`v_k = k_p e_k + k_i \sum_{j \le k} e_j T_s - k_d (y_k - y_{k-1})/T_s`

    (derivative on the measurement, so a setpoint jump gives no kick), held until the next
    sample (zero-order hold).  The voltage applied at time ``t`` is
    ``U(t) = feedforward(t) + v_k``, limited to ``output_limits``.  The integral is not
    increased while the output is at a limit and the error would drive it further
    (conditional integration: no wind-up).

    Parameters
    ----------
    kp : float
        Proportional gain [V/m].  The three gains share one sign (all ``>= 0`` when a
        positive voltage raises the tip); all zero needs a ``feedforward``.
    ki : float, optional
        Integral gain [V/(m s)].
    kd : float, optional
        Derivative gain [V s/m].
    sample_time : float
        Controller period ``T_s`` [s], ``> 0`` (its own rate, independent of the solver step).
    setpoint : float or callable
        Wanted tip deflection ``r(t)`` [m].
    feedforward : float or callable, optional
        Feedforward voltage program [V] added to the feedback (e.g. from
        :func:`exudyn_atcm.model.feedforward.feedforward_program`), evaluated at every step.
    output_limits : (float, float), optional
        Lowest and highest voltage [V].  Limiting is counted, never silent: see
        :meth:`summary` (``limited_samples``, ``largest_excess [V]``).

    Notes
    -----
    Initial state (after :meth:`reset`): no integral, feedback output 0 until the first
    observation (at the simulation's ``t = 0`` post-step).
    """

    def __init__(
        self,
        kp: float,
        ki: float = 0.0,
        kd: float = 0.0,
        *,
        sample_time: float,
        setpoint: TimeFunction,
        feedforward: TimeFunction | None = None,
        output_limits: tuple[float, float] | None = None,
    ) -> None:
        self.kp = finite_float("kp", kp)
        self.ki = finite_float("ki", ki)
        self.kd = finite_float("kd", kd)
        gains = (self.kp, self.ki, self.kd)
        if any(g > 0 for g in gains) and any(g < 0 for g in gains):
            raise ValueError(
                f"kp, ki, kd must share one sign (all >= 0 when a positive voltage raises the tip, all <= 0 for a "
                f"bender with active_side='left'); mixed signs make one term fight the others, got kp={kp!r}, "
                f"ki={ki!r}, kd={kd!r}")
        if not any(gains) and feedforward is None:
            raise ValueError("kp, ki and kd are all 0 and there is no feedforward: the controller would hold 0 V; "
                             "give a gain (e.g. kp [V/m]) or a feedforward program")
        self.sample_time = positive_float("sample_time", sample_time)
        self._setpoint = _time_function("setpoint", setpoint)
        self._feedforward = None if feedforward is None else _time_function("feedforward", feedforward)
        if output_limits is None:
            self.output_limits = (-math.inf, math.inf)
        else:
            try:
                lo, hi = (finite_float("output_limits", v) for v in output_limits)
            except TypeError:
                raise ValueError(f"output_limits must be a pair (low, high) [V], got {shown(output_limits)}") from None
            if not hi > lo:
                raise ValueError(f"output_limits must have high > low, got {shown(output_limits)}")
            self.output_limits = (lo, hi)
        self.reset()

    def reset(self) -> None:
        """No integral, zero feedback, counters cleared."""
        self._integral = 0.0
        self._feedback = 0.0
        self._last_y: float | None = None
        self._next_sample = 0.0
        self.samples = 0
        self.limited_samples = 0
        self.largest_excess = 0.0
        self._limited_sign = 0
        self._last_t: float | None = None
        self.late_samples = 0
        self.largest_interval = 0.0
        #: ``setpoint - output`` and the output [m] at the first and the last sample (``nan`` before any)
        self.first_error = self.last_error = math.nan
        self.first_output = self.last_output = math.nan

    def _unlimited(self, t: float) -> float:
        ff = 0.0 if self._feedforward is None else float(self._feedforward(t))
        return ff + self._feedback

    def voltage_at(self, t: float) -> float:
        """Feedforward at ``t`` plus the held feedback, limited to ``output_limits`` [V]."""
        lo, hi = self.output_limits
        return min(max(self._unlimited(t), lo), hi)

    def observe(self, t: float, tip_deflection: float) -> None:
        """Take a sample if one is due at ``t``: update the integral and the held feedback."""
        if t < self._next_sample - 1e-6 * self.sample_time:
            return
        y = finite_float("tip_deflection", tip_deflection)
        if self._last_t is not None:
            interval = t - self._last_t
            self.largest_interval = max(self.largest_interval, interval)
            if interval > 1.5 * self.sample_time:
                self.late_samples += 1
                if self.late_samples == 1:
                    warnings.warn(
                        f"PID sample_time = {self.sample_time:g} s, but consecutive samples came {interval:g} s apart "
                        f"(at t = {t:g} s): the controller samples only at accepted solver steps, so its integral "
                        f"and derivative (computed with sample_time) are off by that ratio. Use a sample_time that "
                        f"is a multiple of the solver step (step <= {self.sample_time:g} s)",
                        AccuracyWarning, stacklevel=2)
        self._last_t = t
        error = float(self._setpoint(t)) - y
        if self.samples == 0:
            self.first_error, self.first_output = error, y
        self.last_error, self.last_output = error, y
        # conditional integration: not while limited in the direction the error pushes
        if not (self._limited_sign > 0 and error > 0.0) and not (self._limited_sign < 0 and error < 0.0):
            self._integral += error * self.sample_time
        derivative = 0.0 if self._last_y is None else -(y - self._last_y) / self.sample_time
        self._last_y = y
        self._feedback = self.kp * error + self.ki * self._integral + self.kd * derivative
        raw = self._unlimited(t)
        lo, hi = self.output_limits
        self._limited_sign = 1 if raw > hi else -1 if raw < lo else 0
        if self._limited_sign:
            self.limited_samples += 1
            self.largest_excess = max(self.largest_excess, raw - hi if raw > hi else lo - raw)
        self.samples += 1
        self._next_sample = (math.floor(t / self.sample_time + 1e-6) + 1) * self.sample_time

    def summary(self) -> dict:
        """Samples taken, samples at an output limit and the largest excess over a limit [V]."""
        return {
            "controller": "PID",
            "kp [V/m]": self.kp,
            "ki [V/(m s)]": self.ki,
            "kd [V s/m]": self.kd,
            "sample_time [s]": self.sample_time,
            "samples": self.samples,
            "limited_samples": self.limited_samples,
            "largest_excess [V]": self.largest_excess,
            "output_limits [V]": list(self.output_limits),
            "late_samples": self.late_samples,
            "first_error [m]": self.first_error,
            "last_error [m]": self.last_error,
            "first_output [m]": self.first_output,
            "last_output [m]": self.last_output,
            "largest_sample_interval [s]": self.largest_interval,
        }

    def __repr__(self) -> str:
        return (f"PIDController(kp={self.kp!r}, ki={self.ki!r}, kd={self.kd!r}, sample_time={self.sample_time!r}, "
                f"output_limits={self.output_limits!r}, feedforward={'yes' if self._feedforward else 'no'})")
