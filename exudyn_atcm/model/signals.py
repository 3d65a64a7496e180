"""Voltage programs: objects that carry their parameters and are callable on times.

Every signal is called as ``signal(t)`` with ``t`` in seconds, a float or a numpy array, and
returns volts of the same shape (a float for a scalar ``t``).  ``signal.parameters`` gives
the parameters as a dict (written into CSV metadata).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Literal, Union

import numpy as np

from .signal_columns import column_index, header_scale, read_signal_table
from .._checks import finite_array, finite_float, positive_float, shown, warn_implausible

__all__ = ["Signal", "Constant", "Triangle", "Sine", "Steps", "PiecewiseLinear", "CsvSignal", "ForcProgram",
           "SWITCH_TOLERANCE"]

TimeLike = Union[float, np.ndarray]


class Signal:
    """Base class: subclasses implement :meth:`_values` on a float array of times."""

    def __call__(self, t: Any) -> TimeLike:
        if type(t) is float:  # fast path: a solver asks for one time per step
            if not math.isfinite(t):
                raise ValueError(f"t must be finite, got {shown(t)}")
            return self._scalar(t)
        times = np.asarray(t, dtype=float)
        if not np.all(np.isfinite(times)):
            raise ValueError(f"t must be finite, got {shown(t)}")
        values = self._values(np.atleast_1d(times))
        if times.ndim == 0:
            return float(values[0])
        return values.reshape(times.shape)

    def _values(self, t: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def _scalar(self, t: float) -> float:
        """Value at one time; subclasses may override with a faster scalar formula."""
        return float(self._values(np.array([t]))[0])

    def shortest_feature(self, t_end: float | None = None) -> tuple[float, str] | None:
        """The shortest interval [s] between corners of the program up to ``t_end``, and what it is.

        A solver must take several steps across it to follow the program (see
        :func:`exudyn_atcm.solve.run_checks.check_step_against_program`): the ramp of a triangle
        (half a period), half a sine period (extremum to extremum), the dwell of a step program, the
        shortest stretch between reversals or marked kinks of a piecewise-linear program.  ``None``
        for a program without corners (a constant).

        Parameters
        ----------
        t_end : float, optional
            Only features that start before ``t_end`` [s] count (default: all).
        """
        return None

    @property
    def parameters(self) -> dict[str, Any]:
        """The signal's kind and parameters, in SI units."""
        return {"signal": type(self).__name__, **self._parameters()}

    def _parameters(self) -> dict[str, Any]:
        return {}

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self._parameters().items())
        return f"{type(self).__name__}({args})"


class Constant(Signal):
    """A constant voltage ``value`` [V]."""

    def __init__(self, value: float) -> None:
        self.value = finite_float("value", value)

    def _values(self, t: np.ndarray) -> np.ndarray:
        return np.full(t.shape, self.value)

    def _scalar(self, t: float) -> float:
        return self.value

    def _parameters(self) -> dict[str, Any]:
        return {"value": self.value}


class Triangle(Signal):
    r"""Symmetric triangle wave of the paper's Eq. 11.

    :math:`U(t) = U_{med} + U_{amp}(4t/T - 1 - 2k)(-1)^k`, :math:`k = \lfloor 2t/T \rfloor`:
    ``u_med - u_amp`` at ``t = 0`` (and every multiple of ``period``), ``u_med + u_amp`` at ``period/2``
    (the paper calls it a saw tooth).  For ``t < 0`` it continues periodically (floor, not truncation).

    Parameters
    ----------
    u_med : float
        Mean voltage [V].
    u_amp : float
        Amplitude [V], ``>= 0``.
    period : float
        Period ``T`` [s], ``> 0``.
    """

    def __init__(self, u_med: float, u_amp: float, period: float) -> None:
        self.u_med = finite_float("u_med", u_med)
        self.u_amp = finite_float("u_amp", u_amp)
        if self.u_amp < 0.0:
            raise ValueError(f"u_amp must be >= 0, got {shown(u_amp)}")
        self.period = positive_float("period", period)

    def _values(self, t: np.ndarray) -> np.ndarray:
        phase = 2.0 * t / self.period
        k = np.floor(phase)
        sign = np.where(np.mod(k, 2.0) == 0.0, 1.0, -1.0)
        return self.u_med + self.u_amp * (2.0 * phase - 1.0 - 2.0 * k) * sign

    def _scalar(self, t: float) -> float:
        phase = 2.0 * t / self.period
        k = math.floor(phase)
        return self.u_med + self.u_amp * (2.0 * phase - 1.0 - 2.0 * k) * (1.0 if k % 2 == 0 else -1.0)

    def shortest_feature(self, t_end: float | None = None) -> tuple[float, str] | None:
        if self.u_amp == 0.0:
            return None
        return 0.5 * self.period, f"a ramp of the triangle wave (half its period of {self.period:g} s)"

    def _parameters(self) -> dict[str, Any]:
        return {"u_med": self.u_med, "u_amp": self.u_amp, "period": self.period}


