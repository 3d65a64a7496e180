"""What solving a built system again saves against building it for every solve (issue 30, part 2).

:func:`exudyn_atcm.solve_static` and :func:`exudyn_atcm.simulate` build a new Exudyn system for
every call; :class:`exudyn_atcm.BuiltSystem` builds once and restores the built state before each
solve.  For the README's four-bar and a lone actuator (a one-bender cantilever, rigid and beam
cells) this script times, side by side in one run (interleaved, each ``--repeats`` times, the
fastest kept):

* 20 static solves at 20 voltages (0 to 1000 V), one-off calls against one ``BuiltSystem``;
* 10 short simulations (5 ms at 0.1 ms steps) of the same program, one-off against one ``BuiltSystem``;

and checks that both ways give the same numbers.  Usage:
``python benchmarks/bench_rebuild.py [--repeats 3]``.  Prints a table and writes JSON to
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
import warnings

import exudyn
import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm.io.atomic import write_text
from exudyn_atcm.model import Triangle

from readme_systems import CFC, MFC, readme_four_bar

VOLTAGES = np.linspace(0.0, 1000.0, 20)
SIMULATIONS, T_END, STEP = 10, 5e-3, 1e-4


def four_bar() -> atcm.Mechanism:
    """The README's four-bar (six cells of the default kind in the crank)."""
    return readme_four_bar(Triangle(750.0, 750.0, 0.1))


def lone(cell: str, n: int):
    def make() -> atcm.Mechanism:
        b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=n, cell=cell,
                        drive=atcm.PiezoDrive(Triangle(750.0, 750.0, 0.1)))
        return atcm.Mechanism("actuator").add(b).ground(b.base)
    return make


SYSTEMS = {
    "README four-bar (6 rod cells)": four_bar,
    "lone actuator, 8 rigid cells": lone("rigid", 8),
    "lone actuator, 32 beam cells": lone("beam", 32),
}


def statics_fresh(make) -> list:
    return [atcm.solve_static(make(), voltage=float(v)) for v in VOLTAGES]


def statics_built(make) -> list:
    built = atcm.BuiltSystem(make())
    return [built.solve_static(float(v)) for v in VOLTAGES]


def dynamics_fresh(make) -> list:
    return [atcm.simulate(make(), T_END, step=STEP) for _ in range(SIMULATIONS)]


def dynamics_built(make) -> list:
    built = atcm.BuiltSystem(make())
    return [built.simulate(T_END, step=STEP) for _ in range(SIMULATIONS)]


def timed(run, make) -> tuple[float, list]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        start = time.perf_counter()
        results = run(make)
        return time.perf_counter() - start, results


def largest_difference(a: list, b: list) -> float:
    return max(float(np.max(np.abs(x[c] - y[c]))) for x, y in zip(a, b) for c in x)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="solving a built system again against building it per solve")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results"))
    args = parser.parse_args(argv)
    rows = []
    print(f"{'system':34s} {'what':28s} {'fresh [s]':>10s} {'built [s]':>10s} {'saved':>7s} {'max diff':>9s}")
    for name, make in SYSTEMS.items():
        for what, fresh_run, built_run in ((f"{len(VOLTAGES)} static solves", statics_fresh, statics_built),
                                           (f"{SIMULATIONS} simulations of {T_END * 1e3:g} ms", dynamics_fresh,
                                            dynamics_built)):
            fresh, built = math.inf, math.inf
            for _ in range(args.repeats):  # interleaved: the machine's load affects both alike
                t, a = timed(fresh_run, make)
                fresh = min(fresh, t)
                t, b = timed(built_run, make)
                built = min(built, t)
            diff = largest_difference(a, b)
            rows.append({"system": name, "what": what, "fresh_s": fresh, "built_s": built,
                         "saved_fraction": 1.0 - built / fresh, "largest_difference": diff})
            print(f"{name:34s} {what:28s} {fresh:10.3f} {built:10.3f} {1.0 - built / fresh:7.0%} {diff:9.1e}")
    stamp = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    payload = {"benchmark": "bench_rebuild", "voltages": VOLTAGES.tolist(), "simulations": SIMULATIONS,
               "t_end_s": T_END, "step_s": STEP, "repeats": args.repeats, "rows": rows,
               "package": atcm.__version__, "exudyn": exudyn.__version__, "python": platform.python_version()}
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, f"bench_rebuild_{stamp}.json")
    write_text(path, json.dumps(payload, indent=2))
    print(f"written {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
