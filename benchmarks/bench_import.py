"""Start-up cost: ``import exudyn_atcm``, ``exudyn-atcm --help`` and ``import exudyn`` (issue 31, part 4).

Each command runs in a fresh interpreter (``python -c ...``), timed from outside as the whole process's wall
time; the table gives the best and the median of ``--repeats`` runs after one warm-up.  The bare interpreter
(``python -c pass``) is timed too, so the package's own share can be read off.

With ``--vs DIR`` a second checkout (e.g. the main branch's) is timed in the same run, interleaved
A B A B per command, so that both columns saw the same machine load.  The checkout is chosen by the working
directory: ``python -c`` puts it first on ``sys.path``, so ``import exudyn_atcm`` finds that checkout's package.

Goals (issue 31): ``import exudyn_atcm`` <= 0.3 s and ``exudyn-atcm --help`` <= 0.5 s.  The script reports the
figures against the goals; it does not fail when a goal is missed.

Usage: ``python benchmarks/bench_import.py [--repeats 7] [--vs /path/to/other/checkout]``.  Writes JSON to
``benchmarks/results/`` (git-ignored).  Takes well under a minute.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import platform
import statistics
import subprocess
import sys
import time

from exudyn_atcm.io.atomic import write_text

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

COMMANDS = {
    "python -c pass": "pass",
    "import exudyn": "import exudyn",
    "import exudyn_atcm": "import exudyn_atcm",
    "exudyn-atcm --help": ("import sys; sys.argv = ['exudyn-atcm', '--help']\n"
                           "from exudyn_atcm.cli import main\nsys.exit(main())"),
}
GOALS = {"import exudyn_atcm": 0.3, "exudyn-atcm --help": 0.5}
HEAVY = ("scipy", "scipy.linalg", "scipy.optimize", "scipy.signal", "scipy.stats", "scipy.io", "scipy.sparse",
         "matplotlib", "h5py")


def run_once(code: str, checkout: str) -> float:
    """Wall time [s] of one fresh ``python -c code`` started in ``checkout``."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], cwd=checkout, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def heavy_loaded(checkout: str) -> list[str]:
    """Which of ``HEAVY`` a fresh ``import exudyn_atcm`` in ``checkout`` leaves in ``sys.modules``."""
    code = f"import sys, exudyn_atcm; print(' '.join(m for m in {HEAVY!r} if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], cwd=checkout, check=True, capture_output=True, text=True)
    return out.stdout.split()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=7, help="fresh processes per command and checkout")
    parser.add_argument("--vs", default=None, help="a second checkout to time side by side (e.g. main's)")
    args = parser.parse_args()
    if args.repeats < 1:
        raise ValueError(f"--repeats must be at least 1, got {args.repeats}")
    checkouts = {"this": ROOT}
    if args.vs is not None:
        if not os.path.isdir(os.path.join(args.vs, "exudyn_atcm")):
            raise ValueError(f"--vs must be a checkout holding exudyn_atcm/, got {args.vs!r}")
        checkouts["vs"] = os.path.abspath(args.vs)
    times: dict[str, dict[str, list[float]]] = {name: {c: [] for c in checkouts} for name in COMMANDS}
    for name, code in COMMANDS.items():
        for label, path in checkouts.items():
            run_once(code, path)  # warm-up: file cache, .pyc
        for _ in range(args.repeats):
            for label, path in checkouts.items():
                times[name][label].append(run_once(code, path))
    rows = []
    head = f"{'command':<22}" + "".join(f"{label + ' best':>12}{label + ' median':>14}" for label in checkouts)
    head += f"{'goal':>8}" + (f"{'ratio med':>11}" if "vs" in checkouts else "")
    print(f"start-up wall time [s], {args.repeats} fresh processes each, python {platform.python_version()}")
    for label, path in checkouts.items():
        print(f"  {label}: {path}")
    print(head)
    for name in COMMANDS:
        row = {"command": name, "goal_s": GOALS.get(name)}
        line = f"{name:<22}"
        for label in checkouts:
            best, med = min(times[name][label]), statistics.median(times[name][label])
            row[label] = {"best_s": best, "median_s": med, "runs_s": times[name][label]}
            line += f"{best:>12.3f}{med:>14.3f}"
        line += f"{GOALS[name]:>8.2f}" if name in GOALS else f"{'':>8}"
        if "vs" in checkouts:
            ratio = row["this"]["median_s"] / row["vs"]["median_s"]
            row["ratio_median_this_over_vs"] = ratio
            line += f"{ratio:>11.2f}"
        rows.append(row)
        print(line)
    heavy = {label: heavy_loaded(path) for label, path in checkouts.items()}
    for label, mods in heavy.items():
        print(f"heavy modules after import exudyn_atcm ({label}): {', '.join(mods) or 'none'}")
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    out = os.path.join(HERE, "results", f"import_{stamp}.json")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    write_text(out, json.dumps({"repeats": args.repeats, "checkouts": checkouts, "python": sys.version,
                                "machine": platform.platform(), "rows": rows, "heavy_loaded": heavy}, indent=2))
    print(f"JSON: {out}")


if __name__ == "__main__":
    main()
