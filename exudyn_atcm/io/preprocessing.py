"""Optional corrections of a measured record: linear drift, offset (from the rest before the excitation), trimmed start, decimation."""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from typing import Any

import numpy as np

from .._checks import finite_float, positive_int, shown
from ..errors import AccuracyWarning
from .record import Record

__all__ = ["preprocess"]


def preprocess(
    record: Record,
    *,
    offset_samples: int | None = None,
    offset_window: tuple[float, float] | None = None,
    drift: bool = False,
    trim_start: float = 0.0,
    decimate: int = 1,
) -> Record:
    """Optional corrections for measured records, each written into ``processing``.

    Applied in this order, on the record's own time axis:

    1. ``drift``: remove a linear drift of the output, the straight line fitted (least squares)
       through the output at the input's local minima after the settling start
       (``trim_start``).  At those instants a periodic input is in the same state every cycle,
       so a rate-independent output would repeat: what changes is drift.  Needs at least two
       minima.  The line is subtracted from the whole record as ``slope (t - time[0])``, so the
       output keeps its level at the record's start.
    2. the offset: subtract the mean output over ``offset_window`` (``(t0, t1)`` [s], the
       sensor's zero while the actuator is at rest) or over the first ``offset_samples``
       samples of the record as given, *before* the start is trimmed: the rest before the
       excitation is usually what the trim removes.  If the input or the output varies over
       these samples by more than their noise suggests, an
       :class:`~exudyn_atcm.errors.AccuracyWarning` says so (see Warns).
    3. ``trim_start``: drop the samples before ``time[0] + trim_start`` [s] (a settling start).
    4. ``decimate``: replace each block of ``decimate`` samples by its mean (time, input and
       output alike; averaging rather than picking lowers the noise; a trailing partial block
       is dropped and said).

    Parameters
    ----------
    record : Record
        The record.
    offset_samples : int, optional
        Number of leading samples whose mean output is the offset; ``None`` keeps the offset.
    offset_window : (float, float), optional
        Times ``t0 < t1`` [s] on the record's time axis (as in ``record.time``, before any
        trim) whose samples' mean output is the offset; not together with ``offset_samples``.
    drift : bool, optional
        Remove the linear output drift (default ``False``).
    trim_start : float, optional
        Settling time trimmed from the start [s], ``>= 0``.
    decimate : int, optional
        Block length of the decimation, ``>= 1`` (1: none).

    Returns
    -------
    Record
        A new record; the original is unchanged.

    Raises
    ------
    ValueError
        For a negative ``trim_start``, ``decimate < 1``, both offset arguments, an
        ``offset_window`` that is not ``(t0, t1)`` with ``t0 < t1`` or holds no sample, more
        ``offset_samples`` than samples, or steps that leave fewer than 2 samples.

    Warns
    -----
    AccuracyWarning
        When the offset samples are not at rest: over at least 3 samples, the input or output
        spreads (standard deviation) by more than 3 times its sample-to-sample noise
        (the robust spread of successive differences over ``√2``) *and* by more than 1 % of
        its range over the record; the mean then is not the sensor's zero (a window that
        reaches into the excitation).  The 1 % floor keeps filtered (correlated) noise, whose
        successive differences understate it, from warning.
    """
    if not isinstance(record, Record):
        raise ValueError(f"record must be a Record (see read_record), got {type(record).__name__}")
    trim_start = finite_float("trim_start", trim_start)
    if trim_start < 0.0:
        raise ValueError(f"trim_start must be >= 0 s, got {shown(trim_start)}")
    decimate = positive_int("decimate", decimate)
    if offset_samples is not None and offset_window is not None:
        raise ValueError(
            f"give the offset by offset_samples or by offset_window, not both; got offset_samples = {offset_samples!r} "
            f"and offset_window = {offset_window!r}"
        )
    t, u, y = record.time, record.input, record.output
    notes = list(record.processing)
    unit = record.units.get("output", "")
    keep = t >= t[0] + trim_start
    if trim_start > 0.0 and keep.sum() < 2:
        raise ValueError(f"trim_start = {trim_start!r} s leaves fewer than 2 samples of the record")
    if drift:
        kept = np.flatnonzero(keep)
        minima = kept[_local_minima(u[kept])]
        if minima.size < 2:
            raise ValueError(
                f"drift=True needs at least 2 local minima of the input to estimate a drift, found {minima.size}"
            )
        slope, _ = np.polyfit(t[minima], y[minima], 1)
        y = y - slope * (t - t[0])
        notes.append(
            f"removed a linear output drift of {slope:.6g} {unit}/s (fitted through the output at "
            f"{minima.size} input minima)"
        )
    if offset_samples is not None or offset_window is not None:
        rest, where = _offset_samples(t, offset_samples, offset_window)
        offset = float(np.mean(y[rest]))
        _check_at_rest(record, u, y, rest, where, offset)
        y = y - offset
        notes.append(f"removed an output offset of {offset:.6g} {unit} (mean of {where})")
    if trim_start > 0.0:
        notes.append(f"trimmed {int((~keep).sum())} samples of the first {trim_start:g} s (settling)")
        t, u, y = t[keep], u[keep], y[keep]
    if decimate > 1:
        blocks = t.size // decimate
        if blocks < 2:
            raise ValueError(f"decimate = {decimate} leaves fewer than 2 samples of {t.size}")
        rest_count = t.size - blocks * decimate
        cut = blocks * decimate

        def mean(a: np.ndarray) -> np.ndarray:
            return a[:cut].reshape(blocks, decimate).mean(axis=1)

        t, u, y = mean(t), mean(u), mean(y)
        notes.append(
            f"decimated by {decimate} (block means)"
            + (f", dropped the last {rest_count} samples (partial block)" if rest_count else "")
        )
    return replace(record, time=t, input=u, output=y, processing=tuple(notes))


