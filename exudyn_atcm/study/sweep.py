"""Parameter studies: run a case over many points, in parallel, resumably.

>>> from exudyn_atcm.casework import load_case
>>> from exudyn_atcm.study import RunOptions, sweep
>>> case = load_case("paper_stroke_table")
>>> table = sweep(case, {"period": [1.0, 2.0], "points_per_period": [10, 20]},
...               run=RunOptions(out="out/study"))  # doctest: +SKIP

See :doc:`/studies` for engines (process pool, Dask), resuming and the command line.
"""

from __future__ import annotations

import os
import time
from collections import Counter
from contextlib import nullcontext
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._checks import hide_keywords, option_values, options_from_keywords
from ..io.atomic import make_directory, write_json
from .._version import __version__
from ..casework import Case, load_case, versions
from .design import GridError, check_point, explicit_points, full_grid, sample_points
from .engines import case_spec, make_engine
from .lock import TableLock
from .options import RunOptions
from .inputs import environment, run_identity, run_inputs
from .store import RunStore, run_key, run_key_before_inputs
from .table import Column, StudyTable, table_columns, to_table, write_table_csv

__all__ = ["sweep", "run_study", "StudyResult", "study_points", "StudyProgress"]

#: ``progress(done, total, failed)``: runs finished (reused ones included), runs in the study, runs failed.
StudyProgress = Callable[[int, int, int], None]


@dataclass
class StudyResult:
    """The outcome of :func:`run_study`.

    Attributes
    ----------
    table : StudyTable
        One row per point (see :mod:`exudyn_atcm.study.table`); ``table.to_pandas()`` for a DataFrame.
    records : list of dict
        The run records in study order (``values``, ``status``, ``error``, ``scalars`` ...).
    columns : list of Column
        The table's columns (names, units, values).
    varied : list of str
        The parameters that vary between the points (in the order given).
    executed : int
        Runs executed by this call (the others came from the store or were duplicates).
    reused : int
        Points answered from the store.
    stale : int
        Runs executed again because the store held a result of the same case and parameter
        values computed from other inputs (a changed file a parameter names, case source or
        version); each record's ``stale`` says what changed (``""`` if nothing).
    failed : int
        Rows whose run failed.
    csv_path : pathlib.Path or None
        The table's CSV file (with ``out``).
    wall_time : float
        Wall time of the study [s].
    engine : str
        ``serial``, ``process`` or ``dask``.
    """

    table: StudyTable
    records: list[dict[str, Any]]
    columns: list[Column]
    varied: list[str]
    executed: int = 0
    reused: int = 0
    stale: int = 0
    failed: int = 0
    csv_path: Path | None = None
    wall_time: float = 0.0
    engine: str = "serial"
    workers: int = 1
    files: list[Path] = field(default_factory=list)


def _as_case(case: Case | str | os.PathLike) -> Case:
    return case if isinstance(case, Case) else load_case(case)


def study_points(
    case: Case,
    grid: Mapping[str, Any] | None = None,
    *,
    samples: int | None = None,
    bounds: Mapping[str, tuple[float, float]] | None = None,
    method: str = "lhs",
    seed: int | None = 0,
    points: Sequence[Mapping[str, Any]] | None = None,
) -> list[dict[str, Any]]:
    """The points of a study (see :func:`sweep` for the arguments): grid x samples, or explicit points."""
    if points is not None:
        if grid or samples is not None or bounds:
            raise GridError("give either points or grid/samples, not both")
        return explicit_points(case, points)
    if samples is None and bounds:
        raise GridError("bounds are for sampling: give samples=N as well (or use grid= for a full grid)")
    base = full_grid(case, grid) if grid else [{}]
    if samples is not None:
        if not bounds:
            raise GridError("samples needs bounds={name: (low, high)} of the sampled parameters")
        overlap = sorted(set(bounds) & set(grid or {}))
        if overlap:
            raise GridError(f"parameters {overlap} are both in grid and in bounds")
        drawn = sample_points(case, bounds, samples, method=method, seed=seed)
        return [{**g, **s} for g in base for s in drawn]
    if not grid:
        raise GridError("nothing to vary: give grid={name: values}, samples=N with bounds, or points=[...]")
    return base


def _varied(points: Sequence[Mapping[str, Any]]) -> list[str]:
    names: list[str] = []
    for point in points:
        for name in point:
            if name not in names:
                names.append(name)
    return [n for n in names if len({repr(p.get(n)) for p in points}) > 1]


