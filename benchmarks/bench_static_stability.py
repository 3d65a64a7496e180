"""Cost of the stability check of static equilibria (issue 29, finding 1).

Every point of :func:`exudyn_atcm.static_sweep` is checked for stability
(:mod:`exudyn_atcm.solve.static_stability`).  This script runs the same 100-point sweep with the
check and with a stand-in that does nothing (``unchecked_probe.py``: the same solver settings as
the real probe makes the sweep use), interleaved, each ``--repeats`` times, the fastest kept, for a
cantilever of each cell kind and the shipped parallel guide, and prints the wall times and their
ratio.  Goal: a 100-point sweep not much slower (the issue asks it).  The check is the proof from
the running solver's Jacobian inside the continuation where Exudyn's Jacobian is the tangent (rigid,
beam and rod cells), else the grouped tangent and a Cholesky factorisation of every point after the
solve (six-bar and ANCF cells).  Until 2026-11-29 the stand-in lacked what the continuation sweep
asks of a probe and the script stopped at its first system.

Usage: ``python benchmarks/bench_static_stability.py [--repeats 3]``.  Writes JSON to
``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import importlib.util
import json
import math
import os
import pathlib
import platform
import time
import warnings

import exudyn
import numpy as np

from exudyn_atcm import Bender, Layer, Mechanism, PiezoDrive, __version__, static_sweep
from exudyn_atcm.casework.parameters import Parameters
from exudyn_atcm.io.atomic import write_text
from exudyn_atcm.solve import mechanism_solve

from unchecked_probe import unchecked_probe

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
CASES = pathlib.Path(__file__).resolve().parents[1] / "cases"


def cantilever(cell: str, n: int) -> tuple[Mechanism, np.ndarray]:
    b = Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=n, drive=PiezoDrive(0.0), cell=cell)
    m = Mechanism("cantilever").add(b)
    m.ground(b.base)
    m.force(b.tip, (-2.0, 0.01))  # an axial load of 0.16 P_cr: the check has joint forces to differentiate
    return m, np.linspace(0.0, 1000.0, 100)


def parallel_guide() -> tuple[Mechanism, dict]:
    spec = importlib.util.spec_from_file_location("parallel_guide", CASES / "parallel_guide.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    p = Parameters(mod.PARAMETERS, {d.name: d.default for d in mod.PARAMETERS})
    volts = np.linspace(0.0, 1000.0, 100)
    return mod.build_mechanism(p), {"lower.1": volts, "lower.2": -volts, "upper.1": volts, "upper.2": -volts}


SYSTEMS = {
    "rigid 16": lambda: cantilever("rigid", 16),
    "six-bar 16": lambda: cantilever("six-bar", 16),
    "beam 16": lambda: cantilever("beam", 16),
    "beam 64": lambda: cantilever("beam", 64),
    "ancf 16": lambda: cantilever("ancf", 16),
    "rod 4": lambda: cantilever("rod", 4),
    "parallel guide (rigid, 2 x 8 cells)": parallel_guide,
}


def timed(build, check: bool) -> float:
    mech, volts = build()
    original = mechanism_solve.stability_probe
    if not check:
        mechanism_solve.stability_probe = unchecked_probe
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            start = time.perf_counter()
            static_sweep(mech, volts)
            return time.perf_counter() - start
    finally:
        mechanism_solve.stability_probe = original


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="cost of the stability check of a static sweep")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results"))
    args = parser.parse_args(argv)
    rows = []
    print(f"{'system':40s} {'without [s]':>12s} {'with [s]':>10s} {'ratio':>7s}")
    for name, build in SYSTEMS.items():
        without, with_check = math.inf, math.inf
        for _ in range(args.repeats):  # interleaved: the machine's load affects both alike
            without = min(without, timed(build, False))
            with_check = min(with_check, timed(build, True))
        rows.append({"system": name, "without_s": without, "with_s": with_check, "ratio": with_check / without})
        print(f"{name:40s} {without:12.3f} {with_check:10.3f} {with_check / without:7.2f}")
    stamp = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    payload = {"benchmark": "bench_static_stability", "points": 100, "repeats": args.repeats, "rows": rows,
               "package": __version__, "exudyn": exudyn.__version__, "python": platform.python_version()}
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, f"bench_static_stability_{stamp}.json")
    write_text(path, json.dumps(payload, indent=2))
    print(f"written {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
