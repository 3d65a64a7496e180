"""Cost of building the Exudyn model of a bender, per cell kind: wall time and memory before the first step.

The run-time estimate (:func:`exudyn_atcm.solve.build_cost.build_estimate`) adds the build to the
steps, so that a model of very many cells is announced before it is built (issue 29, finding 9:
1e5 rigid cells took about 20 s and 1.2 GB to build, unannounced).  This script builds a
cantilever of the paper's laminate (30 mm, 10 mm wide, unpowered) for every listed cell kind
(:data:`exudyn_atcm.cells.CELL_KINDS`) at several cell counts, each in a fresh process (the peak
resident memory then belongs to that build alone), best of ``--repeats``, and prints the measured
wall time and memory per cell next to the constants in use
(:attr:`exudyn_atcm.cells.CellKind.build_cost`), with the non-negative least-squares fits
``seconds = n (a + b n)`` and ``bytes = n (m + k n)`` per kind (quadratic terms for the modal
kinds, whose matrices are dense in the number of modes).

Usage: ``python benchmarks/bench_build_cost.py [--cells 200 800 3200] [--modes 8 32 128] [--repeats 2]``.
Writes JSON to ``benchmarks/results/`` (git-ignored).  Default run: about a minute.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import platform
import subprocess
import sys

import exudyn
import numpy as np
from scipy.optimize import nnls

from exudyn_atcm import __version__
from exudyn_atcm.cells import CELL_KINDS

#: The cell kinds whose ``n_cells`` counts assumed modes (dense in the count): measured at ``--modes``.
MODAL = ("ritz", "rod")

CHILD = r"""
import resource, sys, time, warnings
warnings.simplefilter("ignore")
import exudyn_atcm as atcm
from exudyn_atcm.mbs import builder
cell, n = sys.argv[1], int(sys.argv[2])
cfc = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
mfc = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
b = atcm.Bender("b", width=10e-3, passive=cfc, active=mfc, length=0.03, n_cells=n, drive=atcm.PiezoDrive(0.0), cell=cell)
m = atcm.Mechanism().add(b).ground(b.base)
if cell in ("rod",):  # compile the rod kernels before timing (once per process, not per cell)
    builder.build(atcm.Mechanism().add(atcm.Bender("w", width=10e-3, passive=cfc, active=mfc, length=0.03,
                                                   n_cells=2, drive=atcm.PiezoDrive(0.0), cell=cell)).ground("w.base"))
rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
start = time.perf_counter()
model = builder.build(m)
wall = time.perf_counter() - start
rss1 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(wall, (rss1 - rss0) * 1024)
"""


def measure(cell: str, n: int) -> tuple[float, float]:
    """(wall time [s], peak memory growth [bytes]) of building ``n`` cells of ``cell`` in a fresh process."""
    out = subprocess.run([sys.executable, "-c", CHILD, cell, str(n)], capture_output=True, text=True, check=True)
    wall, memory = out.stdout.split()[-2:]
    return float(wall), float(memory)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, nargs="+", default=[200, 800, 3200])
    parser.add_argument("--modes", type=int, nargs="+", default=[8, 32, 128])
    parser.add_argument("--repeats", type=int, default=2, help="builds per point, the fastest counts (default 2)")
    parser.add_argument("--kinds", nargs="+", default=list(CELL_KINDS), choices=list(CELL_KINDS))
    args = parser.parse_args()
    rows = []
    for cell in args.kinds:
        for n in (args.modes if cell in MODAL else args.cells):
            runs = [measure(cell, n) for _ in range(args.repeats)]
            wall = min(r[0] for r in runs)
            memory = min(r[1] for r in runs)
            estimate = CELL_KINDS[cell].estimate_build(n)
            rows.append({"cell": cell, "n_cells": n, "wall [s]": wall, "memory [MB]": memory / 1e6,
                         "per cell [us]": 1e6 * wall / n, "memory per cell [kB]": memory / n / 1e3,
                         "estimate [s]": None if estimate is None else estimate[0],
                         "estimated memory [MB]": None if estimate is None else estimate[1] / 1e6,
                         "estimate / measured": None if estimate is None else estimate[0] / wall})
    print("| cell | cells | wall [s] | per cell [µs] | memory [MB] | per cell [kB] | estimate / measured: time | memory |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        ratio = "-" if r["estimate / measured"] is None else f"{r['estimate / measured']:.2f}"
        memory = "-" if r["estimated memory [MB]"] is None else f"{r['estimated memory [MB]'] / max(r['memory [MB]'], 1e-6):.2f}"
        print(f"| {r['cell']} | {r['n_cells']} | {r['wall [s]']:.3f} | {r['per cell [us]']:.1f} | "
              f"{r['memory [MB]']:.1f} | {r['memory per cell [kB]']:.2f} | {ratio} | {memory} |")
    fits = {}
    for cell in args.kinds:
        mine = [r for r in rows if r["cell"] == cell]
        n = np.array([r["n_cells"] for r in mine], dtype=float)
        basis = np.column_stack([n, n**2])
        scale = basis.max(axis=0)  # relative weights: each point's error in proportion to its value
        wall = np.array([r["wall [s]"] for r in mine])
        memory = np.array([r["memory [MB]"] for r in mine]) * 1e6
        (a, b), _ = nnls(basis / scale / wall[:, None], np.ones_like(wall))
        (m, k), _ = nnls(basis / scale / np.maximum(memory, 1.0)[:, None], np.ones_like(memory))
        a, b, m, k = a / scale[0], b / scale[1], m / scale[0], k / scale[1]
        fits[cell] = {"a [s]": a, "b [s]": b, "m [bytes]": m, "k [bytes]": k}
        print(f"{cell}: time n ({a:.3g} + {b:.3g} n) s, memory n ({m:.3g} + {k:.3g} n) bytes "
              f"(tuple: ({a:.2g}, {b:.2g}, {m:.2g}, {k:.2g})); in use: {CELL_KINDS[cell].build_cost}")
    out = os.path.join(os.path.dirname(__file__), "results")
    os.makedirs(out, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = os.path.join(out, f"build_cost_{stamp}.json")
    with open(path, "w", encoding="utf-8") as handle:
        json.dump({"rows": rows, "fits": fits, "exudyn_atcm": __version__, "exudyn": exudyn.__version__,
                   "platform": platform.platform()}, handle, indent=2)
    print(f"\nwrote {path}")


if __name__ == "__main__":
    main()
