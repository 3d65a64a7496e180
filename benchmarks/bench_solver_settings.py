"""Newton variants for mechanism dynamics: cost and accuracy against a tight reference, side by side.

The four-bar and the gripper of ``bench_mechanisms.py`` (8 rigid cells per bender, step 1e-4 s,
the paper's triangle through its Preisach loop) are integrated for ``t_sim`` with the package's
dynamic settings (:func:`exudyn_atcm.mbs.solver_settings.dynamic_settings`: modified Newton
renewing the Jacobian below contraction 0.2, no analytic connector derivative, absolute tolerance
1e-8) and with variants that change one choice each.  Accuracy: the tracked point's largest
distance from a reference run with full Newton at absolute and relative tolerance 1e-12, relative
to its largest travel (the same step, so only the Newton tolerance differs).  Beam cells raise every
absolute tolerance to their residual floor (``MechanismModel.newton_tolerance_floor``: 2.3e-8 for the
four-bar with 16 beam cells), the reference's too: their row compares modified with full Newton at
that floor, so its errors are lower bounds.  Cost: wall seconds per simulated second, best of
``repeats``, the variants interleaved; the build and the initial equilibrium are counted in (12-22 %
of a 0.25 s run at 4e-4 s), which pulls every ratio towards 1 (the gripper's 0.80 is about 0.74 for
the integration alone).

Issue 31 (part 3) added the ``rod`` cell (3 modes), larger rigid and beam chains and the variants of the
linear solver (Exudyn's dense LU against the package's sparse one) and of the absolute tolerance
(1e-7, 1e-6: the residual's norm per coordinate, in N and N m), to choose both per system
(``--systems all``; ``--step`` sets the step).  Measured on 2026-11-29 (shared 2-core machine, step 4e-4 s,
0.25 s simulated, best of 3; cost relative to the package's defaults, error of the path against the tight
reference relative to the travel):

==================  ======  ====================  =====================  =====================
system              dense   abs 1e-7              abs 1e-6               abs 1e-6 + dense
==================  ======  ====================  =====================  =====================
four-bar rod 3      0.98    0.96, 1.9e-6          0.96, 6.1e-6           0.95, 6.1e-6
four-bar rigid 8    1.05    0.89, 1.9e-6          0.86, 1.1e-5           0.88, 1.1e-5
gripper rod 3       0.99    0.96, 1.6e-6          0.93, 3.1e-5           0.92, 3.1e-5
gripper rigid 8     1.09    0.88, 5.6e-6          0.80, 6.2e-5           0.89, 6.2e-5
four-bar rigid 32   1.40    0.90, 5.3e-6          0.83, 4.6e-5           1.24, 4.6e-5
four-bar beam 16    1.99    0.92, 1.5e-8          1.47, 2.7e-7           1.04, 2.7e-7
==================  ======  ====================  =====================  =====================

(the defaults' own errors: 3e-7 ... 1e-6, beam 1e-8).  The dense solver gains nothing measurable on the
smallest systems (33 coordinates) and costs up to 2x on larger ones: the package keeps the sparse solver
at every size.  A looser absolute tolerance saves 4-20 %, but the error it leaves is not a fixed multiple
of it (1e-7: 1.6e-6 ... 5.6e-6 of the travel; 1e-6: 6e-6 ... 6e-5), so no single value keeps the error
below 2e-6 of the travel, and the package keeps 1e-8.

Usage: ``python benchmarks/bench_solver_settings.py [--t-sim 0.1] [--repeats 3] [--systems all] [--step 4e-4]``.  Prints a table
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
DENSE = exudyn.LinearSolverType.EigenDense
#: issue 31, part 3: the linear solver and the absolute tolerance, per system (``--systems all``)
SIZE_VARIANTS = {
    "package defaults": None,
    "dense linear solver": {"linearSolver.solverType": DENSE},
    "absolute tolerance 1e-7": {"timeIntegration.newton.absoluteTolerance": 1e-7},
    "absolute tolerance 1e-6": {"timeIntegration.newton.absoluteTolerance": 1e-6},
    "absolute 1e-6, dense": {"timeIntegration.newton.absoluteTolerance": 1e-6, "linearSolver.solverType": DENSE},
}
#: (mechanism, cells per bender, cell) of ``--systems all``
SYSTEMS = [("four_bar", 3, "rod"), ("four_bar", 8, "rigid"), ("gripper", 3, "rod"), ("gripper", 8, "rigid"),
           ("four_bar", 32, "rigid"), ("four_bar", 16, "beam")]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="exudyn_atcm Newton variants for mechanisms")
    parser.add_argument("--t-sim", type=float, default=0.1, help="simulated time per run [s] (default 0.1)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per variant, best taken (default 3)")
    parser.add_argument("--out", default=RESULTS)
    parser.add_argument("--systems", default="rigid", choices=("rigid", "all"),
                        help="rigid: the four-bar and the gripper with 8 rigid cells and the Newton variants; all: "
                             "rod, rigid and beam systems with the linear solver and absolute tolerance variants")
    parser.add_argument("--step", type=float, default=STEP, help="time step [s] (default 1e-4)")
    args = parser.parse_args(argv)
    systems = ([(name, CELLS, "rigid") for name in bm.MECHANISMS] if args.systems == "rigid" else SYSTEMS)
    variants = VARIANTS if args.systems == "rigid" else SIZE_VARIANTS
    step = args.step
    print(f"exudyn_atcm {__version__}, exudyn {exudyn.__version__}, python {platform.python_version()}, "
          f"{os.cpu_count()} cpus; step {step:g} s, {args.t_sim:g} s simulated, "
          f"best of {args.repeats}")
    header = f"{'mechanism':>22} | {'variant':>32} | {'cost [s/s]':>10} | {'Newton steps':>12} | {'path error [-]':>14}"
    print(header)
    print("-" * len(header))
    table: dict[str, dict] = {}
    for name, cells, cell in systems:
        build = bm.MECHANISMS[name]
        key = f"{name} {cell} {cells}"
        reference = simulate(build(cells, cell), args.t_sim, step=step, settings=TIGHT)
        best = {k: float("inf") for k in variants}
        info = {}
        for _ in range(args.repeats):
            for label, settings in variants.items():
                system = build(cells, cell)
                start = time.perf_counter()
                result = simulate(system, args.t_sim, step=step, settings=settings)
                best[label] = min(best[label], (time.perf_counter() - start) / args.t_sim)
                info[label] = {"newton_steps": result.info["newton_steps"],
                               "path_error": bm.path_error(result, reference, bm.TRACKED[name])}
        table[key] = {k: {"cost_s_per_s": best[k], "relative_cost": best[k] / best["package defaults"], **info[k]}
                      for k in variants}
        for label in variants:
            row = table[key][label]
            print(f"{key:>22} | {label:>32} | {row['cost_s_per_s']:>10.3f} | {row['newton_steps']:>12} | "
                  f"{row['path_error']:>14.2e}", flush=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = Path(args.out) / f"bench_solver_settings_{stamp}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    write_json(path, {"exudyn_atcm": __version__, "exudyn": exudyn.__version__, "python": platform.python_version(),
                      "cpus": os.cpu_count(), "step_s": step, "t_sim_s": args.t_sim, "repeats": args.repeats,
                      "systems": [list(x) for x in systems], "reference": TIGHT, "results": table})
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
