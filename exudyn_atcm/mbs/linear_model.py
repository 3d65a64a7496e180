"""Linear equations of motion of a built mechanism about its current (equilibrium) state.

About a static equilibrium ``q0`` (with the joints' multipliers ``lambda0``) the mechanism's
equations ``M q'' = f(q, q', eps) - C_q^T lambda``, ``C(q) = 0`` are linearised as

    M dq'' + D dq' + K_T dq = (d f / d eps) d eps + J_P^T dF,   C_q dq = 0,

with

* ``K_T = -d(f + C_q^T lambda)/dq`` the tangent stiffness *with* the constraint forces'
  geometric stiffness (:func:`~exudyn_atcm.mbs.eigen.tangent_system`, which explains why
  Exudyn's own ``ComputeLinearizedSystem`` leaves that part out);
* ``D = -d f / d q'`` the damping the simulation has (the springs' and beam elements'
  stiffness-proportional damping, the mass dampers, the rod's modal damping), by central
  differences of Exudyn's residual with respect to the velocities (the same numbers as
  Exudyn's ``ComputeJacobianODE2RHS`` with the velocity factor, which ``ComputeLinearizedSystem``
  uses: the forces are linear in the velocities);
* ``d f / d eps`` the generalised force of a unit free strain of each strain source (the drives'
  actuation torques, offsets and the cells' own strain writers), by central differences at fixed
  coordinates;
* ``J_P`` the Jacobian of a point's position: ``J_P^T e`` is the generalised force of a unit dead
  force in direction ``e`` at the point (virtual work).

The coordinates are restricted to the null space ``N`` of ``C_q`` (``dq = N y``; a singular value
decomposition, as the eigenfrequencies do), which removes the multipliers.  A strain that enters
the constraints themselves (the six-bar cells' prescribed motor strokes) would be a prescribed
motion, not a force: it is refused (:func:`strain_forces` raises).
"""

from __future__ import annotations

from dataclasses import dataclass

import exudyn as exu
import numpy as np

from .eigen import tangent_system
from .model import MechanismModel
from .recording import make_result
from .tangent import static_settings
from .blas_threads import on_one_blas_thread

__all__ = ["LinearMatrices", "linear_matrices", "null_space", "damping_matrix", "strain_forces", "output_columns",
           "output_jacobian", "point_jacobians"]

#: units of the result columns a linear model may output (point coordinates and angles)
OUTPUT_UNITS = ("m", "rad")


@dataclass(frozen=True)
class LinearMatrices:
    """The linearised equations of a built mechanism (full ODE2 coordinates).

    Attributes
    ----------
    M, K, D : numpy.ndarray
        Mass [kg ...], tangent stiffness with geometric stiffness [N/m ...] (unsymmetrised) and
        damping [N s/m ...] matrices, n x n.
    N : numpy.ndarray
        Orthonormal basis of the constraints' null space, n x n_free.
    q0 : numpy.ndarray
        The coordinates of the state of linearisation.
    residual : float
        Largest static residual at the state [N, N m] (zero at an equilibrium).
    """

    M: np.ndarray
    K: np.ndarray
    D: np.ndarray
    N: np.ndarray
    q0: np.ndarray
    residual: float


@on_one_blas_thread
def null_space(Cq: np.ndarray, n: int, tolerance: float = 1e-9) -> np.ndarray:
    """Orthonormal basis (n x n_free) of the null space of the constraint Jacobian ``Cq`` (m x n)."""
    if Cq.shape[0] == 0:
        return np.eye(n)
    U, sv, _ = np.linalg.svd(Cq.T)
    rank = int(np.sum(sv > tolerance * max(float(sv.max()), 1e-300)))
    return U[:, rank:]


