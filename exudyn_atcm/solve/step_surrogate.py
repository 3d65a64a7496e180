"""A one-mode stand-in of a run that predicts its time-step error before the run: :class:`StandIn`.

The step of a mechanism run is decided by the ringing of its lowest mode: every corner of the
drive (a voltage step, a ramp's start and end, and at every reversal the Preisach operator's
jump from the steep to the flat branch, however smooth the voltage) starts a lightly damped
vibration, and the integrator's period error (about ``(ω h)²/12`` per period) shifts its phase
while it rings.  The stand-in is the lowest mode alone, driven quasi-statically by the
drive's free strain scaled to a unit travel:

    x'' + ω² x = ω² s(t),   s = (ε(t) - ε(0)) / (max ε - min ε),

with ``ε(t)`` the drive's voltage program passed through its hysteresis operator offline
(:func:`unit_strain`).  Its exact solution for ``s`` linear between fine samples is a sum of
free vibrations started at every slope change (:func:`exact_response`); the run's integrator
(generalized-alpha, spectral radius 0.8, as the solver settings use) applied to the same
equation at a step ``h`` (:func:`alpha_response`) differs from it by about what the run at ``h``
misses of its travel.  Undamped, so it overstates a damped mechanism's error (the probe run
of :mod:`exudyn_atcm.solve.step_choice` measures the real one); a mode the drive hardly excites (a
slow sine, whose strain has no slope jump at its reversals) gives a small error at coarse
steps that do not resolve the mode at all, as the run does.

No Exudyn import; numpy only (the filters: :mod:`exudyn_atcm.solve.linear_recurrence`).
"""

from __future__ import annotations

import copy
import inspect
import math
import warnings
from typing import Any

import numpy as np

from ..model.signals import Signal
from .linear_recurrence import first_component, first_order

__all__ = ["SPECTRAL_RADIUS", "program_voltages", "unit_strain", "other_excitation", "exact_response", "alpha_response",
           "ExactResponse", "StandIn"]

#: Spectral radius at infinity of the generalized-alpha integration (the package's solver setting).
SPECTRAL_RADIUS = 0.8


def program_voltages(drive: Any, times: np.ndarray) -> np.ndarray:
    """The drive's voltage program [V] at ``times`` [s] (the package's programs take arrays at once; any other
    callable is asked sample by sample)."""
    program = drive.voltage
    if isinstance(program, Signal):
        return np.asarray(program(times), dtype=float)
    return np.array([drive.voltage_at(float(t)) for t in times])


def unit_strain(drive: Any, times: np.ndarray) -> np.ndarray | None:
    """The drive's free strain at ``times`` [s] from its reset state, scaled to ``s(0) = 0`` and unit range.

    The voltage program is sampled at ``times`` and passed through a copy of the hysteresis
    operator (the drive's own memory is not touched; range warnings are left to the run).
    ``None`` for a drive set by a controller (its voltage depends on the run) or whose strain
    does not change.
    """
    if getattr(drive, "controller", None) is not None:
        return None
    volts = program_voltages(drive, times)
    operator = drive.hysteresis
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the run itself says what is out of range
        if operator is None:
            strain = np.asarray(drive.linear_strain(volts), dtype=float)  # d33 U / t_IDE, elementwise
        else:
            operator = copy.deepcopy(operator)
            takes_time = "t" in inspect.signature(operator.apply).parameters
            strain = np.asarray(operator.apply(volts, times) if takes_time else operator.apply(volts), dtype=float)
    span = float(np.ptp(strain))
    if not span > 0.0 or not math.isfinite(span):
        return None
    return (strain - strain[0]) / span


def other_excitation(mech: Any) -> str | None:
    """What moves a mechanism besides its drives' programs, in words, or ``None``: a controller setting a drive's
    voltage during the run, or a load given as a function of time.  Without either, a mechanism whose drives'
    strains do not change stays at rest in the equilibrium it starts from."""
    if any(getattr(d, "controller", None) is not None for d in mech.drives.values()):
        return "a controller sets a drive's voltage during the run"
    if any(callable(getattr(load, name, None)) for load in (*mech.forces, *mech.torques) for name in ("force", "torque")):
        return "a load changes with time"
    return None


def exact_response(s: np.ndarray, dt: float, omega: float, zeta: float = 0.0,
                   times: np.ndarray | None = None) -> np.ndarray:
    """Exact ``x`` of ``x'' + 2ζω x' + ω² x = ω² s``, ``s`` sampled at spacing ``dt`` [s] and linear between.

    At the samples, or at ``times`` [s] (anywhere in the sampled span: the solution between
    samples is exact too).  Starts at rest in equilibrium (``s(0) = 0``, ``x = x' = 0``).  Between
    samples ``y = x - s`` is the constant lag ``-2ζ s'/ω`` plus a free damped vibration
    ``w = Re(c e^{λ(t - t_k)})``, ``λ = -ζω + iω_d``; at every slope change ``Δs'`` the lag jumps
    and ``w`` takes the jump (``Δw = 2ζΔs'/ω``, ``Δw' = -Δs'``, ``x`` and ``x'`` continuous).  The
    amplitudes ``c_k`` are one complex first-order filter of the kicks (:class:`ExactResponse`).
    """
    exact = ExactResponse(s, dt, omega, zeta)
    return exact(np.arange(s.size) * dt if times is None else times)


