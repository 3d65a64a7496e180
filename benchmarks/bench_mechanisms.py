"""Cost of mechanism simulations against the number of cells (issue 7, part 5).

The compliant four-bar (``cases/compliant_four_bar.py``: one bender crank, three PRBM flexure
hinges, two links, a closed loop) and the micro-gripper (``cases/micro_gripper.py``: two
benders with jaws squeezing a spring object) are built from their cases with 2, 4, 8 and 16
rigid cells per bender and simulated dynamically: the paper's triangle voltage (-500 ...
1500 V, period 0.5 s) through the paper's continuous Preisach loop, evaluated in the solver
step (one operator per drive), step 1e-4 s.

Cost = (wall time of a run of ``t_sim`` - wall time of a run of one step) / ``t_sim``: wall
seconds per simulated second without the set-up (building the Exudyn system, initial
assembly).  Best of ``repeats`` runs (the machine is shared).  The set-up time is reported
too.

Usage: ``python benchmarks/bench_mechanisms.py [--t-sim 0.2] [--repeats 3] [--cells 2,4,8,16]``.
Prints a table and writes JSON to ``benchmarks/results/`` (git-ignored).

``--record-every N`` runs only :func:`record_every_cost`: both mechanisms recording every step
against every ``N``-th step, and the cost of the copy a skipped step made before the record was
closed by reading the last step's state once after the run.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import importlib.util
import os
import platform
import sys
import time
from pathlib import Path

import exudyn
import numpy as np

from exudyn_atcm._atomic import write_json
from exudyn_atcm._version import __version__
from exudyn_atcm.cases import find_case
from exudyn_atcm.parameter_sets import paper_strain_preisach
from exudyn_atcm.signals import Triangle
from exudyn_atcm import simulate

CASES = Path(__file__).resolve().parents[1] / "cases"
RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
STEP = 1e-4  # s
PERIOD = 0.5  # s


def case_module(name: str):
    """The case file as a module (its CASE and its build_mechanism)."""
    spec = importlib.util.spec_from_file_location(name, find_case(name, CASES))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def four_bar(n_cells: int):
    module = case_module("compliant_four_bar")
    p = module.CASE.resolve({"n_cells": n_cells})
    return module.build_mechanism(p, paper_strain_preisach(), Triangle(500.0, 1000.0, PERIOD))


def gripper(n_cells: int):
    module = case_module("micro_gripper")
    p = module.CASE.resolve({"n_cells": n_cells})
    return module.build_mechanism(p, p.object_stiffness, Triangle(500.0, 1000.0, PERIOD))


MECHANISMS = {"four_bar": four_bar, "gripper": gripper}


def timed(build, n_cells: int, t_sim: float) -> tuple[float, dict]:
    mech = build(n_cells)
    start = time.perf_counter()
    result = simulate(mech, t_sim, step=STEP)
    return time.perf_counter() - start, dict(result.info)


def skipped_step_copy_cost(build, n_cells: int, calls: int = 2000) -> float:
    """Wall time [s] of what a skipped step used to copy: the coordinates and every spring and stop force.

    Measured on the built model in its reference state (the cost does not depend on the state).
    """
    from exudyn_atcm.mbs import builder as mb  # noqa: PLC0415 - only this function needs the model

    model = mb.build(build(n_cells))
    start = time.perf_counter()
    for _ in range(calls):
        np.array(model.coordinates())
        model.connector_forces()
    return (time.perf_counter() - start) / calls


def record_every_cost(t_sim: float = 0.2, repeats: int = 3, n_cells: int = 4, every: int = 100,
                      out: str | os.PathLike | None = None) -> dict:
    """Mechanism runs thinned by ``record_every`` against the every-step record, side by side.

    For each mechanism: the wall time of a run recording every step, of one recording every
    ``every``-th step (the skipped steps keep only time, voltages and strains; the last step's
    state is read once after the run), and the cost per step of the copy a skipped step used
    to make (coordinates plus every spring and stop force), with what it added to the thinned run
    (skipped steps x that cost).  Best of ``repeats``.  Prints a table, writes JSON.
    """
    print(f"record_every = {every} steps against every step: {n_cells} cells per bender, step {STEP:g} s, "
          f"{t_sim:g} s simulated, best of {repeats}")
    header = (f"{'mechanism':>10} | {'every step [s]':>14} | {'every ' + str(every) + ' [s]':>14} | "
              f"{'old copy [us/step]':>18} | {'old copy x skipped [s]':>22} | {'saved [%]':>9}")
    print(header)
    print("-" * len(header))
    table = {}
    for name, build in MECHANISMS.items():
        wall = {}
        for label, record in (("every_step", None), ("thinned", every)):
            times = []
            for _ in range(repeats):
                mech = build(n_cells)
                start = time.perf_counter()
                result = simulate(mech, t_sim, step=STEP, record_every=record)
                times.append(time.perf_counter() - start)
            wall[label] = min(times)
            wall[label + "_rows"] = result.n_rows
        copy = min(skipped_step_copy_cost(build, n_cells) for _ in range(repeats))
        skipped = int(round(t_sim / STEP)) + 1 - wall["thinned_rows"]
        old_extra = copy * skipped
        saved = 100.0 * old_extra / (wall["thinned"] + old_extra)
        table[name] = {"every_step_s": wall["every_step"], "thinned_s": wall["thinned"], "rows_every_step":
                       wall["every_step_rows"], "rows_thinned": wall["thinned_rows"], "skipped_steps": skipped,
                       "old_copy_per_skipped_step_s": copy, "old_copy_total_s": old_extra, "saved_percent": saved}
        print(f"{name:>10} | {wall['every_step']:>14.3f} | {wall['thinned']:>14.3f} | {copy * 1e6:>18.2f} | "
              f"{old_extra:>22.3f} | {saved:>9.1f}")
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = Path(out or RESULTS) / f"bench_mechanisms_record_every_{stamp}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    write_json(path, {"exudyn_atcm": __version__, "exudyn": exudyn.__version__, "python": platform.python_version(),
                      "cpus": os.cpu_count(), "step_s": STEP, "t_sim_s": t_sim, "repeats": repeats,
                      "cells_per_bender": n_cells, "record_every_steps": every, "results": table})
    print(f"wrote {path}")
    return table


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="exudyn_atcm mechanism benchmark")
    parser.add_argument("--t-sim", type=float, default=0.2, help="simulated time per run [s] (default 0.2)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per point, best taken (default 3)")
    parser.add_argument("--cells", default="2,4,8,16", help="cells per bender (default 2,4,8,16)")
    parser.add_argument("--out", default=RESULTS)
    parser.add_argument("--record-every", type=int, default=None, metavar="N",
                        help="only compare a record of every N-th step with the every-step record "
                             "(record_every_cost, with the first value of --cells)")
    args = parser.parse_args(argv)
    if args.record_every is not None:
        record_every_cost(args.t_sim, args.repeats, int(args.cells.split(",")[0]), args.record_every, args.out)
        return 0
    cells = [int(c) for c in args.cells.split(",") if c.strip()]
    print(f"exudyn_atcm {__version__}, exudyn {exudyn.__version__}, python {platform.python_version()}, "
          f"{os.cpu_count()} cpus; step {STEP:g} s, {args.t_sim:g} s simulated per run, best of {args.repeats}")
    table: dict[str, dict[str, dict]] = {}
    header = f"{'cells/bender':>12} | " + " | ".join(f"{name + ' [s/s]':>16} | {'set-up [s]':>10}" for name in MECHANISMS)
    print(header)
    print("-" * len(header))
    for n in cells:
        row = []
        for name, build in MECHANISMS.items():
            setup = min(timed(build, n, STEP)[0] for _ in range(args.repeats))
            runs = [timed(build, n, args.t_sim) for _ in range(args.repeats)]
            total, info = min(runs, key=lambda r: r[0])
            cost = (total - setup) / args.t_sim
            table.setdefault(name, {})[str(n)] = {
                "wall_per_simulated_second": cost, "setup_s": setup, "run_s": total,
                "accepted_steps": info.get("accepted_steps"), "rejected_steps": info.get("rejected_steps"),
                "newton_steps": info.get("newton_steps"),
            }
            row.append(f"{cost:>16.3f} | {setup:>10.3f}")
        print(f"{n:>12} | " + " | ".join(row))
    for name in MECHANISMS:
        first, last = str(cells[0]), str(cells[-1])
        ratio = table[name][last]["wall_per_simulated_second"] / table[name][first]["wall_per_simulated_second"]
        print(f"{name}: {last} / {first} cells per bender = {ratio:.2f}x")
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = Path(args.out) / f"bench_mechanisms_{stamp}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    write_json(path, {"exudyn_atcm": __version__, "exudyn": exudyn.__version__, "python": platform.python_version(),
                      "machine": platform.machine(), "cpus": os.cpu_count(), "step_s": STEP, "t_sim_s": args.t_sim,
                      "repeats": args.repeats, "voltage": "Triangle(500, 1000, 0.5 s), paper Preisach loop",
                      "results": table})
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
