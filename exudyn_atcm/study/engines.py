"""Engines that execute the runs of a study: in this process, a process pool, or Dask.

Every engine executes :func:`execute_run` on a case shipped as a :class:`CaseSpec` (name, source
text, fingerprint, the user's modules it reads) and yields the run records in the order the runs
*finish* (the study sorts them back).  Each worker process loads the case once (the pool's
initializer; a per-process cache on Dask workers) and builds one Exudyn system per run.

* :class:`SerialEngine`: runs in the calling process (``workers=1``; debugging).
* :class:`ProcessEngine`: a pool of worker processes on this machine (default: one per
  core), reused for all runs of the study; at most ``2 x workers`` runs are queued at a
  time, so an interrupted study leaves little work in flight.  The workers end with the
  study's process however it ends, ``SIGKILL`` included
  (:func:`~exudyn_atcm.study.parent_watch.end_with_parent`).
* :class:`DaskEngine`: the runs go to the workers of a Dask distributed cluster (a ``Client`` or
  its scheduler's address; ``pip install "exudyn-atcm[distributed]"``).  Workers need this package
  installed, not the case file: the case's source text travels with the runs.
"""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
import multiprocessing
import os
import signal
import socket
import threading
import time
import traceback
from collections.abc import Iterator, Sequence
from typing import Any

from .._checks import shown
from ..casework.termination import STOP_SIGNALS
from .parent_watch import end_with_parent
from .case_spec import CaseSpec, case_spec, load_spec

__all__ = ["CaseSpec", "case_spec", "execute_run", "SerialEngine", "ProcessEngine", "DaskEngine", "make_engine"]

#: A run to execute: (index in the study, run key, parameter values).
Task = tuple[int, str, dict[str, Any]]


def _one_line(exc: BaseException) -> str:
    message = " ".join(str(exc).split())
    return f"{type(exc).__name__}: {message}" if message else type(exc).__name__


def execute_run(spec: CaseSpec, index: int, key: str, values: dict[str, Any]) -> dict[str, Any]:
    """Run the case once; the record of the run (never raises for a failing run).

    The record holds ``key``, ``index``, ``case``, ``values``, ``status`` (``"ok"`` or
    ``"failed"``), ``error`` (one line; empty if ok), ``traceback``, ``scalars`` and
    ``scalar_units`` (the case's key scalars), ``steps``, ``wall_time`` [s], ``cpu_time`` [s]
    (of the worker process; much below ``wall_time`` means the run waited for a core) and
    ``worker``.
    """
    start = time.perf_counter()
    cpu_start = time.process_time()
    record: dict[str, Any] = {
        "key": key,
        "index": int(index),
        "case": spec.name,
        "values": dict(values),
        "status": "ok",
        "error": "",
        "traceback": "",
        "scalars": {},
        "scalar_units": {},
        "steps": None,
        "worker": f"{socket.gethostname()}:{os.getpid()}",
    }
    try:
        case = load_spec(spec)
        output = case.run(values, out_dir=None, plot=False)
        record["scalars"] = {k: float(v) for k, v in output.scalars.items()}
        record["scalar_units"] = dict(output.scalar_units)
        record["steps"] = int(output.steps) if output.steps is not None else None
    except Exception as exc:  # noqa: BLE001 - a failing run is a result of the study
        record["status"] = "failed"
        record["error"] = _one_line(exc)
        record["traceback"] = traceback.format_exc()
    record["wall_time"] = time.perf_counter() - start
    record["cpu_time"] = time.process_time() - cpu_start
    return record


_WORKER_SPEC: CaseSpec | None = None


def _init_worker(spec: CaseSpec, study_pid: int | None = None) -> None:
    global _WORKER_SPEC
    _WORKER_SPEC = spec
    # end with the study's process, however it ends (SIGKILL too): no orphan blocked on the pipe
    if study_pid is not None:
        end_with_parent(study_pid)
    # Ctrl-C in a terminal reaches the whole process group: only the study's process reacts
    # (it stops the workers itself), so no worker dies half-way through a pool operation
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # a forked worker inherits the study's SIGTERM handler (which raises KeyboardInterrupt and
    # would be caught by the pool): SIGTERM ends a worker at once, as by default
    for name in STOP_SIGNALS:
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), signal.SIG_DFL)
    try:
        load_spec(spec)  # once per worker; a failure is reported by each run
    except Exception:  # noqa: BLE001
        pass


def _pool_run(index: int, key: str, values: dict[str, Any]) -> dict[str, Any]:
    assert _WORKER_SPEC is not None
    return execute_run(_WORKER_SPEC, index, key, values)