@hide_keywords
def run_study(
    case: Case | str | os.PathLike,
    grid: Mapping[str, Any] | None = None,
    *,
    samples: int | None = None,
    bounds: Mapping[str, tuple[float, float]] | None = None,
    method: str = "lhs",
    seed: int | None = 0,
    points: Sequence[Mapping[str, Any]] | None = None,
    fixed: Mapping[str, Any] | None = None,
    run: RunOptions | None = None,
    engine: Any = None,
    **legacy: Any,
) -> StudyResult:
    """Run a study and return everything about it (:func:`sweep` returns only the table).

    Parameters are those of :func:`sweep`; ``engine`` (an object from
    :mod:`exudyn_atcm.study.engines`) replaces ``run.workers``/``run.client``/``run.scheduler`` and is
    left open (for a caller that runs several studies on one pool).

    A ``KeyboardInterrupt`` (Ctrl-C; ``SIGTERM`` inside
    :func:`~exudyn_atcm.casework.termination.stop_signals_as_interrupt`) stops the workers at once and
    propagates with three attributes: ``stored_runs`` (distinct runs of the study in the store
    now), ``distinct_runs`` (distinct runs of the study) and ``store_directory`` (``None``
    without a store), so that the caller can say what a new start will resume from.
    """
    start = time.perf_counter()
    (run,) = options_from_keywords("run_study", legacy, run=(RunOptions, run))
    workers, client, scheduler, out, store, retry_failed, progress, use_pandas = option_values(run)
    case = _as_case(case)
    spec = case_spec(case)
    fixed_values = check_point(case, fixed or {})
    pts = study_points(case, grid, samples=samples, bounds=bounds, method=method, seed=seed, points=points)
    clash = sorted(set(fixed_values) & {n for p in pts for n in p})
    if clash:
        raise GridError(f"parameters {clash} are both fixed and varied")
    full = [dict(case.resolve({**fixed_values, **p})) for p in pts]
    versions_now = environment()
    inputs = [run_inputs(case, spec.fingerprint, values, versions_now) for values in full]
    keys = [run_key(spec.fingerprint, values, inputs=given) for values, given in zip(full, inputs)]

    out_dir = make_directory(out) if out is not None else None
    lock = TableLock(out_dir / f"{case.name}_sweep.csv", f"sweep of {case.name}") if out_dir is not None else nullcontext()
    with lock:
        return _run_locked(case, spec, fixed_values, pts, full, keys, inputs, out_dir, store, retry_failed, progress,
                           use_pandas, engine, workers, client, scheduler, start)


def _run_locked(case: Case, spec: Any, fixed_values: dict[str, Any], pts: list[dict[str, Any]], full: list[dict[str, Any]],
                keys: list[str], inputs: list[dict[str, Any]], out_dir: Path | None, store: Any, retry_failed: bool, progress: StudyProgress | None,
                use_pandas: bool | None, engine: Any, workers: int | None, client: Any, scheduler: str | None,
                start: float) -> StudyResult:
    """The body of :func:`run_study` once the table is locked (two studies never write one table)."""
    if isinstance(store, RunStore):
        run_store: RunStore | None = store
    elif store is not None:
        run_store = RunStore(store)
    elif out_dir is not None:
        run_store = RunStore(out_dir / "runs")
    else:
        run_store = None

    by_key: dict[str, dict[str, Any]] = {}
    reused = 0
    for key in dict.fromkeys(keys):
        record = run_store.load(key) if run_store is not None else None
        if record is not None and (record.get("status") == "ok" or not retry_failed):
            by_key[key] = record
            reused += 1
    todo = []
    queued: set[str] = set()
    for index, (key, values) in enumerate(zip(keys, full)):
        if key not in by_key and key not in queued:
            queued.add(key)
            todo.append((index, key, values))
    rows_of = Counter(keys)
    inputs_of = dict(zip(keys, inputs))
    identity_of = {key: run_identity(case, values, given) for key, values, given in zip(keys, full, inputs)}
    stale = {key: run_store.why_stale(identity_of[key], key, inputs_of[key], run_key_before_inputs(spec.fingerprint, values))
             for _, key, values in todo} if run_store is not None else {}

    total = len(pts)
    done = sum(1 for k in keys if k in by_key)
    failed = sum(1 for k in keys if k in by_key and by_key[k]["status"] != "ok")
    if progress is not None:
        progress(done, total, failed)
    executed = 0
    own_engine = engine is None
    runner = make_engine(workers, client, scheduler) if own_engine else engine
    try:
        if todo:
            for record in runner.run(spec, todo):
                executed += 1
                record["inputs"] = inputs_of[record["key"]]
                if run_store is not None and not record.get("transient"):
                    run_store.save(record)
                    run_store.remember(identity_of[record["key"]], record["key"], record["inputs"])
                by_key[record["key"]] = record
                n_rows = rows_of[record["key"]]
                done += n_rows
                failed += n_rows if record["status"] != "ok" else 0
                if progress is not None:
                    progress(done, total, failed)
    except BaseException as exc:
        # interrupted (Ctrl-C, a failing progress callback ...): finished runs are stored;
        # stop the workers at once instead of waiting for the runs in flight
        runner.abort()
        if isinstance(exc, KeyboardInterrupt):  # say what a new start would find
            # counted in the store itself: a signal between saving a run and noting it here must not undercount
            exc.stored_runs = sum(1 for k in set(keys) if k in run_store) if run_store is not None else 0
            exc.distinct_runs = len(set(keys))
            exc.store_directory = run_store.directory if run_store is not None else None
        raise
    finally:
        if own_engine:
            runner.close()

    records = []
    for index, (key, values) in enumerate(zip(keys, full)):
        record = dict(by_key[key])
        record["index"] = index
        record["values"] = values
        record["stale"] = stale.get(key, "")
        records.append(record)
    columns = table_columns(case, records)
    result = StudyResult(
        table=to_table(columns, use_pandas=use_pandas),
        records=records,
        columns=columns,
        varied=_varied(pts),
        executed=executed,
        reused=reused,
        stale=sum(1 for key in set(keys) if stale.get(key)),
        failed=sum(1 for r in records if r["status"] != "ok"),
        engine=runner.name,
        workers=int(getattr(runner, "workers", 1)),
    )
    result.wall_time = time.perf_counter() - start
    if out_dir is not None:
        comments = {"case": case.name, "exudyn_atcm": __version__, "runs": total, "failed": result.failed}
        result.csv_path = write_table_csv(out_dir / f"{case.name}_sweep.csv", columns, comments)
        info = {
            "case": case.name,
            "source": spec.path,
            "varied": result.varied,
            "fixed": {k: list(v) if isinstance(v, tuple) else v for k, v in fixed_values.items()},
            "runs": total,
            "executed": executed,
            "reused_from_store": reused,
            "stale": {reason: n for reason, n in Counter(stale[k] for k in set(keys) if stale.get(k)).items()},
            "failed": result.failed,
            "engine": result.engine,
            "workers": result.workers,
            "store": str(run_store.directory) if run_store is not None else None,
            "wall_time [s]": result.wall_time,
            "versions": versions(),
        }
        json_path = write_json(out_dir / f"{case.name}_sweep.json", info)
        result.files = [result.csv_path, json_path]
    return result


