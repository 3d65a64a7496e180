"""Cost and accuracy of mechanism simulations against the number of cells, rigid and beam cells.

The compliant four-bar (``cases/compliant_four_bar.py``: one bender crank, three PRBM flexure
hinges, two links, a closed loop) and the micro-gripper (``cases/micro_gripper.py``: two
benders with jaws squeezing a spring object) are built from their cases with 2, 4, 8 and 16
cells per bender, once with rigid cells (``cell="rigid"``) and once with geometrically exact
beam elements (``cell="beam"``), and simulated dynamically: the paper's triangle voltage
(-500 ... 1500 V, period 0.5 s) through the paper's continuous Preisach loop, evaluated in the
solver step (one operator per drive), step 1e-4 s.

Cost = (wall time of a run of ``t_sim`` - wall time of a run of one step) / ``t_sim``: wall
seconds per simulated second without the set-up (building the Exudyn system, initial
assembly).  Best of ``repeats`` runs (the machine is shared).  The set-up time is reported
too.

Accuracy = the largest distance over the run between the tracked point (the four-bar's
coupler point ``coupler.P``, the gripper's lower jaw point ``lower_jaw.jaw``) and the same
point of a reference run with ``--reference-cells`` beam elements per bender (same step, so
the time discretisation is common to all runs), relative to the point's largest travel.
Both cells converge to the same continuous beam, so one reference serves both; "cheaper at
equal accuracy" is read off one table: the summary names, for each beam run, the cheapest
rigid run at least as accurate.

Usage: ``python benchmarks/bench_mechanisms.py [--t-sim 0.2] [--repeats 3] [--cells 2,4,8,16]
[--reference-cells 64]``.  Prints a table and writes JSON to ``benchmarks/results/`` (git-ignored).
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
from exudyn_atcm.mechanism import Bender
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


CELLS = ("rigid", "beam")


def four_bar(n_cells: int, cell: str):
    module = case_module("compliant_four_bar")
    p = module.CASE.resolve({"n_cells": n_cells, "cell": cell})
    return module.build_mechanism(p, paper_strain_preisach(), Triangle(500.0, 1000.0, PERIOD))


def with_cell(mech, cell: str):
    """``mech`` with every bender rebuilt with ``cell`` (same name, laminate, segments, pose, drives)."""
    for b in list(mech.benders):
        mech.components[b.name] = Bender(b.name, width=b.width, passive=b.passive, active=b.active,
                                         segments=b.segments, base=b.base_position, angle=b.angle, cell=cell,
                                         stiffness=b.stiffness, active_side=b.active_side, damping=b.damping)
    return mech


def gripper(n_cells: int, cell: str):
    module = case_module("micro_gripper")
    p = module.CASE.resolve({"n_cells": n_cells})
    return with_cell(module.build_mechanism(p, p.object_stiffness, Triangle(500.0, 1000.0, PERIOD)), cell)


MECHANISMS = {"four_bar": four_bar, "gripper": gripper}
TRACKED = {"four_bar": "coupler.P", "gripper": "lower_jaw.jaw"}


def timed(build, n_cells: int, cell: str, t_sim: float) -> tuple[float, dict, np.ndarray]:
    """Wall time [s], solver info and the tracked point's path of one run."""
    mech = build(n_cells, cell)
    start = time.perf_counter()
    result = simulate(mech, t_sim, step=STEP)
    return time.perf_counter() - start, dict(result.info), result


def path(result, point: str) -> np.ndarray:
    return np.stack([result[f"{point}_x"], result[f"{point}_y"]], axis=-1)


def path_error(result, reference, point: str) -> float:
    """Largest distance to the reference path relative to the reference point's largest travel [-]."""
    p, q = path(result, point), path(reference, point)
    travel = float(np.max(np.linalg.norm(q - q[0], axis=1)))
    return float(np.max(np.linalg.norm(p - q, axis=1))) / travel


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="exudyn_atcm mechanism benchmark")
    parser.add_argument("--t-sim", type=float, default=0.2, help="simulated time per run [s] (default 0.2)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per point, best taken (default 3)")
    parser.add_argument("--cells", default="2,4,8,16", help="cells per bender (default 2,4,8,16)")
    parser.add_argument("--reference-cells", type=int, default=64,
                        help="beam elements per bender of the reference run (default 64)")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "results"))
    args = parser.parse_args(argv)
    cells = [int(c) for c in args.cells.split(",") if c.strip()]
    print(f"exudyn_atcm {__version__}, exudyn {exudyn.__version__}, python {platform.python_version()}, "
          f"{os.cpu_count()} cpus; step {STEP:g} s, {args.t_sim:g} s simulated per run, best of {args.repeats}")
    references = {}
    for name, build in MECHANISMS.items():
        wall, _, references[name] = timed(build, args.reference_cells, "beam", args.t_sim)
        print(f"reference {name}: {args.reference_cells} beam elements per bender, {wall:.1f} s")
    table: dict[str, dict[str, dict[str, dict]]] = {}
    header = f"{'cells/bender':>12} | " + " | ".join(
        f"{name + ' ' + cell + ' [s/s]':>22} | {'error [-]':>9} | {'set-up [s]':>10}"
        for name in MECHANISMS for cell in CELLS)
    print(header)
    print("-" * len(header))
    for n in cells:
        row = []
        for name, build in MECHANISMS.items():
            for cell in CELLS:
                setup = min(timed(build, n, cell, STEP)[0] for _ in range(args.repeats))
                runs = [timed(build, n, cell, args.t_sim) for _ in range(args.repeats)]
                total, info, result = min(runs, key=lambda r: r[0])
                cost = (total - setup) / args.t_sim
                error = path_error(result, references[name], TRACKED[name])
                table.setdefault(name, {}).setdefault(cell, {})[str(n)] = {
                    "wall_per_simulated_second": cost, "setup_s": setup, "run_s": total, "path_error": error,
                    "accepted_steps": info.get("accepted_steps"), "rejected_steps": info.get("rejected_steps"),
                    "newton_steps": info.get("newton_steps"),
                }
                row.append(f"{cost:>22.3f} | {error:>9.2e} | {setup:>10.3f}")
        print(f"{n:>12} | " + " | ".join(row))
    for name in MECHANISMS:
        rigid, beam = table[name]["rigid"], table[name]["beam"]
        for n, b in beam.items():
            good = [(r["wall_per_simulated_second"], m) for m, r in rigid.items() if r["path_error"] <= b["path_error"]]
            if good:
                cost, m = min(good)
                print(f"{name}: beam {n} cells (error {b['path_error']:.2e}, {b['wall_per_simulated_second']:.3f} s/s); "
                      f"cheapest rigid run as accurate: {m} cells, {cost:.3f} s/s "
                      f"({cost / b['wall_per_simulated_second']:.2f}x the beam's cost)")
            else:
                print(f"{name}: beam {n} cells (error {b['path_error']:.2e}, {b['wall_per_simulated_second']:.3f} s/s); "
                      f"no rigid run here is as accurate")
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = Path(args.out) / f"bench_mechanisms_{stamp}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    write_json(path, {"exudyn_atcm": __version__, "exudyn": exudyn.__version__, "python": platform.python_version(),
                      "machine": platform.machine(), "cpus": os.cpu_count(), "step_s": STEP, "t_sim_s": args.t_sim,
                      "repeats": args.repeats, "voltage": "Triangle(500, 1000, 0.5 s), paper Preisach loop",
                      "reference": f"{args.reference_cells} beam elements per bender; error: largest distance of "
                                   "the tracked point from the reference path / its largest travel",
                      "tracked": TRACKED,
                      "results": table})
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
