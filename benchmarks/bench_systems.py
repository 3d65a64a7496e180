"""The mechanisms the mechanism benchmarks run: the compliant four-bar and the micro-gripper of the
case scripts, at a given number of cells and cell kind, and their tracked points' paths.

Shared by ``bench_mechanisms.py``, ``mechanism_targets.py`` and ``bench_step_overhead.py``.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

import numpy as np

from exudyn_atcm import simulate
from exudyn_atcm import casework
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import Triangle

CASES = Path(__file__).resolve().parents[1] / "cases"
RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
STEP = 1e-4  # s
PERIOD = 0.5  # s


def case_module(name: str):
    """The case file as a module (its CASE and its build_mechanism)."""
    return casework.case_module(name, CASES)


CELLS = ("rigid", "beam")


def four_bar(n_cells: int, cell: str):
    module = case_module("compliant_four_bar")
    p = module.CASE.resolve({"n_cells": n_cells, "cell": cell})
    return module.build_mechanism(p, paper_strain_preisach(), Triangle(500.0, 1000.0, PERIOD))


def gripper(n_cells: int, cell: str):
    module = case_module("micro_gripper")
    p = module.CASE.resolve({"n_cells": n_cells, "cell": cell})
    return module.build_mechanism(p, p.object_stiffness, Triangle(500.0, 1000.0, PERIOD))


MECHANISMS = {"four_bar": four_bar, "gripper": gripper}
TRACKED = {"four_bar": "coupler.P", "gripper": "lower_jaw.jaw"}


def timed(build, n_cells: int, cell: str, t_sim: float) -> tuple[float, dict, np.ndarray]:
    """Wall time [s], solver info and the tracked point's path of one run."""
    mech = build(n_cells, cell)
    start = time.perf_counter()
    result = simulate(mech, t_sim, step=STEP)
    return time.perf_counter() - start, dict(result.info), result


def path(result, point: str) -> np.ndarray:
    return np.stack([result[f"{point}_x"], result[f"{point}_y"]], axis=-1)


def path_error(result, reference, point: str) -> float:
    """Largest distance to the reference path relative to the reference point's largest travel [-]."""
    p, q = path(result, point), path(reference, point)
    travel = float(np.max(np.linalg.norm(q - q[0], axis=1)))
    return float(np.max(np.linalg.norm(p - q, axis=1))) / travel
