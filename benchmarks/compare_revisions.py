"""Side-by-side cost of two revisions of exudyn_atcm in one run, interleaved.

Each revision is a checkout with its own Python (a venv with that checkout installed).  The
benchmark scripts of each checkout run alternately, ``--rounds`` times (old, new, old, new,
...), so that the machine's load affects both alike; each revision's best cost per point is
compared.  Supports ``bench_mechanisms.py`` (cost per simulated second of the four-bar and the
gripper at equal cells per bender), ``bench_discretisation.py`` (cost per simulated second of
each discretisation at equal cells) and ``bench_rod_dynamics.py`` (the rod cell's observed order,
undamped energy drift and cost per step; the *new* checkout's script, which carries the exact
reference, runs under both revisions' interpreters; the orders and drifts are deterministic, the
costs the best of the rounds).

Usage::

    python benchmarks/compare_revisions.py --old DIR:PYTHON --new DIR:PYTHON \
        [--rounds 2] [--mechanisms-args "--t-sim 0.1 --cells 4,8 --repeats 2 --reference-cells 16"] \
        [--discretisation-args "--quick"] [--rod-dynamics-args "--quick"]

Prints a table per benchmark and writes JSON to ``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"


def run(checkout: str, python: str, script: str, extra: str, out: Path, script_checkout: str | None = None) -> dict:
    out.mkdir(parents=True, exist_ok=True)
    before = set(out.glob("*.json"))
    cmd = [python, str(Path(script_checkout or checkout) / "benchmarks" / script), *shlex.split(extra), "--out", str(out)]
    env = dict(os.environ, MPLBACKEND="Agg")
    subprocess.run(cmd, cwd=checkout, check=True, env=env, stdout=subprocess.DEVNULL)
    (new,) = set(out.glob("*.json")) - before
    return json.loads(new.read_text())


def mechanism_costs(payload: dict) -> dict[str, float]:
    return {f"{name} {cell} {n} cells": v["wall_per_simulated_second"]
            for name, cells in payload["results"].items() for cell, ns in cells.items() for n, v in ns.items()}


def discretisation_costs(payload: dict) -> dict[str, float]:
    return {f"{name} N={m['n']}": m["cost [s/s]"] for name, ms in payload["runs"].items() for m in ms}


def rod_dynamics_figures(payload: dict) -> dict[str, float]:
    """Per-step costs (``cost:`` keys, the best of the rounds is kept) and the orders and drifts (deterministic)."""
    out = {f"cost: {row['system']} [us/step]": row["wall per step [us]"] for row in payload["cost"]}
    out.update({f"passes/step: {row['system']}": row["passes per step"] for row in payload["cost"]})
    for row in payload["orders"]:
        for k, order in enumerate(row["orders"]):
            out[f"order {row['case']} halving {k + 1}"] = order
    for row in payload["drift"]:
        for rho in ("0.8", "1"):
            out[f"drift {row['geometry']} {row['case']} rho {rho} [%/s]"] = row[f"drift rho {rho} [%/s]"]
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old", required=True, help="CHECKOUT:PYTHON of the old revision")
    parser.add_argument("--new", required=True, help="CHECKOUT:PYTHON of the new revision")
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--mechanisms-args", default="--t-sim 0.1 --cells 4,8 --repeats 2 --reference-cells 16")
    parser.add_argument("--discretisation-args", default="--quick")
    parser.add_argument("--rod-dynamics-args", default="--quick")
    parser.add_argument("--skip", default="", help="comma-separated: mechanisms, discretisation, rod_dynamics")
    args = parser.parse_args(argv)
    revisions = {"old": args.old.split(":", 1), "new": args.new.split(":", 1)}
    benches = {"mechanisms": ("bench_mechanisms.py", args.mechanisms_args, mechanism_costs),
               "discretisation": ("bench_discretisation.py", args.discretisation_args, discretisation_costs),
               "rod_dynamics": ("bench_rod_dynamics.py", args.rod_dynamics_args, rod_dynamics_figures)}
    skip = {s.strip() for s in args.skip.split(",") if s.strip()}
    report = {}
    with tempfile.TemporaryDirectory() as tmp:
        for bench, (script, extra, costs_of) in benches.items():
            if bench in skip:
                continue
            best: dict[str, dict[str, float]] = {"old": {}, "new": {}}
            for r in range(args.rounds):
                for rev, (checkout, python) in revisions.items():
                    print(f"{bench}: round {r + 1}/{args.rounds}, {rev} ({checkout})", flush=True)
                    script_checkout = revisions["new"][0] if bench == "rod_dynamics" else None
                    costs = costs_of(run(checkout, python, script, extra, Path(tmp) / f"{bench}-{rev}-{r}",
                                         script_checkout))
                    for key, value in costs.items():
                        keep_last = bench == "rod_dynamics" and not key.startswith("cost:")
                        best[rev][key] = value if keep_last else min(value, best[rev].get(key, float("inf")))
            keys = [k for k in best["old"] if k in best["new"]]
            what = ("the rod cell: orders, drifts, best cost" if bench == "rod_dynamics"
                    else "best cost [wall s per simulated s]")
            print(f"\n{bench}: {what} of {args.rounds} interleaved rounds")
            print(f"{'point':>48} | {'old':>8} | {'new':>8} | {'new/old':>7}")
            for k in keys:
                ratio = best["new"][k] / best["old"][k] if best["old"][k] else float("nan")
                print(f"{k:>48} | {best['old'][k]:>8.3f} | {best['new'][k]:>8.3f} | {ratio:>7.2f}")
            report[bench] = {k: {"old": best["old"][k], "new": best["new"][k]} for k in keys}
    RESULTS.mkdir(parents=True, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = RESULTS / f"compare_revisions_{stamp}.json"
    tmp_path = path.with_suffix(".json.tmp")
    tmp_path.write_text(json.dumps({"old": args.old, "new": args.new, "rounds": args.rounds, "results": report}, indent=2))
    os.replace(tmp_path, path)  # atomic: a reader never sees half a file
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
