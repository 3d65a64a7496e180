"""The tangent stiffness from Exudyn's own system Jacobian, for the systems where it is the true tangent.

Exudyn's static solver forms the Jacobian of its residual item by item in C++ (analytic where an
item has one, else numerical differences of that item alone).  With
``newton.numericalDifferentiation.jacobianConnectorDerivative = True`` it includes the constraint
forces' geometric stiffness ``-(d C_q^T/dq) lambda`` that :mod:`exudyn_atcm.mbs.eigen` explains, and
then equals the tangent of :class:`~exudyn_atcm.mbs.tangent.TangentPlan` at about 1/50 of its cost
(10 us against 0.3 to 0.6 ms for 10 to 30 coordinates, measured).

Not as Exudyn gives it: its Jacobian of a revolute joint leaves out the derivative of the joint
force's moment about a rigid body's reference point (zero in Exudyn, ``lambda . R p`` in truth;
:class:`JointLevers` adds it).  Without it a chain of rigid cells under a tip force was 0.2 % off
the grouped differences, and a link on pins carrying a force would have been too stiff by that
term: a rigid-cell column past its buckling load was proved stable from it
(``tests/test_sweep_solve.py``).  With it, rigid cells (bent, loaded) agree to 1e-11.  Not for
every system even so: six-bar cells (``JointPrismatic2D``, ``MarkerBodiesRelativeTranslationCoordinate``)
differ by 0.8 % of the projected tangent (measured; the item not isolated).  The Jacobian is
therefore used only for systems made of the item types in :data:`EXACT_TYPES`, each checked against
the grouped differences on a loaded, bent state by the tests (rigid, beam, ANCF and rod cells, and
links on revolute joints); for the others :attr:`SolverJacobian.exact` is ``False``.
Exudyn's Jacobian leaves out the loads, too: a system with a load that depends on the coordinates
(:func:`constant_load`) is not exact either.
The item-wise differences are one-sided: the tangent agrees with the central differences to about
1e-8 of its largest entry (measured 8e-12 to 1e-8), which :mod:`exudyn_atcm.mbs.stability` allows for.
"""

from __future__ import annotations

import exudyn as exu
import numpy as np

from .tangent import static_settings

__all__ = ["EXACT_TYPES", "JointLevers", "SolverJacobian", "constant_load"]

#: item types whose Exudyn Jacobian (with the connector derivative, and the revolute joints' geometric stiffness
#: added by :class:`JointLevers`) is the tangent of the grouped differences
EXACT_TYPES = frozenset({"Ground", "RigidBody2D", "JointRevolute2D", "BeamGeometricallyExact2D", "ANCFCable2D",
                         "ConnectorCoordinate", "ConnectorCoordinateVector", "GenericODE2",
                         "ConnectorCoordinateSpringDamper"})


