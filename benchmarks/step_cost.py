"""The step's own cost (issue 31, part 3): the package's four-bar against the hand-built linkage, side by side.

Run as ``python benchmarks/bench_mechanisms.py --step-cost [--t-sim 0.5] [--repeats 5] [--steps 1e-4,4e-4]``.

Models, at each step (the case's compliant four-bar, the paper's triangle through its Preisach loop):

* ``package rod``: ``simulate`` of the case's four-bar with a 3-mode ``rod`` crank;
* ``hand-built linkage``: :mod:`handbuilt` with one ``ObjectBeamGeometricallyExact2D`` per bender (the
  linkage with the same hysteresis hooks, no package layer): what the linkage itself costs in Exudyn.

Cost per step [us]: ((best of ``repeats`` runs of ``t_sim``) - (best of ``repeats`` runs of one step)) /
steps, the models interleaved in every round (the machine is shared).  ``rod hooks [us/step]``: the rod's
own Python (its strain writer before every attempted step and its post-Newton check after every Newton
solve) timed from the inside with ``time.perf_counter`` in one more run per model (about 0.1 us of the
figure is the timer).  ``path error``: the coupler point's largest distance from a reference run (the
package's four-bar with ``--reference-cells`` beam elements, same step), relative to its largest travel.
"""

from __future__ import annotations

import datetime as _dt
import os
import platform
import time
import warnings
from pathlib import Path

import exudyn
import numpy as np

from exudyn_atcm import __version__, simulate
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.mbs.chains import rod as rod_chain

import bench_systems as bm
import handbuilt
from mechanism_targets import path_error

PACKAGE, HAND = "package rod (3 modes)", "hand-built linkage (1 GE element)"
MODES = 3


class RodHookTimer:
    """Time the rod cells' strain writers and post-Newton checks built while it is active."""

    def __init__(self) -> None:
        self.seconds = 0.0
        self._original = rod_chain.add_rod_bender

    def __enter__(self) -> "RodHookTimer":
        original, timer = self._original, self

        def timed_add(ctx, bender):
            add_post_newton = ctx.add_post_newton

            def add_timed(check):
                def timed(mbs, t):
                    start = time.perf_counter()
                    try:
                        return check(mbs, t)
                    finally:
                        timer.seconds += time.perf_counter() - start
                add_post_newton(timed)

            ctx.add_post_newton = add_timed
            writer, hook = original(ctx, bender)

            def timed_writer(strains):
                start = time.perf_counter()
                try:
                    writer(strains)
                finally:
                    timer.seconds += time.perf_counter() - start
            return timed_writer, hook

        rod_chain.add_rod_bender = timed_add
        return self

    def __exit__(self, *exc) -> None:
        rod_chain.add_rod_bender = self._original


def package_run(t_end: float, step: float) -> tuple[float, np.ndarray, np.ndarray, dict]:
    mech = bm.four_bar(MODES, "rod")
    with warnings.catch_warnings():  # a one-step run sees almost none of the program: expected here
        warnings.simplefilter("ignore", RuntimeWarning)
        start = time.perf_counter()
        result = simulate(mech, t_end, step=step)
        wall = time.perf_counter() - start
    return wall, np.asarray(result["time"]), bm.path(result, "coupler.P"), dict(result.info)


def step_cost_table(t_sim: float = 0.5, repeats: int = 5, steps=(1e-4, 4e-4), reference_cells: int = 64,
                    out: str | os.PathLike | None = None) -> dict:
    """Measure, print the table, write JSON; returns the JSON's content."""
    print(f"exudyn_atcm {__version__}, exudyn {exudyn.__version__}, python {platform.python_version()}, "
          f"{os.cpu_count()} cpus; four-bar, {t_sim:g} s simulated per run, best of {repeats}, interleaved "
          f"(shared machine)")
    rows = {}
    for h in steps:
        rt, rp = package_reference(t_sim, h, reference_cells)
        best = {PACKAGE: [np.inf, np.inf], HAND: [np.inf, np.inf]}
        errors, info = {}, {}
        for _ in range(repeats):
            for label in (PACKAGE, HAND):
                if label == PACKAGE:
                    one = package_run(h, h)[0]
                    wall, times, path, info = package_run(t_sim, h)
                else:
                    one = handbuilt.run("four_bar", 1, h, h)[0]
                    wall, times, path = handbuilt.run("four_bar", 1, t_sim, h)
                best[label][0] = min(best[label][0], one)
                best[label][1] = min(best[label][1], wall)
                errors[label] = path_error(times, path, rt, rp)
        with RodHookTimer() as timer:
            package_run(t_sim, h)
        n_steps = t_sim / h
        cost = {label: (b[1] - b[0]) / n_steps * 1e6 for label, b in best.items()}
        rows[f"{h:g}"] = {
            "package_us_per_step": cost[PACKAGE], "hand_built_us_per_step": cost[HAND],
            "ratio": cost[PACKAGE] / cost[HAND], "rod_hooks_us_per_step": timer.seconds / info["attempted_steps"] * 1e6,
            "package_path_error": errors[PACKAGE], "hand_built_path_error": errors[HAND],
            "package_newton_steps": info["newton_steps"], "steps": info["attempted_steps"]}
    header = (f"{'step [s]':>8} | {'package [us/step]':>17} | {'hand-built [us/step]':>20} | {'ratio':>5} | "
              f"{'rod hooks [us/step]':>19} | {'package error':>13} | {'hand-built error':>16}")
    print(header)
    print("-" * len(header))
    for h, r in rows.items():
        print(f"{h:>8} | {r['package_us_per_step']:>17.1f} | {r['hand_built_us_per_step']:>20.1f} | {r['ratio']:>5.2f} | "
              f"{r['rod_hooks_us_per_step']:>19.1f} | {r['package_path_error']:>13.1e} | {r['hand_built_path_error']:>16.1e}")
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = Path(out or bm.RESULTS) / f"bench_mechanisms_step_cost_{stamp}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    payload = {"exudyn_atcm": __version__, "exudyn": exudyn.__version__, "python": platform.python_version(),
               "cpus": os.cpu_count(), "t_sim_s": t_sim, "repeats": repeats, "models": [PACKAGE, HAND],
               "reference": f"package four-bar, {reference_cells} beam elements, same step", "rows": rows}
    write_json(path, payload)
    print(f"wrote {path}")
    return payload


def package_reference(t_sim: float, step: float, cells: int) -> tuple[np.ndarray, np.ndarray]:
    """Times and coupler path of the reference run (``cells`` beam elements on the crank)."""
    result = simulate(bm.four_bar(cells, "beam"), t_sim, step=step)
    return np.asarray(result["time"]), bm.path(result, "coupler.P")
