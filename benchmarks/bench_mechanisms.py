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

``--targets`` runs only ``mechanism_targets.targets_table`` (issue 15, part 3): for each mechanism a ladder of
cells per bender (``--cells``, default 2,4,8,16,32 there) for the package's rigid and beam cells
and for the same mechanism built by hand in Exudyn (``benchmarks/handbuilt.py``: GE beam
elements, the same in-step hysteresis, no package layer), all interleaved, best of
``--repeats``; per accuracy target (1e-2, 1e-3, 1e-4) the cheapest configuration of each model,
its speed-up over the hand-built one, and Exudyn's empty-step floor
(``bench_step_overhead.exudyn_floor``) with the four-bar's ratio to it.  ``--large-step 5e-4,1e-3``
runs every model at those steps too (each row names its step).  Default 0.5 s simulated (one voltage period).

``--step-cost`` runs only ``step_cost.step_cost_table`` (issue 31, part 3): the package's four-bar with a
3-mode ``rod`` crank against the hand-built linkage (one GE element per bender, ``handbuilt.py``) at
``--steps`` (default 1e-4,4e-4), microseconds per step side by side, the rod's own Python per step, and both
path errors against a beam reference at the same step.

``--record-every N`` runs only :func:`record_every_cost`: both mechanisms recording every step
against every ``N``-th step, and the cost of the copy a skipped step made before the record was
closed by reading the last step's state once after the run.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import platform
import sys
import time
import warnings
from pathlib import Path

import exudyn
import numpy as np

from exudyn_atcm.io.atomic import write_json
from exudyn_atcm import __version__

import mechanism_targets
import step_cost
from bench_systems import CELLS, MECHANISMS, RESULTS, STEP, TRACKED, path_error, timed
from exudyn_atcm import simulate

def skipped_step_copy_cost(build, n_cells: int, calls: int = 2000) -> float:
    """Wall time [s] of what a skipped step used to copy: the coordinates and every spring and stop force.

    Measured on the built model in its reference state (the cost does not depend on the state).
    """
    from exudyn_atcm.mbs import builder as mb  # noqa: PLC0415 - only this function needs the model

    model = mb.build(build(n_cells, "rigid"))
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
                mech = build(n_cells, "rigid")
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
    parser.add_argument("--t-sim", type=float, default=None,
                        help="simulated time per run [s] (default 0.2; 0.5 with --targets)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per point, best taken (default 3)")
    parser.add_argument("--cells", default=None, help="cells per bender (default 2,4,8,16; 2,4,8,16,32 with --targets)")
    parser.add_argument("--reference-cells", type=int, default=64,
                        help="beam elements per bender of the reference run (default 64)")
    parser.add_argument("--out", default=RESULTS)
    parser.add_argument("--record-every", type=int, default=None, metavar="N",
                        help="only compare a record of every N-th step with the every-step record "
                             "(record_every_cost, with the first value of --cells)")
    parser.add_argument("--targets", action="store_true",
                        help="only the cost at equal accuracy against the hand-built GE beam models and "
                             "Exudyn's floor (mechanism_targets.py; --cells default 2,4,8,16,32, --t-sim 0.5)")
    parser.add_argument("--large-step", default=None,
                        help="with --targets: also run every model at these steps [s] (comma list, e.g. 5e-4,1e-3)")
    parser.add_argument("--models", default=None,
                        help="with --targets: only these models (comma list of rigid, beam, rod, hand; default all)")
    parser.add_argument("--step-cost", action="store_true",
                        help="only the package's rod four-bar against the hand-built linkage, us per step (step_cost.py)")
    parser.add_argument("--steps", default="1e-4,4e-4", help="with --step-cost: the steps [s] (comma list)")
    args = parser.parse_args(argv)
    if args.step_cost:
        step_cost.step_cost_table(t_sim=0.5 if args.t_sim is None else args.t_sim, repeats=args.repeats,
                                  steps=[float(h) for h in args.steps.split(",") if h.strip()],
                                  reference_cells=args.reference_cells, out=args.out)
        return 0
    if args.targets:
        mechanism_targets.targets_table(
            t_sim=0.5 if args.t_sim is None else args.t_sim, repeats=args.repeats,
            cells=None if args.cells is None else [int(c) for c in args.cells.split(",") if c.strip()],
            reference_cells=args.reference_cells, out=args.out,
            large_step=None if args.large_step is None else [float(h) for h in args.large_step.split(",") if h.strip()],
            models=None if args.models is None else [m.strip() for m in args.models.split(",") if m.strip()])
        return 0
    args.t_sim = 0.2 if args.t_sim is None else args.t_sim
    args.cells = "2,4,8,16" if args.cells is None else args.cells
    if args.record_every is not None:
        record_every_cost(args.t_sim, args.repeats, int(args.cells.split(",")[0]), args.record_every, args.out)
        return 0
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
                with warnings.catch_warnings():  # a one-step run sees almost none of the program: expected here
                    warnings.simplefilter("ignore", RuntimeWarning)
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
