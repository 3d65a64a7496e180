"""The workers a search holds over its stages, for its evaluations per core, and one worker for a serial stage.

A differential evolution runs each generation's designs at once on all the workers of its engine;
its polish (Nelder-Mead) asks for one design at a time.  :func:`one_worker_for` gives that stage a
pool of one forked worker in place of a larger one (closed), so that the search does not hold
cores it cannot use, and the one worker keeps its caches warm (a pool's idle workers take the next
run in turn: about 15 % dearer per run on the ``synthesise_path`` case, measured with two workers
against one).  :class:`CoreClock` adds up the workers held times the wall time [s] of each stage.

May import: the study's engines.
"""

from __future__ import annotations

import time
from typing import Any

from .engines import ProcessEngine

__all__ = ["CoreClock", "one_worker_for", "workers_of"]


def workers_of(engine: Any) -> int:
    """The workers an engine runs on (1 for the calling process)."""
    return int(getattr(engine, "workers", 1) or 1)


def one_worker_for(engine: Any) -> Any:
    """The engine for a stage that runs one design at a time: a new pool of one worker in place of a pool
    of several that starts its workers by ``fork`` (closed here; a fork is cheap, where ``forkserver`` and
    ``spawn`` import the case again), else ``engine`` itself."""
    if isinstance(engine, ProcessEngine) and engine.workers > 1 and engine.start_method == "fork":
        engine.close()
        return ProcessEngine(1, start_method="fork")
    return engine


class CoreClock:
    """Wall time [s] times the workers held, stage by stage: :meth:`switch` at each change of engine,
    :meth:`stop` at the end; :attr:`stages` holds ``(workers, seconds)`` per stage."""

    def __init__(self, engine: Any) -> None:
        self.stages: list[tuple[int, float]] = []
        self._workers = workers_of(engine)
        self._since = time.perf_counter()

    def switch(self, engine: Any) -> None:
        """The stage so far ends; the next runs on ``engine``."""
        now = time.perf_counter()
        self.stages.append((self._workers, now - self._since))
        self._workers, self._since = workers_of(engine), now

    def stop(self) -> None:
        """The last stage ends (once; later calls change nothing)."""
        if self._since is not None:
            self.stages.append((self._workers, time.perf_counter() - self._since))
            self._since = None

    @property
    def core_seconds(self) -> float:
        """The sum of workers times wall time [s] over the stages ended."""
        return float(sum(w * s for w, s in self.stages))
