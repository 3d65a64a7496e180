"""The ``rod`` cell's time integration at large motion: observed order, undamped energy drift, cost per step.

Against the exact integration of the same Ritz space (:mod:`exudyn_atcm.theory.rod_motion`, scipy's
DOP853 at relative tolerance 1e-10), for the clamped rod of the tests (28 mm x 60 mm, the paper's
laminate, 4 modes, f1 = 76 Hz) released from rest under loads that rise over 2 ms:

* ``order``: the tip's largest error over 0.02 s per travel at steps 1e-4, 5e-5, 2.5e-5 s, and
  the observed orders ``log2(e_h / e_h/2)`` for both halvings, for a dead tip force of 1 and
  3 EI/L^2, a follower force of 3 EI/L^2 and a free curvature (actuation) that turns the tip by
  2 rad;
* ``drift``: the slope of the undamped energy over ``--drift-t`` s at 1e-4 s (least squares after the
  onset, modes from the cells' mean rotations, rates by fourth-order central differences), in % of
  the largest kinetic energy per second, at the package's spectral radius 0.8 and at 1 (no numerical
  damping: the rod's own energy error), also for the stiffer 10 mm x 30 mm rod of issue 29
  (f1 = 302 Hz, h omega = 0.19 at 1e-4 s);
* ``cost``: wall time per step (best of ``--repeats``) and Newton passes per step (Exudyn's
  discontinuous iterations) of the dead 3 EI/L^2 swing (0.05 s) and of the compliant four-bar and
  the micro-gripper with 4-mode rods with the paper's Preisach operator in the step (0.1 s of
  ``Triangle(500, 1000, 0.5)`` V: the rising branch from -500 to 300 V, no reversal), at 1e-4 s.

Before/after in one run: ``python benchmarks/compare_revisions.py --old DIR:PYTHON --new DIR:PYTHON
--skip mechanisms,discretisation --rod-dynamics-args "--quick"`` runs *this* script (of the new
checkout, with its reference) under both revisions' interpreters, interleaved.

Usage: ``python benchmarks/bench_rod_dynamics.py [--quick] [--repeats 3] [--drift-t 0.3] [--out DIR]``.
Prints a table and writes JSON to ``benchmarks/results/`` (git-ignored).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import importlib.util
import math
import os
import platform
import sys
import time
import warnings
from pathlib import Path

import exudyn
import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm import __version__
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.mbs import solver_runs
from exudyn_atcm.theory import ritz_beam

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_systems as bm  # noqa: E402 - the mechanisms of the mechanism benchmarks


def _reference_module():
    """This checkout's exact integration, also under an older revision of the package (same name, its file)."""
    path = Path(__file__).resolve().parents[1] / "exudyn_atcm" / "theory" / "rod_motion.py"
    spec = importlib.util.spec_from_file_location("exudyn_atcm.theory.rod_motion", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


rm = _reference_module()
RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
N, ONSET = 4, 2e-3
GEOMETRY = {"28x60 mm": (28e-3, 0.06), "10x30 mm": (10e-3, 0.03)}
U, D33 = 1500.0, 2.3e-9
STEPS = (1e-4, 5e-5, 2.5e-5)
RHO1 = {"timeIntegration.generalizedAlpha.spectralRadius": 1.0}


def bender(width: float, length: float, drive=None) -> atcm.Bender:
    return atcm.Bender("b", width=width, passive=CFC, active=MFC, length=length, n_cells=N, cell="rod", damping=0.0,
                       drive=drive if drive is not None else atcm.PiezoDrive(0.0))


def reference_rod(case: str, width: float, length: float):
    lam = bender(width, length).laminate
    ei = lam.bending_stiffness
    if case == "moment":
        kappa = lam.curvature_per_strain * D33 * U / 0.5e-3
        return rm.ClampedRod(N, length, ei, lam.mass_per_length, lam.rotary_inertia_per_length, tip_moment=ei * kappa,
                             onset=ONSET)
    kind, alpha = case.split()
    return rm.ClampedRod(N, length, ei, lam.mass_per_length, lam.rotary_inertia_per_length,
                         (0.0, float(alpha) * ei / length**2), follower=kind == "follower", onset=ONSET)


def mechanism(case: str, rod, width: float) -> atcm.Mechanism:
    if case == "moment":
        b = bender(width, rod.length, atcm.PiezoDrive(lambda t: U * rod.load_factor(t), d33=D33))
        return atcm.Mechanism().add(b).ground(b.base)
    b = bender(width, rod.length)
    force = np.array(rod.tip_force)
    m = atcm.Mechanism().add(b).ground(b.base)
    return m.force(b.tip, lambda t: tuple(rod.load_factor(t) * force), follower=rod.follower)


class Passes:
    """``solver_runs.run_dynamic`` with its statistics kept (Newton passes: Exudyn's discontinuous iterations)."""

    def __enter__(self) -> "Passes":
        self.stats: dict = {}
        self._original = original = solver_runs.run_dynamic

        def run(*args, **kwargs):
            out = original(*args, **kwargs)
            self.stats = dict(out)
            return out
        solver_runs.run_dynamic = run
        return self

    def __exit__(self, *exc) -> None:
        solver_runs.run_dynamic = self._original


def order_row(case: str) -> dict:
    width, length = GEOMETRY["28x60 mm"]
    rod = reference_rod(case, width, length)
    t_end = 0.02
    motion = rm.integrate_clamped_rod(rod, t_end)
    errors, turn = [], 0.0
    for step in STEPS:
        r = atcm.simulate(mechanism(case, rod, width), t_end, step=step)
        tip = np.array([rm.tip_position(rod, y) for y in motion(r["time"])[:N].T])
        travel = np.max(np.linalg.norm(tip - [length, 0.0], axis=1))
        errors.append(float(np.max(np.hypot(r["b.tip_x"] - tip[:, 0], r["b.tip_y"] - tip[:, 1])) / travel))
        turn = max(turn, float(np.max(np.abs(r["b.tip_angle"]))))
    return {"case": case, "tip rotation [rad]": turn, "errors per travel": errors,
            "orders": [math.log2(a / b) for a, b in zip(errors, errors[1:])]}


def drift(case: str, geometry: str, settings, t_end: float, step: float = 1e-4) -> float:
    """Slope of the undamped energy after the onset [% of the largest kinetic energy per s]."""
    width, length = GEOMETRY[geometry]
    rod = reference_rod(case, width, length)
    r = atcm.simulate(mechanism(case, rod, width), t_end, step=step, settings=settings)
    angles = np.array([r[f"b.cell_angle_{j + 1}"] for j in range(N)])
    q = np.linalg.solve(ritz_beam.segment_rotation_matrix(N, N), angles)
    rates = (q[:, :-4] - 8.0 * q[:, 1:-3] + 8.0 * q[:, 3:-1] - q[:, 4:]) / (12.0 * step)
    q, t = q[:, 2:-2], r["time"][2:-2]
    after = np.flatnonzero(t > ONSET + 1e-3)
    energies = np.array([rm.energy(rod, q[:, k], rates[:, k]) for k in after])
    kinetic = max(0.5 * rates[:, k] @ rod.inertia(q[:, k], rates[:, k])[0] @ rates[:, k] for k in range(0, len(t), 5))
    return float(np.polyfit(t[after], energies, 1)[0] / kinetic * 100.0)


def cost_row(name: str, build, t_sim: float, repeats: int) -> dict:
    best, stats, steps = math.inf, {}, 0
    for _ in range(repeats):
        mech = build()
        with Passes() as passes:
            start = time.perf_counter()
            r = atcm.simulate(mech, t_sim, step=1e-4)
            wall = time.perf_counter() - start
        best = min(best, wall)
        stats, steps = passes.stats, int(r.info.get("accepted_steps", len(r["time"]) - 1))
    return {"system": name, "wall per step [us]": best / steps * 1e6,
            "passes per step": stats.get("discontinuous_iterations", 0) / max(steps, 1),
            "Newton iterations per step": stats.get("newton_steps", 0) / max(steps, 1), "steps": steps}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="orders of two cases, drift over 0.1 s, one repeat")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--drift-t", type=float, default=0.3, help="length of the drift runs [s]")
    parser.add_argument("--out", default=RESULTS)
    args = parser.parse_args(argv)
    repeats = 1 if args.quick else args.repeats
    drift_t = 0.1 if args.quick else args.drift_t
    warnings.simplefilter("ignore", atcm.AccuracyWarning)  # the stiff rod's coarse-step warning is the point

    cases = ("dead 3", "moment") if args.quick else ("dead 1", "dead 3", "follower 3", "moment")
    orders = [order_row(c) for c in cases]
    drifts = []
    for geometry in GEOMETRY:
        for case in ("dead 1", "dead 3"):
            drifts.append({"geometry": geometry, "case": case,
                           "drift rho 0.8 [%/s]": drift(case, geometry, None, drift_t),
                           "drift rho 1 [%/s]": drift(case, geometry, RHO1, drift_t)})
    width, length = GEOMETRY["28x60 mm"]
    swing = reference_rod("dead 3", width, length)
    costs = [cost_row("dead 3 EI/L^2 swing", lambda: mechanism("dead 3", swing, width), 0.05, repeats),
             cost_row("four-bar, 4-mode rods", lambda: bm.four_bar(4, "rod"), 0.1, repeats),
             cost_row("gripper, 4-mode rods", lambda: bm.gripper(4, "rod"), 0.1, repeats)]

    print(f"exudyn_atcm {__version__} ({Path(atcm.__file__).resolve().parents[1]}), exudyn {exudyn.__version__}")
    print(f"{'case':>12} | {'tip [rad]':>9} | {'err 1e-4':>9} | {'err 5e-5':>9} | {'err 2.5e-5':>10} | orders")
    for row in orders:
        e = row["errors per travel"]
        print(f"{row['case']:>12} | {row['tip rotation [rad]']:>9.2f} | {e[0]:>9.2e} | {e[1]:>9.2e} | {e[2]:>10.2e} | "
              + ", ".join(f"{o:.2f}" for o in row["orders"]))
    print(f"\n{'geometry':>9} | {'case':>7} | {'drift rho 0.8 [%/s]':>19} | {'drift rho 1 [%/s]':>17}")
    for row in drifts:
        print(f"{row['geometry']:>9} | {row['case']:>7} | {row['drift rho 0.8 [%/s]']:>+19.3f} | "
              f"{row['drift rho 1 [%/s]']:>+17.4f}")
    print(f"\n{'system':>22} | {'us/step':>8} | {'passes/step':>11} | {'Newton it./step':>15}")
    for row in costs:
        print(f"{row['system']:>22} | {row['wall per step [us]']:>8.1f} | {row['passes per step']:>11.2f} | "
              f"{row['Newton iterations per step']:>15.2f}")

    stamp = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    os.makedirs(args.out, exist_ok=True)
    write_json(os.path.join(args.out, f"rod_dynamics_{stamp}.json"), {
        "benchmark": "bench_rod_dynamics", "exudyn_atcm": __version__, "exudyn": exudyn.__version__,
        "package_path": str(Path(atcm.__file__).resolve().parents[1]), "python": platform.python_version(),
        "quick": args.quick, "drift_t [s]": drift_t, "orders": orders, "drift": drifts, "cost": costs})
    return 0


if __name__ == "__main__":
    sys.exit(main())
