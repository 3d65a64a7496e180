"""Start-up cost: ``import exudyn_atcm``, ``exudyn-atcm --help`` and ``import exudyn`` (issue 31, part 4).

Each command runs in a fresh interpreter (``python -c ...``), timed from outside as the whole process's wall
time; the table gives the best and the median of ``--repeats`` runs after one warm-up.  The bare interpreter
(``python -c pass``) is timed too, so the package's own share can be read off.

With ``--vs DIR`` (a checkout) or ``--vs REF`` (a git revision of this repository, e.g. ``main``: its
``exudyn_atcm/`` is extracted with ``git archive`` into a temporary directory) the other revision is timed in
the same run, interleaved A B A B per command, so that both columns saw the same machine load; the table
then shows before (the other revision) and after (this checkout) side by side with the ratio of the best
times.  The checkout is chosen by the working directory: ``python -c`` puts it first on ``sys.path``, so
``import exudyn_atcm`` finds that checkout's package (the same interpreter and installed dependencies serve
both).

Goals (issue 31): ``import exudyn_atcm`` <= 0.3 s and ``exudyn-atcm --help`` <= 0.5 s, judged on the best of
the runs (the least disturbed by other load on a shared machine).  The script reports the figures against the
goals; it does not fail when a goal is missed.  Two more commands have no goal: a fresh process's first
``static_sweep``, first fixed-step ``simulate`` and first ``simulate(accuracy=1e-2)`` of a small actuator (import, build, solve), what a script pays
before its first answer.

Usage: ``python benchmarks/bench_import.py [--repeats 7] [--vs main | --vs /path/to/other/checkout]``.  Writes
JSON to ``benchmarks/results/`` (git-ignored).  Takes about a minute.
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
import tarfile
import tempfile
import time

from exudyn_atcm.io.atomic import write_text

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

#: a small actuator, built by every command that solves (the paper's laminate, 3 rod cells, 87 mm)
ACTUATOR = ("import warnings; warnings.simplefilter('ignore')\nimport exudyn_atcm as atcm\n"
            "from exudyn_atcm.mechanism.actuator import BendingActuator\n"
            "from exudyn_atcm.model.drive import PiezoDrive\nfrom exudyn_atcm.model.materials import Layer\n"
            "from exudyn_atcm.model.signals import Triangle\n"
            "act = BendingActuator(3, 29e-3, 28e-3, Layer(0.2e-3, 70e9, 1550.0), Layer(0.3e-3, 30.336e9, 5440.0), "
            "PiezoDrive(Triangle(750.0, 750.0, 0.02)), cell='rod')\n")
COMMANDS = {
    "python -c pass": "pass",
    "import exudyn": "import exudyn",
    "import exudyn_atcm": "import exudyn_atcm",
    "exudyn-atcm --help": ("import sys; sys.argv = ['exudyn-atcm', '--help']\n"
                           "from exudyn_atcm.cli import main\nsys.exit(main())"),
    # what a script that solves something pays before its first answer (the import of what the solve needs
    # and the solve of a 3-cell rod actuator: three sweep points, a 20-step run)
    "first static_sweep": ACTUATOR + "atcm.static_sweep(act, [0.0, 500.0, 1000.0])",
    "first simulate": ACTUATOR + "atcm.simulate(act, 0.02, step=1e-3)",
    "first accuracy run": ACTUATOR + "atcm.simulate(act, 0.02, accuracy=1e-2)",
}
GOALS = {"import exudyn_atcm": 0.3, "exudyn-atcm --help": 0.5}
HEAVY = ("exudyn", "numpy", "scipy", "scipy.linalg", "scipy.optimize", "scipy.signal", "scipy.stats", "scipy.io", "scipy.sparse",
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


def extract_revision(ref: str, into: str) -> str:
    """Extract ``exudyn_atcm/`` of git revision ``ref`` into the directory ``into``; returns ``into``."""
    try:
        archive = subprocess.run(["git", "-C", ROOT, "archive", "--format=tar", ref, "exudyn_atcm"], check=True,
                                 capture_output=True).stdout
    except subprocess.CalledProcessError as exc:
        raise ValueError(f"--vs must be a checkout directory or a git revision of {ROOT}, got {ref!r}: "
                         f"{exc.stderr.decode(errors='replace').strip()}") from None
    path = os.path.join(into, "archive.tar")
    with open(path, "wb") as handle:
        handle.write(archive)
    with tarfile.open(path) as tar:
        if hasattr(tarfile, "data_filter"):  # Python >= 3.10.12 / 3.11.4
            tar.extractall(into, filter="data")
        else:  # our own git archive of exudyn_atcm/ only
            tar.extractall(into)
    return into


def revision_label(ref: str) -> str:
    """``ref`` with its short commit (``main@698381f``), for the table's header."""
    out = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", ref], capture_output=True, text=True)
    return f"{ref}@{out.stdout.strip()}" if out.returncode == 0 else ref


