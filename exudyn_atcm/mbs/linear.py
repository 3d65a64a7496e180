"""Linearisation of a built mechanism model: eigenfrequencies and degrees of freedom."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import linear_model as lm
from . import solver_runs as runs
from .blas_threads import one_blas_thread
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


def damped_modes(model: MechanismModel, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Lowest ``n`` undamped eigenfrequencies [Hz] about the model's current (equilibrium) state, as
    :func:`eigenfrequencies` gives them, and each mode's damping ratio [-] ``phi^T D phi / (2 omega phi^T M phi)``.

    ``D = -d f / d q'`` is the damping the simulation has (:func:`~exudyn_atcm.mbs.linear_model.damping_matrix`: the
    laminates' and flexures' Rayleigh damping, mass dampers, the rod's modal damping), projected on each undamped
    mode: exact where the damping is a combination of ``M`` and ``K`` (the same ``alpha`` and ``beta`` in every part),
    else its first-order (diagonal) approximation.  A mechanism's parts damp its lowest mode together: in the
    ``compliant_four_bar`` case the flexures' ratio at 55 Hz is 1.6e-4, the bender's 0.02, the mode's 0.0125 (the
    linear model's pole gives the same).  Unstable modes (negative frequency) get ``nan``.
    """
    from scipy.linalg import eigh  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
    mats = lm.linear_matrices(model, damping=True)
    N = mats.N
    if n > N.shape[1]:
        raise ValueError(f"n must be <= the number of degrees of freedom ({N.shape[1]}), got {n}")
    with one_blas_thread():
        Kr, Mr, Dr = (N.T @ A @ N for A in (mats.K, mats.M, mats.D))
        w2, vecs = eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T), subset_by_index=[0, n - 1])
        modal_mass = np.einsum("im,ij,jm->m", vecs, Mr, vecs)
        modal_damping = np.einsum("im,ij,jm->m", vecs, 0.5 * (Dr + Dr.T), vecs)
    omega = np.sqrt(np.abs(w2))
    with np.errstate(divide="ignore", invalid="ignore"):
        zeta = np.where(w2 > 0.0, modal_damping / (2.0 * omega * modal_mass), np.nan)
    return np.sign(w2) * omega / (2.0 * np.pi), zeta


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
