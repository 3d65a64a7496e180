"""Stop signals of schedulers and services handled like Ctrl-C.

``timeout``, batch schedulers (Slurm, PBS), ``docker stop`` and systemd stop a program with
``SIGTERM`` (a closed terminal sends ``SIGHUP``); Python's default is to die at once, writing
nothing.  Inside :func:`stop_signals_as_interrupt` these signals raise ``KeyboardInterrupt``
as Ctrl-C does, so every path that handles Ctrl-C (a simulation writing what it computed,
marked partial; a study stopping its workers and keeping its stored runs) handles them too.
The command line then exits with the shell's status for the signal, ``128 + signal number``
(143 for ``SIGTERM``, 129 for ``SIGHUP``, 130 for Ctrl-C).

A signal the process ignores when the block starts (``nohup`` ignores ``SIGHUP``) stays
ignored.  Only the first stop signal raises; later ones are ignored until the block ends, so
that writing the partial result is not interrupted in turn.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from types import FrameType

__all__ = ["StopSignal", "stop_signals_as_interrupt", "STOP_SIGNALS"]

#: Signals turned into ``KeyboardInterrupt`` (those that exist on the platform).
STOP_SIGNALS = ("SIGTERM", "SIGHUP")


@dataclass
class StopSignal:
    """Which stop signal arrived inside :func:`stop_signals_as_interrupt` (``None``: none, or Ctrl-C).

    Attributes
    ----------
    signum : int or None
        The signal number, ``None`` if no stop signal arrived.
    """

    signum: int | None = None

    @property
    def name(self) -> str:
        """``"SIGTERM"``, ``"SIGHUP"``, or ``"SIGINT"`` when no stop signal arrived (Ctrl-C)."""
        return signal.Signals(self.signum).name if self.signum is not None else "SIGINT"

    @property
    def exit_status(self) -> int:
        """``128 + signal number`` (130 for Ctrl-C, 143 for ``SIGTERM``)."""
        return 128 + (self.signum if self.signum is not None else int(signal.SIGINT))

    def describe(self) -> str:
        """``"interrupted (Ctrl-C)"`` or ``"terminated (SIGTERM)"``, for messages."""
        return "interrupted (Ctrl-C)" if self.signum is None else f"terminated ({self.name})"


@contextmanager
def stop_signals_as_interrupt() -> Iterator[StopSignal]:
    """Within the block, ``SIGTERM`` and ``SIGHUP`` raise ``KeyboardInterrupt`` like Ctrl-C.

    Yields
    ------
    StopSignal
        Filled in when a stop signal arrives (its ``exit_status`` is the command's).

    Notes
    -----
    Signal handlers can only be set in the main thread; elsewhere the block changes nothing.
    The previous handlers are restored when the block ends.
    """
    received = StopSignal()
    if threading.current_thread() is not threading.main_thread():
        yield received
        return

    def handler(signum: int, frame: FrameType | None) -> None:
        if received.signum is None:
            received.signum = signum
            raise KeyboardInterrupt(signal.Signals(signum).name)

    previous = {}
    for name in STOP_SIGNALS:
        number = getattr(signal, name, None)
        if number is None or signal.getsignal(number) is signal.SIG_IGN:
            continue
        previous[number] = signal.signal(number, handler)
    try:
        yield received
    finally:
        for number, old in previous.items():
            signal.signal(number, old if old is not None else signal.SIG_DFL)
