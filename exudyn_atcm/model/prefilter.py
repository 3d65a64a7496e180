"""Dynamic pre-filters for a feedforward command: a lightly damped mode must not ring.

A wanted trajectory ``r(t)`` with corners (a ramp that turns) excites every mode of a mechanism
at every corner; a mode with a damping ratio of a few per mille then rings for seconds.  The
filters here turn the wanted trajectory into a *quasi-static command* ``q(t)``: the output the
quasi-static map is asked for at each instant (:func:`exudyn_atcm.solve.feedforward_mechanism.mechanism_feedforward`).

* ``"inversion"`` (:func:`invert_mode`): the corners are rounded over ``window`` [s] (two
  centred moving averages, so the rounded trajectory has a continuous acceleration and no delay),
  then the dominant mode, ``y'' + 2 zeta omega y' + omega^2 y = omega^2 q``, is inverted:
  ``q = r_s + (2 zeta / omega) r_s' + r_s'' / omega^2``.  A mechanism that is this mode follows
  ``r_s`` exactly; the error against ``r`` is the rounding (about ``slope change x window / 12``
  at a corner, for ``window`` s only).
* ``"zv"`` / ``"zvd"`` (:func:`shape`): input shaping (Singer & Seering 1990), the command
  convolved with two (ZV) or three (ZVD) impulses that cancel the mode's residual vibration,
  then advanced by the impulses' centroid so that a ramp keeps its timing; the corners are
  rounded over half a damped period (ZV) or one (ZVD), so the tracking error at a corner is of
  the order ``slope x period / 4``.
* ``"smooth"`` (:func:`smooth`): the corners rounded over one period of the mode (one centred
  moving average); most of the ringing gone, the corners' error as large as for ZVD.

All functions work on a uniform time grid; values before the first and after the last sample
are held (the mechanism at rest at the trajectory's ends).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import finite_array, finite_float, positive_float, positive_int, shown

__all__ = ["PREFILTERS", "DAMPING_FROM", "Prefilter", "shaper_impulses", "shape", "smooth", "invert_mode",
           "uniform_grid"]

#: The pre-filters :func:`~exudyn_atcm.solve.feedforward_mechanism.mechanism_feedforward` knows.
PREFILTERS = ("inversion", "zv", "zvd", "smooth", "none")
#: Where the modes' damping ratios come from (:attr:`Prefilter.damping_from`).
DAMPING_FROM = ("linear", "description")


@dataclass(frozen=True)
class Prefilter:
    """The dynamic pre-filter of :func:`~exudyn_atcm.mechanism_feedforward` and its settings.

    Parameters
    ----------
    kind : {"inversion", "zv", "zvd", "smooth", "none"}
        ``"inversion"`` (default): the first mode inverted, corners rounded over ``window``;
        ``"zv"`` / ``"zvd"``: input shaping of the first ``shaped_modes`` modes, time-advanced by
        the shaper's centroid; ``"smooth"``: corners rounded over ``window``; ``"none"``: the
        quasi-static inverse only (module docstring).
    window : float, optional
        Rounding window of the corners [s]: default one period of the second mode for
        ``"inversion"`` (so the rounded corners do not excite it), one period of the first mode
        for ``"smooth"``.
    shaped_modes : int, optional
        Modes shaped by ``"zv"`` / ``"zvd"`` (1 or 2).
    damping_ratio : float, optional
        Damping ratio [-] of the first mode (and of the second, for ``shaped_modes=2``), in
        [0, 1); overrides ``damping_from``.
    damping_from : {"linear", "description"}, optional
        Whence the modes' damping ratios when ``damping_ratio`` is not given: ``"linear"``
        (default) the linear model about the middle wanted output (:func:`~exudyn_atcm.linearise`,
        ascending branch: the damping the simulation has; the description for a drive with creep
        or rate dynamics, which has no linear model); ``"description"`` the mechanism's Rayleigh
        damping description (an estimate when the parts' coefficients differ).
    """

    kind: str = "inversion"
    window: float | None = None
    shaped_modes: int = 1
    damping_ratio: float | None = None
    damping_from: str = "linear"

    def __post_init__(self) -> None:
        if self.kind not in PREFILTERS:
            raise ValueError(f"prefilter must be one of {', '.join(map(repr, PREFILTERS))}, got {self.kind!r}")
        if self.damping_from not in DAMPING_FROM:
            raise ValueError(f"damping_from must be one of {', '.join(map(repr, DAMPING_FROM))}, "
                             f"got {self.damping_from!r}")
        if self.window is not None:
            object.__setattr__(self, "window", positive_float("window", self.window))
        modes = positive_int("shaped_modes", self.shaped_modes)
        if modes > 2:
            raise ValueError(f"shaped_modes must be 1 or 2, got {self.shaped_modes!r}")
        object.__setattr__(self, "shaped_modes", modes)
        if self.damping_ratio is not None:
            zeta = finite_float("damping_ratio", self.damping_ratio)
            if not 0.0 <= zeta < 1.0:
                raise ValueError(f"damping_ratio must be in [0, 1) (a lightly damped mode), got {self.damping_ratio!r}")
            object.__setattr__(self, "damping_ratio", zeta)


def uniform_grid(times: Any, values: Any, sample_time: float) -> tuple[np.ndarray, np.ndarray]:
    """``values`` [any unit] at ``times`` [s] resampled linearly on a grid of ``sample_time`` [s].

    The grid starts at ``times[0]`` and ends at the last multiple not beyond ``times[-1]``
    (plus ``times[-1]`` itself when it is not on the grid).
    """
    t = finite_array("times", times, min_length=2)
    y = finite_array("wanted", values, min_length=2)
    if np.any(np.diff(t) <= 0.0):
        raise ValueError("times must be strictly increasing [s]")
    dt = positive_float("sample_time", sample_time)
    n = int(math.floor((t[-1] - t[0]) / dt + 1e-9))
    grid = t[0] + dt * np.arange(n + 1)
    if t[-1] - grid[-1] > 1e-9 * dt:
        grid = np.append(grid, t[-1])
    return grid, np.interp(grid, t, y)


def _held(grid: np.ndarray, values: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Linear interpolation with the end values held outside the grid."""
    return np.interp(at, grid, values, left=values[0], right=values[-1])


def _moving_average(grid: np.ndarray, values: np.ndarray, window: float) -> np.ndarray:
    """Centred moving average over ``window`` [s] of the piecewise-linear signal (ends held), exact
    for a piecewise-linear signal up to the quadrature of its integral on a 4x finer grid."""
    if window <= 0.0:
        return values.copy()
    dt = float(np.min(np.diff(grid)))
    m = max(8, int(math.ceil(4.0 * window / dt)))
    # trapezoidal average over the window at m+1 points: exact for linear pieces between the points
    offsets = np.linspace(-0.5 * window, 0.5 * window, m + 1)
    weights = np.full(m + 1, 1.0 / m)
    weights[[0, -1]] *= 0.5
    out = np.zeros_like(values)
    for off, w in zip(offsets, weights):
        out += w * _held(grid, values, grid + off)
    return out


def smooth(grid: Any, values: Any, window: float, passes: int = 1) -> np.ndarray:
    """The signal rounded by ``passes`` centred moving averages of ``window`` [s] each (no delay).

    Parameters
    ----------
    grid : array_like
        Sample times [s], increasing.
    values : array_like
        The signal at those times (any unit), held before and after.
    window : float
        Averaging window [s], ``>= 0`` (0: unchanged).
    passes : int, optional
        Number of averages: 1 gives a continuous slope, 2 a continuous acceleration.
    """
    t = finite_array("grid", grid, min_length=2)
    y = finite_array("values", values, min_length=2)
    w = finite_float("window", window)
    if w < 0.0:
        raise ValueError(f"window must be >= 0 [s], got {shown(window)}")
    for _ in range(int(passes)):
        y = _moving_average(t, y, w)
    return y


def shaper_impulses(frequency: float, damping_ratio: float, kind: str = "zv") -> tuple[np.ndarray, np.ndarray]:
    """Times [s] and amplitudes [-] of a ZV or ZVD input shaper for one mode (sum of amplitudes 1).

    With ``K = exp(-zeta pi / sqrt(1 - zeta^2))`` and the damped half period ``T_d / 2``:
    ZV ``[1, K] / (1 + K)`` at ``[0, T_d/2]``; ZVD ``[1, 2K, K^2] / (1 + K)^2`` at
    ``[0, T_d/2, T_d]`` (Singer & Seering 1990).

    Parameters
    ----------
    frequency : float
        Undamped natural frequency of the mode [Hz], > 0.
    damping_ratio : float
        Its damping ratio [-], ``0 <= zeta < 1``.
    kind : {"zv", "zvd"}
    """
    f = positive_float("frequency", frequency)
    zeta = finite_float("damping_ratio", damping_ratio)
    if not 0.0 <= zeta < 1.0:
        raise ValueError(f"damping_ratio must be in [0, 1) for an input shaper, got {shown(damping_ratio)}")
    k = math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta**2))
    half = 0.5 / (f * math.sqrt(1.0 - zeta**2))
    if kind == "zv":
        return np.array([0.0, half]), np.array([1.0, k]) / (1.0 + k)
    if kind == "zvd":
        return np.array([0.0, half, 2.0 * half]), np.array([1.0, 2.0 * k, k * k]) / (1.0 + k) ** 2
    raise ValueError(f"kind must be 'zv' or 'zvd', got {shown(kind)}")


