"""A progress display on simulated time and on the work after it (plots, animations), for terminals.

A case passes ``ctx.progress`` (a :class:`ProgressBar` or a no-op) to anything that can report
how far the simulated time has come, as ``progress(t, t_end)`` with both in seconds;
:func:`~exudyn_atcm.solve.simulation.simulate` calls it every 1 % of ``t_end`` and at least every
0.5 s of wall time, so a run whose simulated time crawls still shows life.  Work after the
simulation (plots, GIF frames) reports through :func:`report_task` (every GIF frame of
:func:`~exudyn_atcm.plots.gif.save_gif`) and :func:`count_task` (every figure of
:func:`~exudyn_atcm.plots.style.save_figure`), which reach the bar made active with
:func:`reporting` (the case runner does this), so the display does not fall silent after 100 %.
A run of several simulations reports the fraction of the whole through
:meth:`ProgressBar.stage` (:class:`~exudyn_atcm.solve.run_plan.RunPlan`).

The bar appears only when the stream is a terminal and the run has lasted ``delay`` seconds
of wall time, so short runs and redirected output stay clean.  It is our own ~100 lines
rather than ``tqdm``: the bar counts simulated seconds, not iterations, and needs stages
after the run; that is no less code with tqdm, and no extra dependency.
"""

from __future__ import annotations

import contextlib
import contextvars
import sys
import time
from collections.abc import Iterator
from typing import IO, Any, Protocol

__all__ = ["ProgressCallback", "ProgressBar", "no_progress", "report_task", "count_task", "reporting", "format_duration"]


class ProgressCallback(Protocol):
    """Called as ``progress(t, t_end)`` with the simulated time reached and the end time [s]."""

    def __call__(self, t: float, t_end: float) -> None: ...


def no_progress(t: float, t_end: float) -> None:
    """A progress callback that does nothing."""


def format_duration(seconds: float, *, rough: bool = False) -> str:
    """A duration [s] as text: ``"42 s"``, ``"3 min 05 s"`` or ``"2 h 07 min"``.

    With ``rough`` (for estimates, whose seconds mean nothing): ``"42 s"`` below 2 min,
    ``"14 min"`` below 2 h, else ``"2.5 h"``.

    >>> format_duration(185.0), format_duration(840.0, rough=True), format_duration(9000.0, rough=True)
    ('3 min 05 s', '14 min', '2.5 h')
    """
    seconds = max(0.0, float(seconds))
    if rough:
        if seconds < 120.0:
            return f"{seconds:.0f} s"
        if seconds < 7200.0:
            return f"{seconds / 60.0:.0f} min"
        return f"{seconds / 3600.0:.1f} h"
    if seconds < 60.0:
        return f"{seconds:.0f} s"
    if seconds < 3600.0:
        minutes, rest = divmod(int(round(seconds)), 60)
        return f"{minutes} min {rest:02d} s"
    hours, rest = divmod(int(round(seconds)), 3600)
    return f"{hours} h {rest // 60:02d} min"