@hide_keywords
def sweep(
    case: Case | str | os.PathLike,
    grid: Mapping[str, Any] | None = None,
    *,
    samples: int | None = None,
    bounds: Mapping[str, tuple[float, float]] | None = None,
    method: str = "lhs",
    seed: int | None = 0,
    points: Sequence[Mapping[str, Any]] | None = None,
    fixed: Mapping[str, Any] | None = None,
    run: RunOptions | None = None,
    **legacy: Any,
):
    """Run a case over many parameter points and return the table of results.

    Parameters
    ----------
    case : Case or str or os.PathLike
        A loaded case (:func:`~exudyn_atcm.casework.discovery.load_case`) or its name or file.
    grid : mapping of str to list or array, optional
        Full grid: every combination of the values (the last name varies fastest), e.g.
        ``{"n_cells": [2, 4, 8], "period": np.linspace(0.5, 2.0, 4)}``.
    samples : int, optional
        Number of sampled points within ``bounds`` (crossed with ``grid`` if both are given).
    bounds : mapping of str to (low, high), optional
        Ranges of the sampled float or int parameters (integers inclusive).
    method : {"lhs", "random"}
        Sampling: Latin hypercube (:class:`scipy.stats.qmc.LatinHypercube`) or uniform.
    seed : int or None
        Seed of the sampler (default 0: the same points every time, so a study resumes).
    points : sequence of mapping, optional
        An explicit list of points instead of ``grid``/``samples``.
    fixed : mapping, optional
        Values of further parameters, the same for every run (others keep their defaults).
    run : RunOptions, optional
        Where the runs execute and are stored (:class:`~exudyn_atcm.study.options.RunOptions`:
        ``workers``, ``client``, ``scheduler``, ``out``, ``store``, ``retry_failed``, ``progress``,
        ``use_pandas``).  With ``out``, the directory gets ``<case>_sweep.csv`` (the table, units
        in the header), ``<case>_sweep.json`` (what was run, how) and, unless ``store`` is given,
        the run store ``runs/``.  These names as flat keywords (``sweep(..., workers=2)``, the
        earlier signature) still work for one release, with an
        :class:`~exudyn_atcm.AtcmDeprecationWarning`.

    Returns
    -------
    StudyTable
        The same type whatever is installed (``.to_pandas()``, ``.to_numpy()`` convert it).
        One row per point in the study's order: ``run [-]``, the case's parameters, its key
        scalars, ``status [-]``, ``error [-]``, ``stale [-]``, ``wall_time [s]``, ``key [-]`` (all ``name [unit]``).
        Identical (bar wall times) whatever the engine or number of workers.

    Raises
    ------
    GridError
        For an unknown parameter (the closest name is suggested), a value of the wrong
        type, an empty range or ``samples < 1``.
    CaseError
        If the case cannot be loaded or has no source file.
    exudyn_atcm.study.lock.StudyLockedError
        If another study is writing the same table (``out`` and case) now.
    exudyn_atcm.io.atomic.WriteError
        (an ``OSError``) if ``out`` or the store cannot be created, naming it and the reason.

    Notes
    -----
    A run that raises is recorded with status ``failed`` and its error and does not stop
    the study.  Each finished run is stored at once under a hash of the case (name and
    source text), all its parameter values and the package version; running the same
    study again (after an interruption, or with more points) executes only the runs not
    yet stored.
    """
    (run,) = options_from_keywords("sweep", legacy, run=(RunOptions, run))
    return run_study(case, grid, samples=samples, bounds=bounds, method=method, seed=seed, points=points, fixed=fixed,
                     run=run).table