class ExactResponse:
    """:func:`exact_response` with its amplitudes computed once, evaluated at any times [s] (``__call__``)."""

    def __init__(self, s: np.ndarray, dt: float, omega: float, zeta: float = 0.0) -> None:
        slopes = np.diff(s) / dt
        self.slopes = np.r_[slopes, slopes[-1:] if slopes.size else 0.0]  # the slope after each sample
        kicks = np.diff(np.r_[0.0, self.slopes])
        kicks[-1] = 0.0
        damped = omega * math.sqrt(max(1.0 - zeta * zeta, 1e-12))
        self.lam = complex(-zeta * omega, damped)
        dw = 2.0 * zeta * kicks / omega
        self.c = first_order(np.exp(self.lam * dt), dw - 1j * (-kicks + zeta * omega * dw) / damped)
        self.s, self.dt, self.lag = np.asarray(s, dtype=float), dt, 2.0 * zeta / omega

    def __call__(self, times: np.ndarray) -> np.ndarray:
        t = np.asarray(times, dtype=float)
        k = np.clip(np.floor(t / self.dt + 1e-9).astype(np.int64), 0, self.s.size - 1)
        tau = t - k * self.dt
        slope = self.slopes[k]
        return self.s[k] + slope * (tau - self.lag) + (self.c[k] * np.exp(self.lam * tau)).real


def _alpha_constants(rho: float) -> tuple[float, float, float, float]:
    """``α_m, α_f, γ, β`` of generalized-alpha (Chung and Hulbert, 1993) for spectral radius ``rho``."""
    alpha_m = (2.0 * rho - 1.0) / (rho + 1.0)
    alpha_f = rho / (rho + 1.0)
    gamma = 0.5 - alpha_m + alpha_f
    return alpha_m, alpha_f, gamma, 0.25 * (gamma + 0.5) ** 2


def alpha_response(s: np.ndarray, h: float, omega: float, zeta: float = 0.0,
                   rho: float = SPECTRAL_RADIUS) -> np.ndarray:
    """``x`` of ``x'' + 2ζω x' + ω² x = ω² s`` at steps ``h`` [s] by generalized-alpha (``s`` at the steps, ``s[0] = 0``).

    The Arnold-Brüls form Exudyn integrates with (the algorithmic acceleration ``a`` apart from
    the acceleration ``x''``), started at rest in equilibrium (all zero, as ``s(0) = 0``).  The
    recurrence of the state ``(x, v, a, f)`` is linear, so it runs as one filter of the input
    (:func:`~exudyn_atcm.solve.linear_recurrence.first_component`).
    """
    am, af, gamma, beta = _alpha_constants(rho)
    w2, c = omega * omega, 2.0 * zeta * omega
    # x'' = f - w2 x - c v; (1-am) a1 + am a0 = (1-af) x''1 + af x''0, x1 = x0 + h v0 + h^2 ((0.5-beta) a0 + beta a1),
    # v1 = v0 + h ((1-gamma) a0 + gamma a1) give a1 = row . (x0, v0, a0, f0) + f1 / d
    q = af / (1.0 - af)
    d = (1.0 - am) / (1.0 - af) + w2 * h * h * beta + c * h * gamma
    row = np.array([-w2 * (1.0 + q), -w2 * h - c * (1.0 + q), -w2 * h * h * (0.5 - beta) - c * h * (1.0 - gamma)
                    - am / (1.0 - af), q]) / d
    transition = np.zeros((4, 4))
    transition[0] = [1.0, h, h * h * (0.5 - beta), 0.0] + h * h * beta * row
    transition[1] = [0.0, 1.0, h * (1.0 - gamma), 0.0] + h * gamma * row
    transition[2] = row
    drive = np.array([h * h * beta / d, h * gamma / d, 1.0 / d, 1.0])  # the input f_{n+1}; the last row keeps it
    out = np.zeros(len(s))
    out[1:] = first_component(transition, drive, w2 * np.asarray(s[1:], dtype=float))
    return out


class StandIn:
    """The one-mode stand-in of a run: the drives' unit strains (:func:`unit_strain`, spacing ``dt`` [s] over
    ``t_end`` [s]), the mode's ``omega`` [rad/s] and damping ratio ``zeta``; :meth:`error` at a step count."""

    def __init__(self, strains: list[np.ndarray], dt: float, t_end: float, omega: float, zeta: float) -> None:
        self.strains, self.dt, self.t_end, self.omega, self.zeta = strains, dt, t_end, omega, zeta
        self.exact = [ExactResponse(s, dt, omega, zeta) for s in strains]

    def error(self, n: int) -> float:
        """Largest error [-] (of the unit travel) of the stand-in at the step ``t_end / n``, the worst drive's."""
        return float(np.max(self.errors(n)))

    def errors(self, n: int) -> np.ndarray:
        """Error [-] of the stand-in at each of the ``n + 1`` instants of the step ``t_end / n``, the worst drive's."""
        t = np.linspace(0.0, self.t_end, n + 1)
        worst = np.zeros(n + 1)
        for s_fine, exact in zip(self.strains, self.exact):
            s = np.interp(t, np.arange(s_fine.size) * self.dt, s_fine)
            x = alpha_response(s, self.t_end / n, self.omega, self.zeta)
            worst = np.maximum(worst, np.abs(x - exact(t)))
        return worst
