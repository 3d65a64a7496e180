"""Linearisation of a built mechanism model: eigenfrequencies and degrees of freedom."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _mbs_builder as runs
from .model import MechanismModel


def eigenfrequencies(model: MechanismModel, n: int) -> np.ndarray:
    """Lowest ``n`` undamped eigenfrequencies [Hz] about the model's initial state.

    Exudyn's ``ComputeODE2Eigenvalues`` with the constraints kept (its null-space
    projection).  The drive torques and loads act as constant loads during the linearisation.
    It leaves out the geometric stiffness of the joints' internal forces (the Lagrange
    multipliers times the constraints' second derivatives): exact where the joints carry no
    force (see :func:`constraint_forces`).  Every mechanism eigenvalue computation of the
    package goes through this function, so a solver that adds that term replaces it here.
    """
    return runs.eigenfrequencies(model, n)


def constraint_forces(model: MechanismModel) -> float:
    """Largest Lagrange multiplier of the current state [N or N m]: the joints' internal forces."""
    values = np.asarray(model.mbs.systemData.GetAECoordinates(), dtype=float)
    return float(np.max(np.abs(values))) if values.size else 0.0


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
    runs._quiet()
    try:
        info = model.mbs.ComputeSystemDegreeOfFreedom(verbose=False)
    finally:
        runs._loud()
    return DofReport(int(info["degreeOfFreedom"]), int(info["nODE2"]), int(info["nAE"]),
                     int(info["redundantConstraints"]))


__all__ = ["eigenfrequencies", "constraint_forces", "DofReport", "degrees_of_freedom"]
