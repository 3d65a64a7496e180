"""Cost per cell and step of the time integration, the basis of the long-run warning (issue 9).

:func:`exudyn_atcm.solve.run_checks.estimate_run_time` predicts the wall time of a run as steps x a
cost per step ``a + b n + c n^2`` for the cell type and ``n`` cells (``run_checks.COST_PER_STEP``).
This script measures that cost on the bender of the paper's actuator (87 mm, paper laminate, the paper's Preisach
loop in the step, triangle of 0.5 s, step 1e-4 s) for every listed cell kind
(:data:`exudyn_atcm.cells.CELL_KINDS`) at several cell counts, side by side in one run, best of
``--repeats``, and prints the measured costs next to the constants in use
(:attr:`exudyn_atcm.cells.CellKind.cost_per_step`), with the estimate's error for each run and
the least-squares fit ``a + b n + c n^2`` per kind (with ``c`` = 0 when three counts cannot
resolve it: a negative ``c`` is refitted without it).  The cost of the steps is the run's wall time
minus a one-step run's (the build, the initial equilibrium, the checks and the result, which the
run-time estimate adds apart from its build-cost estimate); until 2026-11-29 it was counted in,
10-20 % of a 0.2 s run's cost at 40 cells (the constants measured then overestimate by that).

Usage: ``python benchmarks/bench_run_cost.py [--t-sim 0.2] [--cells 3 10 40] [--repeats 3]``.  Writes JSON to
``benchmarks/results/`` (git-ignored).  Default run: about a minute.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import platform
import time
import warnings

import exudyn

from exudyn_atcm import __version__
from exudyn_atcm.cells import CELL_KINDS
from exudyn_atcm.mechanism.actuator import BendingActuator
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.materials import Layer
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
import numpy as np

from exudyn_atcm.solve.run_checks import COST_PER_STEP, estimate_run_time
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.solve import simulate

STEP = 1e-4


def actuator(n_cells: int, cell: str) -> BendingActuator:
    drive = PiezoDrive(Triangle(500.0, 1000.0, 0.5), hysteresis=paper_strain_preisach())
    return BendingActuator(n_cells, 87e-3 / n_cells, 28e-3, Layer(0.2e-3, 70e9, 1550.0),
                           Layer(0.3e-3, 30.336e9, 5440.0), drive, cell=cell)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--t-sim", type=float, default=0.2, help="simulated time per run [s]")
    parser.add_argument("--cells", type=int, nargs="+", default=[3, 10, 40])
    parser.add_argument("--repeats", type=int, default=3, help="runs per point, the fastest counts (default 3)")
    parser.add_argument("--kinds", nargs="+", default=list(CELL_KINDS), choices=list(CELL_KINDS),
                        help="cell kinds to measure (default: all)")
    args = parser.parse_args()
    rows = []
    for n in args.cells:
        for cell in args.kinds:
            act = actuator(n, cell)
            wall, setup = float("inf"), float("inf")
            for _ in range(args.repeats):  # interleaving the kinds would not help: the repeats are back to back
                start = time.perf_counter()
                result = simulate(act, args.t_sim, step=STEP, record_every=10)
                whole = time.perf_counter() - start
                with warnings.catch_warnings():  # a one-step run "hardly covers" the program: it is meant to
                    warnings.simplefilter("ignore")
                    start = time.perf_counter()
                    simulate(act, STEP, step=STEP)  # the set-up alone: build, initial equilibrium, checks, result
                    setup = min(setup, time.perf_counter() - start)
                wall = min(wall, whole)
            wall -= setup  # the steps' cost (the build is estimated apart: mechanism.build_cost)
            steps = int(result.info["accepted_steps"]) - 1
            estimate = estimate_run_time(cell, n, steps)
            rows.append({
                "cell": cell, "n_cells": n, "steps": steps, "wall [s]": wall,
                "cost per cell-step [us]": 1e6 * wall / (n * steps),
                "cost per step [us]": 1e6 * wall / steps,
                "estimate [s]": estimate, "estimate / measured": None if estimate is None else estimate / wall,
            })
    print("| cell | cells | steps | wall [s] | per step [µs] | per cell-step [µs] | estimate / measured |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        ratio = "-" if r["estimate / measured"] is None else f"{r['estimate / measured']:.2f}"
        print(f"| {r['cell']} | {r['n_cells']} | {r['steps']} | {r['wall [s]']:.3f} | {r['cost per step [us]']:.1f} | "
              f"{r['cost per cell-step [us]']:.1f} | {ratio} |")
    fits = {}
    for cell in args.kinds:
        mine = [r for r in rows if r["cell"] == cell]
        n = np.array([r["n_cells"] for r in mine], dtype=float)
        b = np.array([r["cost per step [us]"] for r in mine])
        coef, *_ = np.linalg.lstsq(np.column_stack([np.ones_like(n), n, n**2]), b, rcond=None)
        if coef[2] < 0.0:
            coef = np.append(np.linalg.lstsq(np.column_stack([np.ones_like(n), n]), b, rcond=None)[0], 0.0)
        fits[cell] = {"a [us]": coef[0], "b [us]": coef[1], "c [us]": coef[2]}
        used = COST_PER_STEP.get(cell)
        in_use = "none" if used is None else " + ".join(f"{1e6 * v:.3g}" for v in used)
        print(f"{cell}: fit per step a + b n + c n^2 = {coef[0]:.1f} + {coef[1]:.2f} n + {coef[2]:.3f} n^2 µs "
              f"(tuple in s: ({coef[0] * 1e-6:.2g}, {coef[1] * 1e-6:.2g}, {coef[2] * 1e-6:.2g})); "
              f"in use [µs]: {in_use}")
    out = os.path.join(os.path.dirname(__file__), "results")
    os.makedirs(out, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = os.path.join(out, f"run_cost_{stamp}.json")
    with open(path, "w", encoding="utf-8") as handle:
        json.dump({"rows": rows, "fits": fits, "t_sim [s]": args.t_sim, "step [s]": STEP, "exudyn_atcm": __version__,
                   "exudyn": exudyn.__version__, "platform": platform.platform()}, handle, indent=2)
    print(f"\nwrote {path}")


if __name__ == "__main__":
    main()
