"""Runs with a stated accuracy (issue 31, part 1): ``simulate(system, t_end, accuracy=...)`` against a search.

For each system (the README four-bar with a 3-mode rod crank, the micro gripper of
``cases/micro_gripper.py`` with 4-mode rod benders and the paper's Preisach operator, the lone
paper actuator as a 3-mode rod) and drive (triangle, sine, step program; for the lone actuator and the four-bar
also a measured voltage record: a sine sampled every millisecond with 5 V of noise, reversing at nearly
every sample; for the lone actuator also a square wave switching every 5 ms), one period:

* ``simulate(..., accuracy=target)``: the step it chose, its error against a time-converged
  reference (a run at a quarter of the finest step searched, or of the chosen step if finer), and
  its CPU time, the prediction and the probe runs included;
* a search over steps ``t_end / n`` (``n`` on a ladder of ratio 2^(1/4), at least 20 steps per shortest
  feature of the drive, or for a record the grid of its samples, as ``accuracy=`` keeps: no warning about
  the program's resolution, :func:`exudyn_atcm.solve.corner_grid.feature_steps`): the
  coarsest step whose run meets the target against the same reference, and its CPU time (one run);
* the ratio of the two CPU times (goal: at most 1.5), ``run alone``: the ratio for the run at the
  chosen step without the prediction and the probe (what the choice of the step itself costs), and
  ``steps``: the steps the call integrated (the probe over its window, the run, a refined run) over
  the cheapest run's, a measure of the work free of timing noise (it leaves out the prediction and
  the fixed cost of each run).

CPU times (``time.process_time``), best of ``--repeats``, measured side by side in one process
(the machine is shared; compare within a run only).  ``--quick``: the lone actuator and the
four-bar's triangle only, one repeat.  Writes JSON to ``benchmarks/results/`` (git-ignored).

``--cells``: the same for benders whose cells are left open (``n_cells="auto", cell="auto"``: the
four-bar's crank, the gripper's benders, and the paper actuator as a cantilever ``Bender``, which
takes ``ritz``): the call chooses the cells and the step; its error is taken against ten ``rod``
modes at a quarter of the finest step searched, and the search runs over the kinds the bender allows
and 2 ... 5 modes, each on the ladder of steps (coarse to fine, the first count to pass its cheapest).

Usage: ``python benchmarks/bench_accuracy.py [--quick] [--cells] [--repeats 2] [--only four-bar/steps ...]``.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import platform
import sys
import time
import warnings

import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm.casework import Parameters
from exudyn_atcm.io.atomic import write_text
from exudyn_atcm.model import Sine, Steps, Triangle
from exudyn_atcm.model.sampled_program import SampledProgram
from exudyn_atcm.solve.corner_grid import feature_steps, grid_unit

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "cases"))
import micro_gripper  # noqa: E402
from readme_systems import CFC, MFC, readme_four_bar  # noqa: E402



def four_bar(program) -> atcm.Mechanism:
    return readme_four_bar(program, n_cells=3, cell="rod")


def gripper(program) -> atcm.Mechanism:
    values = {p.name: p.default for p in micro_gripper.PARAMETERS}
    values.update(n_cells=4, cell="rod")
    return micro_gripper.build_mechanism(Parameters(micro_gripper.PARAMETERS, values), 200.0, program)


def lone(program) -> atcm.BendingActuator:
    return atcm.BendingActuator(3, 29e-3, 28e-3, CFC, MFC, atcm.PiezoDrive(program), cell="rod")


def four_bar_cells(program, n_cells="auto", cell="auto") -> atcm.Mechanism:
    return readme_four_bar(program, n_cells=n_cells, cell=cell)


def gripper_cells(program, n_cells="auto", cell="auto") -> atcm.Mechanism:
    values = {p.name: p.default for p in micro_gripper.PARAMETERS}
    values.update(n_cells=n_cells, cell=cell)
    return micro_gripper.build_mechanism(Parameters(micro_gripper.PARAMETERS, values), 200.0, program)


def lone_cells(program, n_cells="auto", cell="auto") -> atcm.Mechanism:
    """The paper actuator's laminate (29 mm wide ... as ``lone``) as a cantilever Bender of 3 x 29 mm."""
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=n_cells, cell=cell,
                    drive=atcm.PiezoDrive(program))
    return atcm.Mechanism("lone").add(b).ground(b.base)


