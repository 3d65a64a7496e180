"""Eigenfrequencies of a constrained Exudyn system about its current (equilibrium) state.

Why not Exudyn's own routine
----------------------------
``MainSystem.ComputeODE2Eigenvalues`` (and ``ComputeLinearizedSystem``) of Exudyn 1.13 take
the stiffness matrix as ``K = -d f/d q`` of the ODE2 right-hand side only, project it onto the
null space of the constraint Jacobian ``C_q`` and solve ``N^T K N v = w^2 N^T M N v``.  The
constraint forces ``C_q^T lambda`` are left out of the linearisation.  About a state where the
joints carry no force (an undeformed chain, or a rigid chain under an end torque) that is
exact.  About a state where they do, it is not: the correct tangent stiffness of the
constrained equilibrium is

    K_T = -d/dq [ f(q) + C_q(q)^T lambda ],   projected as  N^T K_T N,

and the term ``-(d C_q^T/dq) lambda`` (the constraint forces' geometric stiffness) is of the
same order as the bending stiffness.  In a bent chain of six-bar cells the prismatic motors
push the two layers against each other: at 1500 V on the reference bender of the actuator docs (3 x 29 mm,
CFC on MFC) the joints carry about 53 N, and leaving the term out gave 10.4 Hz instead of
31.9 Hz at 4 cells (-67 %) and 89.6 Hz instead of 35.7 Hz at 16 cells (+151 %).  The same
holds for any chain under a tip load, whose joints carry the load.

What this module does
---------------------
It differentiates the full static residual ``r(q) = f(q) + C_q(q)^T lambda`` (Exudyn's static
solver residual, with the multipliers held at their equilibrium values) and the constraint
values ``C(q)`` by central differences, takes the null space of ``C_q`` from a singular value
decomposition, and solves the projected symmetric eigenproblem.  The prescribed motion of
motors (constraints with a given offset) is held at its current value, which is the
linearisation at a fixed drive strain.

Two details of Exudyn 1.13 found on the way and avoided here: ``ComputeJacobianAE`` adds into
the stored system Jacobian without clearing it (repeated calls accumulate, and in dense mode
the first call starts from uninitialised memory), so the constraint Jacobian is not read from
it; and the Jacobian of ``MarkerBodiesRelativeTranslationCoordinate`` leaves out the derivative
of the axis with respect to the body rotation, which is zero at an aligned state but makes the
numerically differentiated ``K_T`` slightly unsymmetric in directions the constraints remove;
after the projection the asymmetry is at round-off level and the matrix is symmetrised.
"""

from __future__ import annotations

import math
import warnings

import exudyn as exu
import numpy as np

from .._checks import shown
from ..errors import AccuracyWarning
from .tangent import TangentPlan, static_settings
from .blas_threads import one_blas_thread

__all__ = ["constrained_eigenfrequencies", "exudyn_eigenfrequencies", "tangent_system"]


def tangent_system(mbs, relative_step: float = 1e-7) -> dict:
    """Mass matrix, tangent stiffness and constraint Jacobian of ``mbs`` at its current state.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        An assembled system.  Its current ODE2 coordinates and algebraic (Lagrange multiplier)
        coordinates are the state of linearisation, normally a static equilibrium.
    relative_step : float, optional
        Central-difference step per coordinate, ``h_i = relative_step * (1 + |q_i|)`` [m or rad].

    Returns
    -------
    dict
        ``M`` (n x n) [kg, kg m, kg m^2], ``K`` (n x n, unsymmetrised tangent stiffness
        ``-d(f + C_q^T lambda)/dq``) [N/m, N/rad, N m/rad ...], ``Cq`` (m x n) constraint Jacobian,
        ``residual`` (n,) the ODE2 part of the static residual at the state [N, N m].

    Notes
    -----
    The differences are grouped by the items' coordinates (:class:`~exudyn_atcm.mbs.tangent.TangentPlan`:
    the same numbers as one coordinate at a time, at a fraction of the cost).  The current and
    initial states of ``mbs`` are restored on return.
    """
    return TangentPlan(mbs).system(relative_step)