# ------------------------------------------------------------------------- engines
class SerialEngine:
    """Runs one after another in the calling process."""

    name = "serial"
    workers = 1

    def run(self, spec: CaseSpec, tasks: Sequence[Task]) -> Iterator[dict[str, Any]]:
        """Execute ``tasks``; yields records as runs finish."""
        for index, key, values in tasks:
            yield execute_run(spec, index, key, values)

    def close(self) -> None:
        """Nothing to release."""

    def abort(self) -> None:
        """Stop at once (after an interruption): runs in flight are abandoned."""
        self.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _default_context() -> str:
    methods = multiprocessing.get_all_start_methods()
    if "fork" in methods and threading.active_count() == 1:
        return "fork"  # no re-import of the caller's script: no `if __name__ == "__main__"` needed
    return "forkserver" if "forkserver" in methods else "spawn"


class ProcessEngine(SerialEngine):
    """A pool of worker processes on this machine, reused for all runs.

    Parameters
    ----------
    workers : int, optional
        Number of worker processes (default: ``os.cpu_count()``).
    start_method : str, optional
        ``multiprocessing`` start method.  Default: ``"fork"`` on POSIX when the calling
        process runs a single thread (fast start, and scripts need no
        ``if __name__ == "__main__":`` guard), otherwise ``"forkserver"`` (POSIX) or
        ``"spawn"`` (Windows, macOS), which re-import the calling script in each worker and
        so need that guard, as Exudyn's ``ParameterVariation`` does.
    """

    name = "process"

    def __init__(self, workers: int | None = None, start_method: str | None = None) -> None:
        count = (os.cpu_count() or 1) if workers is None else workers
        if isinstance(count, bool) or not isinstance(count, int) or count < 1:
            raise ValueError(f"workers must be an integer >= 1, got {shown(workers)}")
        self.workers = count
        self.start_method = start_method or _default_context()
        self._pool: cf.ProcessPoolExecutor | None = None
        self._spec: CaseSpec | None = None

    def _start(self, spec: CaseSpec) -> cf.ProcessPoolExecutor:
        if self._pool is None or self._spec != spec:
            self.close()
            context = multiprocessing.get_context(self.start_method)
            if self.start_method == "forkserver":
                context.set_forkserver_preload(["exudyn_atcm.study.engines", "exudyn"])
            self._pool = cf.ProcessPoolExecutor(self.workers, mp_context=context, initializer=_init_worker,
                                                initargs=(spec, os.getpid()))
            self._spec = spec
        return self._pool

    def run(self, spec: CaseSpec, tasks: Sequence[Task]) -> Iterator[dict[str, Any]]:
        """Execute ``tasks`` on the pool (at most ``2 x workers`` queued); yields records as runs finish.

        If a worker process dies (a crash inside a run: a segmentation fault, the memory
        limit), every run in flight is lost with the pool.  The pool is restarted and those
        runs are executed again one at a time: the one that kills its worker again, alone,
        is recorded as failed with that error; the others finish normally.
        """
        pending = list(tasks)[::-1]  # a stack: pop() gives the next run in study order
        suspects: list[Task] = []  # runs lost with a broken pool, to run again one at a time
        alone: Task | None = None  # the suspect running alone now
        window = 2 * self.workers
        in_flight: dict[cf.Future, Task] = {}
        try:
            while pending or suspects or in_flight:
                pool = self._start(spec)
                broken = False
                try:
                    if suspects or alone is not None:
                        if not in_flight:
                            in_flight[pool.submit(_pool_run, *suspects[0])] = suspects[0]
                            alone = suspects.pop(0)
                    else:
                        while pending and len(in_flight) < window:
                            in_flight[pool.submit(_pool_run, *pending[-1])] = pending[-1]
                            pending.pop()
                except cf.process.BrokenProcessPool:
                    broken = True  # it broke since the last results; what is in flight tells more
                done = cf.wait(list(in_flight), return_when=cf.FIRST_COMPLETED)[0] if in_flight else set()
                for future in done:
                    task = in_flight.pop(future)
                    try:
                        yield future.result()
                    except cf.process.BrokenProcessPool as exc:
                        broken = True
                        if task is alone:
                            yield _crash_record(spec, task, exc)
                        else:
                            suspects.append(task)
                    if task is alone:
                        alone = None
                if broken:
                    suspects.extend(in_flight.values())
                    suspects.sort(key=lambda t: t[0])
                    in_flight.clear()
                    alone = None
                    self.close()
        finally:
            for future in in_flight:
                future.cancel()

    def close(self) -> None:
        """Shut the pool down (pending runs are cancelled, running ones finish)."""
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None
            self._spec = None

    def abort(self) -> None:
        """Terminate the worker processes (runs in flight are lost, not stored) and the pool."""
        if self._pool is not None:
            for process in list((getattr(self._pool, "_processes", None) or {}).values()):
                if process.is_alive():
                    process.terminate()
        self.close()