class _Residual:
    """Exudyn's static residual (ODE2 and algebraic rows) at the model's current state, with the
    velocities or strains changed; the current and initial states are restored by :meth:`close`."""

    def __init__(self, model: MechanismModel) -> None:
        self.model = model
        mbs = model.mbs
        sd = self.sd = mbs.systemData
        self.cur = exu.ConfigurationType.Current
        ini = exu.ConfigurationType.Initial
        self.current_state = sd.GetSystemState(configuration=self.cur)
        self.initial_state = sd.GetSystemState(configuration=ini)
        self.n = len(sd.GetODE2Coordinates())
        self.settings = static_settings()
        self.solver = exu.MainSolverStatic()
        sd.SetSystemState(systemStateList=self.current_state, configuration=ini)
        zeros = np.zeros(self.n)
        sd.SetODE2Coordinates_t(zeros, configuration=ini)
        sd.SetODE2Coordinates_tt(zeros, configuration=ini)
        self.solver.InitializeSolver(mbs, self.settings)

    def __call__(self, velocities: np.ndarray) -> np.ndarray:
        self.sd.SetODE2Coordinates_t(velocities, configuration=self.cur)
        self.solver.ComputeNewtonResidual(self.model.mbs, self.settings)
        return np.array(self.solver.GetSystemResidual(), dtype=float)

    def close(self) -> None:
        self.solver.FinalizeSolver(self.model.mbs, self.settings)
        self.sd.SetSystemState(systemStateList=self.initial_state, configuration=exu.ConfigurationType.Initial)
        self.sd.SetSystemState(systemStateList=self.current_state, configuration=self.cur)


def damping_matrix(model: MechanismModel, velocity_step: float = 1e-4) -> np.ndarray:
    """``D = -d f / d q'`` [N s/m, N m s/rad ...] at the current state, by central differences.

    The forces are linear in the velocities (spring-dampers, beam and modal damping), so the
    differences are exact up to round-off for any ``velocity_step`` [m/s, rad/s].
    """
    res = _Residual(model)
    try:
        n = res.n
        D = np.zeros((n, n))
        v = np.zeros(n)
        for i in range(n):
            v[i] = velocity_step
            rp = res(v)[:n]
            v[i] = -velocity_step
            rm = res(v)[:n]
            v[i] = 0.0
            D[:, i] = -(rp - rm) / (2.0 * velocity_step)
    finally:
        res.close()
    return D


@on_one_blas_thread
def linear_matrices(model: MechanismModel, *, relative_step: float = 1e-7,
                    singular_values_tolerance: float = 1e-9, damping: bool = True) -> LinearMatrices:
    """:class:`LinearMatrices` of ``model`` at its current state (normally a static equilibrium);
    ``damping=False``: ``D`` is left zero (for the undamped modes)."""
    ts = tangent_system(model.mbs, relative_step)
    M, K, Cq = ts["M"], ts["K"], ts["Cq"]
    N = null_space(Cq, M.shape[0], singular_values_tolerance)
    D = damping_matrix(model) if damping else np.zeros_like(M)
    res = ts["residual"]
    return LinearMatrices(M=M, K=K, D=D, N=N, q0=np.array(model.coordinates(), dtype=float),
                          residual=float(np.max(np.abs(res))) if res.size else 0.0)


def strain_forces(model: MechanismModel, strains: np.ndarray, strain_step: float = 1e-6) -> np.ndarray:
    """Generalised force per unit free strain of each source, ``d f / d eps`` (n x n_sources) [N, N m].

    Central differences of the residual at the current coordinates with each source's strain moved
    by ``+- strain_step``; the strains ``strains`` are written back afterwards.

    Raises
    ------
    ValueError
        If a strain moves a constraint (the six-bar cells' prescribed motor strokes): such a drive
        is a prescribed motion, which this linear model does not represent.
    """
    strains = np.asarray(strains, dtype=float)
    n_src = strains.size
    res = _Residual(model)
    try:
        n = res.n
        B = np.zeros((n, n_src))
        zero = np.zeros(n)
        for k in range(n_src):
            e = np.zeros(n_src)
            e[k] = strain_step
            model.set_strains(strains + e)
            rp = res(zero)
            model.set_strains(strains - e)
            rm = res(zero)
            derivative = (rp - rm) / (2.0 * strain_step)
            algebraic = derivative[n:]
            if algebraic.size and np.max(np.abs(algebraic)) > 1e-9 * max(1.0, float(np.max(np.abs(derivative[:n])))):
                names = [d for d, s in model.drive_source.items() if s == k]
                raise ValueError(
                    f"drive {', '.join(map(repr, names))}: its strain moves a joint of the mechanism (a prescribed "
                    "motion, as the six-bar cells' motor strokes are), which a linear model with force inputs does "
                    "not represent; build the bender with cell='rod', 'beam' or 'rigid' for a linear model")
            B[:, k] = derivative[:n]
    finally:
        model.set_strains(strains)
        res.close()
    return B


