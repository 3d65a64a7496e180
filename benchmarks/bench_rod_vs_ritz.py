"""``cell="rod"`` against ``cell="ritz"`` for a lone actuator at equal accuracy (issue 30, part 5).

The paper's actuator (3 x 29 mm, 28 mm wide, CFC 0.2 mm on MFC 0.3 mm, docs/theory.rst) at 1500 V, for
``n`` = 2, 3, 4, 6, 8 modes of each cell, against the references the tests use:

* the static tip angle against beam theory's exact arc, ``kappa L`` (``kappa`` the free curvature);
* f1 of the straight cantilever against the clamped-free Euler-Bernoulli beam
  (:func:`exudyn_atcm.theory.first_bending_frequency`; rotary inertia lowers the models' f1 by ~2e-5,
  the floor of this error);
* f1 of the bent state (1500 V) against 64 geometrically exact beam elements (``cell="beam"``) about the
  same state (their own discretisation error, ~(h/L)^2 ~ 1e-4 at 8 elements, ~2e-6 at 64).

For each target error (1e-3 and 1e-4 on all three) the cheapest ``n`` of each cell reaching it is taken and
its cost measured side by side, interleaved, best of ``--repeats``: the wall time of the three solves
(``solve_static``, ``eigenfrequencies`` straight and bent) and the wall time per step of a 0.05 s
``simulate`` through a 50 Hz sine of 0..1500 V at 1e-4 s.

Usage: ``python benchmarks/bench_rod_vs_ritz.py [--repeats 3] [--out DIR]``.  Prints a table and writes
JSON to ``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import math
import os
import platform
import sys
import time
import warnings
from pathlib import Path

import exudyn

import exudyn_atcm as atcm
from exudyn_atcm import __version__
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.theory import first_bending_frequency

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
LENGTH, WIDTH, VOLTAGE = 0.087, 28e-3, 1500.0
MODES = (2, 3, 4, 6, 8)
TARGETS = (1e-3, 1e-4)
T_END, STEP = 0.05, 1e-4


def actuator(cell: str, n: int, drive=None) -> atcm.BendingActuator:
    return atcm.BendingActuator(n, LENGTH / n, WIDTH, CFC, MFC,
                                drive if drive is not None else atcm.PiezoDrive(VOLTAGE), cell=cell)


def sine(t: float) -> float:
    return 0.5 * VOLTAGE * (1.0 - math.cos(2.0 * math.pi * 50.0 * t))


def references() -> dict:
    a = actuator("beam", 64)
    kappa = a.curvature_per_strain * a.drive.static_strain(VOLTAGE)
    return {"tip angle [rad]": kappa * LENGTH,
            "f1 [Hz]": first_bending_frequency(a.bending_stiffness, a.mass_per_length, LENGTH),
            "bent f1 [Hz]": float(atcm.eigenfrequencies(a, n=1, voltage=VOLTAGE)[0])}


def accuracy(cell: str, n: int, ref: dict) -> dict:
    a = actuator(cell, n)
    tip = float(atcm.solve_static(a, voltage=VOLTAGE)["actuator.tip_angle"][-1])
    f1 = float(atcm.eigenfrequencies(a, n=1)[0])
    fb = float(atcm.eigenfrequencies(a, n=1, voltage=VOLTAGE)[0])
    errors = {"tip angle": abs(tip / ref["tip angle [rad]"] - 1.0), "f1": abs(f1 / ref["f1 [Hz]"] - 1.0),
              "bent f1": abs(fb / ref["bent f1 [Hz]"] - 1.0)}
    return {"cell": cell, "n": n, "tip angle [rad]": tip, "f1 [Hz]": f1, "bent f1 [Hz]": fb,
            "relative errors": errors, "worst": max(errors.values())}


def solve_cost(cell: str, n: int) -> float:
    t0 = time.perf_counter()
    a = actuator(cell, n)
    atcm.solve_static(a, voltage=VOLTAGE)
    atcm.eigenfrequencies(a, n=1)
    atcm.eigenfrequencies(a, n=1, voltage=VOLTAGE)
    return time.perf_counter() - t0


def step_cost(cell: str, n: int) -> float:
    """Wall time [s] per step: the run's minus a one-step run's (the build and the initial equilibrium, which
    every run pays once; until 2026-11-29 they were counted in, about 3-5 us of each step here), per further step."""
    a = actuator(cell, n, atcm.PiezoDrive(sine))
    t0 = time.perf_counter()
    atcm.simulate(a, T_END, step=STEP)
    whole = time.perf_counter() - t0
    t0 = time.perf_counter()
    atcm.simulate(actuator(cell, n, atcm.PiezoDrive(sine)), STEP, step=STEP)
    one = time.perf_counter() - t0
    return (whole - one) / (round(T_END / STEP) - 1)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=RESULTS)
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore", atcm.AccuracyWarning)
    ref = references()
    rows = [accuracy(cell, n, ref) for n in MODES for cell in ("ritz", "rod")]
    for cell in ("ritz", "rod"):  # warm-up: imports and first builds outside the timings
        solve_cost(cell, 2)
        step_cost(cell, 2)
    picks = []
    for target in TARGETS:
        pick = {"target": target}
        for cell in ("ritz", "rod"):
            ok = [r["n"] for r in rows if r["cell"] == cell and r["worst"] <= target]
            pick[cell] = min(ok) if ok else None
        picks.append(pick)
    costs: dict = {}
    for (cell, n) in sorted({(c, p[c]) for p in picks for c in ("ritz", "rod") if p[c] is not None}):
        costs[(cell, n)] = {"solves [s]": math.inf, "per step [us]": math.inf}
    for _ in range(args.repeats):  # interleaved: ritz, rod, ritz, rod, ...
        for key in costs:
            costs[key]["solves [s]"] = min(costs[key]["solves [s]"], solve_cost(*key))
            costs[key]["per step [us]"] = min(costs[key]["per step [us]"], 1e6 * step_cost(*key))

    print(f"exudyn_atcm {__version__} ({Path(atcm.__file__).resolve().parents[1]}), exudyn {exudyn.__version__}")
    print("references: " + ", ".join(f"{k} {v:.9g}" for k, v in ref.items()))
    print(f"{'cell':>5} | {'n':>2} | {'tip angle err':>13} | {'f1 err':>8} | {'bent f1 err':>11}")
    for r in rows:
        e = r["relative errors"]
        print(f"{r['cell']:>5} | {r['n']:>2} | {e['tip angle']:>13.1e} | {e['f1']:>8.1e} | {e['bent f1']:>11.1e}")
    print(f"\n{'target':>7} | {'cell':>5} | {'n':>2} | {'solves [ms]':>11} | {'us/step':>8} | rod/ritz solves, steps")
    table = []
    for p in picks:
        cr, cd = costs.get(("ritz", p["ritz"])), costs.get(("rod", p["rod"]))
        for cell in ("ritz", "rod"):
            c = costs.get((cell, p[cell]))
            if c is None:
                print(f"{p['target']:>7.0e} | {cell:>5} |  - | not reached")
                continue
            ratio = ""
            if cell == "rod" and cr is not None:
                ratio = f"{cd['solves [s]'] / cr['solves [s]']:.2f}, {cd['per step [us]'] / cr['per step [us]']:.2f}"
            print(f"{p['target']:>7.0e} | {cell:>5} | {p[cell]:>2} | {1e3 * c['solves [s]']:>11.1f} | "
                  f"{c['per step [us]']:>8.1f} | {ratio}")
            table.append({"target": p["target"], "cell": cell, "n": p[cell], **c})
    stamp = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    os.makedirs(args.out, exist_ok=True)
    write_json(os.path.join(args.out, f"rod_vs_ritz_{stamp}.json"), {
        "benchmark": "bench_rod_vs_ritz", "exudyn_atcm": __version__, "exudyn": exudyn.__version__,
        "python": platform.python_version(), "repeats": args.repeats, "references": ref,
        "accuracy": rows, "cost": table})
    return 0


if __name__ == "__main__":
    sys.exit(main())
