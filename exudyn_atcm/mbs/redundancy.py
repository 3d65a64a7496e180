"""Dependent (redundant) constraints of a built mechanism, named by the joints they realise.

The constraint Jacobian ``C_q`` of the assembled system in its reference pose is taken from
Exudyn (``ComputeJacobianAE``, the same matrix that
:meth:`Mechanism.degrees_of_freedom() <exudyn_atcm.Mechanism.degrees_of_freedom>` counts with
Exudyn's ``ComputeSystemDegreeOfFreedom``, so the two agree).  When its rank is below its
number of rows, a combination of constraints is dependent: the vectors ``v`` with
``C_q^T v = 0`` (right singular vectors of ``C_q^T`` for zero singular values, the same
threshold as ``numpy.linalg.matrix_rank``) say which rows take part, and the builder's record of
which joint each Exudyn object realises (``model.constraint_labels``) names them.

Why the package refuses such a mechanism instead of solving it: Exudyn's static and implicit
dynamic solvers factor the Jacobian and stop on the singular one (reported until now as "did not
converge ... use more cells"); its ``linearSolver.ignoreSingularJacobian`` (full-pivot LU, dense
only) resolves it by least squares "but may also lead to erroneous results" (Exudyn's
documentation).  Two kinds of redundancy occur:

* joints that repeat what others already fix (three pins pairwise at one point): the positions
  are determinate but the joint forces are not; removing one joint loses nothing;
* a chain of cells that cannot stretch (rigid, six-bar, rod), held straight between two points
  at exactly its length (a bender welded to the ground at both ends): its axial direction is
  fixed twice.  Solved anyway, such a chain is locked (no transverse deflection under any load),
  while the real bender deflects by its axial stretch: a wrong answer.  Beam elements stretch,
  so the same mechanism of ``cell="beam"`` has no dependent constraint and solves.
"""

from __future__ import annotations

from contextlib import contextmanager

import exudyn as exu
import numpy as np

from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..mechanism.connections import joint_label
from ..mechanism.points import MechanismError, PointRef
from . import solver_runs as runs
from .model import MechanismModel
from .blas_threads import one_blas_thread

__all__ = ["constraint_jacobian", "dependent_constraints", "refuse_redundant", "labelled", "end_label", "CELLS_LABEL"]

#: Label of the constraints inside a bender's chain of cells (``CELLS_LABEL.format(name=...)``).
CELLS_LABEL = "the cells of bender {name!r}"


@contextmanager
def labelled(mbs, model: MechanismModel, label: str):
    """Context manager: the Exudyn objects added inside the block realise ``label`` (``model.constraint_labels``;
    an object labelled already keeps its label)."""
    first = mbs.systemData.NumberOfObjects()
    yield
    for obj in range(first, mbs.systemData.NumberOfObjects()):
        model.constraint_labels.setdefault(obj, label)


def end_label(mech: Mechanism, bender: Bender, end: str) -> str:
    """The joints at a bender end, for messages (``"weld(b.tip, ground)"``), or ``"the tip of bender 'b'"``."""
    point = PointRef(bender.name, end)
    labels = [joint_label(j) for j in mech.joints if point in (j.p, j.q)]
    return " and ".join(labels) if labels else f"the {end} of bender {bender.name!r}"