def _offset_samples(t: np.ndarray, offset_samples: Any, offset_window: Any) -> tuple[slice | np.ndarray, str]:
    """The samples whose mean output is the offset, and how to call them in notes."""
    if offset_samples is not None:
        n = positive_int("offset_samples", offset_samples)
        if n > t.size:
            raise ValueError(f"offset_samples must be <= the number of samples ({t.size}), got {n}")
        return slice(0, n), f"the first {n} samples"
    try:
        t0, t1 = offset_window
    except (TypeError, ValueError):
        raise ValueError(f"offset_window must be a pair (t0, t1) of times [s], got {shown(offset_window)}") from None
    t0, t1 = finite_float("offset_window[0]", t0), finite_float("offset_window[1]", t1)
    if not t0 < t1:
        raise ValueError(f"offset_window must have t0 < t1, got {shown(offset_window)}")
    inside = np.flatnonzero((t >= t0) & (t <= t1))
    if inside.size == 0:
        raise ValueError(
            f"offset_window = ({t0:g}, {t1:g}) s holds no sample of the record (its times run from "
            f"{float(t[0]):g} to {float(t[-1]):g} s, on the record's own time axis)"
        )
    return inside, f"the {inside.size} samples in t = {t0:g} ... {t1:g} s"


#: a window's spread must exceed this many times its sample-to-sample noise to count as motion
REST_NOISE_FACTOR = 3.0
#: ... and this fraction of the signal's range over the record
REST_RANGE_FRACTION = 0.01


def _moving(values: np.ndarray, whole: np.ndarray) -> tuple[float, float] | None:
    """``(spread, noise)`` of ``values`` when they are not at rest (see :func:`preprocess`), else ``None``."""
    if values.size < 3:
        return None
    spread = float(np.std(values))
    steps = np.diff(values)
    noise = 1.4826 * float(np.median(np.abs(steps - np.median(steps)))) / math.sqrt(2.0)
    if spread > REST_NOISE_FACTOR * noise and spread > REST_RANGE_FRACTION * float(np.ptp(whole)):
        return spread, noise
    return None


def _check_at_rest(record: Record, u: np.ndarray, y: np.ndarray, rest: Any, where: str, offset: float) -> None:
    problems = []
    for role, values in (("input", u), ("output", y)):
        found = _moving(values[rest], values)
        if found is not None:
            unit = record.units.get(role, "")
            problems.append(
                f"the {role} spreads by {found[0]:.3g} {unit} (standard deviation; "
                f"{100.0 * found[0] / float(np.ptp(values)):.2g} % of its range over the record), "
                f"{found[0] / max(found[1], 1e-300):.3g} times its sample-to-sample noise"
            )
    if problems:
        warnings.warn(
            f"preprocess: the offset samples ({where}) are not at rest: " + "; ".join(problems)
            + f"; their mean output {offset:.6g} {record.units.get('output', '')} is then not the sensor's zero. "
            "Give offset_window=(t0, t1) [s] (record time) over samples before the excitation starts",
            AccuracyWarning,
            stacklevel=3,
        )


def _local_minima(u: np.ndarray) -> np.ndarray:
    """Indices of the input's cycle minima: the lowest sample of every falling-then-rising stretch.

    Reversals smaller than 5 % of the input range are ignored (noise).
    """
    tolerance = 0.05 * float(np.ptp(u)) if u.size else 0.0
    minima = []
    low_index = 0
    falling = True
    high = low = float(u[0])
    for i, v in enumerate(u.tolist()):
        if falling:
            if v < low:
                low, low_index = v, i
            elif v > low + tolerance:
                minima.append(low_index)
                falling, high = False, v
        else:
            if v > high:
                high = v
            elif v < high - tolerance:
                falling, low, low_index = True, v, i
    if falling and low_index not in minima and low_index != 0:
        minima.append(low_index)
    return np.asarray(minima, dtype=int)
