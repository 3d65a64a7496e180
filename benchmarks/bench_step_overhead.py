"""The package's Python work per solver step, against Exudyn's own floor, and the memory of a long record.

For each system (the lone actuator of the paper's Fig. 12 with rigid cells; the compliant
four-bar, one drive; the micro-gripper, two drives; 8 rigid cells per bender) one run of
``t_sim`` at step 1e-4 s with the paper's continuous Preisach operator in the step, driven by
``Triangle(500, 1000, 0.5)`` V from -500 V (over the default 0.2 s the rising branch to 1100 V: no
reversal is timed), with the package's
pre-step and post-step hooks timed from the inside (``time.perf_counter`` around each call;
the instrumentation itself adds about 0.1 us per call):

* ``pre [us/step]``: the hooks before every attempted step (voltage, hysteresis trial, strains
  written into the model), per attempted step;
* ``post [us/step]``: the hooks after every accepted step (hysteresis commit, recording), per
  accepted step;
* ``budget [us/step]``: the goal of 10 us per drive plus 2 us per recorded channel (the floats
  written per step: time, voltage and strain per drive, the coordinates the result needs,
  spring forces);
* ``run [s/s]``: the whole run's wall time per simulated second; ``exudyn [s/s]`` the same
  minus the hooks' time: Exudyn's own work (Newton iterations included) *and* the package's work
  around the steps (the build, the initial equilibrium, the run's checks, the result), which a
  one-step run measures at 4-13 ms, 8-12 % of the column at the default 0.2 s.

Exudyn's floor: a system with one point mass on a linear spring and trivial ``PreStep`` and
``PostStep`` Python functions (``return True``), integrated with the same solver settings and
step: the cheapest a run with Python hooks can be.

``--rod-mass`` compares the two ways the ``rod`` cell hands its mass matrix (rewritten every step)
to Exudyn, on the four-bar and the gripper with 4-mode rods at step 5e-4 s, interleaved: a
``massMatrixUserFunction`` (what a user's system after ``add_to`` gets) and the item's parameter
re-read by the solver (``reuseConstantMassMatrix = False``, the package's own runs).  Cost:
(best run of ``t_sim``) - (best run of one step), per simulated second.

``--memory`` measures, in child processes, the peak resident memory added by recording every
step of a long run of the Fig. 12 actuator (default 20 s, 200,001 rows, six-bar cells): peak RSS of
the run minus the peak RSS of the same process after a 0.01 s run.

Usage: ``python benchmarks/bench_step_overhead.py [--t-sim 0.2] [--repeats 3] [--rod-mass] [--memory [--memory-t 20]]``.
Prints a table and writes JSON to ``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import platform
import resource
import subprocess
import sys
import time
import warnings
from pathlib import Path

import exudyn

from exudyn_atcm import __version__, simulate
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.mbs import solver_runs

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_systems as bm  # noqa: E402 - the mechanisms of the mechanism benchmarks

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
STEP = 1e-4  # s
CELLS = 8


class HookTimer:
    """``solver_runs.run_dynamic`` with its two hooks timed from the inside."""

    def __init__(self) -> None:
        self.pre = self.post = 0.0
        self.pre_calls = self.post_calls = 0
        self._original = solver_runs.run_dynamic

    def __enter__(self) -> "HookTimer":
        original = self._original

        def timed_run(model, settings, pre_step, post_step):
            def pre(t):
                start = time.perf_counter()
                try:
                    return pre_step(t)
                finally:
                    self.pre += time.perf_counter() - start
                    self.pre_calls += 1

            def post(t):
                start = time.perf_counter()
                try:
                    return post_step(t)
                finally:
                    self.post += time.perf_counter() - start
                    self.post_calls += 1

            return original(model, settings, None if pre_step is None else pre, post)

        solver_runs.run_dynamic = timed_run
        return self

    def __exit__(self, *exc) -> None:
        solver_runs.run_dynamic = self._original


def actuator(n_cells: int, cell: str):
    module = bm.case_module("paper_bending_actuator")
    return module.build(module.CASE.resolve({"cell": cell, "n_cells": n_cells}))


SYSTEMS = {
    "actuator": (lambda: actuator(3, "rigid"), 1),
    "four_bar": (lambda: bm.four_bar(CELLS, "rigid"), 1),
    "gripper": (lambda: bm.gripper(CELLS, "rigid"), 2),
}


def channels(result) -> int:
    """Floats recorded per step: the width of the recorder's row minus the time."""
    return int(result.info.get("recorded_channels", 0))