def constraint_jacobian(mbs) -> np.ndarray:
    """Exudyn's constraint Jacobian ``C_q`` (m x n) of ``mbs`` at its initial state (as ``ComputeSystemDegreeOfFreedom``)."""
    settings = exu.SimulationSettings()
    settings.solution.file.write = False
    settings.solution.file.writeInitialValues = False
    settings.solution.sensors.writePeriod = 1e30
    settings.linearSolver.solverType = exu.LinearSolverType.EXUdense
    settings.parallel.numberOfThreads = 1
    solver = exu.MainSolverStatic()
    runs.quiet_console()
    try:
        solver.InitializeSolver(mbs, settings)
        n2, n_ae = solver.GetODE2size(), solver.GetAEsize()
        # the ODE2 part first: it initialises the stored Jacobian, which ComputeJacobianAE adds into
        solver.ComputeJacobianODE2RHS(mbs, scalarFactor_ODE2=-1.0, scalarFactor_ODE2_t=0.0, scalarFactor_ODE1=0.0)
        solver.ComputeJacobianAE(mbs, scalarFactor_ODE2=1.0, scalarFactor_ODE2_t=0.0, scalarFactor_ODE1=1.0,
                                 velocityLevel=False)
        jacobian = np.array(solver.GetSystemJacobian(), dtype=float)
        solver.FinalizeSolver(mbs, settings)
    finally:
        runs.restore_console()
    return jacobian[:n2, n2:n2 + n_ae].T.copy()


def dependent_constraints(model: MechanismModel) -> tuple[int, int, list[str]]:
    """``(redundant, equations, labels)``: the number of dependent constraint equations of the built ``model``,
    the number of constraint equations, and the labels (joints, ``"the cells of bender 'b'"``) of the
    constraints that take part, in building order."""
    from scipy.linalg import svd  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
    mbs = model.mbs
    cq = constraint_jacobian(mbs)
    m = cq.shape[0]
    if m == 0:
        return 0, 0, []
    with one_blas_thread():  # after the import: scipy's own BLAS limited too
        _, sv, vt = svd(cq.T, full_matrices=True)
    tol = (sv.max() if sv.size else 0.0) * max(cq.shape) * np.finfo(float).eps
    rank = int(np.sum(sv > tol))
    if rank == m:
        return 0, m, []
    null = vt[rank:].T  # m x (m - rank): combinations of constraint rows that vanish
    weight = np.max(np.abs(null), axis=1)
    involved = set(np.nonzero(weight > 1e-8)[0].tolist())
    sd = mbs.systemData
    labels: list[str] = []
    for obj in range(sd.NumberOfObjects()):
        rows = set(sd.GetObjectLTGAE(obj))
        if rows & involved:
            label = model.constraint_labels.get(obj, f"an internal joint (Exudyn object {obj})")
            if label not in labels:
                labels.append(label)
    return m - rank, m, labels


def refuse_redundant(model: MechanismModel) -> None:
    """Raise :class:`~exudyn_atcm.MechanismError` naming the joints when the built ``model``'s constraints are
    dependent in the reference pose (module docstring: why, and what to do)."""
    redundant, equations, labels = dependent_constraints(model)
    if not redundant:
        return
    mech = model.mechanism
    chains = [b for b in mech.benders if CELLS_LABEL.format(name=b.name) in labels]
    for b in chains:  # the joints holding such a chain's ends take part (named even where its cells realise them)
        for j in mech.joints:
            if b.name in (j.p.component, None if j.q is None else j.q.component) and joint_label(j) not in labels:
                labels.append(joint_label(j))
    listed = ", ".join(labels[:-1]) + (" and " if len(labels) > 1 else "") + labels[-1]
    head = (f"mechanism {mech.name!r} is over-constrained in its reference pose: the constraints of {listed} are "
            f"dependent ({redundant} of {equations} constraint equations redundant). "
            "Exudyn's solvers cannot solve a singular constraint Jacobian")
    if chains:
        kinds = ", ".join(sorted({b.cell.name for b in chains}))
        names = ", ".join(repr(b.name) for b in chains)
        advice = (f"; bender(s) {names} of {kinds} cells cannot stretch, and held straight between points at "
                  "exactly their length their axial direction is fixed twice: solved anyway, such a chain would "
                  "be locked (no deflection under any load). Use cell='beam' (beam elements stretch; the same "
                  "mechanism then solves), or let one end slide (mechanism.ground(point, joint='slider', "
                  "axis=...) or a slider joint along the bender)")
    else:
        advice = ("; remove one of these joints: the others already fix what it fixes (its force would be "
                  "indeterminate)")
    raise MechanismError(head + advice)
