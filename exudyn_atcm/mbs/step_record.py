"""Every accepted solver step, stored in preallocated blocks: the one recorder of every solve (simulate, the static solves, add_to).

Internal API of the Exudyn layer (documented for tests and benchmarks; used through :class:`~exudyn_atcm.mbs.stepping.Stepping`).  A run's post-step hook
writes one row of floats per accepted step (time first, then what the path needs to rebuild
its result columns: voltages, strains, coordinates, forces) between :meth:`StepRecord.begin`
and :meth:`StepRecord.end`.  The rows go into a preallocated block of
:attr:`StepRecord.block_rows` rows, not into Python lists, so the per-step cost is a few element
writes and memory is 8 bytes per value.

Two things are made from the rows:

* the **record**: the rows the :class:`~exudyn_atcm.model.recording.RecordingSchedule` keeps
  (``record_every``), plus the last accepted step, kept whole; the run's
  :class:`~exudyn_atcm.Result` is built from them;
* the **every-step columns**: when the schedule thins the record, each full block is reduced
  (``reduce(rows) -> 2-D array``, vectorised) to the columns a case computes its scalars from
  (:attr:`exudyn_atcm.Result.every_step`), so extremes, crossings and last-cycle figures do
  not depend on how often the run is recorded.  When every step is recorded they are the
  record itself and nothing is reduced.

Long runs spill: once the kept rows exceed :data:`SPILL_BYTES`, full blocks are appended to
an anonymous temporary file instead of being held in memory, and read back once when the
result is made (the memory peak of a long every-step record is then one block plus the
result's own columns).
"""

from __future__ import annotations

import tempfile
from typing import Callable

import numpy as np

__all__ = ["StepRecord", "check_view", "BLOCK_ROWS", "SPILL_BYTES"]

#: Rows per preallocated block.
BLOCK_ROWS = 4096

#: Kept rows held in memory before further blocks are written to a temporary file [bytes].
SPILL_BYTES = 64 * 2**20