def measure(build, t_sim: float) -> dict:
    system = build()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        with HookTimer() as timer:
            start = time.perf_counter()
            result = simulate(system, t_sim, step=STEP)
            wall = time.perf_counter() - start
    hooks = timer.pre + timer.post
    return {"run_s_per_s": wall / t_sim, "exudyn_s_per_s": (wall - hooks) / t_sim,
            "pre_us": 1e6 * timer.pre / max(timer.pre_calls, 1), "post_us": 1e6 * timer.post / max(timer.post_calls, 1),
            "attempted": timer.pre_calls, "accepted": timer.post_calls, "channels": channels(result)}


def exudyn_floor(t_sim: float, step: float = STEP) -> float:
    """Wall seconds per simulated second of a one-mass Exudyn system with trivial Python hooks, at ``step`` [s]."""
    import exudyn.itemInterface as ii  # noqa: PLC0415 - only the floor system needs Exudyn's items

    from exudyn_atcm.mbs import solver_settings  # noqa: PLC0415

    SC = exudyn.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(ii.ObjectGround())
    node = mbs.AddNode(ii.NodePoint2D(referenceCoordinates=[0.0, 0.0]))
    mass = mbs.AddObject(ii.MassPoint2D(mass=1.0, nodeNumber=node))
    m0 = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0]))
    m1 = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=mass, localPosition=[0.0, 0.0, 0.0]))
    mbs.AddObject(ii.CartesianSpringDamper(markerNumbers=[m0, m1], stiffness=[1e3, 1e3, 0.0], damping=[1.0, 1.0, 0.0]))
    mbs.AddLoad(ii.LoadForceVector(markerNumber=m1, loadVector=[1.0, 0.0, 0.0]))
    mbs.SetPreStepUserFunction(lambda mbs_, t: True)
    mbs.SetPostStepUserFunction(lambda mbs_, t: True)
    mbs.Assemble()
    settings = solver_settings.dynamic_settings(t_sim, step)
    start = time.perf_counter()
    exudyn.SolveDynamic(mbs, settings, showHints=False)
    return (time.perf_counter() - start) / t_sim


ROD_MASS_STEP = 5e-4  # s


def rod_mass_paths(t_sim: float, repeats: int) -> dict:
    """Cost [s/s] of the rod mechanisms with the mass matrix as a user function and as a re-read parameter."""
    from exudyn_atcm.mbs import builder  # noqa: PLC0415 - the toggle of the rod's mass path

    original = builder.add_mechanism
    paths = {"user function": False, "parameter": True}
    out = {}
    for name in ("four_bar", "gripper"):
        best = {label: [float("inf"), float("inf")] for label in paths}  # [t_sim run, one-step run]
        for _ in range(repeats):
            for label, by_parameter in paths.items():
                def add(mbs, mech, ground_item=None, free_end_bodies=False, stroke_path="prestep",
                        package_solves=False, _flag=by_parameter):
                    return original(mbs, mech, ground_item, free_end_bodies, stroke_path, package_solves and _flag)

                builder.add_mechanism = add
                try:
                    for k, t in enumerate((t_sim, ROD_MASS_STEP)):
                        system = bm.MECHANISMS[name](4, "rod")
                        with warnings.catch_warnings():
                            warnings.simplefilter("ignore", RuntimeWarning)
                            start = time.perf_counter()
                            simulate(system, t, step=ROD_MASS_STEP)
                            best[label][k] = min(best[label][k], time.perf_counter() - start)
                finally:
                    builder.add_mechanism = original
        out[name] = {label: (b[0] - b[1]) / t_sim for label, b in best.items()}
    return out


def memory_child(t_sim: float) -> None:
    """Run the Fig. 12 actuator recording every step for ``t_sim`` s; print the peak RSS [MB] before and after."""
    module = bm.case_module("paper_bending_actuator")
    p = module.CASE.resolve({"step": 1e-4})  # the fixed step this measures (the case chooses one for accuracy by default)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        simulate(module.build(p), 0.01, step=p.step)
        before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
        result = simulate(module.build(p), t_sim, step=p.step)
    after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"{before} {after} {result.n_rows} {sum(result[n].nbytes for n in result) / 2**20}")