def record(mean: float, amplitude: float, period: float, sample: float = 1e-3, noise: float = 5.0) -> SampledProgram:
    """A measured voltage record [V] of one period: ``mean - amplitude cos`` sampled every ``sample`` [s] with Gaussian
    noise of ``noise`` [V] (seeded): it reverses at nearly every sample."""
    t = np.arange(0.0, period + 0.5 * sample, sample)
    v = mean - amplitude * np.cos(2.0 * math.pi * t / period) + np.random.default_rng(1).normal(0.0, noise, t.size)
    return SampledProgram(t, v)


#: the systems of ``--cells``: name -> builder(program, n_cells, cell) and the kinds its benders allow
CELL_SYSTEMS = {"lone actuator": (lone_cells, ("ritz", "rod")), "four-bar": (four_bar_cells, ("rod",)),
                "gripper": (gripper_cells, ("rod",))}


#: (system, drive, builder, program, t_end [s], target)
CASES = [
    ("lone actuator", "triangle", lone, Triangle(500.0, 500.0, 0.1), 0.1, 1e-3),
    ("lone actuator", "sine", lone, Sine(500.0, 500.0, 0.1, -math.pi / 2), 0.1, 1e-3),
    ("lone actuator", "steps", lone, Steps([0.0, 0.02, 0.06], [0.0, 1000.0, 0.0]), 0.1, 1e-2),
    ("lone actuator", "record", lone, record(500.0, 500.0, 0.1), 0.1, 1e-3),
    ("lone actuator", "square", lone, Steps(np.arange(0.0, 0.1, 0.005).tolist(), [0.0, 1000.0] * 10), 0.1, 1e-2),
    ("four-bar", "triangle", four_bar, Triangle(750.0, 750.0, 0.5), 0.5, 1e-3),
    ("four-bar", "sine", four_bar, Sine(750.0, 750.0, 0.5, -math.pi / 2), 0.5, 1e-3),
    ("four-bar", "steps", four_bar, Steps([0.0, 0.05, 0.15], [0.0, 1500.0, 0.0]), 0.2, 1e-2),
    ("four-bar", "record", four_bar, record(750.0, 750.0, 0.5), 0.5, 1e-3),
    ("gripper", "triangle", gripper, Triangle(500.0, 1000.0, 0.5), 0.5, 1e-3),
    ("gripper", "sine", gripper, Sine(500.0, 1000.0, 0.5, -math.pi / 2), 0.5, 1e-3),
    ("gripper", "steps", gripper, Steps([0.0, 0.05, 0.15], [-500.0, 1500.0, -500.0]), 0.2, 1e-2),
]
QUICK = [("lone actuator", "triangle"), ("lone actuator", "sine"), ("four-bar", "triangle")]


def cpu(fn, repeats: int):
    best, out = math.inf, None
    for _ in range(repeats):
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
    return best, out


def rel_error(run, reference) -> float:
    cols = [c for c in run.names if run.unit(c) == "m"]
    travel = max(float(np.ptp(reference[c])) for c in cols)
    return max(float(np.max(np.abs(np.asarray(run[c]) - np.interp(run["time"], reference["time"], reference[c]))))
               for c in cols) / travel


def steps_integrated(info, t_end) -> float:
    """Steps the call integrated (the probe over its window, the run, a refined run): CPU work free of timing noise."""
    acc = info["accuracy"]
    n0 = t_end / (acc["probe_step [s]"] / 2.0)
    window = acc.get("probe_window [s]", t_end)
    return n0 / 2.0 * window / t_end + n0 + (t_end / acc["step [s]"] if acc["refined"] else 0.0)