class Sine(Signal):
    """``u_med + u_amp·sin(2π t/period + phase)`` [V].

    Parameters
    ----------
    u_med : float
        Mean voltage [V].
    u_amp : float
        Amplitude [V].
    period : float
        Period [s], ``> 0``.
    phase : float, optional
        Phase [rad]; ``-pi/2`` starts at the minimum.
    """

    def __init__(self, u_med: float, u_amp: float, period: float, phase: float = 0.0) -> None:
        self.u_med = finite_float("u_med", u_med)
        self.u_amp = finite_float("u_amp", u_amp)
        self.period = positive_float("period", period)
        self.phase = finite_float("phase", phase)
        warn_implausible("phase", self.phase, "angle", "Sine")  # 90 for 90 degrees is 90 rad

    def _values(self, t: np.ndarray) -> np.ndarray:
        return self.u_med + self.u_amp * np.sin(2.0 * math.pi * t / self.period + self.phase)

    def _scalar(self, t: float) -> float:
        return self.u_med + self.u_amp * math.sin(2.0 * math.pi * t / self.period + self.phase)

    def shortest_feature(self, t_end: float | None = None) -> tuple[float, str] | None:
        if self.u_amp == 0.0:
            return None
        return 0.5 * self.period, f"half a period of the sine (period {self.period:g} s)"

    def _parameters(self) -> dict[str, Any]:
        return {"u_med": self.u_med, "u_amp": self.u_amp, "period": self.period, "phase": self.phase}


def _breakpoints(times: Any, values: Any) -> tuple[np.ndarray, np.ndarray]:
    t = finite_array("times", times)
    v = finite_array("values", values)
    if t.size != v.size:
        raise ValueError(f"times and values must have the same length, got {t.size} and {v.size}")
    steps = np.diff(t)
    if (steps <= 0).any():
        i = int(np.argmax(steps <= 0)) + 1
        raise ValueError(f"times must be strictly increasing, got times[{i}] = {float(t[i])!r} after {float(t[i - 1])!r}")
    return t, v


SWITCH_TOLERANCE = 1e-9  #: fraction of ``max(1 s, |t|)`` before a :class:`Steps` switch that counts as at it


class Steps(Signal):
    """Piecewise-constant program: ``values[k]`` from ``times[k]`` until ``times[k+1]``.

    Before ``times[0]`` the signal is ``values[0]``; after the last time it holds the last value.  A
    time within :data:`SWITCH_TOLERANCE` ``max(1 s, |t|)`` before a switch counts as at it: step times
    miss ``k h`` by round-off (3000 steps of 1e-4 s end 1.7e-14 s before 0.3 s).

    Parameters
    ----------
    times : array_like
        Switching times [s], strictly increasing.
    values : array_like
        Voltages [V], one per switching time.
    """

    def __init__(self, times: Any, values: Any) -> None:
        self.times, self.values = _breakpoints(times, values)

    def _values(self, t: np.ndarray) -> np.ndarray:
        at = np.searchsorted(self.times, t + SWITCH_TOLERANCE * np.maximum(1.0, np.abs(t)), side="right") - 1
        return self.values[np.clip(at, 0, None)]

    def shortest_feature(self, t_end: float | None = None) -> tuple[float, str] | None:
        # dwell between successive switches that change the value (only those before t_end)
        change = np.flatnonzero(np.diff(self.values) != 0.0) + 1
        switches = self.times[change]
        if switches.size < 2:
            return None
        dwell = np.diff(switches)
        if t_end is not None:
            dwell = np.where(switches[:-1] < t_end, dwell, np.inf)
        k = int(np.argmin(dwell))
        if not np.isfinite(dwell[k]):
            return None
        return float(dwell[k]), f"the dwell of {float(dwell[k]):g} s from t = {float(switches[k]):g} s of the step program"

    def _parameters(self) -> dict[str, Any]:
        return {"times": self.times.tolist(), "values": self.values.tolist()}


