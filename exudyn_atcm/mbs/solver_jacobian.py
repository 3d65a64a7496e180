"""The tangent stiffness from Exudyn's own system Jacobian, for the systems where it is the true tangent.

Exudyn's static solver forms the Jacobian of its residual item by item in C++ (analytic where an
item has one, else numerical differences of that item alone).  With
``newton.numericalDifferentiation.jacobianConnectorDerivative = True`` it includes the constraint
forces' geometric stiffness ``-(d C_q^T/dq) lambda`` that :mod:`exudyn_atcm.mbs.eigen` explains, and
then equals the tangent of :class:`~exudyn_atcm.mbs.tangent.TangentPlan` at about 1/50 of its cost
(10 us against 0.3 to 0.6 ms for 10 to 30 coordinates, measured).

Not for every system: for lone benders of rigid and six-bar cells (bent, loaded) it differs from
the grouped differences by 0.2 % (rigid cells) to 0.8 % (six-bar cells) of the projected tangent, and
moved the six-bar chain's lowest eigenvalue by a factor of two (measured).  Those systems hold
``ConnectorCoordinateSpringDamper`` items (the cells' hinge springs; the six-bar cells also
``JointPrismatic2D``), which the exact systems do not; which item's Jacobian is off was not isolated.  The
Jacobian is therefore used only for systems made of the item types in :data:`EXACT_TYPES`, each
checked against the grouped differences on a loaded, bent state by the tests (beam, ANCF and rod
cells, and links on revolute joints); for the others :attr:`SolverJacobian.exact` is ``False``.
Exudyn's Jacobian leaves out the loads, too: a system with a load that depends on the coordinates
(:func:`constant_load`) is not exact either.
The item-wise differences are one-sided: the tangent agrees with the central differences to about
1e-8 of its largest entry (measured 8e-12 to 1e-8), which :mod:`exudyn_atcm.mbs.stability` allows for.
"""

from __future__ import annotations

import exudyn as exu
import numpy as np

from .tangent import static_settings

__all__ = ["EXACT_TYPES", "SolverJacobian", "constant_load"]

#: item types whose Exudyn Jacobian (with the connector derivative) is the tangent of the grouped differences
EXACT_TYPES = frozenset({"Ground", "RigidBody2D", "JointRevolute2D", "BeamGeometricallyExact2D", "ANCFCable2D",
                         "ConnectorCoordinate", "ConnectorCoordinateVector", "GenericODE2"})


def constant_load(mbs, index: int) -> bool:
    """Whether load ``index`` is a constant generalised force (Exudyn's Jacobian leaves the loads out).

    True for coordinate loads, forces at a node's position or at a 2D rigid body's reference point,
    and torques on a node's or a 2D rigid body's rotation (in the plane the rotation is a coordinate);
    false for anything else, e.g. a force at a point of a link away from its reference point (its
    lever arm turns with the link: measured 2 % off the projected tangent of the README four-bar
    with a force at its coupler point) or a torque on a point of an ANCF cable.
    """
    load = mbs.GetLoad(index)
    if load.get("bodyFixed", False):
        return False
    kind = load["loadType"]
    if kind == "Coordinate":
        return True
    marker = mbs.GetMarker(load["markerNumber"])
    marker_type = marker["markerType"]
    if marker_type == "NodePosition":
        return kind == "ForceVector"
    if marker_type == "NodeRigid":
        return kind in ("ForceVector", "TorqueVector") and mbs.GetNode(marker["nodeNumber"])["nodeType"] == "RigidBody2D"
    if marker_type in ("BodyPosition", "BodyRigid"):
        on_rigid_body = mbs.GetObject(marker["bodyNumber"])["objectType"] == "RigidBody2D"
        at_reference = not np.any(np.asarray(marker.get("localPosition", [0.0]), dtype=float))
        return on_rigid_body and (kind == "TorqueVector" or (kind == "ForceVector" and at_reference))
    return False


class SolverJacobian:
    """Exudyn's system Jacobian of an assembled system as its tangent stiffness (see the module docstring).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        An assembled system without ODE1 coordinates.
    """

    def __init__(self, mbs) -> None:
        self.mbs = mbs
        sd = mbs.systemData
        self.types = frozenset(mbs.GetObject(i)["objectType"] for i in range(sd.NumberOfObjects()))
        #: whether every item's Jacobian is the true tangent and no load depends on the coordinates (only then
        #: :meth:`system` may be used)
        self.exact = self.types <= EXACT_TYPES and all(constant_load(mbs, i) for i in range(sd.NumberOfLoads()))
        self.n_ode2 = len(sd.GetODE2Coordinates())
        self._settings = static_settings()
        self._settings.staticSolver.newton.numericalDifferentiation.jacobianConnectorDerivative = True

    def system(self, mass: bool = True) -> dict:
        """``M`` (or ``None``), ``K`` (unsymmetrised tangent stiffness) and ``Cq`` at the current state.

        The same keys and units as :meth:`~exudyn_atcm.mbs.tangent.TangentPlan.system` (without the
        residual).  The current and initial states are restored on return.
        """
        mbs = self.mbs
        sd = mbs.systemData
        cur, ini = exu.ConfigurationType.Current, exu.ConfigurationType.Initial
        current_state = sd.GetSystemState(configuration=cur)
        initial_state = sd.GetSystemState(configuration=ini)
        n2 = self.n_ode2
        settings = self._settings
        solver = exu.MainSolverStatic()
        try:
            sd.SetSystemState(systemStateList=current_state, configuration=ini)
            solver.InitializeSolver(mbs, settings)
            if solver.GetODE1size() != 0 or solver.GetODE2size() != n2:
                raise RuntimeError("solver Jacobian: the system changed since it was set up, or has ODE1 coordinates")
            m = None
            if mass:
                solver.ComputeMassMatrix(mbs)
                m = np.array(solver.GetSystemMassMatrix(), dtype=float)[:n2, :n2]
            # the ODE2 part first (it sets the whole stored Jacobian), then the constraints' part is added
            solver.ComputeJacobianODE2RHS(mbs, scalarFactor_ODE2=-1.0, scalarFactor_ODE2_t=0.0, scalarFactor_ODE1=0.0)
            solver.ComputeJacobianAE(mbs, scalarFactor_ODE2=1.0, scalarFactor_ODE2_t=0.0, scalarFactor_ODE1=0.0,
                                     velocityLevel=False)
            jacobian = np.array(solver.GetSystemJacobian(), dtype=float)
            solver.FinalizeSolver(mbs, settings)
        finally:
            sd.SetSystemState(systemStateList=initial_state, configuration=ini)
            sd.SetSystemState(systemStateList=current_state, configuration=cur)
        return {"M": m, "K": jacobian[:n2, :n2], "Cq": jacobian[n2:, :n2]}