class ProgressBar:
    """Text progress bar ``[#####.....]  52% t = 1.04 / 2 s  3 s elapsed, ETA 3 s`` on a terminal stream.

    Parameters
    ----------
    stream : file-like, optional
        Output stream (default ``sys.stderr``); nothing is drawn unless ``stream.isatty()``
        or ``force`` is true.
    delay : float
        Wall time [s] before the bar first appears.
    width : int
        Number of bar characters.
    force : bool
        Draw even when the stream is not a terminal (for tests).
    """

    def __init__(self, stream: IO[str] | None = None, delay: float = 2.0, width: int = 30, force: bool = False) -> None:
        self.stream = stream if stream is not None else sys.stderr
        isatty = getattr(self.stream, "isatty", None)
        self.enabled = bool(force or (isatty is not None and isatty()))
        self.delay = float(delay)
        self.width = int(width)
        self._start = time.perf_counter()
        self._last_draw = -1.0
        self._drawn = False
        self._length = 0
        self._task: str | None = None
        self._task_start = self._start

    def _ready(self, now: float, final: bool = False) -> bool:
        if now - self._start < self.delay:
            return False
        return final or now - self._last_draw >= 0.1

    def _draw(self, text: str, now: float) -> None:
        pad = max(0, self._length - len(text))
        self.stream.write("\r" + text + " " * pad)
        self.stream.flush()
        self._length = len(text)
        self._last_draw = now
        self._drawn = True

    def _bar(self, share: float) -> str:
        filled = int(round(share * self.width))
        return "[" + "#" * filled + "." * (self.width - filled) + "]"

    @staticmethod
    def _timing(elapsed: float, share: float) -> str:
        text = f"{format_duration(elapsed)} elapsed"
        if 0.0 < share < 1.0:
            text += f", ETA {format_duration(elapsed * (1.0 - share) / share)}"
        return text

    def __call__(self, t: float, t_end: float) -> None:
        if not self.enabled or t_end <= 0.0:
            return
        now = time.perf_counter()
        if not self._ready(now):
            return
        share = min(max(t / t_end, 0.0), 1.0)
        elapsed = now - self._start
        self._draw(f"{self._bar(share)} {100 * share:3.0f}% t = {t:.4g} / {t_end:.4g} s  {self._timing(elapsed, share)}", now)

    def task(self, label: str, done: int, total: int | None) -> None:
        """Report work after the simulation: ``label done/total`` (e.g. plots, GIF frames).

        ``total`` ``None``: open-ended work (figures written one by one), drawn as ``label: done``.
        """
        if not self.enabled or (total is not None and total <= 0):
            return
        now = time.perf_counter()
        if label != self._task:
            self._task, self._task_start = label, now
        if not self._ready(now, final=total is not None and done >= total):
            return
        elapsed = now - self._task_start
        if total is None:
            self._draw(f"{label}: {done}  {format_duration(elapsed)} elapsed", now)
            return
        share = min(max(done / total, 0.0), 1.0)
        self._draw(f"{self._bar(share)} {label} {done}/{total}  {self._timing(elapsed, share)}", now)

    def stage(self, label: str, share: float, detail: str = "") -> None:
        """Report a run of several parts: ``share`` of the whole done, in part ``label`` (e.g. ``simulation 2/4``).

        The elapsed time and the ETA are those of the whole run
        (:class:`~exudyn_atcm.solve.run_plan.RunPlan` calls this).
        """
        if not self.enabled:
            return
        now = time.perf_counter()
        share = min(max(float(share), 0.0), 1.0)
        if not self._ready(now, final=share >= 1.0):
            return
        text = f"{label}: {detail}" if detail else label
        self._draw(f"{self._bar(share)} {100 * share:3.0f}% {text}  {self._timing(now - self._start, share)}", now)

    def close(self) -> None:
        """End the bar's line if anything was drawn."""
        if self._drawn:
            self.stream.write("\n")
            self.stream.flush()
            self._drawn = False
            self._length = 0


_ACTIVE: contextvars.ContextVar[Any] = contextvars.ContextVar("exudyn_atcm_progress", default=None)
_COUNTS: contextvars.ContextVar[dict | None] = contextvars.ContextVar("exudyn_atcm_progress_counts", default=None)


@contextlib.contextmanager
def reporting(progress: Any) -> Iterator[None]:
    """Make ``progress`` (an object with ``task(label, done, total)``) receive :func:`report_task` calls."""
    token = _ACTIVE.set(progress)
    counts = _COUNTS.set({})
    try:
        yield
    finally:
        _COUNTS.reset(counts)
        _ACTIVE.reset(token)


def report_task(label: str, done: int, total: int | None) -> None:
    """Report ``done`` of ``total`` units of the work ``label`` to the active progress display, if any.

    ``total`` ``None`` for open-ended work (see :func:`count_task`).
    """
    active = _ACTIVE.get()
    task = getattr(active, "task", None)
    if task is not None:
        task(label, done, total)


def count_task(label: str) -> int:
    """One more unit of open-ended work ``label`` (e.g. a figure written); reports the count so far.

    The count starts at 0 in each :func:`reporting` block; outside one nothing is reported and 0
    is returned.
    """
    counts = _COUNTS.get()
    if counts is None:
        return 0
    counts[label] = counts.get(label, 0) + 1
    report_task(label, counts[label], None)
    return counts[label]
