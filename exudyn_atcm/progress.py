"""A progress bar on simulated time, for terminals only.

A case passes ``ctx.progress`` (a :class:`ProgressBar` or a no-op) to anything that can report
how far the simulated time has come, as ``progress(t, t_end)`` with both in seconds.  The bar
appears only when the stream is a terminal and the run has lasted ``delay`` seconds of wall
time, so short runs and redirected output stay clean.
"""

from __future__ import annotations

import sys
import time
from typing import IO, Protocol

__all__ = ["ProgressCallback", "ProgressBar", "no_progress"]


class ProgressCallback(Protocol):
    """Called as ``progress(t, t_end)`` with the simulated time reached and the end time [s]."""

    def __call__(self, t: float, t_end: float) -> None: ...


def no_progress(t: float, t_end: float) -> None:
    """A progress callback that does nothing."""


class ProgressBar:
    """Text progress bar ``[#####.....]  52% t = 1.04 / 2 s`` on a terminal stream.

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

    def __call__(self, t: float, t_end: float) -> None:
        if not self.enabled or t_end <= 0.0:
            return
        now = time.perf_counter()
        if now - self._start < self.delay or now - self._last_draw < 0.1:
            return
        self._last_draw = now
        share = min(max(t / t_end, 0.0), 1.0)
        filled = int(round(share * self.width))
        bar = "#" * filled + "." * (self.width - filled)
        self.stream.write(f"\r[{bar}] {100 * share:3.0f}% t = {t:.4g} / {t_end:.4g} s")
        self.stream.flush()
        self._drawn = True

    def close(self) -> None:
        """End the bar's line if anything was drawn."""
        if self._drawn:
            self.stream.write("\n")
            self.stream.flush()
            self._drawn = False
