"""Creep after a voltage step: a linear creep law in series with a hysteresis operator (offline).

A piezo actuator's displacement keeps drifting for seconds after a voltage step, roughly
logarithmically in time, and its loops change with the drive frequency.  :class:`Creep` models
this as a linear system in series *after* the rate-independent hysteresis output ``h``:

``y = h + Σ_k c_k z_k``,   ``τ_k dz_k/dt = h − z_k``,   ``c_k >= 0``,

i.e. the transfer function ``1 + Σ_k c_k / (1 + τ_k s)``: after a step of ``h`` the output
jumps by the step and then creeps by ``Σ c_k (1 − e^{−t/τ_k})`` times it; time constants spread
evenly in ``log τ`` give the logarithmic creep measured on piezo stacks (a sum of first-order
lags is the usual approximation of ``γ log10(t/t0)``).  At high frequency the creep part
lags behind, which widens and tilts the loops with frequency (a rate effect the
rate-independent operators do not have).

:class:`CreepHysteresis` puts a hysteresis operator and a :class:`Creep` in series, with
:meth:`CreepHysteresis.fit` (alternating: the hysteresis on the output with the creep removed,
the creep coefficients by non-negative least squares on the lag responses) and an exact
inverse of the discretised creep (:meth:`Creep.inverse_response`), so a feedforward program
can cancel both.  The lags are integrated exactly for an ``h`` linear between samples (any
sample spacing).

Scope: these are offline models (records and programs with their sample times).  In the
solver step (inside :func:`exudyn_atcm.simulate`) a creep law is evaluated by
:class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`, which uses the same exact lag update;
identification from a step record: :func:`~exudyn_atcm.hysteresis.dynamics_fit.creep_from_step`.
"""

from __future__ import annotations

import copy
import math
import warnings
from typing import Any, Callable

import numpy as np

from .._checks import finite_array, same_length, sample_times, shown
from ..errors import AtcmDeprecationWarning
from .base import forward_model
from .inverse import inverse_operator
from .model_files import SavableModel

__all__ = ["Creep", "CreepHysteresis", "CreepHysteresisInverse"]