def memory(t_sim: float) -> dict:
    out = subprocess.run([sys.executable, __file__, "--memory-child", str(t_sim)], check=True, capture_output=True,
                         text=True, env={**os.environ, "MPLBACKEND": "Agg"})
    before, after, rows, result_mb = (float(v) for v in out.stdout.split()[-4:])
    return {"t_sim_s": t_sim, "rows": int(rows), "peak_added_MB": after - before, "result_columns_MB": result_mb}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="exudyn_atcm per-step overhead benchmark")
    parser.add_argument("--t-sim", type=float, default=0.2, help="simulated time per run [s] (default 0.2)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per system, best taken (default 3)")
    parser.add_argument("--memory", action="store_true", help="also measure the memory of a long every-step record")
    parser.add_argument("--memory-t", type=float, default=20.0, help="simulated time of the memory run [s]")
    parser.add_argument("--memory-child", type=float, default=None, help=argparse.SUPPRESS)
    parser.add_argument("--rod-mass", action="store_true",
                        help="also compare the rod cell's two mass matrix paths (4 modes, step 5e-4 s)")
    parser.add_argument("--out", default=RESULTS)
    args = parser.parse_args(argv)
    if args.memory_child is not None:
        memory_child(args.memory_child)
        return 0
    print(f"exudyn_atcm {__version__}, exudyn {exudyn.__version__}, python {platform.python_version()}, "
          f"{os.cpu_count()} cpus; step {STEP:g} s, {args.t_sim:g} s simulated, best of {args.repeats}")
    header = (f"{'system':>9} | {'drives':>6} | {'channels':>8} | {'pre [us/step]':>13} | {'post [us/step]':>14} | "
              f"{'budget [us/step]':>16} | {'run [s/s]':>9} | {'exudyn [s/s]':>12}")
    print(header)
    print("-" * len(header))
    table = {}
    for name, (build, drives) in SYSTEMS.items():
        runs = [measure(build, args.t_sim) for _ in range(args.repeats)]
        best = min(runs, key=lambda r: r["pre_us"] + r["post_us"])
        best["run_s_per_s"] = min(r["run_s_per_s"] for r in runs)
        best["exudyn_s_per_s"] = min(r["exudyn_s_per_s"] for r in runs)
        best["drives"] = drives
        best["budget_us"] = 10.0 * drives + 2.0 * best["channels"]
        table[name] = best
        print(f"{name:>9} | {drives:>6} | {best['channels']:>8} | {best['pre_us']:>13.2f} | {best['post_us']:>14.2f} | "
              f"{best['budget_us']:>16.1f} | {best['run_s_per_s']:>9.3f} | {best['exudyn_s_per_s']:>12.3f}")
    floor = min(exudyn_floor(args.t_sim) for _ in range(args.repeats))
    print(f"Exudyn's floor (one mass, trivial Python hooks): {floor:.4f} s/s")
    out = {"exudyn_atcm": __version__, "exudyn": exudyn.__version__, "python": platform.python_version(),
           "cpus": os.cpu_count(), "step_s": STEP, "t_sim_s": args.t_sim, "repeats": args.repeats,
           "systems": table, "exudyn_floor_s_per_s": floor}
    if args.rod_mass:
        rod = rod_mass_paths(max(args.t_sim, 0.5), args.repeats)
        out["rod_mass_paths_s_per_s"] = rod
        print(f"rod cell (4 modes, step {ROD_MASS_STEP:g} s): mass matrix as a user function / as a re-read parameter")
        for name, costs in rod.items():
            print(f"{name:>9} | {costs['user function']:.4f} s/s | {costs['parameter']:.4f} s/s | "
                  f"{costs['user function'] / costs['parameter']:.2f}x")
    if args.memory:
        mem = memory(args.memory_t)
        out["memory"] = mem
        print(f"every-step record of {mem['t_sim_s']:g} s ({mem['rows']} rows): peak memory added "
              f"{mem['peak_added_MB']:.1f} MB; the result's columns {mem['result_columns_MB']:.1f} MB")
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = Path(args.out) / f"bench_step_overhead_{stamp}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    write_json(path, out)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