class JointLevers:
    """The geometric stiffness of the revolute joints at points away from a rigid body's reference point.

    Exudyn's Jacobian of an ``ObjectJointRevolute2D`` (``ComputeJacobianAE``, also with
    ``jacobianConnectorDerivative``) leaves out the derivative of the constraint force's moment
    about the body's reference point: for a joint marker at ``p`` (body frame) on a body turned by
    ``theta``, the joint's multipliers ``lambda`` (its two algebraic coordinates) contribute
    ``s lambda . (R(theta) p)`` to the tangent's ``(theta, theta)`` entry, ``s = +1`` for the
    joint's second marker and ``-1`` for its first (``d^2 (R p) / d theta^2 = -R p``).  Measured:
    a pinned bar with multipliers (1.5, -0.7) N, marker 0.05 m from its reference point, turned
    0.3 rad: Exudyn 0, central differences -0.0613 N m, this term -0.0613 N m
    (``tests/test_sweep_solve.py``).  Without it the tangent of a chain of rigid cells under a tip
    force of 0.02 N was 4e-4 N m/rad too stiff on every cell's rotation (``F L_c``), and a proof of
    stability from it could pass a state the true tangent fails.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        An assembled system.
    objects : list of dict, optional
        Its objects as ``mbs.GetObject`` gives them, when the caller has read them already (each
        read copies the object's data: about 4 us an object); default: read here.
    """

    def __init__(self, mbs, objects: list[dict] | None = None) -> None:
        sd = mbs.systemData
        if objects is None:
            objects = [mbs.GetObject(i) for i in range(sd.NumberOfObjects())]
        entries = []
        for i, obj in enumerate(objects):
            if obj["objectType"] != "JointRevolute2D":
                continue
            for sign, marker_number in zip((-1.0, 1.0), obj["markerNumbers"]):
                marker = mbs.GetMarker(marker_number)
                if marker["markerType"] not in ("BodyPosition", "BodyRigid"):
                    continue  # a node's position: no lever
                body = objects[marker["bodyNumber"]]
                local = np.asarray(marker.get("localPosition", [0.0, 0.0, 0.0]), dtype=float)[:2]
                if body["objectType"] != "RigidBody2D" or not np.any(local):
                    continue
                node = body["nodeNumber"]
                angle0 = float(mbs.GetNode(node)["referenceCoordinates"][2])
                entries.append((i, sign, int(sd.GetNodeLTGODE2(node)[2]), angle0, local))
        #: (joint object, sign, rotation coordinate, reference angle [rad], marker position [m]) per lever
        self.entries = entries
        n = len(entries)
        self._rows = np.array([e[2] for e in entries], dtype=int)
        self._signs = np.array([e[1] for e in entries], dtype=float)
        self._angles = np.array([e[3] for e in entries], dtype=float)
        self._local = np.array([e[4] for e in entries], dtype=float).reshape(n, 2)
        self._ae = np.array([np.asarray(sd.GetObjectLTGAE(e[0]), dtype=int)[:2] for e in entries], dtype=int).reshape(n, 2)

    @property
    def arrays(self) -> tuple[np.ndarray, ...]:
        """The levers as arrays: rotation coordinates, signs, reference angles [rad], marker positions [m] (n x 2)
        and the joints' multiplier indices (n x 2), in the order
        :func:`~exudyn_atcm.mbs.definite_kernel.add_lever_terms` takes them."""
        return self._rows, self._signs, self._angles, self._local, self._ae

    def add_to(self, k: np.ndarray, q: np.ndarray, multipliers: np.ndarray) -> None:
        """Add the joints' terms to the tangent ``k`` (in place) at coordinates ``q`` and multipliers ``multipliers``
        (compiled: :func:`~exudyn_atcm.mbs.definite_kernel.add_lever_terms`; a body with levers at both ends gets
        both)."""
        if not self.entries:
            return
        from .definite_kernel import add_lever_terms  # noqa: PLC0415 - lazy: numba is slow to import
        add_lever_terms(k, *self.arrays, np.asarray(q, dtype=float), np.asarray(multipliers, dtype=float))


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
        objects = [mbs.GetObject(i) for i in range(sd.NumberOfObjects())]  # read once (each read copies its data)
        self.types = frozenset(obj["objectType"] for obj in objects)
        #: whether every item's Jacobian is the true tangent and no load depends on the coordinates (only then
        #: :meth:`system` may be used)
        self.exact = self.types <= EXACT_TYPES and all(constant_load(mbs, i) for i in range(sd.NumberOfLoads()))
        self.n_ode2 = len(sd.GetODE2Coordinates())
        self.levers = JointLevers(mbs, objects)
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
        return self.split(jacobian, m)

    def split(self, jacobian: np.ndarray, m: np.ndarray | None, q: np.ndarray | None = None,
              multipliers: np.ndarray | None = None) -> dict:
        """``M``, ``K`` (with the joints' lever terms) and ``Cq`` of the system Jacobian ``jacobian`` (``m``: the mass
        matrix or ``None``) at the ODE2 coordinates ``q`` and multipliers ``multipliers`` (default: the current
        state's)."""
        n2 = self.n_ode2
        k = jacobian[:n2, :n2]
        if self.levers.entries:
            sd = self.mbs.systemData
            self.levers.add_to(k, sd.GetODE2Coordinates(copy=False) if q is None else q,
                               sd.GetAECoordinates(copy=False) if multipliers is None else multipliers)
        return {"M": m, "K": k, "Cq": jacobian[n2:, :n2]}

    def running_system(self, solver, mass: bool = True) -> dict:
        """:meth:`system` from a static solver that is running on this system, in one of its step hooks.

        The solver's own Jacobian functions at the current state: no solver of its own and no state
        saved or restored (a few microseconds instead of about 40).  The solver's settings must have
        ``staticSolver.newton.numericalDifferentiation.jacobianConnectorDerivative = True`` (as
        :meth:`system` uses; otherwise the constraint forces' geometric stiffness is missing); the
        solver forms its Jacobian afresh in the next Newton iteration (full Newton), so nothing it
        holds is disturbed.  Equal to :meth:`system` to the last bit (measured on the README four-bar
        and a lone rod bender; ``tests/test_sweep_solve.py``).
        """
        jacobian, m = self.running_jacobian(solver, mass)
        return self.split(jacobian, m)

    def running_jacobian(self, solver, mass: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
        """The running solver's system Jacobian as Exudyn forms it (without the lever terms) and the mass matrix
        (or ``None``): what :meth:`running_system` splits."""
        n2 = self.n_ode2
        m = None
        # Exudyn hands out fresh float arrays (copies); the arguments by position (its keywords: scalarFactor_ODE2,
        # scalarFactor_ODE2_t, scalarFactor_ODE1[, velocityLevel]): keyword parsing costs 1-2 us a call, in every
        # point of a sweep
        if mass:  # formed every time: a rigid cell's mass matrix turns with it (its centre of mass is off its node)
            solver.ComputeMassMatrix(self.mbs)
            m = np.asarray(solver.GetSystemMassMatrix(), dtype=float)[:n2, :n2]
        solver.ComputeJacobianODE2RHS(self.mbs, -1.0, 0.0, 0.0)
        solver.ComputeJacobianAE(self.mbs, 1.0, 0.0, 0.0, False)
        return np.asarray(solver.GetSystemJacobian(), dtype=float), m