class StepRecord:
    """Rows of ``width`` floats, one per accepted step, in preallocated blocks.

    Parameters
    ----------
    width : int
        Floats per row (time first).
    keep : callable
        ``keep(t) -> bool``, called once per accepted step in order: whether the step belongs
        to the record (:meth:`RecordingSchedule.take <exudyn_atcm.model.recording.RecordingSchedule.take>`).
    reduce : callable, optional
        ``reduce(rows) -> ndarray`` of shape ``(len(rows), k)``: the every-step columns of a
        block of rows.  ``None`` when every step is recorded (the record is every step).
    on_block : callable, optional
        ``on_block(rows)`` for every block of accepted rows (for checks over every step, e.g.
        the range of the voltages and strains).
    block_rows : int, optional
        Rows per block (default :data:`BLOCK_ROWS`).
    spill_bytes : int, optional
        Kept bytes held in memory before blocks spill to a temporary file (default
        :data:`SPILL_BYTES`).
    """

    def __init__(self, width: int, keep: Callable[[float], bool], reduce: Callable[[np.ndarray], np.ndarray] | None = None,
                 on_block: Callable[[np.ndarray], None] | None = None, block_rows: int = BLOCK_ROWS,
                 spill_bytes: int = SPILL_BYTES) -> None:
        if width < 1 or block_rows < 1:
            raise ValueError(f"width and block_rows must be >= 1, got {width} and {block_rows}")
        self.width = int(width)
        self.block_rows = int(block_rows)
        self.spill_bytes = int(spill_bytes)
        self._keep = keep
        self._reduce = reduce
        self._on_block = on_block
        self._block = np.empty((self.block_rows, self.width))
        self._kept_flags = np.zeros(self.block_rows, dtype=bool)
        self._n = 0
        self._kept: list[np.ndarray] = []
        self._kept_rows = 0
        self._spill = None
        self._spilled_rows = 0
        self._did_spill = False
        self._last_kept = False
        self._every: list[np.ndarray] = []
        #: accepted steps added so far
        self.accepted = 0
        #: the last row added (a view; valid until the next :meth:`add`)
        self.last: np.ndarray | None = None

    # ------------------------------------------------------------------ hot path
    def begin(self, t: float) -> np.ndarray:
        """The row of the accepted step ending at ``t`` [s], time written; fill it, then call :meth:`end`."""
        row = self._block[self._n]
        row[0] = t
        return row

    def end(self, t: float) -> None:
        """Close the row :meth:`begin` gave (the schedule decides whether it joins the record)."""
        n = self._n
        self._kept_flags[n] = self._keep(t)
        self.accepted += 1
        self.last = self._block[n]
        self._n = n + 1
        if self._n == self.block_rows:
            self._flush(close=False)

    # ------------------------------------------------------------------ blocks
    def _flush(self, close: bool) -> None:
        n = self._n
        if n == 0:
            if close and self.last is not None and not self._last_kept:
                # the last accepted step ended a block that the schedule skipped: it closes the record
                self._store(self.last[None, :].copy())
                self._last_kept = True
            return
        rows = self._block[:n]
        flags = self._kept_flags[:n]
        if close and not flags[-1]:
            flags[-1] = True  # the end of the run is always in the record
        self._last_kept = bool(flags[-1])
        if self._on_block is not None:
            self._on_block(rows)
        if self._reduce is not None:
            self._every.append(np.asarray(self._reduce(rows), dtype=float))
        if flags.all():
            kept = rows
            if n == self.block_rows:  # keep this block itself, take a fresh one
                self._block = np.empty((self.block_rows, self.width))
            else:
                kept = rows.copy()
        else:
            kept = rows[flags].copy()
        self._store(kept)
        self._n = 0
        self._kept_flags[:] = False

    def _store(self, kept: np.ndarray) -> None:
        if not kept.size:
            return
        if self._spill is None and (self._kept_rows + len(kept)) * self.width * 8 > self.spill_bytes:
            self._spill = tempfile.TemporaryFile(prefix="exudyn_atcm_record_")
            self._did_spill = True
        if self._spill is not None:
            np.ascontiguousarray(kept).tofile(self._spill)
            self._spilled_rows += len(kept)
        else:
            self._kept.append(kept)
            self._kept_rows += len(kept)

    def close(self) -> None:
        """Flush the last block; the last accepted step joins the record if the schedule skipped it."""
        self._flush(close=True)

    # ------------------------------------------------------------------ results
    @property
    def spilled(self) -> bool:
        """Whether some kept rows were written to the temporary file during the run."""
        return self._did_spill

    def rows(self) -> np.ndarray:
        """The kept rows, shape ``(n, width)`` (call :meth:`close` first)."""
        parts = list(self._kept)
        if self._spill is not None:
            self._spill.seek(0)
            spilled = np.fromfile(self._spill, dtype=float, count=self._spilled_rows * self.width)
            parts.append(spilled.reshape(self._spilled_rows, self.width))
            self._spill.close()
            self._spill = None
            self._kept = [np.concatenate(parts)] if parts else []
            self._kept_rows += self._spilled_rows
            self._spilled_rows = 0
            return self._kept[0] if self._kept else np.empty((0, self.width))
        if not parts:
            return np.empty((0, self.width))
        return parts[0] if len(parts) == 1 else np.concatenate(parts)

    def every_step(self) -> np.ndarray | None:
        """The every-step columns of all accepted steps (``None`` without ``reduce``)."""
        if not self._every:  # no reduce, or nothing recorded
            return None
        return np.concatenate(self._every) if len(self._every) > 1 else self._every[0]


def check_view(view: np.ndarray, fresh: np.ndarray) -> None:
    """Refuse a record read through a view of Exudyn's coordinates that no longer is Exudyn's vector.

    Exudyn 1.13 keeps the current coordinates in one vector for the whole run
    (``tests/test_step_record_view.py``); should a later version move it, the record would be
    stale, so this raises instead of returning it.
    """
    if not np.shares_memory(view, fresh):
        raise RuntimeError("Exudyn moved its coordinate vector during the run, so the recorded states are stale; "
                           "this Exudyn version is not supported by the recorder (exudyn==1.13.* is)")
