"""Optional corrections of a measured record: trimmed start, linear drift, offset, decimation."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .._checks import finite_float, positive_int
from .record import Record

__all__ = ["preprocess"]


def preprocess(
    record: Record,
    *,
    offset_samples: int | None = None,
    drift: bool = False,
    trim_start: float = 0.0,
    decimate: int = 1,
) -> Record:
    """Optional corrections for measured records, each written into ``processing``.

    Applied in this order:

    1. ``trim_start``: drop the samples before ``time[0] + trim_start`` [s] (a settling start).
    2. ``drift``: remove a linear drift of the output, the straight line fitted (least squares)
       through the output at the input's local minima.  At those instants a periodic input is
       in the same state every cycle, so a rate-independent output would repeat: what changes
       is drift.  Needs at least two minima.
    3. ``offset_samples``: subtract the mean output of the first ``offset_samples`` samples
       (the sensor's zero before the excitation).
    4. ``decimate``: replace each block of ``decimate`` samples by its mean (time, input and
       output alike; averaging rather than picking lowers the noise; a trailing partial block
       is dropped and said).

    Parameters
    ----------
    record : Record
        The record.
    offset_samples : int, optional
        Number of leading samples whose mean output is the offset; ``None`` keeps the offset.
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
    """
    if not isinstance(record, Record):
        raise ValueError(f"record must be a Record (see read_record), got {type(record).__name__}")
    trim_start = finite_float("trim_start", trim_start)
    if trim_start < 0.0:
        raise ValueError(f"trim_start must be >= 0 s, got {trim_start!r}")
    decimate = positive_int("decimate", decimate)
    t, u, y = record.time, record.input, record.output
    notes = list(record.processing)
    unit = record.units.get("output", "")
    if trim_start > 0.0:
        keep = t >= t[0] + trim_start
        if keep.sum() < 2:
            raise ValueError(f"trim_start = {trim_start!r} s leaves fewer than 2 samples of the record")
        notes.append(f"trimmed {int((~keep).sum())} samples of the first {trim_start:g} s (settling)")
        t, u, y = t[keep], u[keep], y[keep]
    if drift:
        minima = _local_minima(u)
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
    if offset_samples is not None:
        n = positive_int("offset_samples", offset_samples)
        if n > y.size:
            raise ValueError(f"offset_samples must be <= the number of samples ({y.size}), got {n}")
        offset = float(np.mean(y[:n]))
        y = y - offset
        notes.append(f"removed an output offset of {offset:.6g} {unit} (mean of the first {n} samples)")
    if decimate > 1:
        blocks = t.size // decimate
        if blocks < 2:
            raise ValueError(f"decimate = {decimate} leaves fewer than 2 samples of {t.size}")
        rest = t.size - blocks * decimate
        cut = blocks * decimate

        def mean(a: np.ndarray) -> np.ndarray:
            return a[:cut].reshape(blocks, decimate).mean(axis=1)

        t, u, y = mean(t), mean(u), mean(y)
        notes.append(
            f"decimated by {decimate} (block means)" + (f", dropped the last {rest} samples (partial block)" if rest else "")
        )
    return replace(record, time=t, input=u, output=y, processing=tuple(notes))


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
