"""Benchmark of the study engines (issue 10, part 4): throughput, parallel efficiency, per-run overhead.

Side by side in one run, for the same points:

1. A CPU-bound case of about 0.5 s per run (``--target``): ``paper_bending_actuator`` with
   rigid cells, one triangle period whose length is calibrated first so that one run lasts
   about the target on this machine, no files (the points differ in the damping ratio so that no two are
   the same run).  Engines: this process (serial, the reference), the process pool with 1
   and 2 workers, and a Dask ``LocalCluster`` of 2 single-threaded worker processes.
   Reported: runs per second, speed-up over serial, parallel efficiency
   ``speed-up / workers``, and the *busy share* ``sum of run times / (workers x elapsed)``.
2. Per-run overhead with an empty run (the synthetic test case, ~20 µs of work): elapsed
   time per run x workers, for each engine: what the engine costs per run (submission,
   pickling, result transfer, bookkeeping of the study).  Engine start-up (pool, cluster,
   importing and loading the case in each worker) is measured separately (``start``: the
   time to the first results minus one run) and excluded.

Goals (issue 10): parallel efficiency >= 85 % on 2 cores for 0.5 s runs; per-run overhead
< 50 ms with the process pool.  The script reports the figures; it does not fail.
No run store is used (nothing is reused between engines).

Usage: ``python benchmarks/bench_study.py [--runs 8] [--empty-runs 200] [--no-dask]``.
Writes a table to stdout and JSON to ``benchmarks/results/`` (git-ignored).  Default run:
about a minute on an idle 2-core machine.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

from exudyn_atcm import __version__
from exudyn_atcm.casework import load_case
from exudyn_atcm.study import DaskEngine, ProcessEngine, SerialEngine, run_study

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
EMPTY_CASE = REPO / "tests" / "study_cases" / "synthetic_study.py"
HEAVY_FIXED = {"cell": "rigid", "cycles": 1, "period": 2.0, "animation": False, "step": 1e-4}  # the fixed step it was sized for


def _measure(case, points, fixed, engine) -> dict:
    start = time.perf_counter()
    result = run_study(case, points=points, fixed=fixed, engine=engine)
    elapsed = time.perf_counter() - start
    runs = np.array([r["wall_time"] for r in result.records], dtype=float)
    failed = sum(r["status"] != "ok" for r in result.records)
    workers = int(getattr(engine, "workers", 1))
    return {
        "engine": engine.name,
        "workers": workers,
        "runs": len(points),
        "failed": failed,
        "elapsed [s]": elapsed,
        "runs_per_second [1/s]": len(points) / elapsed,
        "mean_run_time [s]": float(runs.mean()),
        "mean_run_cpu_time [s]": float(np.mean([r.get("cpu_time", np.nan) for r in result.records])),
        "busy_share [-]": float(runs.sum() / (workers * elapsed)),
        "overhead_per_run [s]": float((workers * elapsed - runs.sum()) / len(points)),
    }


def _engines(use_dask: bool):
    """(label, factory) of the engines compared; the factories return (engine, start-up time, closer)."""

    def serial():
        return SerialEngine(), 0.0, lambda: None

    def pool(n):
        def make():
            engine = ProcessEngine(n)  # processes start with the first runs (the warm-up)
            return engine, 0.0, engine.close
        return make

    def dask():
        from dask.distributed import Client, LocalCluster

        start = time.perf_counter()
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        engine = DaskEngine(client)

        def close():
            client.close()
            cluster.close()
        return engine, time.perf_counter() - start, close

    engines = [("serial", serial), ("process x1", pool(1)), ("process x2", pool(2))]
    if use_dask:
        engines.append(("dask LocalCluster x2", dask))
    return engines


def heavy_mean(engine, case) -> float:
    """Wall time of the warm-up runs (one per worker, in parallel): about one run."""
    return _LAST_WARM[0]


_LAST_WARM = [0.0]


def _warm(engine, case, fixed, points) -> None:
    """One short study on the engine first: workers import and load the case before timing."""
    result = run_study(case, points=points[: max(1, int(getattr(engine, "workers", 1)))], fixed=fixed, engine=engine)
    _LAST_WARM[0] = max(r["wall_time"] for r in result.records)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="exudyn_atcm study engine benchmark")
    parser.add_argument("--runs", type=int, default=8, help="runs of the 0.5 s case per engine (default 8)")
    parser.add_argument("--empty-runs", type=int, default=200, help="runs of the empty case per engine (default 200)")
    parser.add_argument("--target", type=float, default=0.5, help="wall time of one heavy run [s] (default 0.5)")
    parser.add_argument("--no-dask", action="store_true", help="skip the Dask LocalCluster")
    parser.add_argument("--out", default=str(HERE / "results"))
    args = parser.parse_args(argv)
    use_dask = not args.no_dask
    if use_dask:
        try:
            import dask.distributed  # noqa: F401
        except ImportError:
            print("dask.distributed is not installed: Dask engine skipped (pip install 'exudyn-atcm[distributed]')")
            use_dask = False

    heavy = load_case("paper_bending_actuator", REPO / "cases")
    empty = load_case(EMPTY_CASE)
    # calibrate: the triangle period (simulated time) that makes one run last about --target seconds here
    probe = min(heavy.run({**HEAVY_FIXED, "period": 1.0}, plot=False).wall_time for _ in range(3))  # the first is slower
    period = float(np.clip(round(args.target / probe, 1), 0.2, 20.0))
    HEAVY_FIXED["period"] = period
    heavy_points = [{"damping": float(d)} for d in np.linspace(0.02, 0.03, args.runs)]
    warm_points = [{"damping": 0.019}, {"damping": 0.0191}]
    empty_points = [{"x": float(x)} for x in np.linspace(0.0, 1.0, args.empty_runs)]
    rows = []
    for label, factory in _engines(use_dask):
        engine, startup, close = factory()
        try:
            start = time.perf_counter()
            _warm(engine, heavy, HEAVY_FIXED, warm_points)  # start-up = engine + first runs minus their run time
            startup += time.perf_counter() - start - heavy_mean(engine, heavy)
            heavy_row = _measure(heavy, heavy_points, HEAVY_FIXED, engine)
            _warm(engine, empty, {}, [{"x": -1.0}, {"x": -2.0}])
            empty_row = _measure(empty, empty_points, {}, engine)
        finally:
            close()
        rows.append({"label": label, "startup [s]": startup, "heavy": heavy_row, "empty": empty_row})
        print(f"  {label}: done", file=sys.stderr)

    serial_rate = rows[0]["heavy"]["runs_per_second [1/s]"]
    serial_cpu = rows[0]["heavy"]["mean_run_cpu_time [s]"]
    for row in rows:
        speedup = row["heavy"]["runs_per_second [1/s]"] / serial_rate
        row["speedup [-]"] = speedup
        row["parallel_efficiency [-]"] = speedup / row["heavy"]["workers"]
        # what the efficiency would be with one free core per worker: the share of the workers'
        # time spent in runs, times how much CPU a run needs there compared with serial
        row["efficiency_estimate_free_cores [-]"] = (row["heavy"]["busy_share [-]"]
                                                     * serial_cpu / row["heavy"]["mean_run_cpu_time [s]"])

    print(f"\nStudy engines: {args.runs} runs of ~{rows[0]['heavy']['mean_run_time [s]']:.2f} s "
          f"(paper_bending_actuator, rigid, one {period:g} s period), {args.empty_runs} empty runs; load average "
          f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores\n")
    header = (f"{'engine':<22}{'start [s]':>10}{'run [s]':>9}{'cpu [s]':>9}{'runs/s':>9}{'speed-up':>10}{'efficiency':>12}"
              f"{'busy':>8}{'est. eff.':>11}{'overhead/run (empty)':>22}")
    print(header)
    print("-" * len(header))
    for row in rows:
        h, e = row["heavy"], row["empty"]
        print(f"{row['label']:<22}{row['startup [s]']:>10.2f}{h['mean_run_time [s]']:>9.3f}{h['mean_run_cpu_time [s]']:>9.3f}"
              f"{h['runs_per_second [1/s]']:>9.2f}"
              f"{row['speedup [-]']:>10.2f}{100 * row['parallel_efficiency [-]']:>11.0f}%"
              f"{100 * h['busy_share [-]']:>7.0f}%{100 * row['efficiency_estimate_free_cores [-]']:>10.0f}%"
              f"{1e3 * e['overhead_per_run [s]']:>19.2f} ms")
    print("\nefficiency = speed-up over serial / workers; busy = run time / (workers x elapsed);")
    print("overhead/run = (workers x elapsed - run time) / runs, with the empty case;")
    print("run, cpu = mean wall and CPU time of one run in its worker (cpu << run: the run waited for a core).")
    print("est. eff. = busy x serial CPU per run / CPU per run: the efficiency to expect with a free core per")
    print("worker (an estimate; on a machine shared with other jobs the measured efficiency reflects their load).")
    pool2 = next(r for r in rows if r["label"] == "process x2")
    pool1 = next(r for r in rows if r["label"] == "process x1")
    print(f"\ngoal: efficiency >= 85 % on 2 cores: process x2 {100 * pool2['parallel_efficiency [-]']:.0f} % measured, "
          f"{100 * pool2['efficiency_estimate_free_cores [-]']:.0f} % estimated with free cores "
          f"(load average {os.getloadavg()[0]:.1f})")
    print(f"goal: overhead < 50 ms per run (process pool): x1 {1e3 * pool1['empty']['overhead_per_run [s]']:.2f} ms, "
          f"x2 {1e3 * pool2['empty']['overhead_per_run [s]']:.2f} ms")

    os.makedirs(args.out, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    payload = {
        "benchmark": "bench_study",
        "date": stamp,
        "exudyn_atcm": __version__,
        "python": platform.python_version(),
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
        "load_average_1min": os.getloadavg()[0],
        "heavy_case": {"case": "paper_bending_actuator", **HEAVY_FIXED},
        "rows": rows,
    }
    path = os.path.join(args.out, f"bench_study_{stamp}.json")
    with open(path, "w", encoding="utf-8") as handle:
        json.dump(payload, handle, indent=2, default=float)
    print(f"\nwrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
