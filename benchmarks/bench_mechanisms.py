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

from exudyn_atcm._atomic import write_json
from exudyn_atcm._version import __version__
from exudyn_atcm.cases import find_case
from exudyn_atcm.parameter_sets import paper_strain_preisach
from exudyn_atcm.signals import Triangle
from exudyn_atcm import simulate

CASES = Path(__file__).resolve().parents[1] / "cases"
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


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="exudyn_atcm mechanism benchmark")
    parser.add_argument("--t-sim", type=float, default=0.2, help="simulated time per run [s] (default 0.2)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per point, best taken (default 3)")
    parser.add_argument("--cells", default="2,4,8,16", help="cells per bender (default 2,4,8,16)")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "results"))
    args = parser.parse_args(argv)
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
