"""The time grid of a run: equal steps that end at ``t_end``, the steps that divide a run, grid times.

* :func:`time_grid` -- the step actually used for ``t_end`` (warns when the requested step
  does not divide the run, suggesting steps that do: :func:`dividing_steps`);
* :func:`snap_time` / :func:`snap_times` -- solver times put back on the grid.

Independent of Exudyn and of the model type (as :mod:`exudyn_atcm.solve.run_checks`, which re-exports them).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import AccuracyWarning

__all__ = ["TimeGrid", "time_grid", "dividing_steps", "SUGGESTION_COUNTS", "snap_time", "snap_times"]


@dataclass(frozen=True)
class TimeGrid:
    """The time steps of a run: ``n_steps`` equal steps of ``step`` [s] up to ``t_end`` [s]."""

    t_end: float
    step: float
    n_steps: int
    requested_step: float

    @property
    def adjusted(self) -> bool:
        """True when the step used differs from the requested one."""
        return self.step != self.requested_step

    def describe(self) -> str:
        """The step for messages, as the user gave it: ``step = 0.3 s (used: 0.25 s, so that it
        divides t_end = 1 s)`` when adjusted, else ``step = 0.25 s``."""
        if not self.adjusted:
            return f"step = {self.step:.6g} s"
        return (f"step = {self.requested_step!r} s (used: {self.step:.6g} s, so that it divides "
                f"t_end = {self.t_end:.6g} s)")


def time_grid(t_end: float, step: float, *, warn: bool = True, stacklevel: int = 4) -> TimeGrid:
    """Equal steps that end exactly at ``t_end``.

    ``n = ceil(t_end/step)`` steps of ``t_end/n`` (what the solver does with a step that does
    not divide the run).  If that differs from ``step`` by more than round-off, a
    ``RuntimeWarning`` says so, and the returned :attr:`TimeGrid.step` is the one to record.

    Parameters
    ----------
    t_end : float
        End time [s], > 0.
    step : float
        Requested step [s], ``0 < step <= t_end``.
    warn : bool, optional
        Issue the warning (default True).
    stacklevel : int, optional
        Passed to ``warnings.warn`` (the frame the warning points at); the same in the
        other checks.
    """
    ratio = t_end / step
    n = max(1, int(math.ceil(ratio - 1e-9)))
    used = t_end / n
    if abs(used - step) <= 1e-9 * step:
        return TimeGrid(t_end, step, n, step)
    if warn:
        finer, coarser = dividing_steps(t_end, step)
        warnings.warn(
            f"step = {step!r} s does not divide t_end = {t_end!r} s ({ratio:.6g} steps); the run uses "
            f"{n} steps of {used:.6g} s, and that step is recorded (info 'step [s]'). Choose a step "
            f"that divides t_end (e.g. {finer!r} or {coarser!r} s) to silence this",
            AccuracyWarning,
            stacklevel=stacklevel,
        )
    return TimeGrid(t_end, used, n, step)


def _divides(t_end: float, step: float) -> bool:
    """Whether ``step`` divides ``t_end`` as :func:`time_grid` checks it (within 1e-9 of the step)."""
    n = max(1, int(math.ceil(t_end / step - 1e-9)))
    return abs(t_end / n - step) <= 1e-9 * step


#: Step counts :func:`dividing_steps` tries on either side of the requested step (a few milliseconds at most).
SUGGESTION_COUNTS = 400


def dividing_steps(t_end: float, step: float, digits: int = 6) -> tuple[float, float]:
    """The steps nearest ``step`` [s] below and above it that divide ``t_end`` [s] (as :func:`time_grid` checks),
    each written with the fewest significant digits (at most ``digits``) that still divide; the exact quotient
    ``t_end / n`` where no shorter one does.  The suggestions of :func:`time_grid`'s warning: ``0.00029994`` (the
    quotient ``1/3334`` to 6 digits) was suggested for ``t_end = 1`` and warned again."""
    ratio = t_end / step
    out = []
    for counts in (range(math.ceil(ratio), math.ceil(ratio) + SUGGESTION_COUNTS),  # finer steps
                   range(max(math.floor(ratio), 1), max(math.floor(ratio) - SUGGESTION_COUNTS, 0), -1)):  # coarser
        best = None
        for n in counts:
            for d in range(1, digits + 1):
                short = float(f"{t_end / n:.{d}g}")
                if round(t_end / short) == n and _divides(t_end, short):  # still n steps, and divides
                    best = short
                    break
            if best is not None:
                break
        out.append(best if best is not None else t_end / counts[0])
    return out[0], out[1]


def snap_time(t: float, step: float) -> float:
    """``t`` [s] put on the grid ``k * step`` when it is within round-off of it.

    Solver times accumulate round-off (``1.9998999999997962`` for ``19999 * 1e-4``).  A time
    within ``1e-6`` steps of a grid point becomes that grid point, written with 15
    significant digits so that its shortest representation is short (``1.9999``).  Times off
    the grid (steps the solver halved) are returned unchanged.
    """
    k = round(t / step)
    grid = k * step
    if abs(t - grid) <= 1e-6 * step:
        return float(f"{grid:.15g}")
    return t


def snap_times(times, step: float) -> np.ndarray:
    """:func:`snap_time` applied to every element of ``times`` [s] (vectorised, same values).

    A grid time ``g`` becomes ``rint(g 10^d) / 10^d`` with ``d = 14 - floor(log10 |g|)`` (15
    significant digits, the nearest double to that decimal, as ``float(f"{g:.15g}")``); where
    that could differ (``g 10^d`` near a rounding tie, ``|g|`` near a power of ten, or
    ``10^d`` not exact) the element is formatted as :func:`snap_time` does.
    """
    t = np.array(times, dtype=float).ravel()
    grid = np.round(t / step) * step
    on = np.abs(t - grid) <= 1e-6 * step
    out = t.copy()
    g = grid[on]
    snapped = g.copy()  # zeros stay zero
    nz = g != 0.0
    gn = g[nz]
    with np.errstate(divide="ignore", invalid="ignore"):
        exponent = np.floor(np.log10(np.abs(gn)))
    digits = 14.0 - exponent
    exact = (digits >= 0.0) & (digits <= 22.0)  # 10^d exact in double precision
    scale = 10.0 ** np.where(exact, digits, 0.0)
    scaled = gn * scale
    rounded = np.rint(scaled)
    value = rounded / scale
    mantissa = np.abs(gn) / 10.0 ** exponent
    safe = (exact & (np.abs(np.abs(scaled - rounded) - 0.5) > 1e-3)
            & (mantissa > 1.0 + 1e-9) & (mantissa < 10.0 - 1e-8) & (np.abs(rounded) < 2.0**53))
    for i in np.flatnonzero(~safe):
        value[i] = float(f"{gn[i]:.15g}")
    snapped[nz] = value
    out[on] = snapped
    return out.reshape(np.shape(times))