class PiecewiseLinear(Signal):
    """Linear interpolation between points ``(times[k], values[k])``: ramps and holds.

    Parameters
    ----------
    times : array_like
        Times [s], strictly increasing.
    values : array_like
        Voltages [V] at those times.
    outside : {"hold", "error"}, optional
        Outside ``[times[0], times[-1]]``: hold the end value (default) or raise ``ValueError``.
    """

    def __init__(self, times: Any, values: Any, outside: Literal["hold", "error"] = "hold") -> None:
        self.times, self.values = _breakpoints(times, values)
        if outside not in ("hold", "error"):
            raise ValueError(f"outside must be 'hold' or 'error', got {shown(outside)}")
        self.outside = outside

    def _values(self, t: np.ndarray) -> np.ndarray:
        if self.outside == "error":
            bad = (t < self.times[0]) | (t > self.times[-1])
            if bad.any():
                raise ValueError(
                    f"t = {float(t[bad][0])!r} s lies outside the signal's time range "
                    f"[{float(self.times[0])!r}, {float(self.times[-1])!r}] s (outside='error')"
                )
        return np.interp(t, self.times, self.values)

    #: A breakpoint whose slope change exceeds this fraction of the program's steepest slope is
    #: a corner (see :meth:`shortest_feature`).
    KINK_FRACTION = 0.1

    def shortest_feature(self, t_end: float | None = None) -> tuple[float, str] | None:
        """The shortest interval [s] between corners of the program, and what it is.

        A *corner* is a breakpoint where the program reverses (the slope changes sign, a hold
        counting as its own sign: the hysteresis input turns there) or kinks markedly (the
        slope changes by more than :attr:`KINK_FRACTION` of the program's steepest slope).
        Breakpoints where the slope changes a little, as in a smooth curve sampled densely
        (a sine sampled every millisecond has slope changes of ``2 pi dt / period`` of its
        steepest slope), are not corners: a solver step spanning several of them misses at
        most ``|slope change| x step / 4`` of the value at each, which is what a step check
        against the smooth curve allows anyway.  Collinear points are never corners.
        """
        t, v = self.times, self.values
        if t.size < 2:
            return None
        slopes = np.diff(v) / np.diff(t)
        if not np.any(slopes != 0.0):
            return None
        scale = float(np.max(np.abs(slopes)))
        sign = np.sign(slopes)
        change = np.abs(np.diff(slopes))
        corner = (sign[1:] != sign[:-1]) | (change > self.KINK_FRACTION * scale)
        corners = np.concatenate([[t[0]], t[1:-1][corner], [t[-1]]])
        segments = np.diff(corners)
        if t_end is not None:
            segments = segments[corners[:-1] < t_end]
        segments = segments[segments > 0.0]
        if segments.size == 0:
            return None
        k = int(np.argmin(segments))
        return float(segments[k]), f"a segment of {float(segments[k]):g} s between corners (reversals or kinks) of the piecewise-linear program"

    def corner_times(self, t_end: float | None = None) -> np.ndarray:
        """Times [s] of every breakpoint where the slope changes (collinear points left out), up to ``t_end``.

        Used by :func:`exudyn_atcm.solve.run_checks.corners_on_grid`: a program whose corners all
        lie on the solver's step grid is sampled exactly.
        """
        t, v = self.times, self.values
        if t.size < 2:
            return t.copy()
        slopes = np.diff(v) / np.diff(t)
        scale = max(float(np.max(np.abs(slopes))), 1e-300)
        kink = np.abs(np.diff(slopes)) > 1e-12 * scale
        corners = np.concatenate([[t[0]], t[1:-1][kink], [t[-1]]])
        if t_end is not None:
            corners = corners[corners <= t_end]
        return corners

    def _parameters(self) -> dict[str, Any]:
        return {"times": self.times.tolist(), "values": self.values.tolist(), "outside": self.outside}