def case(system, drive, build, program, t_end, target, repeats):
    c_acc, chosen = cpu(lambda: atcm.simulate(build(program), t_end, accuracy=target), repeats)
    h_chosen = chosen.info["step [s]"]
    c_run, _ = cpu(lambda: atcm.simulate(build(program), t_end, step=h_chosen), repeats)  # the chosen run alone
    # step counts on the drive's grid (its corners and switches on step instants, as accuracy= keeps them: a switch
    # inside a step is a first-order error that varies from one count to the next, so the first count off the grid
    # to pass can be a lucky one; until 2026-11-29 the search took any even count)
    system_ = build(program)
    mech = system_ if isinstance(system_, atcm.Mechanism) else system_.as_mechanism()
    ladder = ladder_for(mech, t_end, 0.25 * h_chosen)  # warning-free for the program, up to 4x the chosen count
    n_reference = 4 * max(round(t_end / h_chosen), ladder[-1])  # a multiple of the grid's unit too
    reference = atcm.simulate(build(program), t_end, step=t_end / n_reference)
    err_chosen = rel_error(chosen, reference)
    cheapest = None
    for n in ladder:  # coarse to fine: the first that meets the target is the cheapest
        r = atcm.simulate(build(program), t_end, step=t_end / n)
        if rel_error(r, reference) <= target:
            c_min, _ = cpu(lambda: atcm.simulate(build(program), t_end, step=t_end / n), repeats)
            cheapest = (t_end / n, c_min, rel_error(r, reference))
            break
    row = {"system": system, "drive": drive, "target": target, "t_end [s]": t_end, "chosen step [s]": h_chosen,
           "achieved error": err_chosen, "cpu [s]": c_acc, "run alone cpu [s]": c_run, "refined": chosen.info["accuracy"]["refined"],
           "estimated error": chosen.info["accuracy"]["estimated_error"], "step_choice": chosen.info["step_choice"],
           "probe window [s]": chosen.info["accuracy"].get("probe_window [s]", t_end)}
    if cheapest:
        row.update({"cheapest step [s]": cheapest[0], "cheapest cpu [s]": cheapest[1],
                    "cheapest error": cheapest[2], "ratio": c_acc / cheapest[1],
                    "run alone ratio": c_run / cheapest[1],
                    "steps ratio": steps_integrated(chosen.info, t_end) / (t_end / cheapest[0])})
    return row


def ladder_for(mech, t_end, finest: float) -> list[int]:
    """Step counts on the drive's grid, warning-free for the program (at least 20 steps per shortest feature, or
    the grid of a record's samples, as accuracy= keeps), up to ``t_end / finest``."""
    unit = math.lcm(2, grid_unit(mech, t_end))
    ladder = sorted({unit * math.ceil(20 * 2.0 ** (k / 4) / unit) for k in range(0, 80)})
    floor = feature_steps(mech, t_end, 20, 1)[0]
    return [n for n in ladder if floor <= n <= t_end / finest + 1]


def case_cells(system, drive, program, t_end, target, repeats):
    """``--cells``: the call with open cells against a search over kinds, counts and steps."""
    build, kinds = CELL_SYSTEMS[system]
    c_acc, chosen = cpu(lambda: atcm.simulate(build(program), t_end, accuracy=target), repeats)
    h_chosen = chosen.info["step [s]"]
    cells = chosen.info["accuracy"]["cells"]
    ladder = ladder_for(build(program, 3, "rod"), t_end, h_chosen / 4)
    n_reference = 4 * max(round(t_end / h_chosen), ladder[-1])
    reference = atcm.simulate(build(program, 10, "rod"), t_end, step=t_end / n_reference)
    err_chosen = rel_error(chosen, reference)
    cheapest = None
    for kind in kinds:
        for count in (2, 3, 4, 5):
            for n in ladder:  # coarse to fine: the first that meets the target is this configuration's cheapest
                r = atcm.simulate(build(program, count, kind), t_end, step=t_end / n)
                if rel_error(r, reference) <= target:
                    c_min, _ = cpu(lambda: atcm.simulate(build(program, count, kind), t_end, step=t_end / n),
                                   repeats)
                    if cheapest is None or c_min < cheapest[1]:
                        cheapest = (t_end / n, c_min, rel_error(r, reference), f"{count} {kind}")
                    break
    row = {"system": system, "drive": drive, "target": target, "t_end [s]": t_end, "chosen step [s]": h_chosen,
           "chosen cells": " ".join(cells.values()), "achieved error": err_chosen, "cpu [s]": c_acc,
           "cell_choice": chosen.info["cell_choice"], "step_choice": chosen.info["step_choice"]}
    if cheapest:
        row.update({"cheapest step [s]": cheapest[0], "cheapest cpu [s]": cheapest[1], "cheapest error": cheapest[2],
                    "cheapest cells": cheapest[3], "ratio": c_acc / cheapest[1]})
    return row


