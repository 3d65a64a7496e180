"""A measured record: time, input and output arrays with their units, names and processing notes."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .._checks import finite_float, shown

__all__ = ["Record"]


@dataclass(frozen=True)
class Record:
    """A measured record: three equally long 1-D arrays and their units.

    Attributes
    ----------
    time : numpy.ndarray
        Sample times [s], strictly increasing.
    input, output : numpy.ndarray
        Input (e.g. voltage [V]) and output (e.g. displacement [m]) samples.
    units : dict
        Units of ``"time"``, ``"input"``, ``"output"`` (``""`` where the file gave none).
    names : dict
        Column names of ``"time"``, ``"input"``, ``"output"`` in the file (without units).
    processing : tuple of str
        Every change made since the file was read (dropped rows, offset, drift, trim,
        decimation, split), in order, with the amounts.
    source : str
        Where the record came from (file path).
    """

    time: np.ndarray
    input: np.ndarray
    output: np.ndarray
    units: dict = field(default_factory=lambda: {"time": "s", "input": "", "output": ""})
    names: dict = field(default_factory=lambda: {"time": "time", "input": "input", "output": "output"})
    processing: tuple = ()
    source: str = ""

    def __post_init__(self) -> None:
        t = np.asarray(self.time, dtype=float)
        u = np.asarray(self.input, dtype=float)
        y = np.asarray(self.output, dtype=float)
        if not (t.ndim == u.ndim == y.ndim == 1) or not (t.size == u.size == y.size):
            raise ValueError(
                f"time, input and output must be 1-D arrays of one length, got sizes {t.size}, {u.size}, {y.size}"
            )
        if t.size >= 2 and np.any(np.diff(t) <= 0.0):
            i = int(np.argmax(np.diff(t) <= 0.0)) + 1
            raise ValueError(
                f"time must be strictly increasing, got time[{i}] = {float(t[i])!r} s after {float(t[i - 1])!r} s"
                + (f" in {self.source}" if self.source else "")
            )
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "input", u)
        object.__setattr__(self, "output", y)

    @property
    def n_samples(self) -> int:
        """Number of samples."""
        return int(self.time.size)

    def __len__(self) -> int:
        return self.n_samples

    def split_index(self, t_split: float) -> int:
        """Index of the first sample at or after ``t_split`` [s] (the start of the held-out part)."""
        t_split = finite_float("t_split", t_split)
        if not self.time[0] < t_split <= self.time[-1]:
            raise ValueError(
                f"t_split must lie in ({float(self.time[0])!r}, {float(self.time[-1])!r}] s (inside the record), "
                f"got {shown(t_split)}"
            )
        return int(np.searchsorted(self.time, t_split, side="left"))

    def split(self, t_split: float) -> tuple["Record", "Record"]:
        """The part before ``t_split`` [s] (to fit on) and the part from ``t_split`` on (held out).

        A hysteresis model's prediction of the held-out part depends on the memory built by the
        first part: run the model over the whole record and compare on the held-out samples
        (the fits of :mod:`exudyn_atcm.hysteresis.identification` take ``n_fit`` for this).
        """
        k = self.split_index(t_split)
        note = f"split at t = {t_split:g} s: samples [0, {k}) and [{k}, {self.n_samples})"
        first = self._take(slice(0, k), note + ", this is the first part")
        second = self._take(slice(k, None), note + ", this is the second part")
        return first, second

    def _take(self, index: Any, note: str) -> "Record":
        return replace(
            self, time=self.time[index], input=self.input[index], output=self.output[index],
            processing=self.processing + (note,),
        )

    def label(self, which: str) -> str:
        """``"name [unit]"`` of ``"time"``, ``"input"`` or ``"output"``."""
        unit = self.units.get(which, "")
        return f"{self.names[which]} [{unit}]" if unit else self.names[which]