def time_commands(checkouts: dict[str, str], repeats: int) -> dict[str, dict[str, list[float]]]:
    """Wall times [s] per command and checkout: one warm-up each, then ``repeats`` rounds interleaved."""
    times: dict[str, dict[str, list[float]]] = {name: {c: [] for c in checkouts} for name in COMMANDS}
    for name, code in COMMANDS.items():
        for path in checkouts.values():
            run_once(code, path)  # warm-up: file cache, .pyc
        for _ in range(repeats):
            for label, path in checkouts.items():
                times[name][label].append(run_once(code, path))
    return times


def report(checkouts: dict[str, str], times: dict[str, dict[str, list[float]]], repeats: int) -> list[dict]:
    """Print the table (before | after side by side when two checkouts); the rows for the JSON."""
    labels = list(checkouts)
    print(f"start-up wall time [s], best and median of {repeats} fresh processes each (interleaved), "
          f"python {platform.python_version()}")
    for label, path in checkouts.items():
        print(f"  {label}: {path}")
    width = max(len(label) for label in labels) + 7
    head = f"{'command':<20}" + "".join(f"{label + ' best':>{width}}{'median':>8}" for label in labels)
    head += f"{'goal':>7}{'met':>5}" + (f"{'after/before':>14}" if len(labels) == 2 else "")
    print(head)
    rows = []
    for name in COMMANDS:
        row: dict = {"command": name, "goal_s": GOALS.get(name)}
        line = f"{name:<20}"
        for label in labels:
            best, med = min(times[name][label]), statistics.median(times[name][label])
            row[label] = {"best_s": best, "median_s": med, "runs_s": times[name][label]}
            line += f"{best:>{width}.3f}{med:>8.3f}"
        this_best = row[labels[-1]]["best_s"]
        if name in GOALS:
            row["goal_met"] = this_best <= GOALS[name]
            line += f"{GOALS[name]:>7.2f}{'yes' if row['goal_met'] else 'no':>5}"
        else:
            line += f"{'':>12}"
        if len(labels) == 2:
            row["ratio_best_after_over_before"] = this_best / row[labels[0]]["best_s"]
            line += f"{row['ratio_best_after_over_before']:>14.2f}"
        rows.append(row)
        print(line)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=7, help="fresh processes per command and checkout")
    parser.add_argument("--vs", default=None, metavar="DIR|REF",
                        help="the revision to compare with (before): a checkout directory or a git revision (main)")
    args = parser.parse_args()
    if args.repeats < 1:
        raise ValueError(f"--repeats must be at least 1, got {args.repeats}")
    with tempfile.TemporaryDirectory(prefix="bench_import_") as scratch:
        checkouts: dict[str, str] = {}
        if args.vs is not None:
            if os.path.isdir(args.vs):
                if not os.path.isdir(os.path.join(args.vs, "exudyn_atcm")):
                    raise ValueError(f"--vs must be a checkout holding exudyn_atcm/, got {args.vs!r}")
                checkouts["before: " + os.path.basename(os.path.abspath(args.vs))] = os.path.abspath(args.vs)
            else:
                checkouts["before: " + revision_label(args.vs)] = extract_revision(args.vs, scratch)
        checkouts[("after: " if checkouts else "") + "this"] = ROOT
        times = time_commands(checkouts, args.repeats)
        rows = report(checkouts, times, args.repeats)
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
