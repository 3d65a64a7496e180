"""Helpers for tests that check that no BLAS worker is left spinning (Linux: the threads' CPU time from /proc)."""

from __future__ import annotations

import os
import time
from typing import Callable

#: whether the threads' CPU time can be read
HAS_PROC = os.path.isdir("/proc/self/task")


def other_threads_ticks() -> int:
    """CPU clock ticks (10 ms) used so far by the process's threads other than the main one."""
    ticks = 0
    for tid in os.listdir("/proc/self/task"):
        if int(tid) != os.getpid():
            with open(f"/proc/self/task/{tid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            ticks += int(fields[11]) + int(fields[12])
    return ticks


def ticks_after(call: Callable[[], object], settle: float = 0.3) -> int:
    """The other threads' ticks during ``call()`` and ``settle`` seconds after it (a spinning worker runs on after
    the call; OpenBLAS's for about 0.1 s).  ``call`` is run once before, to warm up."""
    call()
    time.sleep(settle)
    before = other_threads_ticks()
    call()
    time.sleep(settle)
    return other_threads_ticks() - before
