"""Quasi-static cycles as one solve (issue 31, part 2).

Times, side by side in one run, for a voltage cycle of 100 points (one period of the drive's
triangle, 0 V -> 1500 V -> 0 V): the per-point static sweep (``static_sweep(..., method="points")``,
each point its own equilibrium in load steps), the continuation sweep (the default: each point one
load step from the last), and the dynamic run of the same cycle (``simulate(mech, period)`` at the
default step 1e-4 s, the README's call).  Each timing includes the build; interleaved, each
``--repeats`` times, the fastest kept.  Both sweeps check the stability of every point.  The
largest difference of the position columns between the two sweeps is printed too, and the
continuation's time without the stability check (a stand-in that looks at nothing; the decomposition
of the cost only: the shipped sweep always checks).
Goal: the continuation sweep at least 3 times cheaper than the dynamic run.

Usage: ``python benchmarks/bench_static_sweep.py [--repeats 3]``.  Writes JSON to
``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import platform
import time

import exudyn
import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm.io.atomic import write_text
from exudyn_atcm.mbs.stability import Stability
from exudyn_atcm.solve import mechanism_solve
from exudyn_atcm.model import Triangle
from exudyn_atcm.model.parameter_sets import paper_strain_preisach

CFC = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
PERIOD = 0.1  # s, the README drive's triangle


def readme_four_bar() -> atcm.Mechanism:
    """The README's four-bar as it stands there (default cell and hysteresis)."""
    crank = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=6,
                        drive=atcm.PiezoDrive(Triangle(750.0, 750.0, PERIOD)), angle=math.pi / 2)
    coupler = atcm.Link("coupler", {"A": (0.0, 0.03), "B": (0.04, 0.03), "P": (0.02, 0.05)}, mass=1e-4, inertia=1e-8)
    rocker = atcm.Link("rocker", {"B": (0.04, 0.03), "O": (0.04, 0.0)}, mass=1e-4, inertia=1e-8)
    m = atcm.Mechanism("four_bar").add(crank, coupler, rocker)
    m.ground(crank.base)
    m.pin(crank.tip, coupler.point("A"))
    m.pin("coupler.B", "rocker.B")
    m.ground("rocker.O", joint="pin")
    return m


def lone(cell: str) -> atcm.Mechanism:
    """A lone actuator with the paper's Preisach operator and a tip load."""
    drive = atcm.PiezoDrive(Triangle(750.0, 750.0, PERIOD), hysteresis=paper_strain_preisach())
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=4, drive=drive, cell=cell)
    m = atcm.Mechanism("lone").add(b).ground(b.base)
    m.force(b.tip, (0.0, -0.02))
    return m


CASES = {"README four-bar": readme_four_bar, "lone actuator, rigid cells": lambda: lone("rigid"),
         "lone actuator, rod cells": lambda: lone("rod")}


class _NoCheck:
    """A probe that reports every state stable without looking: the continuation's cost without the check."""

    last = Stability("stable")

    def check(self) -> Stability:
        return self.last


def unchecked_continuation(mech: atcm.Mechanism, volts: np.ndarray):
    """The continuation sweep with the stability check stood in for (a decomposition of the cost only)."""
    original = mechanism_solve.stability_probe
    mechanism_solve.stability_probe = lambda mech_, model_: _NoCheck()
    try:
        return atcm.static_sweep(mech, volts)
    finally:
        mechanism_solve.stability_probe = original


def cycle(mech: atcm.Mechanism, n: int = 100) -> np.ndarray:
    drive = next(iter(mech.drives.values()))
    return np.array([drive.voltage_at(t) for t in np.linspace(0.0, PERIOD, n)])


def timed(fn) -> tuple[float, object]:
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results"))
    args = parser.parse_args()
    rows = []
    for name, make in CASES.items():
        volts = cycle(make())
        best = {"points": math.inf, "continuation": math.inf, "dynamic": math.inf, "unchecked": math.inf}
        results = {}
        for _ in range(args.repeats):
            for method in ("points", "continuation"):
                t, results[method] = timed(lambda: atcm.static_sweep(make(), volts, method=method))
                best[method] = min(best[method], t)
            t, _r = timed(lambda: atcm.simulate(make(), PERIOD))
            best["dynamic"] = min(best["dynamic"], t)
            t, _r = timed(lambda: unchecked_continuation(make(), volts))
            best["unchecked"] = min(best["unchecked"], t)
        a, b = results["points"], results["continuation"]
        diff = max(float(np.max(np.abs(a[c] - b[c]))) for c in a.names if a.unit(c) == "m")
        rows.append({"case": name, "points": len(volts), "points_s": best["points"],
                     "continuation_s": best["continuation"], "dynamic_s": best["dynamic"],
                     "continuation_without_stability_check_s": best["unchecked"],
                     "dynamic_over_continuation": best["dynamic"] / best["continuation"],
                     "points_over_continuation": best["points"] / best["continuation"],
                     "max_position_difference_m": diff, "fallback_points": b.info["fallback_points"]})
    print(f"{'case':28s} {'per-point':>11s} {'continuation':>13s} {'dynamic':>10s} {'per point (cont.)':>18s} "
          f"{'dyn/cont':>9s} {'pts/cont':>9s} {'max |dx| [m]':>13s} {'cont. unchecked':>16s}")
    for r in rows:
        print(f"{r['case']:28s} {r['points_s'] * 1e3:9.1f} ms {r['continuation_s'] * 1e3:10.1f} ms "
              f"{r['dynamic_s'] * 1e3:7.1f} ms {r['continuation_s'] / r['points'] * 1e6:15.0f} us "
              f"{r['dynamic_over_continuation']:8.2f}x {r['points_over_continuation']:8.2f}x "
              f"{r['max_position_difference_m']:13.2e} {r['continuation_without_stability_check_s'] * 1e3:13.1f} ms")
    payload = {"benchmark": "bench_static_sweep", "exudyn_atcm": atcm.__version__, "exudyn": exudyn.__version__,
               "python": platform.python_version(), "machine": platform.machine(), "repeats": args.repeats,
               "goal": "continuation sweep of 100 points at least 3x cheaper than the dynamic run", "rows": rows}
    os.makedirs(args.out, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = os.path.join(args.out, f"bench_static_sweep_{stamp}.json")
    write_text(path, json.dumps(payload, indent=2))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
