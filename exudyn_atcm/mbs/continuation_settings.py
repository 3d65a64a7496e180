"""Exudyn settings of a static sweep's continuation (:func:`exudyn_atcm.mbs.sweep_solve.solve_points`)."""

from __future__ import annotations

import exudyn as exu

from .model import MechanismModel
from .solver_settings import static_settings

__all__ = ["DENSE_SIZE", "NEVER_GROW", "continuation_settings"]

#: largest number of unknowns (coordinates and multipliers) for which a continuation step solves densely
DENSE_SIZE = 64
#: Exudyn's ``staticSolver.adaptiveStepRecoverySteps`` of a continuation: the steps after a reduction before
#: the step grows again, here never (a continuation's points are its whole load steps; a reduced step grown
#: back from inside a point could end beyond the next one, which would then be passed over)
NEVER_GROW = 2**30


def continuation_settings(model: MechanismModel):
    """Settings of a continuation of ``model``: one load step with the loads in full (no load factor; a sweep's
    continuation then sets one load step per point).

    A step the solver reduced is not grown again (:data:`NEVER_GROW`): a sweep's continuation stops at the
    point reached with it and goes on in a new solve (:func:`~exudyn_atcm.mbs.sweep_solve.solve_points`).
    For at most :data:`DENSE_SIZE` unknowns the dense linear solver: 10 % less time on 100-point
    sweeps of the README four-bar and a lone actuator (30, 20 and 16 unknowns), the same equilibria to
    1e-12 m (measured side by side; ``benchmarks/bench_static_sweep.py``).
    """
    settings = static_settings(1)
    settings.staticSolver.useLoadFactor = False
    # a step the solver reduced (halving a failed one) is never grown back: grown, it could step over a point
    settings.staticSolver.adaptiveStepRecoverySteps = NEVER_GROW
    sd = model.mbs.systemData
    if len(sd.GetODE2Coordinates()) + len(sd.GetAECoordinates()) <= DENSE_SIZE:
        settings.linearSolver.solverType = exu.LinearSolverType.EXUdense
    return settings
