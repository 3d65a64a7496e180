"""A lock on a study's output table, so that two studies never write the same table at once.

Two ``exudyn-atcm sweep`` commands with the same ``--out`` and case (two terminals, a job
started twice on a cluster) would each write ``<case>_sweep.csv`` from their own runs, and the
last to finish would silently replace the other's table.  :class:`TableLock` holds an
operating-system lock (``fcntl.flock``; ``msvcrt.locking`` on Windows) on a file
``.<case>_sweep.lock`` beside the table for the whole study.  The lock ends with the process
that holds it, however it ends (even ``SIGKILL``), so a killed study never blocks the next.
The file itself stays (it is empty of meaning once unlocked) and holds the holder's process id,
host and start time for the message.
"""

from __future__ import annotations

import datetime as _dt
import os
import socket
from pathlib import Path
from typing import IO

from ..io.atomic import WriteError, describe_os_error

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None
    import msvcrt

__all__ = ["TableLock", "StudyLockedError"]


class StudyLockedError(RuntimeError):
    """Another study is writing the same table now; the message names it and what to do."""


def _try_lock(handle: IO[str]) -> bool:
    """Take the lock of ``handle`` without waiting; False if another process holds it."""
    if fcntl is None:  # pragma: no cover - Windows
        try:
            msvcrt.locking(handle.fileno(), msvcrt.LK_NBLCK, 1)
        except OSError:
            return False
        return True
    try:
        fcntl.flock(handle.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return False
    return True


class TableLock:
    """Exclusive lock on the table ``table`` for the duration of a ``with`` block.

    Parameters
    ----------
    table : str or os.PathLike
        The table file the study will write (its directory must exist).
    what : str
        What holds the lock, for the message of a second study (e.g. the command line).

    Raises
    ------
    StudyLockedError
        On entering, if another process holds the lock: the message names the table, the
        holder's process id, host and start time, and the choices (wait, or another ``--out``).
    WriteError
        If the lock file cannot be created.
    """

    def __init__(self, table: str | os.PathLike, what: str = "a study") -> None:
        self.table = Path(table)
        self.path = self.table.with_name(f".{self.table.stem}.lock")
        self.what = what
        self._handle: IO[str] | None = None

    def __enter__(self) -> "TableLock":
        try:
            handle = open(self.path, "a+", encoding="utf-8")
        except OSError as exc:
            raise WriteError(f"cannot create the lock file {str(self.path)!r}: {describe_os_error(exc)}") from None
        if not _try_lock(handle):
            handle.seek(0)
            holder = handle.read().strip() or "another process"
            handle.close()
            raise StudyLockedError(
                f"another study is writing {str(self.table)!r} now ({holder}); wait until it ends, or give this one "
                f"another output directory (--out); its lock file is {str(self.path)!r}"
            )
        handle.seek(0)
        handle.truncate()
        started = _dt.datetime.now().astimezone().isoformat(timespec="seconds")
        handle.write(f"pid {os.getpid()} on {socket.gethostname()}, started {started}: {self.what}\n")
        handle.flush()
        self._handle = handle
        return self

    def __exit__(self, *exc: object) -> None:
        if self._handle is not None:
            try:
                self._handle.seek(0)
                self._handle.truncate()
            except OSError:  # pragma: no cover - the lock still ends with close()
                pass
            self._handle.close()  # releases the lock
            self._handle = None
