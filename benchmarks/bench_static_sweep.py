"""Quasi-static cycles as one solve (issue 31, part 2).

Times, side by side in one run, for a voltage cycle of 100 points (one period of the drive's
triangle, 0 V -> 1500 V -> 0 V): the per-point static sweep (``static_sweep(..., method="points")``,
each point its own equilibrium in load steps), the continuation sweep (the default: each point one
load step from the last), and the dynamic run of the same cycle (``simulate(mech, period)`` at the
default step 1e-4 s, the README's call).  Each timing includes the build; interleaved, each
``--repeats`` times, the fastest kept (see below).  Both sweeps check the stability of every point.  The
largest difference of the position columns between the two sweeps is printed too, and the
continuation's time without the stability check (a stand-in that looks at nothing; the decomposition
of the cost only: the shipped sweep always checks).
Goal: the continuation sweep at least 3 times cheaper than the dynamic run.

"Continuation before" is the continuation sweep of another revision (``--before``, default ``main``:
its package and cases are exported with ``git archive`` to a temporary folder); "now" is this
revision's.  Every timing is taken in a fresh subprocess per revision and repeat (warmed up first),
the two revisions alternating, the fastest of the repeats kept (the machine's load changes;
processes of the same kind keep the comparison fair).
The second table gives the evaluations per minute per core of the synthesis case's evaluation
(``cases/synthesise_path.py``: build the design's four-bar and sweep its cycle, in process),
before and now, the same way (the case's default cycle: 9 points).

Usage: ``python benchmarks/bench_static_sweep.py [--repeats 3] [--before REV]`` (``--before ""``
leaves the other revision out).  Writes JSON to ``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import importlib.util
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time

import exudyn
import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm.io.atomic import write_text
from exudyn_atcm.solve import mechanism_solve
from exudyn_atcm.model import Triangle
from exudyn_atcm.model.parameter_sets import paper_strain_preisach

from readme_systems import CFC, MFC, readme_four_bar
from unchecked_probe import unchecked_probe

PERIOD = 0.1  # s, the README drive's triangle




def lone(cell: str) -> atcm.Mechanism:
    """A lone actuator with the paper's Preisach operator and a tip load."""
    drive = atcm.PiezoDrive(Triangle(750.0, 750.0, PERIOD), hysteresis=paper_strain_preisach())
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=4, drive=drive, cell=cell)
    m = atcm.Mechanism("lone").add(b).ground(b.base)
    m.force(b.tip, (0.0, -0.02))
    return m


# the README's drive: 0 -> 1500 -> 0 V in a period (until 2026-11-29 the four-bar was built here with a constant
# 750 V, so its "cycle" held one voltage: its figures before then are not a cycle's; see benchmarks/REPORTS.md)
CASES = {"README four-bar": lambda: readme_four_bar(Triangle(750.0, 750.0, PERIOD)), "lone actuator, rigid cells": lambda: lone("rigid"),
         "lone actuator, rod cells": lambda: lone("rod")}


def unchecked_continuation(mech: atcm.Mechanism, volts: np.ndarray):
    """The continuation sweep with the stability check stood in for (a decomposition of the cost only)."""
    original = mechanism_solve.stability_probe
    mechanism_solve.stability_probe = unchecked_probe
    try:
        return atcm.static_sweep(mech, volts)
    finally:
        mechanism_solve.stability_probe = original


def cycle(mech: atcm.Mechanism, n: int = 100) -> np.ndarray:
    drive = next(iter(mech.drives.values()))
    volts = np.array([drive.voltage_at(t) for t in np.linspace(0.0, PERIOD, n)])
    if not np.ptp(volts) > 0.0:  # a constant drive is no cycle (the four-bar's figures were once measured on one)
        raise ValueError(f"cycle: the drive of {mech.name!r} holds {volts[0]:g} V: no cycle to sweep")
    return volts


def timed(fn) -> tuple[float, object]:
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def synthesis_evaluation(cases_dir: str):
    """A function doing one in-process evaluation of the synthesis case's reference design (build and sweep)."""
    spec = importlib.util.spec_from_file_location("bench_synthesise_path", os.path.join(cases_dir, "synthesise_path.py"))
    case = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(case)
    p = case.CASE.resolve({})
    voltages, _, _ = case.cycle(p.n_steps, p.precision_voltages)
    design = case.reference_design(p)
    return lambda: case.solve_design(p, design, "hysteresis", voltages), len(voltages)


def worker(cases_dir: str, repeats: int) -> dict:
    """Best times [s] with the package on the path: per case the per-point and continuation sweeps, the dynamic
    run and the continuation without the check; and the synthesis evaluation.  Warmed up first."""
    out = {}
    for name, make in CASES.items():
        volts = cycle(make())
        atcm.static_sweep(make(), volts)  # warm-up (imports, compiled kernels)
        runs = {"points": lambda: atcm.static_sweep(make(), volts, method="points"),
                "continuation": lambda: atcm.static_sweep(make(), volts),
                "dynamic": lambda: atcm.simulate(make(), PERIOD),
                "unchecked": lambda: unchecked_continuation(make(), volts)}
        for key, run in runs.items():
            out[f"{name}|{key}"] = min(timed(run)[0] for _ in range(repeats))
    evaluate, _ = synthesis_evaluation(cases_dir)
    evaluate()
    out["synthesis"] = min(timed(evaluate)[0] for _ in range(max(3, repeats)))
    return out