def _lag_states(h: np.ndarray, t: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """``z_k`` along the record, from rest at ``h[0]``, exact for ``h`` linear between samples."""
    z = np.empty((h.size, tau.size))
    z[0] = h[0]
    dt = np.diff(t)
    for k in range(1, h.size):
        a = np.exp(-dt[k - 1] / tau)
        # z' = (h - z)/tau with h linear from h0 to h1 over dt
        ramp = (tau / dt[k - 1]) * (1.0 - a)
        z[k] = a * z[k - 1] + h[k] - a * h[k - 1] - (h[k] - h[k - 1]) * ramp
    return z


class Creep(SavableModel):
    """Linear creep ``y = h + Σ c_k z_k``, ``τ_k z_k' = h − z_k`` (see the module).

    Parameters
    ----------
    tau : array_like
        Time constants [s], positive.
    c : array_like
        Creep coefficients [-], ``>= 0``, one per time constant.
    """

    def __init__(self, tau: Any, c: Any) -> None:
        tau_a = finite_array("tau", tau)
        c_a = finite_array("c", c)
        same_length(("tau", "c"), (tau_a, c_a))
        if (tau_a <= 0).any():
            raise ValueError(f"tau must be > 0 s, got {tau_a.tolist()!r}")
        if (c_a < 0).any():
            raise ValueError(f"c must be >= 0 (creep adds to the step), got {c_a.tolist()!r}")
        self.tau, self.c = tau_a.copy(), c_a.copy()

    @property
    def long_term_gain(self) -> float:
        """Static gain ``1 + Σ c_k``: the fully crept output per unit step of ``h``."""
        return 1.0 + float(self.c.sum())

    def step_response(self, t: Any) -> np.ndarray:
        """Output after a unit step of ``h`` at ``t = 0`` (from rest at 0): ``1 + Σ c_k (1 − e^{−t/τ_k})``."""
        t_a = np.asarray(t, dtype=float)
        return 1.0 + np.sum(self.c * (1.0 - np.exp(-t_a[..., None] / self.tau)), axis=-1)

    def response(self, h: Any, t: Any) -> np.ndarray:
        """Output ``y`` for the hysteresis output ``h`` sampled at times ``t`` [s] (at rest at ``h[0]``)."""
        h_a = finite_array("h", h)
        t_a = sample_times("t", t, h_a.size)
        return h_a + _lag_states(h_a, t_a, self.tau) @ self.c

    def inverse_response(self, y: Any, t: Any) -> np.ndarray:
        """The ``h`` whose :meth:`response` is ``y`` (exact inverse of the discretised lags)."""
        y_a = finite_array("y", y)
        t_a = sample_times("t", t, y_a.size)
        h = np.empty_like(y_a)
        c, tau = self.c, self.tau
        h[0] = y_a[0] / self.long_term_gain
        z = np.full(tau.size, h[0])
        for k in range(1, y_a.size):
            dt = t_a[k] - t_a[k - 1]
            a = np.exp(-dt / tau)
            ramp = (tau / dt) * (1.0 - a)
            # z_new = a z + (1 - ramp) h_new - (a - ramp) h_old, linear in h_new
            coef = 1.0 - ramp
            rest = a * z - (a - ramp) * h[k - 1]
            h[k] = (y_a[k] - float(c @ rest)) / (1.0 + float(c @ coef))
            z = rest + coef * h[k]
        return h

    @classmethod
    def fit(cls, h: Any, y: Any, t: Any, *, tau: Any = None, n_lags: int = 4) -> "Creep":
        """Non-negative creep coefficients for given (or log-spaced) time constants, by least squares.

        ``y − h ≈ Σ_k c_k z_k[h]``; by default ``n_lags`` time constants spread evenly in
        ``log τ`` from four sample spacings to a third of the record.

        Raises
        ------
        ValueError
            For records of different lengths, non-finite values, times that do not increase,
            ``n_lags < 1`` or a record too short for the default time constants.
        """
        from scipy.optimize import nnls  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
        h_a = finite_array("h", h)
        y_a = finite_array("y", y)
        same_length(("h", "y"), (h_a, y_a))
        t_a = sample_times("t", t, h_a.size)
        if tau is None:
            if isinstance(n_lags, bool) or not isinstance(n_lags, int) or n_lags < 1:
                raise ValueError(f"n_lags must be an integer >= 1, got {shown(n_lags)}")
            low, high = 4.0 * float(np.median(np.diff(t_a))), (t_a[-1] - t_a[0]) / 3.0
            if not high > low:
                raise ValueError(f"t: a record of {t_a[-1] - t_a[0]:.3g} s is too short for creep time constants")
            tau = np.geomspace(low, high, n_lags)
        tau_a = finite_array("tau", tau)
        z = _lag_states(h_a, t_a, tau_a)
        c, _ = nnls(z, y_a - h_a)
        return cls(tau_a, c)

    def __repr__(self) -> str:
        return f"Creep(tau={self.tau.tolist()!r}, c={self.c.tolist()!r})"


class CreepHysteresis(SavableModel):
    """A hysteresis operator followed by a :class:`Creep` (offline: records with sample times).

    Parameters
    ----------
    hysteresis : HysteresisOperator
        Rate-independent part (input ``u`` to ``h``).
    creep : Creep
        Linear creep after it.
    """

    def __init__(self, hysteresis: Any, creep: Creep) -> None:
        if not callable(getattr(hysteresis, "apply", None)):
            raise ValueError(f"hysteresis must be a hysteresis operator with apply(u), got {type(hysteresis).__name__}")
        if not isinstance(creep, Creep):
            raise ValueError(f"creep must be a Creep, got {type(creep).__name__}")
        self.hysteresis, self.creep = hysteresis, creep

    def apply(self, u: Any, t: Any) -> np.ndarray:
        """Output for inputs ``u`` at times ``t`` [s], from the hysteresis operator's reset state."""
        return self.creep.response(self.hysteresis.apply(u), t)

    def inverse(self, input_range: tuple[float, float] | None = None) -> "CreepHysteresisInverse":
        """The inverse (offline, like this model): ``inverse().apply(y, t)`` are the inputs that give ``y``.

        ``input_range`` bounds the inputs (default: the hysteresis operator's declared range).
        """
        return CreepHysteresisInverse(self, input_range)

    def inverse_apply(self, y: Any, t: Any, inverse: Any) -> np.ndarray:
        """Deprecated (0.3): use ``inverse().apply(y, t)`` (:meth:`inverse`).

        Inputs that produce the wanted outputs ``y`` at times ``t``: ``inverse`` (the hysteresis
        operator's inverse) from its reset state after the creep's exact inverse.
        """
        warnings.warn("CreepHysteresis.inverse_apply(y, t, inverse) is deprecated: use model.inverse().apply(y, t) "
                      "(the same inputs; inverse(input_range) bounds them)", AtcmDeprecationWarning, stacklevel=2)
        return np.asarray(inverse.apply(self.creep.inverse_response(y, t)), dtype=float)

    @classmethod
    def fit(cls, u: Any, y: Any, t: Any, fit_hysteresis: Callable[[np.ndarray, np.ndarray], Any], *,
            tau: Any = None, n_lags: int = 4, rounds: int = 20) -> tuple["CreepHysteresis", dict]:
        """Identify both parts from one record (steps and cycles at a few rates identify best).

        Alternates ``rounds`` times: ``fit_hysteresis(u, h_target)`` (e.g.
        ``lambda u, h: PrandtlIshlinskii.fit(u, h, 20)[0]``) on the output with the present creep
        removed (:meth:`Creep.inverse_response`; none at first), then :meth:`Creep.fit` on the
        hysteresis output.  The alternation converges slowly where a time constant is as short
        as the input's ramps (the hysteresis fit absorbs part of that creep): measured on a
        PI-plus-creep record (time constants given), RMS error 2.0x the noise after 3 rounds, 1.2x after 20.

        Returns
        -------
        (CreepHysteresis, dict)
            The model and ``{"rms": [...]}``, the RMS error on the record after each round.
        """
        u_a = finite_array("u", u)
        y_a = finite_array("y", y)
        same_length(("u", "y"), (u_a, y_a))
        t_a = sample_times("t", t, u_a.size)
        if isinstance(rounds, bool) or not isinstance(rounds, int) or rounds < 1:
            raise ValueError(f"rounds must be an integer >= 1, got {shown(rounds)}")
        creep = Creep([1.0], [0.0])
        history = []
        hysteresis = None
        for _ in range(rounds):
            hysteresis = fit_hysteresis(u_a, creep.inverse_response(y_a, t_a))
            h = hysteresis.apply(u_a)
            creep = Creep.fit(h, y_a, t_a, tau=tau, n_lags=n_lags)
            history.append(float(math.sqrt(np.mean((creep.response(h, t_a) - y_a) ** 2))))
        return cls(hysteresis, creep), {"rms": history}


class CreepHysteresisInverse(SavableModel):
    """Inverse of a :class:`CreepHysteresis` (offline): the creep's exact inverse
    (:meth:`Creep.inverse_response`), then the hysteresis operator's inverse from its reset state.

    Parameters
    ----------
    model : CreepHysteresis
        The forward model (copied).
    input_range : (float, float), optional
        Inputs the hysteresis operator's inverse may return (default: the range it declares).
    """

    def __init__(self, model: CreepHysteresis, input_range: tuple[float, float] | None = None) -> None:
        if not isinstance(model, CreepHysteresis):
            raise ValueError(f"model must be a CreepHysteresis, got {type(model).__name__}")
        self.model = copy.deepcopy(model)
        self.requested_range = None if input_range is None else tuple(float(v) for v in input_range)
        self.hysteresis_inverse = inverse_operator(self.model.hysteresis, input_range)

    def apply(self, y: Any, t: Any) -> np.ndarray:
        """Inputs that give the wanted outputs ``y`` at times ``t`` [s] (the hysteresis inverse's clip counters
        say what was unreachable)."""
        return np.asarray(self.hysteresis_inverse.apply(self.model.creep.inverse_response(y, t)), dtype=float)

    def inverse(self, input_range: tuple[float, float] | None = None) -> CreepHysteresis:
        """The forward model (a copy).

        Raises
        ------
        ValueError
            If ``input_range`` is given (the forward model takes any input).
        """
        return forward_model(self.model, input_range, reset=False)

    def __repr__(self) -> str:
        return f"CreepHysteresisInverse({self.model!r})"
