"""Tangent stiffness, mass matrix and constraint Jacobian of a constrained Exudyn system, by grouped differences.

The tangent stiffness of a constrained equilibrium is ``K_T = -d/dq [f(q) + C_q(q)^T lambda]``
with the multipliers held (:mod:`exudyn_atcm.mbs.eigen` explains why Exudyn's own Jacobian
leaves the constraint forces' part out).  It is found by central differences of Exudyn's static
residual.  Differencing one coordinate at a time costs ``2 n`` residual evaluations; but a
coordinate changes only the residual rows of the items (bodies, elements, joints, springs) that
hold it, so coordinates whose sets of rows do not overlap are perturbed together (the
Curtis-Powell-Reid grouping of sparse differences).  A chain of bodies needs about nine groups
whatever its length: a 16-cell six-bar chain 15 groups instead of its 240 coordinates (30
residual evaluations instead of 480), with the same differences (each row sees the perturbation
of its own coordinate only, so the numbers are those of the one-at-a-time differences).

:class:`TangentPlan` works out the groups once per assembled system (from
``GetObjectLTGODE2`` / ``GetObjectLTGAE`` of every object) and evaluates the tangent at the
system's current state as often as asked.  The grouping assumes that every coupling between
coordinates goes through an object holding both: true of every item the package builds (user
functions of its springs read their own connector's coordinates only).
"""

from __future__ import annotations

import math

import exudyn as exu
import numpy as np
from .._checks import shown

__all__ = ["TangentPlan", "static_settings"]


def static_settings():
    """Quiet dense static-solver settings for residual evaluations (loads at their full value)."""
    s = exu.SimulationSettings()
    s.solution.file.write = False
    s.solution.file.writeInitialValues = False
    s.solution.sensors.writePeriod = 1e30
    s.staticSolver.verboseMode = 0
    s.staticSolver.useLoadFactor = False  # loads at their full value, not ramped
    s.linearSolver.solverType = exu.LinearSolverType.EXUdense
    s.parallel.numberOfThreads = 1
    return s