def shape(grid: Any, values: Any, modes: list[tuple[float, float]], kind: str = "zv",
          advance: bool = True) -> np.ndarray:
    """The signal convolved with the ZV/ZVD shaper of every mode ``(frequency [Hz], damping ratio [-])``.

    With ``advance`` the result is shifted earlier by the shapers' centroid (the mean delay), so a
    ramp of the shaped signal lies on the ramp of the original (the wanted trajectory is known in
    advance: a feedforward program may start moving before it); ends held.
    """
    t = finite_array("grid", grid, min_length=2)
    y = finite_array("values", values, min_length=2)
    times, amps = np.zeros(1), np.ones(1)
    for f, zeta in modes:
        ti, ai = shaper_impulses(f, zeta, kind)
        times = (times[:, None] + ti[None, :]).ravel()
        amps = (amps[:, None] * ai[None, :]).ravel()
    shift = float(np.dot(times, amps)) if advance else 0.0
    out = np.zeros_like(y)
    for ti, ai in zip(times, amps):
        out += ai * _held(t, y, t - ti + shift)
    return out


def invert_mode(grid: Any, values: Any, frequency: Any, damping_ratio: float, window: float) -> tuple[np.ndarray,
                                                                                                      np.ndarray]:
    """Quasi-static command ``q`` that makes the mode ``y'' + 2 zeta w y' + w^2 y = w^2 q`` follow the
    rounded signal; returns ``(q, rounded)``.

    Parameters
    ----------
    grid : array_like
        Uniform sample times [s].
    values : array_like
        The wanted signal (any unit), held before and after.
    frequency : float or array_like
        The mode's undamped natural frequency [Hz] (a number, or one per sample: a frequency
        that changes along the trajectory, e.g. with the mechanism's pose).
    damping_ratio : float
        Its damping ratio [-], ``>= 0``.
    window : float
        The corners are rounded by two centred moving averages of ``window`` [s] (a continuous
        acceleration; 0: not rounded, then a corner's acceleration is one sample's worth).
    """
    t = finite_array("grid", grid, min_length=3)
    zeta = finite_float("damping_ratio", damping_ratio)
    if zeta < 0.0:
        raise ValueError(f"damping_ratio must be >= 0, got {shown(damping_ratio)}")
    rounded = smooth(t, values, window, passes=2)
    omega = 2.0 * math.pi * np.broadcast_to(np.asarray(frequency, dtype=float), t.shape)
    if np.any(~np.isfinite(omega)) or np.any(omega <= 0.0):
        raise ValueError(f"frequency must be > 0 [Hz], got {shown(frequency)}")
    velocity = np.gradient(rounded, t)
    acceleration = np.gradient(velocity, t)
    return rounded + 2.0 * zeta / omega * velocity + acceleration / omega**2, rounded
