"""Ctrl-C and wall time around a time integration: a clean stop that keeps what was computed.

* :class:`SimulationInterrupted` -- the exception a stopped run raises, with the partial result;
* :class:`InterruptGuard` -- turns Ctrl-C inside a solver hook into a clean stop;
* :class:`WallClock` -- calls a progress callback by share of the run or by wall time.

The names are also importable from :mod:`exudyn_atcm.solve.run_checks`.
"""

from __future__ import annotations

import time
from typing import Any, Callable

__all__ = ["SimulationInterrupted", "InterruptGuard", "WallClock", "is_interrupt"]


class SimulationInterrupted(KeyboardInterrupt):
    """Ctrl-C (or ``KeyboardInterrupt`` from a hook) stopped a time integration.

    A ``KeyboardInterrupt``, so an uncaught one still ends a script as Ctrl-C does;
    catch it to use what was computed.

    Attributes
    ----------
    time : float
        Time [s] of the last accepted step.
    result : Result or None
        The steps computed so far (``result.info["partial"]`` is True), or ``None``.
    """

    def __init__(self, time: float, result: Any = None) -> None:
        super().__init__(f"interrupted at t = {time:.6g} s")
        self.time = time
        self.result = result

    def __str__(self) -> str:
        return str(self.args[0])


def is_interrupt(exc: BaseException) -> bool:
    """Whether an Exudyn failure was a ``KeyboardInterrupt`` raised inside a user function
    (Exudyn reports it in the text of its own error)."""
    return "KeyboardInterrupt" in str(exc)


def _caused_by_interrupt(exc: BaseException) -> bool:
    """Whether ``KeyboardInterrupt`` is in the cause/context chain of ``exc``."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False


class InterruptGuard:
    """Wraps solver hooks so that ``KeyboardInterrupt`` inside them stops the solver cleanly.

    A Ctrl-C during the solver's C++ code surfaces in the next Python hook.  Raised through
    Exudyn it becomes a solver failure with a meaningless time; instead, a wrapped hook
    catches it, remembers it and returns ``False``, which tells Exudyn to stop after the
    current step.  After the solve, :attr:`interrupted` says whether that happened.

    Examples
    --------
    >>> guard = InterruptGuard()
    >>> hook = guard.wrap(lambda t: None)
    >>> hook(0.1), guard.interrupted
    (True, False)
    """

    def __init__(self) -> None:
        self.interrupted = False
        self.at: float | None = None

    def wrap(self, hook: Callable[[float], Any] | None) -> Callable[[float], bool] | None:
        """``hook`` made to return ``True`` (go on) or ``False`` (stop: interrupted)."""
        if hook is None:
            return None

        def guarded(t: float) -> bool:
            if self.interrupted:
                return False
            try:
                hook(t)
            except KeyboardInterrupt:
                self.interrupted = True
                self.at = t
                return False
            except SystemError as exc:
                # a Ctrl-C that lands while a C function returns inside the hook surfaces as
                # "SystemError: ... returned a result with an exception set", caused by the
                # KeyboardInterrupt: still an interrupt, not a fault of the model
                if not _caused_by_interrupt(exc):
                    raise
                self.interrupted = True
                self.at = t
                return False
            return True

        return guarded


class WallClock:
    """Calls ``callback(t, t_end)`` every ``share`` of ``t_end`` or every ``interval`` seconds of wall time.

    So a progress display moves both on fast runs (by simulated time) and on runs whose
    simulated time crawls (by wall time).
    """

    def __init__(self, callback: Callable[[float, float], None] | None, t_end: float,
                 share: float = 0.01, interval: float = 0.5) -> None:
        self.callback = callback
        self.t_end = t_end
        self.share = share
        self.interval = interval
        self._next_t = 0.0
        self._next_wall = time.perf_counter() + interval

    def __call__(self, t: float) -> None:
        if self.callback is None:
            return
        now = time.perf_counter()
        if t >= self._next_t or now >= self._next_wall:
            self.callback(t, self.t_end)
            self._next_t = t + self.share * self.t_end
            self._next_wall = now + self.interval