class TangentPlan:
    """Grouped central differences of an assembled system's static residual.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        An assembled system (its items are not changed after the plan is made).
    """

    def __init__(self, mbs) -> None:
        self.mbs = mbs
        sd = mbs.systemData
        ode2 = [list(sd.GetObjectLTGODE2(o)) for o in range(sd.NumberOfObjects())]
        ae = [list(sd.GetObjectLTGAE(o)) for o in range(sd.NumberOfObjects())]
        self.n_ode2 = len(sd.GetODE2Coordinates())
        self.n_ae = len(sd.GetAECoordinates())
        n2 = self.n_ode2
        rows: list[set[int]] = [set() for _ in range(n2)]
        for coords, algebraic in zip(ode2, ae):
            touched = set(coords) | {n2 + a for a in algebraic}
            for i in coords:
                rows[i] |= touched
        for i in range(n2):
            rows[i].add(i)
        #: the rows (ODE2 then AE indices, AE offset by the ODE2 size) each coordinate changes
        self.rows = [np.array(sorted(r), dtype=int) for r in rows]
        self.groups = _groups(rows)
        # per group: the (row, column) entries its differences fill, as flat index arrays
        self._entries = [(np.concatenate([self.rows[i] for i in g]),
                          np.concatenate([np.full(self.rows[i].size, i) for i in g])) for g in self.groups]
        # the same, for all groups at once: (group, row) of each entry and its (row, column) in the derivative,
        # and the groups' indicator matrix, so that a call does its array work in a few vectorised operations
        self._entry_group = np.concatenate([np.full(r.size, k) for k, (r, _) in enumerate(self._entries)] or
                                           [np.zeros(0, dtype=int)])
        self._entry_row = np.concatenate([r for r, _ in self._entries] or [np.zeros(0, dtype=int)])
        self._entry_column = np.concatenate([c for _, c in self._entries] or [np.zeros(0, dtype=int)])
        self._indicator = np.zeros((len(self.groups), n2))
        for k, g in enumerate(self.groups):
            self._indicator[k, g] = 1.0
        self._settings = static_settings()  # made once: a SimulationSettings costs about 10 us to make

    def system(self, relative_step: float = 1e-7, mass: bool = True) -> dict:
        """Mass matrix, tangent stiffness and constraint Jacobian at the current state.

        Parameters
        ----------
        relative_step : float, optional
            Central-difference step per coordinate, ``h_i = relative_step * (1 + |q_i|)`` [m or rad].
        mass : bool, optional
            Also the mass matrix (``False``: ``M`` is ``None``).

        Returns
        -------
        dict
            ``M`` (n x n) [kg, kg m, kg m^2] or ``None``, ``K`` (n x n, unsymmetrised tangent stiffness
            ``-d(f + C_q^T lambda)/dq``) [N/m, N/rad, N m/rad ...], ``Cq`` (m x n) constraint Jacobian,
            ``residual`` (n,) the ODE2 part of the static residual at the state [N, N m].

        Notes
        -----
        The current and initial states of the system are restored on return (the initial state
        is used temporarily: Exudyn's solver initialisation starts from it).
        """
        if not (relative_step > 0.0 and math.isfinite(relative_step)):
            raise ValueError(f"relative_step must be a finite step > 0, got {shown(relative_step)}")
        mbs = self.mbs
        sd = mbs.systemData
        cur = exu.ConfigurationType.Current
        ini = exu.ConfigurationType.Initial
        current_state = sd.GetSystemState(configuration=cur)
        initial_state = sd.GetSystemState(configuration=ini)
        q0 = np.array(sd.GetODE2Coordinates(configuration=cur), dtype=float)
        n2 = q0.size
        if n2 != self.n_ode2:
            raise RuntimeError("tangent: the system changed since its plan was made")
        settings = self._settings
        solver = exu.MainSolverStatic()
        try:
            # the solver starts from the initial state: make it the current one (zero velocity)
            sd.SetSystemState(systemStateList=current_state, configuration=ini)
            zeros = np.zeros(n2)
            sd.SetODE2Coordinates_t(zeros, configuration=ini)
            sd.SetODE2Coordinates_tt(zeros, configuration=ini)
            solver.InitializeSolver(mbs, settings)
            if solver.GetODE1size() != 0:
                raise ValueError("constrained tangent: systems with ODE1 coordinates are not supported, "
                                 f"this one has {solver.GetODE1size()}")
            if solver.GetODE2size() != n2 or solver.GetAEsize() != self.n_ae:
                raise RuntimeError("tangent: the solver's sizes differ from the system's")
            M = None
            if mass:
                solver.ComputeMassMatrix(mbs)
                M = np.array(solver.GetSystemMassMatrix(), dtype=float)[:n2, :n2]

            def residual(q):
                sd.SetODE2Coordinates(q, configuration=cur)
                solver.ComputeNewtonResidual(mbs, settings)
                return np.array(solver.GetSystemResidual(), dtype=float)

            r0 = residual(q0)
            h = relative_step * (1.0 + np.abs(q0))
            steps = self._indicator * h  # row k: the step of group k's coordinates, zero elsewhere
            plus = [residual(q) for q in q0 + steps]
            minus = [residual(q) for q in q0 - steps]
            derivative = np.zeros((n2 + self.n_ae, n2))
            if self.groups:
                rows, columns, group = self._entry_row, self._entry_column, self._entry_group
                derivative[rows, columns] = ((np.asarray(plus)[group, rows] - np.asarray(minus)[group, rows])
                                             / (2.0 * h[columns]))
            solver.FinalizeSolver(mbs, settings)
        finally:
            sd.SetSystemState(systemStateList=initial_state, configuration=ini)
            sd.SetSystemState(systemStateList=current_state, configuration=cur)
        return {"M": M, "K": -derivative[:n2], "Cq": derivative[n2:], "residual": r0[:n2]}


def _groups(rows: list[set[int]]) -> list[np.ndarray]:
    """Coordinates in groups whose row sets do not overlap (greedy, in coordinate order)."""
    groups: list[list[int]] = []
    used: list[set[int]] = []
    for i, r in enumerate(rows):
        for group, taken in zip(groups, used):
            if not (taken & r):
                group.append(i)
                taken |= r
                break
        else:
            groups.append([i])
            used.append(set(r))
    return [np.array(g, dtype=int) for g in groups]