def _result(model: MechanismModel, q_rows: np.ndarray, strain_rows: np.ndarray):
    rows = q_rows.shape[0]
    forces = np.tile(np.array(model.connector_forces(), dtype=float), (rows, 1))
    return make_result(model, np.zeros(rows), np.zeros_like(strain_rows), strain_rows, q_rows, forces, {},
                       check_finite=False)


def output_columns(model: MechanismModel, strains: np.ndarray) -> dict[str, str]:
    """The result columns a linear model may output (point coordinates, angles), with their units."""
    result = _result(model, np.atleast_2d(np.array(model.coordinates(), dtype=float)), np.atleast_2d(strains))
    connectors = set(model.connector_names())
    return {name: result.units[name] for name in result
            if result.units.get(name) in OUTPUT_UNITS and name not in connectors and name != "time"}


def output_jacobian(model: MechanismModel, names: list[str], strains: np.ndarray,
                    step: float = 1e-7) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Values, ``d y / d q`` (n_out x n) and ``d y / d eps`` (n_out x n_sources) of result columns ``names``.

    Central differences of the result's columns over rows of perturbed coordinates (``step (1 + |q_i|)``)
    and strains (``step``).
    """
    q0 = np.array(model.coordinates(), dtype=float)
    strains = np.asarray(strains, dtype=float)
    n, n_src = q0.size, strains.size
    h = step * (1.0 + np.abs(q0))
    q_rows = np.tile(q0, (2 * n + 2 * n_src + 1, 1))
    s_rows = np.tile(strains, (2 * n + 2 * n_src + 1, 1))
    idx = np.arange(n)
    q_rows[idx, idx] += h
    q_rows[n + idx, idx] -= h
    src = np.arange(n_src)
    s_rows[2 * n + src, src] += step
    s_rows[2 * n + n_src + src, src] -= step
    result = _result(model, q_rows, s_rows)
    values = np.array([result[name][-1] for name in names])
    dq = np.array([(result[name][:n] - result[name][n:2 * n]) / (2.0 * h) for name in names]).reshape(len(names), n)
    de = np.array([(result[name][2 * n:2 * n + n_src] - result[name][2 * n + n_src:2 * n + 2 * n_src]) / (2.0 * step)
                   for name in names]).reshape(len(names), n_src)
    return values, dq, de


def point_jacobians(model: MechanismModel, step: float = 1e-7) -> tuple[list[str], np.ndarray, np.ndarray]:
    """The mechanism's named points and its benders' cell points: names, positions (P x 2) [m] and
    ``d(x, y)/d q`` (P x 2 x n).

    The named points are ``"component.point"``; a bender's cell points ``"bender.cell_j"`` (j from 1)
    are the positions of its cells' bodies or nodes (rigid and six-bar cells: the cell bodies' reference
    points; beam and ANCF benders: their nodes; a rod bender's segments have no position of their own and are
    left out), in the order of the bender.
    """
    q0 = np.array(model.coordinates(), dtype=float)
    n = q0.size
    h = step * (1.0 + np.abs(q0))
    idx = np.arange(n)
    rows = np.tile(q0, (2 * n + 1, 1))
    rows[idx, idx] += h
    rows[n + idx, idx] -= h
    poses = model.poses(rows)
    xy = dict(model.point_positions(poses))
    for bender in model.mechanism.benders:
        for j, key in enumerate(model.cells.get(bender.name, [])):
            xy[f"{bender.name}.cell_{j + 1}"] = poses[key][:, :2]
    names = [name for name in xy if np.all(np.isfinite(xy[name]))]  # rod segments carry an angle only
    positions = np.array([xy[name][-1] for name in names])
    jac = np.array([((xy[name][:n] - xy[name][n:2 * n]) / (2.0 * h)[:, None]).T for name in names])
    return names, positions, jac.reshape(len(names), 2, n)
