"""Linearisation of a built mechanism model: eigenfrequencies and degrees of freedom."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import solver_runs as runs
from .model import MechanismModel


def eigenfrequencies(model: MechanismModel, n: int) -> np.ndarray:
    """Lowest ``n`` undamped eigenfrequencies [Hz] about the model's current (equilibrium) state.

    The tangent stiffness of the constrained system, including the geometric stiffness of the
    joints' internal forces (the Lagrange multipliers times the constraints' second
    derivatives), which Exudyn's ``ComputeODE2Eigenvalues`` leaves out; projected onto the
    constraints' null space (:func:`exudyn_atcm.mbs.eigen.constrained_eigenfrequencies`).  The
    drive torques and loads act as constant loads during the linearisation.
    """
    return runs.eigenfrequencies(model, n)


@dataclass(frozen=True)
class DofReport:
    """Degrees of freedom of a built mechanism (Exudyn's ``ComputeSystemDegreeOfFreedom``).

    Attributes
    ----------
    dof : int
        Degrees of freedom (coordinates minus independent constraints).
    coordinates : int
        Number of ODE2 coordinates (3 per body).
    constraints : int
        Number of algebraic equations (joint constraints).
    redundant : int
        Number of redundant (dependent) constraints.
    """

    dof: int
    coordinates: int
    constraints: int
    redundant: int


def degrees_of_freedom(model: MechanismModel) -> DofReport:
    """The model's :class:`DofReport` in its current (assembled) state."""
    runs.quiet_console()
    try:
        info = model.mbs.ComputeSystemDegreeOfFreedom(verbose=False)
    finally:
        runs.restore_console()
    return DofReport(int(info["degreeOfFreedom"]), int(info["nODE2"]), int(info["nAE"]),
                     int(info["redundantConstraints"]))


__all__ = ["eigenfrequencies", "DofReport", "degrees_of_freedom"]
