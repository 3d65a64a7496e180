"""Instructions executed by the solve of two revisions of exudyn_atcm, counted by callgrind.

Wall times on a shared machine scatter by up to 1.5x between runs of the same code, so a
difference of a few per cent between two revisions (issue 14, part 6) cannot be read off them.
The number of instructions a run executes does not depend on the machine's load: this script
runs the lone actuator of ``bench_discretisation.py`` (87 mm, the paper's laminate, the paper's
Preisach loop in the step, triangle 500 +- 1000 V of period 0.5 s, step 1e-4 s) for each cell
kind and number of cells under ``valgrind --tool=callgrind``, counting only inside Exudyn's
``SolveSystem`` (the time integration with every Python hook it calls; not the import, the
building of the system or the result), for each revision in turn, and prints the counts and
their ratio.  Instructions are not time (a cache miss costs more than an addition), but the
same solver on the same system differs between revisions only in the package's Python work.

Needs ``valgrind`` on the PATH (not a dependency of the package).  Each point takes about a
minute per revision (valgrind runs the code some 50x slower).

Usage::

    python benchmarks/instruction_counts.py --old DIR:PYTHON --new DIR:PYTHON \
        [--points "ritz 1,ritz 3,beam 2,rigid 4"] [--t-sim 0.1]

``DIR`` is a checkout and ``PYTHON`` an interpreter that imports that checkout's exudyn_atcm
(a venv with it installed, or a wrapper script that sets ``PYTHONPATH`` and execs Python).
Writes JSON to ``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

from exudyn_atcm.io.atomic import write_json

RESULTS = Path(__file__).resolve().parent / "results"
DEFAULT_POINTS = "ritz 1,ritz 2,ritz 3,ancf 2,beam 2,rigid 4,six-bar 3"

#: The run counted, written with names every revision since the flat layout has at the top level.
CHILD = """
import sys, warnings
warnings.simplefilter("ignore")
import exudyn_atcm as atcm
try:
    from exudyn_atcm.model.parameter_sets import paper_strain_preisach
except ImportError:  # the flat layout of earlier revisions
    from exudyn_atcm.parameter_sets import paper_strain_preisach
cell, n, t_sim = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
cfc, mfc = atcm.Layer(0.2e-3, 70e9, 1550.0), atcm.Layer(0.3e-3, 30.336e9, 5440.0)
drive = atcm.PiezoDrive(atcm.signals.Triangle(500.0, 1000.0, 0.5), hysteresis=paper_strain_preisach())
actuator = atcm.BendingActuator(n, 0.087 / n, 28e-3, cfc, mfc, drive, cell=cell)
result = atcm.simulate(actuator, t_sim, step=1e-4)
tip_y = result["actuator.tip_y"] if "actuator.tip_y" in result else result["tip_y"]  # before 0.3.0: "tip_y"
print("tip_y", repr(float(tip_y[-1])))
"""


def count(python: str, checkout: str, cell: str, n: int, t_sim: float, workdir: Path) -> tuple[int, float]:
    """(instructions inside ``SolveSystem``, last tip_y [m]) of one run of ``checkout``'s package."""
    child = workdir / "child.py"
    child.write_text(CHILD)
    out = workdir / f"callgrind.{os.getpid()}.out"
    cmd = ["valgrind", "--tool=callgrind", "--trace-children=yes", "--collect-atstart=no",
           "--toggle-collect=CSolverBase::SolveSystem*", f"--callgrind-out-file={out}",
           python, str(child), cell, str(n), str(t_sim)]
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(Path(checkout).resolve()))
    proc = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{proc.stderr[-2000:]}")
    collected = [int(m.group(1)) for m in re.finditer(r"Collected : (\d+)", proc.stderr)]
    tip = re.search(r"tip_y (\S+)", proc.stdout)
    if not collected or tip is None:
        raise RuntimeError(f"no instruction count or tip in the output of {' '.join(cmd)}:\n{proc.stderr[-2000:]}")
    return max(collected), float(tip.group(1))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old", required=True, help="CHECKOUT:PYTHON of the old revision")
    parser.add_argument("--new", required=True, help="CHECKOUT:PYTHON of the new revision")
    parser.add_argument("--points", default=DEFAULT_POINTS, help=f"comma-separated 'cell n' (default {DEFAULT_POINTS!r})")
    parser.add_argument("--t-sim", type=float, default=0.1, help="simulated time [s] per run (default 0.1)")
    parser.add_argument("--out", default=str(RESULTS))
    args = parser.parse_args(argv)
    if shutil.which("valgrind") is None:
        parser.error("valgrind is not on the PATH: install it (e.g. apt install valgrind) to count instructions")
    revisions = {"old": args.old.split(":", 1), "new": args.new.split(":", 1)}
    for rev, parts in revisions.items():
        if len(parts) != 2:
            parser.error(f"--{rev} must be CHECKOUT:PYTHON, got {getattr(args, rev)!r}")
        if not (Path(parts[0]) / "exudyn_atcm").is_dir():
            parser.error(f"--{rev}: {parts[0]!r} is not a checkout of exudyn_atcm (no exudyn_atcm folder in it)")
        if shutil.which(parts[1]) is None:
            parser.error(f"--{rev}: the interpreter {parts[1]!r} is not an executable")
    points = []
    for item in args.points.split(","):
        cell, _, n = item.strip().rpartition(" ")
        if not cell or not n.isdigit():
            parser.error(f"--points: each point is 'cell n' (e.g. 'ritz 3'), got {item!r}")
        points.append((cell, int(n)))
    rows = []
    print(f"{'point':>12} | {'old [M instr]':>13} | {'new [M instr]':>13} | {'new/old':>7} | {'tip_y new - old [m]':>19}")
    with tempfile.TemporaryDirectory() as tmp:
        for cell, n in points:
            counts, tips = {}, {}
            for rev, (checkout, python) in revisions.items():
                counts[rev], tips[rev] = count(python, checkout, cell, n, args.t_sim, Path(tmp))
            ratio = counts["new"] / counts["old"]
            rows.append({"cell": cell, "n": n, "old": counts["old"], "new": counts["new"], "new/old": ratio,
                         "tip_y old [m]": tips["old"], "tip_y new [m]": tips["new"]})
            print(f"{cell + ' ' + str(n):>12} | {counts['old'] / 1e6:>13.2f} | {counts['new'] / 1e6:>13.2f} | "
                  f"{ratio:>7.3f} | {tips['new'] - tips['old']:>19.3g}", flush=True)
    payload = {"benchmark": "instruction_counts", "date": _dt.datetime.now(_dt.timezone.utc).isoformat(),
               "t_sim [s]": args.t_sim, "old": args.old, "new": args.new, "rows": rows}
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = out / f"instruction_counts_{stamp}.json"
    write_json(path, payload)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
