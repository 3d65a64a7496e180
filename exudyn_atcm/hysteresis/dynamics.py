"""Creep and rate dependence evaluated in the solver step: linear lags in series after an operator.

A rate-independent operator gives ``h(t)``; a linear block after it gives the output ``y``:

* :class:`~exudyn_atcm.hysteresis.creep.Creep` (``1 + Σ c_k/(1 + τ_k s)``): the drift after a
  voltage step (roughly logarithmic for time constants spread in ``log τ``);
* :class:`RateLag` (``1/(1 + T s)``): a first-order lag, the Hammerstein form of rate
  dependence; its phase lag ``atan(ω T)`` grows with the frequency ``ω``, so the loops of
  ``y`` against the input widen (and tilt) as the drive gets faster.

Both, and their series ``(1 + Σ c_k/(1 + τ_k s))/(1 + T s)``, are one :class:`LagSum`
``y = d h + Σ_j g_j z_j``, ``τ_j z_j' = h − z_j``: the series is expanded in partial fractions
(``c_k/((1 + τ_k s)(1 + T s)) = c_k/(τ_k − T) (τ_k/(1 + τ_k s) − T/(1 + T s))``, for ``T`` different
from every ``τ_k``), so one set of lag states driven by ``h`` is the whole state.

Discretisation: every lag state is advanced exactly for ``h`` linear in time over the step (first
order hold), ``z ← a z + h₁ − a h₀ − (h₁ − h₀)(τ/Δt)(1 − a)``, ``a = e^{−Δt/τ}``, :func:`lag_step`;
exact (to rounding) wherever ``h`` is linear in time between the committed instants (constant
after a step, a ramp through a linear operator), and second-order accurate in the step elsewhere.
A time step is a function of the committed instant and the new one only, so the output at an
accepted instant does not depend on the trial steps that were tried and rejected before it.

:class:`WithDynamics` puts an operator and these blocks in series with the operators'
``evaluate``/``commit`` interface plus the time: ``evaluate(u, t)`` (trial from the committed
time and state, nothing changed) and ``commit(u, t)``; it has :attr:`WithDynamics.time_dependent`
``= True``, from which the solver step's strain source passes the time.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from .._checks import finite_array, finite_float, positive_float, sample_times, shown
from .base import HysteresisOperator, check_input
from ..errors import AtcmDeprecationWarning
from .creep import Creep
from .dynamics_inverse import DynamicsInverse
from .model_files import SavableModel

__all__ = ["lag_step", "LagSum", "RateLag", "WithDynamics"]


def lag_step(z: np.ndarray, h_old: float, h_new: float, dt: float, tau: np.ndarray) -> np.ndarray:
    """Lag states ``z`` [output units] of ``τ z' = h − z`` advanced by ``dt`` [s], exact for ``h`` linear over it.

    ``dt = 0`` returns ``z`` unchanged (no time has passed).
    """
    if dt == 0.0:
        return z.copy()
    x = dt / tau
    one_minus_a = -np.expm1(-x)
    ramp = one_minus_a / x
    # exact: z₁ = a z + h₁ − a h₀ − (h₁ − h₀)(τ/Δt)(1 − a)
    return z + (h_old - z) * one_minus_a + (h_new - h_old) * (1.0 - ramp)


class LagSum(SavableModel):
    """Linear block ``y = d h + Σ_j g_j z_j``, ``τ_j z_j' = h − z_j`` (transfer function ``d + Σ g_j/(1 + τ_j s)``).

    Parameters
    ----------
    d : float
        Feed-through [-].
    tau : array_like
        Time constants [s], positive and distinct.
    g : array_like
        Lag gains [-], one per time constant (any sign).
    """

    def __init__(self, d: float, tau: Any, g: Any) -> None:
        self.d = finite_float("d", d)
        self.tau = finite_array("tau", tau, min_length=0).copy()
        self.g = finite_array("g", g, min_length=0).copy()
        if self.tau.size != self.g.size:
            raise ValueError(f"tau and g must have the same length, got {self.tau.size} and {self.g.size}")
        if (self.tau <= 0).any():
            raise ValueError(f"tau must be > 0 s, got {self.tau.tolist()!r}")

    @classmethod
    def series(cls, creep: Creep | None, lag: "RateLag | None") -> "LagSum":
        """The block ``creep`` followed by ``lag`` (either may be ``None``) as one lag sum.

        Raises
        ------
        ValueError
            If the lag's ``T`` equals one of the creep's time constants (a double pole, which a
            sum of first-order lags cannot express).
        """
        tau_c = np.zeros(0) if creep is None else creep.tau
        c = np.zeros(0) if creep is None else creep.c
        if lag is None:
            return cls(1.0, tau_c, c)
        T = lag.T
        close = np.abs(tau_c - T) <= 1e-9 * T
        if close.any():
            raise ValueError(f"lag T = {T!r} s equals the creep time constant {float(tau_c[close][0])!r} s; "
                             "choose T different from every creep time constant")
        g_c = c * tau_c / (tau_c - T)
        g_T = 1.0 - float(np.sum(c * T / (tau_c - T)))
        return cls(0.0, np.append(tau_c, T), np.append(g_c, g_T))

    @property
    def static_gain(self) -> float:
        """``d + Σ g_j``: the output per unit of ``h`` held for ever."""
        return self.d + float(self.g.sum())

    def response(self, h: Any, t: Any, rest: float | None = None) -> np.ndarray:
        """Output for ``h`` sampled at times ``t`` [s].

        The lags start at rest at ``rest`` (default ``h[0]``) and no time passes before the
        first sample; between samples ``h`` is linear.
        """
        h_a = finite_array("h", h)
        t_a = sample_times("t", t, h_a.size)
        z = np.full(self.tau.size, h_a[0] if rest is None else finite_float("rest", rest))
        y = np.empty_like(h_a)
        y[0] = self.d * h_a[0] + float(self.g @ z)
        for k in range(1, h_a.size):
            z = lag_step(z, h_a[k - 1], h_a[k], t_a[k] - t_a[k - 1], self.tau)
            y[k] = self.d * h_a[k] + float(self.g @ z)
        return y

    def inverse_response(self, y: Any, t: Any, rest: float | None = None) -> np.ndarray:
        """The ``h`` whose :meth:`response` (same ``t`` and ``rest``) is ``y``: the exact inverse of the discretised block.

        The output at step ``k`` is linear in ``h[k]`` with slope ``d + Σ g_j (1 − ramp_j)`` > 0
        (the block's response to a ramp from 0 to 1 over the step), so each ``h[k]`` follows
        from ``y[k]``.  Without feed-through (``d = 0``: a lag) the output cannot jump: ``h[0]``
        is taken as ``rest`` and ``y[0]`` must be ``static_gain · rest``.  For a lag the inverse
        has an alternating mode (pole near ``−(1 − Δt/(3T))``), which a noisy or kinked ``y``
        excites: it decays, slowly for ``Δt << T``.

        Raises
        ------
        ValueError
            If ``d = 0`` and ``y[0]`` is not the rest output.
        """
        y_a = finite_array("y", y)
        t_a = sample_times("t", t, y_a.size)
        h = np.empty_like(y_a)
        if self.d == 0.0:
            r = float(y_a[0] / self.static_gain) if rest is None else finite_float("rest", rest)
            at_rest = self.static_gain * r
            if abs(y_a[0] - at_rest) > 1e-12 * max(abs(at_rest), abs(y_a[0]), 1e-300):
                raise ValueError(f"y[0] must be the rest output {at_rest!r} (a lag cannot jump), got {float(y_a[0])!r}")
            h[0] = r
        else:
            r = float(y_a[0] / self.static_gain) if rest is None else finite_float("rest", rest)
            h[0] = (y_a[0] - float(self.g.sum()) * r) / self.d
        z = np.full(self.tau.size, r)
        for k in range(1, y_a.size):
            x = (t_a[k] - t_a[k - 1]) / self.tau
            one_minus_a = -np.expm1(-x)
            ramp = one_minus_a / x
            # lag_step is a z + (ramp - a) h_old + (1 - ramp) h_new
            coef = 1.0 - ramp
            rest_part = z * (1.0 - one_minus_a) + h[k - 1] * (ramp - (1.0 - one_minus_a))
            h[k] = (y_a[k] - float(self.g @ rest_part)) / (self.d + float(self.g @ coef))
            z = rest_part + coef * h[k]
        return h

    def __repr__(self) -> str:
        return f"LagSum(d={self.d!r}, tau={self.tau.tolist()!r}, g={self.g.tolist()!r})"


class RateLag(SavableModel):
    """First-order lag ``T y' = w − y`` after an operator (Hammerstein rate dependence).

    Why a lag after the operator, not rate-dependent play weights: for a given ``T`` the model
    output is linear in the operator's weights (the lag is linear), so records at a few rates
    identify it by one scalar search over ``T`` with a linear least-squares fit inside
    (:func:`~exudyn_atcm.hysteresis.dynamics_fit.fit_rate_lag`), and it has an exact inverse for
    sampled records (:meth:`inverse_response`; continuously ``w = y + T y'``).  Rate-dependent
    weights ``p_j(|u'|)`` need a weight law per play fitted across rates (many more parameters
    than a few records at a few rates determine) and an inverse that needs the rate of the input
    it is solving for.

    What it captures: the phase lag that grows with frequency (loops widen and tilt, the peak
    output falls by ``1/√(1 + (ωT)²)``).  What it does not: loops whose shape (not just their
    lag) changes with rate, a frequency dependence that is not first-order.

    Parameters
    ----------
    T : float
        Time constant [s], > 0.
    """

    def __init__(self, T: float) -> None:
        self.T = positive_float("T", T)

    def response(self, w: Any, t: Any) -> np.ndarray:
        """Output for the input ``w`` sampled at times ``t`` [s], at rest at ``w[0]``; ``w`` linear between samples."""
        return LagSum.series(None, self).response(w, t)

    def inverse_response(self, y: Any, t: Any) -> np.ndarray:
        """The ``w`` whose :meth:`response` is ``y`` (exact inverse of the discretised lag; see :meth:`LagSum.inverse_response`)."""
        return LagSum.series(None, self).inverse_response(y, t)

    def __repr__(self) -> str:
        return f"RateLag(T={self.T!r})"


class WithDynamics(HysteresisOperator):
    """A hysteresis operator followed by a creep law and/or a rate lag, evaluated in the solver step.

    ``evaluate(u, t)`` gives the output at time ``t`` [s] from the committed time, lag states
    and operator memory without changing them (any number of trials, for any ``t``);
    ``commit(u, t)`` accepts it.  The lags start at rest at the operator's initial output
    (after :meth:`reset`); the first commit after a reset passes no time (the lags keep their
    rest state, the operator's output jumps).  Between committed instants the operator output
    is taken linear in time (:func:`lag_step`).

    Parameters
    ----------
    operator : HysteresisOperator
        The rate-independent part (e.g. :func:`~exudyn_atcm.model.parameter_sets.paper_strain_preisach`).
    creep : Creep, optional
        Creep law after the operator.
    lag : RateLag, optional
        First-order lag after the creep.  At least one of ``creep`` and ``lag``.
    """

    #: Marks operators whose ``evaluate``/``commit``/``apply`` take the time [s] as well.
    time_dependent = True

    def __init__(self, operator: Any, creep: Creep | None = None, lag: RateLag | None = None) -> None:
        missing = [m for m in ("evaluate", "commit", "reset", "checkpoint", "restore", "apply")
                   if not callable(getattr(operator, m, None))]
        if missing or getattr(operator, "time_dependent", False):
            raise ValueError(f"operator must be a rate-independent hysteresis operator, got {type(operator).__name__}")
        if creep is not None and not isinstance(creep, Creep):
            raise ValueError(f"creep must be a Creep or None, got {type(creep).__name__}")
        if lag is not None and not isinstance(lag, RateLag):
            raise ValueError(f"lag must be a RateLag or None, got {type(lag).__name__}")
        if creep is None and lag is None:
            raise ValueError("give creep, lag or both (without them use the operator itself)")
        self.operator, self.creep, self.lag = operator, creep, lag
        self.lags = LagSum.series(creep, lag)
        self.output_quantity = getattr(operator, "output_quantity", None)
        self.reset()

    @property
    def input_range(self) -> tuple[float, float] | None:
        """The operator's input range."""
        return getattr(self.operator, "input_range", None)

    @property
    def output_range(self) -> tuple[float, float] | None:
        """The operator's output range times the long-term gain ``1 + Σ c_k`` (``None`` if unknown)."""
        low, high = getattr(self.operator, "y_min", None), getattr(self.operator, "y_max", None)
        if low is None or high is None:
            return None
        gain = self.lags.static_gain
        return (gain * float(low), gain * float(high))

    def reset(self) -> None:
        """Operator reset; lags at rest at its initial output; no committed time."""
        self.operator.reset()
        self._h = float(self.operator.output)
        self._z = np.full(self.lags.tau.size, self._h)
        self._t: float | None = None
        self._y = self.lags.static_gain * self._h

    def checkpoint(self) -> tuple:
        """Snapshot of the operator memory, the lag states and the committed time and output."""
        return (self.operator.checkpoint(), self._h, self._z.copy(), self._t, self._y)

    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint`."""
        inner, h, z, t, y = snapshot
        self.operator.restore(inner)
        self._h, self._z, self._t, self._y = float(h), np.array(z, dtype=float), t, float(y)

    @property
    def output(self) -> float:
        """Output at the last committed time."""
        return self._y

    @property
    def committed_time(self) -> float | None:
        """Time [s] of the last commit (``None`` after :meth:`reset`)."""
        return self._t

    def _advance(self, h: float, t: Any) -> tuple[np.ndarray, float, float]:
        if t is None:
            raise ValueError(f"t is required: {type(self).__name__} is time-dependent (creep/rate), so evaluate(u, t) "
                             "and commit(u, t) take the time [s]; a rate-independent use (a static sweep) cannot use it")
        t_f = finite_float("t", t)
        dt = 0.0 if self._t is None else t_f - self._t
        if dt < 0.0:
            raise ValueError(f"t must not precede the committed time {self._t!r} s, got {shown(t_f)}")
        z = lag_step(self._z, self._h, h, dt, self.lags.tau)
        return z, self.lags.d * h + float(self.lags.g @ z), t_f

    def evaluate(self, u: float, t: float | None = None) -> float:
        """Output for input ``u`` at time ``t`` [s] from the committed state; nothing is changed."""
        h = float(self.operator.evaluate(check_input(u)))
        return self._advance(h, t)[1]

    def commit(self, u: float, t: float | None = None) -> float:
        """Accept input ``u`` at time ``t`` [s]: update the operator, the lags and the committed time."""
        u_f = check_input(u)
        self._advance(0.0, t)  # check t before the operator's memory changes
        h = float(self.operator.commit(u_f))
        self._z, self._y, self._t = self._advance(h, t)
        self._h = h
        return self._y

    def apply(self, u_series: Any, t: Any = None) -> np.ndarray:
        """Outputs for inputs ``u_series`` at times ``t`` [s] (increasing), from the reset state; memory kept."""
        u_a = finite_array("u_series", u_series, min_length=0)
        if t is None:
            raise ValueError(f"t is required: {type(self).__name__}.apply(u_series, t) needs the sample times [s]")
        t_a = sample_times("t", t, u_a.size) if u_a.size else np.zeros(0)
        check = getattr(self.operator, "check_fitted_range", None)
        if u_a.size and callable(check):  # a fitted operator warns beyond the range it was fitted on
            check(float(u_a.min()), float(u_a.max()))
        saved = self.checkpoint()
        try:
            self.reset()
            return np.array([self.commit(u, tk) for u, tk in zip(u_a.tolist(), t_a.tolist())], dtype=float)
        finally:
            self.restore(saved)

    def commit_held(self, u: float) -> float:
        """Accept input ``u`` held for ever (a point of a quasi-static sweep): the operator's memory
        is updated and the lags settle at its new output; returns the fully crept output."""
        h = float(self.operator.commit(check_input(u)))
        self._h = h
        self._z = np.full(self.lags.tau.size, h)
        self._y = self.lags.static_gain * h
        return self._y

    def static_output(self, u: float) -> float:
        """Output after ``u`` is reached by a monotone ramp from the reset state and held for ever (fully crept)."""
        h = float(self.operator.apply([check_input(u)])[-1])
        return self.lags.static_gain * h

    def operator_output_for(self, y: float, t: float | None = None) -> float:
        """The operator output ``h`` that makes :meth:`evaluate` give ``y`` at time ``t`` [s] from the committed state.

        The exact inverse of one lag step (``h`` linear in time over it): the output is linear in
        the new ``h`` with slope ``d + Σ g_j (1 − ramp_j)`` > 0.  Where the output does not depend
        on ``h`` (no feed-through and no time passed: a lag cannot jump), the committed ``h``.
        """
        y_f = check_input(y)
        z, _, t_f = self._advance(self._h, t)  # checks t; z: the lags with h held
        dt = 0.0 if self._t is None else t_f - self._t
        if dt == 0.0:
            slope, rest = self.lags.d, float(self.lags.g @ self._z)
        else:
            x = dt / self.lags.tau
            a = np.exp(-x)
            ramp = -np.expm1(-x) / x
            slope = self.lags.d + float(self.lags.g @ (1.0 - ramp))
            rest = float(self.lags.g @ (self._z * a + self._h * (ramp - a)))
        return self._h if slope == 0.0 else (y_f - rest) / slope

    def advance_lags(self, h: float, t: float | None) -> float:
        """Commit the time ``t`` [s] with the operator output ``h`` given, not computed (the operator's memory
        is not touched): what an inverse does, which knows ``h`` and keeps the operator's memory itself.
        Returns the output."""
        self._z, self._y, self._t = self._advance(check_input(h), t)
        self._h = float(h)
        return self._y

    def inverse(self, input_range: tuple[float, float] | None = None) -> HysteresisOperator:
        """The inverse operator with the time, a :class:`~exudyn_atcm.hysteresis.dynamics_inverse.DynamicsInverse`.

        ``inverse().apply(y, t)`` are the inputs that make :meth:`apply` give ``y`` at the times
        ``t`` [s] (feedforward); ``input_range`` bounds them (default: the operator's declared range).
        """
        return DynamicsInverse(self, input_range)

    def inverse_apply(self, y: Any, t: Any, inverse: Any) -> np.ndarray:
        """Deprecated (0.3): use ``inverse().apply(y, t)`` (:meth:`inverse`).

        Inputs that make :meth:`apply` give ``y`` at times ``t`` [s]: ``inverse`` (the operator's
        inverse) applied from its reset state to the lag block's exact inverse
        (:meth:`LagSum.inverse_response` at rest at the operator's initial output).
        """
        warnings.warn("WithDynamics.inverse_apply(y, t, inverse) is deprecated: use model.inverse().apply(y, t) "
                      "(the same inputs; inverse(input_range) bounds them)", AtcmDeprecationWarning, stacklevel=2)
        saved = self.checkpoint()
        try:
            self.reset()
            rest = self._h
        finally:
            self.restore(saved)
        h = self.lags.inverse_response(y, t, rest=rest)
        return np.asarray(inverse.apply(h), dtype=float)

    def __repr__(self) -> str:
        return f"WithDynamics({self.operator!r}, creep={self.creep!r}, lag={self.lag!r})"
