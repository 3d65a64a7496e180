"""Newton tolerances of a static sweep's continuation: iterations, cost and error, side by side (issue 31).

The sweeps of ``bench_static_sweep.py`` (README four-bar, lone rigid-cell and rod-cell actuators;
a 100-point cycle 0 -> 1500 -> 0 V) are run as one continuation with the package's Newton
tolerances (per cell kind: rigid cells relative 1e-10 and absolute 1e-14, rod cells absolute
1e-12 EI/L, otherwise Exudyn's relative 1e-8) and with variants that loosen them: a relative
tolerance of 1e-6 or 1e-4 of each load step's first residual, or an absolute one of 1e-8 or 1e-6
(the residual's norm, in N and N m).  For each: Newton iterations per point, the sweep's time
(build included, best of ``--repeats``, the variants interleaved) and the largest difference of
the position columns from the per-point sweep at the package's tolerances, relative to the
largest travel.

Exudyn's static Newton iteration starts every load step with the constraint multipliers at zero,
so a step's first residual holds the joints' forces whatever the step's size: a relative tolerance
is a share of those forces, not of the deformation the step adds, and an absolute one stands for a
position error only through the compliance.  Measured on 2026-11-29 (see
``benchmarks/REPORTS.md``): only the variants that leave 5e-7 ... 1e-5 of the travel save an
iteration, so the continuation keeps the per-point sweep's tolerances (and its equilibria to
1e-12 m).

Usage: ``python benchmarks/bench_sweep_tolerances.py [--repeats 3]``.  Prints a table and writes
JSON to ``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import time

import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm.io.atomic import write_text
from exudyn_atcm.mbs import stability, sweep_solve

from bench_static_sweep import CASES, cycle

VARIANTS = {"package": {}, "rel 1e-6": {"relativeTolerance": 1e-6}, "rel 1e-4": {"relativeTolerance": 1e-4},
            "abs 1e-8": {"absoluteTolerance": 1e-8}, "abs 1e-6": {"absoluteTolerance": 1e-6}}


class Variant:
    """The continuation's Newton settings changed for one variant, and its Newton iterations counted."""

    def __init__(self, changes: dict) -> None:
        self.changes = changes
        self.steps: list[int] = []

    def __enter__(self) -> "Variant":
        self._apply, self._proof = sweep_solve.apply_static_tolerances, stability.StabilityProbe.proved_in_solve
        changes, steps, proof = self.changes, self.steps, self._proof

        def apply(model, settings):
            self._apply(model, settings)
            for key, value in changes.items():
                setattr(settings.staticSolver.newton, key, value)

        def counting(probe, solver, *state):
            steps.append(solver.it.newtonStepsCount)
            return proof(probe, solver, *state)

        sweep_solve.apply_static_tolerances = apply
        stability.StabilityProbe.proved_in_solve = counting
        return self

    def __exit__(self, *exc) -> None:
        sweep_solve.apply_static_tolerances = self._apply
        stability.StabilityProbe.proved_in_solve = self._proof

    def per_point(self) -> float:
        """Newton iterations per point of the last sweep (between its first and last in-solve proofs)."""
        s = self.steps
        return (s[-1] - s[0]) / (len(s) - 1) if len(s) > 1 else math.nan


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results"))
    args = parser.parse_args()
    rows = []
    for name, make in CASES.items():
        volts = cycle(make())
        reference = atcm.static_sweep(make(), volts, method="points")
        columns = [c for c in reference.names if reference.unit(c) == "m"]
        travel = max(float(np.ptp(reference[c])) for c in columns)
        atcm.static_sweep(make(), volts)  # warm-up (compiled kernels)
        best = {v: math.inf for v in VARIANTS}
        found = {}
        for _ in range(args.repeats):
            for label, changes in VARIANTS.items():
                with Variant(changes) as variant:
                    t0 = time.perf_counter()
                    result = atcm.static_sweep(make(), volts)
                    best[label] = min(best[label], time.perf_counter() - t0)
                error = max(float(np.max(np.abs(result[c] - reference[c]))) for c in columns) / travel
                found[label] = (variant.per_point(), error, result.info["fallback_points"])
        for label in VARIANTS:
            iterations, error, fallbacks = found[label]
            rows.append({"case": name, "variant": label, "newton_per_point": iterations, "time_s": best[label],
                         "time_over_package": best[label] / best["package"], "error_over_travel": error,
                         "fallback_points": fallbacks})
    print(f"{'case':28s} {'variant':10s} {'Newton/pt':>9s} {'time':>9s} {'/package':>9s} {'error/travel':>12s} "
          f"{'fallbacks':>9s}")
    for r in rows:
        print(f"{r['case']:28s} {r['variant']:10s} {r['newton_per_point']:9.2f} {r['time_s'] * 1e3:6.1f} ms "
              f"{r['time_over_package']:8.2f}x {r['error_over_travel']:12.2g} {r['fallback_points']!s:>9s}")
    os.makedirs(args.out, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = os.path.join(args.out, f"bench_sweep_tolerances_{stamp}.json")
    write_text(path, json.dumps({"repeats": args.repeats, "rows": rows}, indent=1, default=str))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