def constrained_eigenfrequencies(mbs, n: int, *, relative_step: float = 1e-7,
                                 residual_tolerance: float = 1e-6,
                                 singular_values_tolerance: float = 1e-9,
                                 return_modes: bool = False):
    """Lowest ``n`` undamped eigenfrequencies [Hz] of a constrained system about its current state.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        Assembled system whose current state (ODE2 coordinates and Lagrange multipliers, as a
        static solve leaves them) is an equilibrium.
    n : int
        Number of frequencies, 1 <= n <= number of unconstrained degrees of freedom.
    relative_step : float, optional
        Central-difference step, see :func:`tangent_system`.
    residual_tolerance : float, optional
        Largest static residual [N, N m] accepted as an equilibrium; above it a
        ``RuntimeWarning`` says that the linearisation is not about an equilibrium.
    singular_values_tolerance : float, optional
        Singular values of the constraint Jacobian below this share of the largest one count as
        zero (redundant constraints).
    return_modes : bool, optional
        Also return the mode shapes in the ODE2 coordinates (one column per frequency).

    Returns
    -------
    numpy.ndarray or (numpy.ndarray, numpy.ndarray)
        Frequencies [Hz], ascending by eigenvalue.  An unstable direction (negative eigenvalue
        of the projected tangent stiffness) is returned as a *negative* number ``-sqrt(|w^2|)/2 pi``
        and warned about.

    Notes
    -----
    The tangent stiffness includes the constraint forces' geometric stiffness
    ``-(d C_q^T / dq) lambda``, which Exudyn's ``ComputeODE2Eigenvalues`` leaves out (see the
    module docstring for the cause and its size).
    """
    from scipy.linalg import eigh, svd  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be an integer >= 1, got {shown(n)}")
    ts = tangent_system(mbs, relative_step)
    M, K, Cq, res = ts["M"], ts["K"], ts["Cq"], ts["residual"]
    n2 = M.shape[0]
    worst = float(np.max(np.abs(res))) if res.size else 0.0
    if worst > residual_tolerance:
        warnings.warn(
            f"constrained eigenfrequencies: the state is not a static equilibrium (largest residual "
            f"{worst:.3g} N or N m, accepted {residual_tolerance:g}); the frequencies are those of the "
            "linearisation about a non-equilibrium state",
            AccuracyWarning, stacklevel=2)
    with one_blas_thread():  # after the import: scipy's own BLAS limited too
        if Cq.shape[0]:
            U, sv, _ = svd(Cq.T)  # columns of U beyond the rank span the null space of Cq
            rank = int(np.sum(sv > singular_values_tolerance * max(sv.max(), 1e-300)))
            N = U[:, rank:]
        else:
            N = np.eye(n2)
        n_free = N.shape[1]
        if n > n_free:
            raise ValueError(f"n must be <= the number of degrees of freedom ({n_free}), got {n}")
        Kr = N.T @ K @ N
        Kr = 0.5 * (Kr + Kr.T)
        Mr = N.T @ M @ N
        Mr = 0.5 * (Mr + Mr.T)
        w2, vecs = eigh(Kr, Mr, subset_by_index=[0, n - 1])
    if np.any(w2 < 0.0):
        warnings.warn(
            f"constrained eigenfrequencies: {int(np.sum(w2 < 0))} of the lowest {n} eigenvalues of the "
            "tangent stiffness are negative: the equilibrium is unstable (buckled); those are returned "
            "as negative frequencies", AccuracyWarning, stacklevel=2)
    freqs = np.sign(w2) * np.sqrt(np.abs(w2)) / (2.0 * math.pi)
    if return_modes:
        return freqs, N @ vecs
    return freqs


def exudyn_eigenfrequencies(mbs, n: int) -> np.ndarray:
    """Lowest ``n`` eigenfrequencies [Hz] from Exudyn's ``ComputeODE2Eigenvalues`` at the current state.

    For comparison only: this routine leaves out the constraint forces' geometric stiffness
    (module docstring).  The current state is copied to the initial state for the call (Exudyn
    linearises about the initial state) and restored afterwards.
    """
    sd = mbs.systemData
    ini = exu.ConfigurationType.Initial
    saved = sd.GetSystemState(configuration=ini)
    sd.SetSystemState(systemStateList=sd.GetSystemState(configuration=exu.ConfigurationType.Current),
                      configuration=ini)
    exu.config.printToConsole = False
    try:
        values, _ = mbs.ComputeODE2Eigenvalues(simulationSettings=static_settings(), useSparseSolver=False,
                                               numberOfEigenvalues=0, convert2Frequencies=False,
                                               useAbsoluteValues=True, ignoreAlgebraicEquations=False,
                                               singularValuesTolerance=1e-10)
    finally:
        exu.config.printToConsole = True
        sd.SetSystemState(systemStateList=saved, configuration=ini)
    values = np.sort(np.abs(np.asarray(values, dtype=float)))
    return np.sqrt(values[:n]) / (2.0 * math.pi)
