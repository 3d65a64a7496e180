"""Newton variants for mechanism dynamics: cost and accuracy against a tight reference, side by side.

The four-bar and the gripper of ``bench_mechanisms.py`` (8 rigid cells per bender, step 1e-4 s,
the paper's triangle through its Preisach loop) are integrated for ``t_sim`` with the package's
dynamic settings (:func:`exudyn_atcm.mbs.solver_settings.dynamic_settings`: modified Newton
renewing the Jacobian below contraction 0.2, no analytic connector derivative, absolute tolerance
1e-8) and with variants that change one choice each.  Accuracy: the tracked point's largest
distance from a reference run with full Newton at absolute and relative tolerance 1e-12, relative
to its largest travel (the same step, so only the Newton tolerance differs).  Cost: wall seconds
per simulated second, best of ``repeats``, the variants interleaved.

Usage: ``python benchmarks/bench_solver_settings.py [--t-sim 0.1] [--repeats 3]``.  Prints a table
and writes JSON to ``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import platform
import sys
import time
from pathlib import Path

import exudyn

from exudyn_atcm import __version__, simulate
from exudyn_atcm.io.atomic import write_json

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_mechanisms as bm  # noqa: E402 - the mechanisms of the mechanism benchmark

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
STEP = 1e-4  # s
CELLS = 8

#: The reference: full Newton, tolerances 1e-12.
TIGHT = {"timeIntegration.newton.useModifiedNewton": False, "timeIntegration.newton.absoluteTolerance": 1e-12,
         "timeIntegration.newton.relativeTolerance": 1e-12}

VARIANTS = {
    "package defaults": None,
    "full Newton": {"timeIntegration.newton.useModifiedNewton": False},
    "modified, renew below 0.5": {"timeIntegration.newton.modifiedNewtonContractivity": 0.5},
    "with connector derivative": {"timeIntegration.newton.numericalDifferentiation.jacobianConnectorDerivative": True},
    "tolerances 1e-12 abs, 1e-10 rel": {"timeIntegration.newton.absoluteTolerance": 1e-12,
                                        "timeIntegration.newton.relativeTolerance": 1e-10},
    # a looser relative tolerance (the package keeps Exudyn's 1e-8): fewer iterations, but the
    # error it leaves depends on the mechanism (rigid gripper, 0.5 s: 4e-4 of the travel at 1e-5)
    "relative tolerance 1e-6": {"timeIntegration.newton.relativeTolerance": 1e-6},
    "relative tolerance 1e-5": {"timeIntegration.newton.relativeTolerance": 1e-5},
}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="exudyn_atcm Newton variants for mechanisms")
    parser.add_argument("--t-sim", type=float, default=0.1, help="simulated time per run [s] (default 0.1)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per variant, best taken (default 3)")
    parser.add_argument("--out", default=RESULTS)
    args = parser.parse_args(argv)
    print(f"exudyn_atcm {__version__}, exudyn {exudyn.__version__}, python {platform.python_version()}, "
          f"{os.cpu_count()} cpus; {CELLS} rigid cells per bender, step {STEP:g} s, {args.t_sim:g} s simulated, "
          f"best of {args.repeats}")
    header = f"{'mechanism':>9} | {'variant':>32} | {'cost [s/s]':>10} | {'Newton steps':>12} | {'path error [-]':>14}"
    print(header)
    print("-" * len(header))
    table: dict[str, dict] = {}
    for name, build in bm.MECHANISMS.items():
        reference = simulate(build(CELLS, "rigid"), args.t_sim, step=STEP, settings=TIGHT)
        best = {k: float("inf") for k in VARIANTS}
        info = {}
        for _ in range(args.repeats):
            for label, settings in VARIANTS.items():
                system = build(CELLS, "rigid")
                start = time.perf_counter()
                result = simulate(system, args.t_sim, step=STEP, settings=settings)
                best[label] = min(best[label], (time.perf_counter() - start) / args.t_sim)
                info[label] = {"newton_steps": result.info["newton_steps"],
                               "path_error": bm.path_error(result, reference, bm.TRACKED[name])}
        table[name] = {k: {"cost_s_per_s": best[k], **info[k]} for k in VARIANTS}
        for label in VARIANTS:
            row = table[name][label]
            print(f"{name:>9} | {label:>32} | {row['cost_s_per_s']:>10.3f} | {row['newton_steps']:>12} | "
                  f"{row['path_error']:>14.2e}")
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = Path(args.out) / f"bench_solver_settings_{stamp}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    write_json(path, {"exudyn_atcm": __version__, "exudyn": exudyn.__version__, "python": platform.python_version(),
                      "cpus": os.cpu_count(), "step_s": STEP, "t_sim_s": args.t_sim, "repeats": args.repeats,
                      "cells_per_bender": CELLS, "reference": TIGHT, "results": table})
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
