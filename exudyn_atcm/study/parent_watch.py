"""Worker processes that end when the study's process is gone.

A process-pool worker waits for work on a pipe from the study's process.  If that process
is killed (``SIGKILL`` from the kernel's out-of-memory killer or a scheduler, ``SIGTERM``
when it has no handler), nothing tells the worker: it stays blocked on the pipe for good,
holding its memory (about 80 MB with Exudyn loaded) and the caller's terminal or log file.
:func:`end_with_parent`, run in each worker when it starts, makes it end with its parent:

* on Linux, ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` (through ``ctypes``): the kernel kills the
  worker the moment its parent process ends, even in the middle of a run;
* on every platform, a daemon thread that checks every :data:`POLL_INTERVAL` seconds whether
  the parent changed (``os.getppid()``: an orphan is adopted by another process) or the study's
  process no longer exists, and then ends the worker with ``os._exit``.

Both act only when the parent is gone; a worker never ends a study that is still running.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import signal
import sys
import threading
import time

__all__ = ["end_with_parent", "POLL_INTERVAL", "parent_alive"]

#: Seconds between two checks of the watchdog thread.
POLL_INTERVAL = 0.5

_PR_SET_PDEATHSIG = 1


def _set_death_signal() -> bool:
    """Ask the Linux kernel to send ``SIGKILL`` to this process when its parent ends; True if set."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        return libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0
    except (OSError, AttributeError):  # pragma: no cover - no libc or no prctl
        return False


def parent_alive(parent: int, study: int) -> bool:
    """Whether this process's parent is still ``parent`` and the study's process ``study`` exists."""
    if os.getppid() != parent:
        return False
    try:
        os.kill(study, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # pragma: no cover - exists, owned by someone else
        return True
    return True


def _watch(parent: int, study: int) -> None:
    while True:
        time.sleep(POLL_INTERVAL)
        if not parent_alive(parent, study):
            os._exit(1)


def end_with_parent(study_pid: int) -> None:
    """Make this (worker) process end when its parent or the study's process ``study_pid`` ends.

    Call it first thing in a worker process (a pool initializer).  The parent is the
    process that started the worker: the study's process, or the fork server of the
    ``forkserver`` start method, which ends with the study's process.

    Parameters
    ----------
    study_pid : int
        Process id of the study's process (``os.getpid()`` there, passed to the worker).
    """
    parent = os.getppid()
    _set_death_signal()
    if not parent_alive(parent, study_pid):  # gone before the death signal was set
        os._exit(1)
    threading.Thread(target=_watch, args=(parent, study_pid), name="exudyn-atcm-parent-watch", daemon=True).start()