def selected(args) -> list[tuple]:
    """The rows of :data:`CASES` that ``--quick`` and ``--only`` select."""
    return [c for c in CASES if not (args.quick and c[:2] not in QUICK or args.only and f"{c[0]}/{c[1]}" not in args.only)]


def write_rows(args, repeats: int, rows: list, name: str) -> None:
    """The rows as JSON in ``args.out`` (atomically), named ``name`` and the time."""
    os.makedirs(args.out, exist_ok=True)
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = os.path.join(args.out, f"{name}_{stamp}.json")
    write_text(path, json.dumps({"machine": platform.platform(), "quick": args.quick, "repeats": repeats,
                                 "rows": rows}, indent=2))
    print(f"wrote {path}")


def main_cells(args, repeats: int) -> None:
    """The ``--cells`` table."""
    rows = []
    head = (f"{'system':>13} | {'drive':>8} | {'target':>6} | {'cells':>7} | {'chosen h':>9} | {'error':>8} | "
            f"{'cpu':>7} | {'cheapest':>8} | {'its h':>9} | {'its cpu':>7} | {'ratio':>5}")
    print(head)
    print("-" * len(head))
    for system, drive, _, program, t_end, target in selected(args):
        r = case_cells(system, drive, program, t_end, target, repeats)
        rows.append(r)
        print(f"{system:>13} | {drive:>8} | {target:>6.0e} | {r['chosen cells']:>7} | {r['chosen step [s]']:>9.3g} | "
              f"{r['achieved error']:>8.2e} | {r['cpu [s]']:>7.3f} | {r.get('cheapest cells', '-'):>8} | "
              f"{r.get('cheapest step [s]', math.nan):>9.3g} | {r.get('cheapest cpu [s]', math.nan):>7.3f} | "
              f"{r.get('ratio', math.nan):>5.2f}", flush=True)
    write_rows(args, repeats, rows, "bench_accuracy_cells")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--cells", action="store_true", help="benders with open cells (n_cells/cell 'auto')")
    parser.add_argument("--only", action="append", default=[], metavar="SYSTEM/DRIVE",
                        help="run only these cases, e.g. 'four-bar/steps' (repeatable; for interleaved A/B runs)")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results"))
    args = parser.parse_args()
    warnings.simplefilter("ignore")  # the steps searched below the comfortable resolution warn; the table says it
    repeats = 1 if args.quick else args.repeats
    # start-up outside the timings: the first linearisation and the first accuracy= call (about 0.07 s once)
    atcm.eigenfrequencies(lone(Triangle(0, 1, 1)), n=1)
    atcm.simulate(lone(Triangle(500.0, 500.0, 0.02)), 0.02, accuracy=1e-2)
    if args.cells:
        main_cells(args, repeats)
        return
    rows = []
    head = (f"{'system':>13} | {'drive':>8} | {'target':>6} | {'chosen h':>9} | {'error':>8} | {'cpu':>7} | "
            f"{'cheapest h':>10} | {'its cpu':>7} | {'ratio':>5} | {'run alone':>9} | {'steps':>5}")
    print(head)
    print("-" * len(head))
    for system, drive, build, program, t_end, target in selected(args):
        r = case(system, drive, build, program, t_end, target, repeats)
        rows.append(r)
        print(f"{system:>13} | {drive:>8} | {target:>6.0e} | {r['chosen step [s]']:>9.3g} | "
              f"{r['achieved error']:>8.2e} | {r['cpu [s]']:>7.3f} | {r.get('cheapest step [s]', math.nan):>10.3g} | "
              f"{r.get('cheapest cpu [s]', math.nan):>7.3f} | {r.get('ratio', math.nan):>5.2f} | "
              f"{r.get('run alone ratio', math.nan):>9.2f} | {r.get('steps ratio', math.nan):>5.2f}", flush=True)
    write_rows(args, repeats, rows, "bench_accuracy")


if __name__ == "__main__":
    main()