def export_revision(rev: str, folder: str) -> None:
    """The package and cases of revision ``rev`` of this repository, unpacked into ``folder``."""
    archive = subprocess.run(["git", "-C", REPO, "archive", rev, "exudyn_atcm", "cases"], check=True,
                             capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", folder], input=archive, check=True)


def run_worker(folder: str) -> dict:
    """:func:`worker` in a subprocess with the package and cases of ``folder`` first on the path."""
    env = dict(os.environ, PYTHONPATH=folder)
    code = (f"import sys, json; sys.path.insert(0, {os.path.dirname(os.path.abspath(__file__))!r}); "
            "import bench_static_sweep as b; "
            f"print(json.dumps(b.worker({os.path.join(folder, 'cases')!r}, 1)))")
    done = subprocess.run([sys.executable, "-c", code], env=env, cwd=folder, check=True, capture_output=True, text=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--before", default="main", help="revision for the 'continuation before' column ('' for none)")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results"))
    args = parser.parse_args()
    scratch = tempfile.TemporaryDirectory(prefix="bench_static_sweep_")  # removed at exit
    folder = scratch.name if args.before else None
    if folder:
        export_revision(args.before, folder)
    before: dict[str, float] = {}
    now: dict[str, float] = {}
    results: dict[str, dict] = {}
    n_points = {name: len(cycle(make())) for name, make in CASES.items()}
    for name, make in CASES.items():  # the equilibria, for the differences (in this process, not timed)
        volts = cycle(make())
        results[name] = {m: atcm.static_sweep(make(), volts, method=m) for m in ("points", "continuation")}
    _, n_synthesis = synthesis_evaluation(os.path.join(REPO, "cases"))
    for repeat in range(args.repeats):  # before and now alternate (which goes first too), each in a fresh process
        pair = ((folder, before), (REPO, now))
        for folder_, store in (pair if repeat % 2 == 0 else pair[::-1]):
            if folder_:
                for key, value in run_worker(folder_).items():
                    store[key] = min(value, store.get(key, math.inf))
    best = {name: {k: now[f"{name}|{k}"] for k in ("points", "continuation", "dynamic", "unchecked")} for name in CASES}
    raw = {"before": dict(before), "now": dict(now)}
    before = {**{name: before.get(f"{name}|continuation", math.nan) for name in CASES},
              "synthesis": before.get("synthesis", math.nan)}
    synthesis_now = now["synthesis"]
    rows = []
    for name in CASES:
        a, b, t = results[name]["points"], results[name]["continuation"], best[name]
        diff = max(float(np.max(np.abs(a[c] - b[c]))) for c in a.names if a.unit(c) == "m")
        rows.append({"case": name, "points": n_points[name], "points_s": t["points"],
                     "continuation_before_s": before.get(name, math.nan), "continuation_s": t["continuation"],
                     "dynamic_s": t["dynamic"], "continuation_without_stability_check_s": t["unchecked"],
                     "dynamic_over_continuation": t["dynamic"] / t["continuation"],
                     "dynamic_over_continuation_before": t["dynamic"] / before.get(name, math.nan),
                     "points_over_continuation": t["points"] / t["continuation"],
                     "before_over_now": before.get(name, math.nan) / t["continuation"],
                     "max_position_difference_m": diff, "fallback_points": b.info["fallback_points"]})
    print(f"{'case':28s} {'per-point':>10s} {'cont. before':>13s} {'cont. now':>10s} {'dynamic':>10s} "
          f"{'now/point':>10s} {'dyn/before':>10s} {'dyn/now':>8s} {'before/now':>10s} {'pts/now':>8s} "
          f"{'max |dx| [m]':>12s} {'now unchecked':>13s}")
    for r in rows:
        print(f"{r['case']:28s} {r['points_s'] * 1e3:7.1f} ms {r['continuation_before_s'] * 1e3:10.1f} ms "
              f"{r['continuation_s'] * 1e3:7.1f} ms {r['dynamic_s'] * 1e3:7.1f} ms "
              f"{r['continuation_s'] / r['points'] * 1e6:7.0f} us {r['dynamic_over_continuation_before']:9.2f}x "
              f"{r['dynamic_over_continuation']:7.2f}x {r['before_over_now']:9.2f}x {r['points_over_continuation']:7.2f}x "
              f"{r['max_position_difference_m']:12.2e} {r['continuation_without_stability_check_s'] * 1e3:10.1f} ms")
    synthesis = {"points": n_synthesis, "before_s": before.get("synthesis", math.nan), "now_s": synthesis_now,
                 "evaluations_per_minute_before": 60.0 / before.get("synthesis", math.nan),
                 "evaluations_per_minute_now": 60.0 / synthesis_now}
    synthesis["now_over_before"] = synthesis["evaluations_per_minute_now"] / synthesis["evaluations_per_minute_before"]
    print(f"\nsynthesis case evaluation (cases/synthesise_path.py, reference design, {n_synthesis}-point sweep, build "
          "included, in process, one core):")
    print(f"  before ({args.before or '-'}): {synthesis['before_s'] * 1e3:.1f} ms = "
          f"{synthesis['evaluations_per_minute_before']:.0f} evaluations/min;  now: {synthesis_now * 1e3:.1f} ms = "
          f"{synthesis['evaluations_per_minute_now']:.0f} evaluations/min ({synthesis['now_over_before']:.2f}x)")
    payload = {"benchmark": "bench_static_sweep", "exudyn_atcm": atcm.__version__, "exudyn": exudyn.__version__,
               "python": platform.python_version(), "machine": platform.machine(), "repeats": args.repeats,
               "before": args.before,
               "goal": "continuation sweep of 100 points at least 3x cheaper than the dynamic run; synthesis "
                       "evaluations per minute per core 3x", "rows": rows, "synthesis": synthesis,
               "best_times_s": raw}
    os.makedirs(args.out, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = os.path.join(args.out, f"bench_static_sweep_{stamp}.json")
    write_text(path, json.dumps(payload, indent=2))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