class ForcProgram(PiecewiseLinear):
    """First-order reversal curves (FORC): the input program that maps the Preisach plane.

    From ``u_min`` (negative saturation) the input rises to ``u_max``; then, for each reversal
    input ``u_r`` from the top down to ``u_min``, it falls from ``u_max`` to ``u_r`` and rises
    back to ``u_max``.  The curve rising from ``u_r`` switches on exactly the relays with
    ``beta >= u_r`` (Mayergoyz 2003), so the set of curves determines the Preisach density
    down to the spacing of the reversal inputs; :meth:`DiscretePreisach.fit
    <exudyn_atcm.hysteresis.DiscretePreisach.fit>` identifies it from such a record like from
    any other.  The program ends with a fall to ``u_min``.  Ramps run at a constant ``rate``.

    Parameters
    ----------
    u_min, u_max : float
        Input range [V], ``u_max > u_min``.
    n_curves : int
        Number of reversal curves, ``>= 1``: reversal inputs
        ``u_max - k (u_max - u_min)/n_curves``, ``k = 1 … n_curves``.
    rate : float
        Ramp rate [V/s], ``> 0``.
    """

    def __init__(self, u_min: float, u_max: float, n_curves: int, rate: float) -> None:
        u_min = finite_float("u_min", u_min)
        u_max = finite_float("u_max", u_max)
        if u_max <= u_min:
            raise ValueError(f"u_max must be > u_min = {u_min!r}, got {shown(u_max)}")
        if isinstance(n_curves, bool) or not isinstance(n_curves, (int, np.integer)) or n_curves < 1:
            raise ValueError(f"n_curves must be an integer >= 1, got {shown(n_curves)}")
        rate = positive_float("rate", rate)
        reversals = u_max - (u_max - u_min) * np.arange(1, n_curves + 1) / n_curves
        corners = [u_min, u_max]
        for r in reversals.tolist():
            corners += [r, u_max]
        corners.append(u_min)
        values = np.array(corners)
        times = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(values)) / rate)])
        self.u_min, self.u_max, self.n_curves, self.rate = u_min, u_max, int(n_curves), rate
        self.reversal_inputs = reversals
        super().__init__(times, values)

    @property
    def duration(self) -> float:
        """Length of the program [s]."""
        return float(self.times[-1])

    def _parameters(self) -> dict[str, Any]:
        return {"u_min": self.u_min, "u_max": self.u_max, "n_curves": self.n_curves, "rate": self.rate}


class CsvSignal(PiecewiseLinear):
    """A voltage time series read from a CSV file, linearly interpolated.

    Lines starting with ``#`` are comments.  The first other line may be a header of column
    names (such as ``time [s],voltage [V]``); columns are chosen by name or by index.  A unit in
    the chosen columns' header (``[ms]``, ``[kV]``, ``[mV]``: the record readers' table,
    :data:`~exudyn_atcm.io.units.SI_SCALE`) is converted to seconds and volts; a column without a
    unit is read as seconds and volts.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    time_column, value_column : str or int, optional
        Column names (with a header) or zero-based indices; by default the columns
        ``time [s]`` and ``voltage [V]`` if the header has them, else columns 0 and 1.
    outside : {"hold", "error"}, optional
        Behaviour outside the file's time range, as in :class:`PiecewiseLinear`.
    """

    def __init__(
        self,
        path: Union[str, Path],
        time_column: Union[str, int, None] = None,
        value_column: Union[str, int, None] = None,
        outside: Literal["hold", "error"] = "hold",
    ) -> None:
        self.path = Path(path)
        header, rows = read_signal_table(self.path)
        t_index = column_index(header, time_column, "time [s]", 0, "time_column", self.path)
        v_index = column_index(header, value_column, "voltage [V]", 1, "value_column", self.path)
        t_scale = header_scale(header, t_index, "s", "time_column", self.path)
        v_scale = header_scale(header, v_index, "V", "value_column", self.path)
        times, values = [], []
        for line_number, row in rows:
            try:
                times.append(float(row[t_index]) * t_scale)
                values.append(float(row[v_index]) * v_scale)
            except (IndexError, ValueError):
                raise ValueError(
                    f"{self.path}: line {line_number} must hold numbers in columns {t_index} and "
                    f"{v_index}, got {shown(row)}"
                ) from None
        if not times:
            raise ValueError(f"{self.path}: no data rows")
        super().__init__(times, values, outside=outside)

    def _parameters(self) -> dict[str, Any]:
        return {"path": str(self.path), "outside": self.outside}


