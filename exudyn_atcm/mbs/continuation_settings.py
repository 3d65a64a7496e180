"""Exudyn settings of a static sweep's continuation (:func:`exudyn_atcm.mbs.sweep_solve.solve_points`)."""

from __future__ import annotations

import exudyn as exu

from .model import MechanismModel
from .solver_settings import static_settings

__all__ = ["DENSE_SIZE", "continuation_settings"]

#: largest number of unknowns (coordinates and multipliers) for which a continuation step solves densely
DENSE_SIZE = 64


def continuation_settings(model: MechanismModel):
    """Settings of a continuation of ``model``: one load step with the loads in full (no load factor; a sweep's
    continuation then sets one load step per point).

    For at most :data:`DENSE_SIZE` unknowns the dense linear solver: 10 % less time on 100-point
    sweeps of the README four-bar and a lone actuator (30, 20 and 16 unknowns), the same equilibria to
    1e-12 m (measured side by side; ``benchmarks/bench_static_sweep.py``).
    """
    settings = static_settings(1)
    settings.staticSolver.useLoadFactor = False
    sd = model.mbs.systemData
    if len(sd.GetODE2Coordinates()) + len(sd.GetAECoordinates()) <= DENSE_SIZE:
        settings.linearSolver.solverType = exu.LinearSolverType.EXUdense
    return settings