def _crash_record(spec: CaseSpec, task: Task, exc: BaseException | None) -> dict[str, Any]:
    """The record of a run whose worker process died while it ran alone (stored like a failure)."""
    index, key, values = task
    return {
        "key": key,
        "index": index,
        "case": spec.name,
        "values": dict(values),
        "status": "failed",
        "error": "the worker process died during this run (run alone: a crash inside the run, "
                 "e.g. a segmentation fault or the memory limit)",
        "traceback": "" if exc is None else _one_line(exc),
        "scalars": {},
        "scalar_units": {},
        "steps": None,
        "wall_time": float("nan"),
        "cpu_time": float("nan"),
        "worker": "",
    }


def _dask_run(spec: CaseSpec, index: int, key: str, values: dict[str, Any]) -> dict[str, Any]:
    return execute_run(spec, index, key, values)


class DaskEngine(SerialEngine):
    """The runs on a Dask distributed cluster.

    Parameters
    ----------
    client : dask.distributed.Client or str
        A connected client, or the scheduler's address (``"tcp://HOST:8786"``), to which a
        client is connected (and closed again by :meth:`close`).

    Notes
    -----
    Start workers with one thread each (``dask worker ADDRESS --nthreads 1 --nworkers N``):
    each run builds its own Exudyn system, and runs in threads of one process would compete
    for the interpreter.
    """

    name = "dask"

    def __init__(self, client: Any) -> None:
        try:
            from dask.distributed import Client
        except ImportError as exc:  # pragma: no cover - depends on the environment
            raise ImportError(
                'the Dask engine needs dask.distributed: pip install "exudyn-atcm[distributed]"'
            ) from exc
        if isinstance(client, str):
            try:
                self.client = Client(client, timeout="20s")
            except OSError as exc:
                raise ValueError(f"scheduler: cannot connect to the Dask scheduler at {client!r}: {exc}") from None
            except ValueError as exc:  # a malformed address (no port, unknown protocol)
                raise ValueError(f"scheduler must be a Dask scheduler address such as 'tcp://HOST:8786', "
                                 f"got {shown(client)} ({exc})") from None
            self._own = True
        elif isinstance(client, Client):
            self.client = client
            self._own = False
        else:
            raise ValueError(f"client must be a dask.distributed.Client or a scheduler address, got {shown(client)}")
        info = self.client.scheduler_info()
        self.workers = max(1, sum(int(w.get("nthreads", 1)) for w in info.get("workers", {}).values()))

    def run(self, spec: CaseSpec, tasks: Sequence[Task]) -> Iterator[dict[str, Any]]:
        """Submit ``tasks`` (at most ``4 x threads`` queued); yields records as runs finish."""
        from dask.distributed import as_completed

        pending = list(tasks)[::-1]
        window = 4 * self.workers
        [spec_future] = self.client.scatter([spec], broadcast=True, hash=False)
        futures = {}

        def submit(task: Task):
            index, key, values = task
            name = "exudyn-atcm-run-" + hashlib.sha1(f"{key}-{time.time_ns()}".encode()).hexdigest()[:16]
            future = self.client.submit(_dask_run, spec_future, index, key, values, pure=False, key=name)
            futures[future] = task
            return future

        self._futures = futures
        queue = as_completed([submit(pending.pop()) for _ in range(min(window, len(pending)))])
        try:
            for future in queue:
                task = futures.pop(future)
                try:
                    yield future.result()
                except Exception as exc:  # noqa: BLE001 - e.g. KilledWorker
                    record = _crash_record(spec, task, exc)
                    record["error"] = f"Dask could not run it: {_one_line(exc)}; not stored, retried on resume"
                    record["transient"] = True  # e.g. workers lost to the cluster, not to this run
                    yield record
                if pending:
                    queue.add(submit(pending.pop()))
        finally:
            for future in futures:
                future.cancel()

    def close(self) -> None:
        """Close the client if this engine connected it."""
        if self._own:
            self.client.close()

    def abort(self) -> None:
        """Cancel the runs submitted and not finished, then close."""
        for future in list(getattr(self, "_futures", {})):
            future.cancel()
        self.close()


def make_engine(workers: int | None = None, client: Any = None, scheduler: str | None = None):
    """The engine for ``workers`` / ``client`` / ``scheduler`` (see :func:`~exudyn_atcm.study.sweep`)."""
    if client is not None and scheduler is not None:
        raise ValueError("give either client or scheduler, not both")
    if client is not None or scheduler is not None:
        return DaskEngine(client if client is not None else scheduler)
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"workers must be an integer >= 1 (or None: one per core), got {shown(workers)}")
    if workers == 1:
        return SerialEngine()
    return ProcessEngine(workers)
