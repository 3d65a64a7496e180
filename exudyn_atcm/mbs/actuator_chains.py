"""Builds and solves the Exudyn multibody system of a :class:`~exudyn_atcm.actuator.BendingActuator`.

This is the only module of the package that calls Exudyn (CamelCase names).  It knows the
two cell types, the solver settings, the hooks through which the stroke enters each solver
step, and how the state is read back; it holds no physics constants of its own (those come
from the actuator) and no file formats.

Model layout (planar, SI units; see :mod:`exudyn_atcm.actuator` for the coordinates):

``"six-bar"`` cell j (``x_j = j L_c``), MODEL.md §2:
    interface element I_j at ``(x_j, 0)`` (reference point on the passive layer, upper point
    at ``(0, -e)`` local; I_0 is the ground), passive bar P_j from ``(x_j, 0)`` to
    ``(x_{j+1}, 0)``, active bodies A1, A2, A3 of length ``L_c/3`` each on ``y = -e``.
    Revolute joints P_j-I_j, P_j-I_{j+1} (lower) and A1-I_j, A3-I_{j+1} (upper), each with a
    torsion spring-damper on the relative rotation.  Prismatic A1-A2 with the motor
    (coordinate constraint on the relative translation, offset = stroke) and prismatic
    A2-A3 with the axial spring ``k1``.
``"rigid"`` cell j:
    one rigid body on the passive layer's mid-plane from ``(x_j, 0)`` to ``(x_{j+1}, 0)``
    carrying both layers' mass, revolute joints at the cell boundaries, torsion springs
    ``2 EI/L_c`` at the clamp and ``EI/L_c`` inside, whose rest angles are the free
    rotation of the half cell (clamp) or two half cells (inside) they stand for.  The tip
    interface's spring (``2 EI/L_c``) carries no moment under a force at the tip point and
    the interface is massless, so its angle is the last body's angle plus half a cell's
    free rotation: that is how the tip angle is computed, without a body.

The stroke reaches the model in one of two ways, chosen by ``stroke_path``:

``"prestep"`` (default)
    A pre-step hook evaluates the strain once for the step's time ``t`` and writes it into
    the motor constraints' ``offset`` (six-bar) or, for the rigid cell, into one torque on
    the last body that equals the net effect of all joints' rest angles (see
    ``_build_rigid``: the rest-angle moments cancel pairwise on every other body).
``"offsets"``
    As ``"prestep"``, but the rigid cell's rest angles are written into every torsion
    spring's ``offset`` (one call per joint and step).
``"user_function"``
    Offset user functions (six-bar) / spring-force user functions with the rest angle
    (rigid) that call the strain source at their ``t``.

These are the same computation: every hook and user function of one solver step receives
the same ``t`` (the end time of the step being attempted, EXUDYN_NOTES.md), and the strain
source evaluates from memory that changes only in the post-step hook, i.e. after the step.
So the offset a user function would return at each Newton iteration is exactly the value the
pre-step hook wrote for that step; the test suite checks the paths against each other.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import exudyn as exu
import numpy as np
from exudyn import itemInterface as ii

from .eigen import constrained_eigenfrequencies

#: Default absolute Newton tolerance in SI units (EXUDYN_NOTES.md: 1e-10 fails from 10 cells).
NEWTON_ABSOLUTE_TOLERANCE = 1e-8

#: How ``cell="rigid"`` is built with the default stroke path: ``"tree"`` (minimal coordinates,
#: one ``ObjectKinematicTree``) or ``"bodies"`` (rigid bodies, revolute joints, springs).
RIGID_FORMULATION = "bodies"


@dataclass
class BuiltModel:
    """Handles of a built system (internal)."""

    SC: Any
    mbs: Any
    cell: str
    n_cells: int
    cell_length: float
    # items whose offset carries the stroke; offset = factor * strain
    offset_items: list = field(default_factory=list)
    offset_factors: list = field(default_factory=list)
    offset_parameter: str = "offset"  # the items' parameter that carries factor * strain
    # rigid cell: tip angle = last angle + tip_rotation_per_strain * strain
    tip_rotation_per_strain: float = 0.0
    # ODE2 indices of (x, y, phi) of the tip node and phi of every cell body
    tip_indices: np.ndarray | None = None
    cell_angle_indices: np.ndarray | None = None
    tip_reference: tuple = (0.0, 0.0, 0.0)
    tip_local_x: float = 0.0  # tip point's local x in the tip node's frame
    tip_load: int = -1
    # strain as a function of the solver's t, used by the user-function path
    uf_strain: Any = None
    # (item, stiffness, damping parameter name) of every spring-damper and beam element, for
    # temporary damping changes (damping = factor * stiffness)
    springs: list = field(default_factory=list)
    # beam cell: the recorded angles are the n + 1 node rotations; a cell's angle is the mean
    # of its two nodes' rotations
    cell_angles_from_nodes: bool = False
    # smallest absolute Newton tolerance [N, N m] the model can reach (round-off of stiff
    # axial forces); the solves raise a tighter tolerance to it
    newton_tolerance_floor: float = 0.0
    # relative Newton tolerance of the static solves, if the default (1e-8 of the first
    # residual of a load step) stops too early for this model
    static_relative_tolerance: float | None = None
    tip_force: tuple = (0.0, 0.0)

    # rigid cell, pre-step path: the rest angles' net effect, one torque on the last body
    torque_load: Any = None
    torque_per_strain: float = 0.0

    def set_strain(self, strain: float) -> None:
        """Write the stroke for free strain ``strain`` into the model (pre-step paths)."""
        mbs = self.mbs
        for item, factor in zip(self.offset_items, self.offset_factors):
            mbs.SetObjectParameter(item, self.offset_parameter, factor * strain)
        if self.torque_load is not None:
            mbs.SetLoadParameter(self.torque_load, "loadVector", [0.0, 0.0, self.torque_per_strain * strain])

    def scale_loads(self, factor: float) -> None:
        """Set the tip load to ``factor`` times the tip force (load ramps of the relaxation)."""
        fx, fy = self.tip_force
        self.mbs.SetLoadParameter(self.tip_load, "loadVector", [factor * fx, factor * fy, 0.0])

    def read_state(self, q: np.ndarray, strain: float) -> tuple:
        """Tip x, y, angle and per-cell angles from the ODE2 coordinates ``q`` (displacements)."""
        xt, yt, pt = q[self.tip_indices]
        x0, y0, p0 = self.tip_reference
        phi = p0 + pt
        x = x0 + xt + self.tip_local_x * math.cos(phi)
        y = y0 + yt + self.tip_local_x * math.sin(phi)
        angle = phi + self.tip_rotation_per_strain * strain
        angles = q[self.cell_angle_indices]
        if self.cell_angles_from_nodes:
            angles = 0.5 * (angles[:-1] + angles[1:])
        return x, y, angle, angles

    @property
    def record_indices(self) -> np.ndarray:
        """ODE2 indices recorded per step: tip node (x, y, phi), then each cell's angle."""
        return np.concatenate([self.tip_indices, self.cell_angle_indices])

    def states_from_records(self, records: np.ndarray, strains: np.ndarray) -> tuple:
        """Vectorised :meth:`read_state` over rows of ``q[record_indices]``."""
        x0, y0, p0 = self.tip_reference
        phi = p0 + records[:, 2]
        x = x0 + records[:, 0] + self.tip_local_x * np.cos(phi)
        y = y0 + records[:, 1] + self.tip_local_x * np.sin(phi)
        angle = phi + self.tip_rotation_per_strain * strains
        angles = records[:, 3:]
        if self.cell_angles_from_nodes:
            angles = 0.5 * (angles[:, :-1] + angles[:, 1:])
        return x, y, angle, angles

    def coordinates(self) -> np.ndarray:
        """Current ODE2 coordinates (a view, no copy)."""
        return self.mbs.systemData.GetODE2Coordinates(copy=False)


def _rigid2d(mbs, position, mass, inertia, com=(0.0, 0.0)):
    """Rigid body 2D; ``inertia`` about the centre of mass ``com`` (local, relative to the node).

    Exudyn's ``inertia`` is taken about the body's reference point (the node), so the
    parallel-axis term is added here.
    """
    inertia = inertia + mass * (com[0] ** 2 + com[1] ** 2)
    node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[position[0], position[1], 0.0],
                                          visualization={'show': False, 'drawSize': -1.,
                                                         'color': [-1., -1., -1., -1.]}))
    body = mbs.AddObject(ii.ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=inertia,
                                              centerOfMass=[com[0], com[1]],
                                              visualization={'show': False, 'graphicsDataUserFunction': 0,
                                                             'graphicsData': []}))
    return node, body


def _pos_marker(mbs, body, local):
    return mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=body, localPosition=[local[0], local[1], 0.0]))


def _rot_marker(mbs, node):
    return mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node, coordinate=2))


def _add_ground(mbs):
    """The clamp: a ground object and a fixed coordinate marker for the first joint's spring."""
    ground = mbs.AddObject(ii.ObjectGround(visualization={'show': False, 'graphicsDataUserFunction': 0,
                                                          'graphicsData': []}))
    gnode = mbs.AddNode(ii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0], visualization=_NOVIS))
    return ground, mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=gnode, coordinate=0))


def _hinge_with_spring(mbs, positions, rotations, stiffness: float, beta: float) -> None:
    """A revolute joint between two position markers and a torsion spring-damper between the
    rotation coordinates of the joined bodies (damping ``beta * stiffness``)."""
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=list(positions), visualization=_NOVIS))
    mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(markerNumbers=list(rotations), stiffness=stiffness,
                                                          damping=beta * stiffness, visualization=_NOVIS))


def _zero(t: float) -> float:
    return 0.0


_NOVIS = {'show': False, 'drawSize': -1., 'color': [-1., -1., -1., -1.]}


def build(actuator, tip_force=(0.0, 0.0), stroke_path: str = "prestep") -> BuiltModel:
    """Build the Exudyn system of ``actuator`` with a dead tip load ``tip_force`` [N].

    With ``stroke_path="user_function"`` the user functions call ``model.uf_strain(t)``,
    which the caller sets (static solve: strain at load factor ``t``; dynamics: the strain source).
    """
    if stroke_path not in ("prestep", "user_function", "offsets"):
        raise ValueError(f"stroke_path must be 'prestep', 'offsets' or 'user_function', got {stroke_path!r}")
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    if actuator.cell == "six-bar":
        model = _build_six_bar(SC, mbs, actuator, stroke_path)
    elif actuator.cell == "beam":
        from .actuator_beam import build_beam  # noqa: PLC0415 - the beam module imports this one
        model = build_beam(SC, mbs, actuator, stroke_path)
    elif actuator.cell == "ancf":
        from .actuator_ancf import build_ancf  # noqa: PLC0415 - the ANCF module imports this one
        model = build_ancf(SC, mbs, actuator, stroke_path)
    elif RIGID_FORMULATION == "tree" and stroke_path == "prestep":
        from .actuator_tree import build_tree  # noqa: PLC0415 - the tree module imports this one
        model = build_tree(SC, mbs, actuator, stroke_path)
    else:
        model = _build_rigid(SC, mbs, actuator, stroke_path)
    model.uf_strain = _zero
    fx, fy = float(tip_force[0]), float(tip_force[1])
    model.tip_load = mbs.AddLoad(ii.LoadForceVector(markerNumber=model._tip_marker,
                                                    loadVector=[fx, fy, 0.0], bodyFixed=False))
    model.tip_force = (fx, fy)
    for i in range(mbs.systemData.NumberOfObjects()):
        if mbs.GetObject(i)["objectType"] == "ConnectorCoordinateSpringDamper":
            model.springs.append((i, float(mbs.GetObjectParameter(i, "stiffness")), "damping"))
    mbs.Assemble()
    if hasattr(model, "finish_indices"):
        model.finish_indices()
        return model
    _finish_indices(model)
    ref = mbs.systemData.GetODE2Coordinates(configuration=exu.ConfigurationType.Reference)
    model.tip_reference = tuple(float(v) for v in np.asarray(ref)[model.tip_indices])
    return model


def _build_six_bar(SC, mbs, act, stroke_path) -> BuiltModel:
    n, lc, e = act.n_cells, act.cell_length, act.layer_offset
    beta = act.stiffness_damping_factor
    k_p, k_a, k1 = act.torsion_stiffness_passive, act.torsion_stiffness_active, act.axial_spring_stiffness
    w = act.width
    h1, h2 = act.passive.thickness, act.active.thickness
    m1_cell = act.passive.mass_per_length(w) * lc
    m2_cell = act.active.mass_per_length(w) * lc
    s = act.interface_length
    keep = 1.0 - s / lc  # share of the layer mass left on the layer bodies
    m_if = act.mass_per_length * s
    j_if = m_if * (s**2 + (e + 0.5 * (h1 + h2)) ** 2) / 12.0

    ground, gcoord = _add_ground(mbs)
    model = BuiltModel(SC=SC, mbs=mbs, cell="six-bar", n_cells=n, cell_length=lc)

    def motor_uf_factory(factor):
        return lambda mbs_, t, itemNumber, lOffset: factor * model.uf_strain(t)

    # previous interface: markers (lower, upper) and rotation-coordinate marker
    prev_lower = _pos_marker(mbs, ground, (0.0, 0.0))
    prev_upper = _pos_marker(mbs, ground, (0.0, -e))
    prev_rot = gcoord
    passive_nodes = []
    last_if_node = None
    for j in range(n):
        x0 = j * lc
        # passive bar
        mp = m1_cell * keep
        npb, bp = _rigid2d(mbs, (x0 + 0.5 * lc, 0.0), mp, mp * (lc**2 + h1**2) / 12.0)
        passive_nodes.append(npb)
        # active bodies A1, A2, A3
        ma = m2_cell * keep / 3.0
        la = lc / 3.0
        ja = ma * (la**2 + h2**2) / 12.0
        nodes_a = []
        bodies_a = []
        for k in range(3):
            nd, bd = _rigid2d(mbs, (x0 + (k + 0.5) * la, -e), ma, ja)
            nodes_a.append(nd)
            bodies_a.append(bd)
        # next interface element (reference point on the passive layer)
        # interface j+1 takes half its lumped mass from cell j and half from cell j+1
        share = 1.0 if j < n - 1 else 0.5
        nif, bif = _rigid2d(mbs, (x0 + lc, 0.0), share * m_if, share * j_if, com=(0.0, -0.5 * e))
        last_if_node = nif
        if_lower = _pos_marker(mbs, bif, (0.0, 0.0))
        if_upper = _pos_marker(mbs, bif, (0.0, -e))
        if_rot = _rot_marker(mbs, nif)
        p_rot = _rot_marker(mbs, npb)
        a1_rot = _rot_marker(mbs, nodes_a[0])
        a3_rot = _rot_marker(mbs, nodes_a[2])
        # lower revolute joints + torsion springs (passive layer)
        mpl = _pos_marker(mbs, bp, (-0.5 * lc, 0.0))
        mpr = _pos_marker(mbs, bp, (0.5 * lc, 0.0))
        _hinge_with_spring(mbs, (prev_lower, mpl), (prev_rot, p_rot), k_p, beta)
        _hinge_with_spring(mbs, (mpr, if_lower), (p_rot, if_rot), k_p, beta)
        # upper revolute joints + torsion springs (active layer)
        ma1 = _pos_marker(mbs, bodies_a[0], (-0.5 * la, 0.0))
        ma3 = _pos_marker(mbs, bodies_a[2], (0.5 * la, 0.0))
        _hinge_with_spring(mbs, (prev_upper, ma1), (prev_rot, a1_rot), k_a, beta)
        _hinge_with_spring(mbs, (ma3, if_upper), (a3_rot, if_rot), k_a, beta)
        # prismatic joints A1-A2 (motor) and A2-A3 (spring k1)
        for left, right in ((0, 1), (1, 2)):
            mr0 = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=bodies_a[left], localPosition=[0.5 * la, 0.0, 0.0]))
            mr1 = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=bodies_a[right], localPosition=[-0.5 * la, 0.0, 0.0]))
            mbs.AddObject(ii.ObjectJointPrismatic2D(markerNumbers=[mr0, mr1], axisMarker0=[1.0, 0.0, 0.0],
                                                    normalMarker1=[0.0, 1.0, 0.0], constrainRotation=True,
                                                    visualization=_NOVIS))
        m_motor = mbs.AddMarker(ii.MarkerBodiesRelativeTranslationCoordinate(
            bodyNumbers=[bodies_a[0], bodies_a[1]], localPosition0=[0.5 * la, 0.0, 0.0],
            localPosition1=[-0.5 * la, 0.0, 0.0], axis0=[1.0, 0.0, 0.0]))
        m_spring = mbs.AddMarker(ii.MarkerBodiesRelativeTranslationCoordinate(
            bodyNumbers=[bodies_a[1], bodies_a[2]], localPosition0=[0.5 * la, 0.0, 0.0],
            localPosition1=[-0.5 * la, 0.0, 0.0], axis0=[1.0, 0.0, 0.0]))
        if stroke_path == "user_function":
            motor = mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[gcoord, m_motor],
                                                               offsetUserFunction=motor_uf_factory(lc),
                                                               visualization=_NOVIS))
        else:
            motor = mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[gcoord, m_motor], offset=0.0,
                                                               visualization=_NOVIS))
            model.offset_items.append(motor)
            model.offset_factors.append(lc)
        mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(markerNumbers=[gcoord, m_spring], stiffness=k1,
                                                              damping=beta * k1, visualization=_NOVIS))
        prev_lower, prev_upper, prev_rot = if_lower, if_upper, if_rot
    model._tip_marker = prev_lower
    model._tip_node = last_if_node
    model._cell_nodes = passive_nodes
    model.tip_local_x = 0.0
    model.tip_rotation_per_strain = 0.0
    return model


def _build_rigid(SC, mbs, act, stroke_path) -> BuiltModel:
    n, lc = act.n_cells, act.cell_length
    beta = act.stiffness_damping_factor
    m, com_offset, j_com = act.laminate.rigid_cell(lc)
    y_com = -com_offset  # active layer at y = -e
    k_in, k_end = act.joint_stiffness_inside, act.joint_stiffness_end
    rot_per_strain = act.curvature_per_strain * lc  # free rotation of one cell per unit strain

    ground, gcoord = _add_ground(mbs)
    model = BuiltModel(SC=SC, mbs=mbs, cell="rigid", n_cells=n, cell_length=lc)

    def spring_uf_factory(factor):
        def uf(mbs_, t, itemNumber, displacement, velocity, stiffness, damping, offset):
            return stiffness * (displacement - factor * model.uf_strain(t)) + damping * velocity
        return uf

    prev_pos = _pos_marker(mbs, ground, (0.0, 0.0))
    prev_rot = gcoord
    nodes = []
    for j in range(n):
        # node (reference point) at the cell's end joint: the tip load then acts at a node
        # and its generalized force does not depend on the body's rotation
        nd, bd = _rigid2d(mbs, ((j + 1.0) * lc, 0.0), m, j_com, com=(-0.5 * lc, y_com))
        nodes.append(nd)
        ml = _pos_marker(mbs, bd, (-lc, 0.0))
        mr = _pos_marker(mbs, bd, (0.0, 0.0))
        rot = _rot_marker(mbs, nd)
        mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[prev_pos, ml], visualization=_NOVIS))
        k = k_end if j == 0 else k_in
        factor = 0.5 * rot_per_strain if j == 0 else rot_per_strain
        if stroke_path == "user_function":
            mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[prev_rot, rot], stiffness=k, damping=beta * k,
                springForceUserFunction=spring_uf_factory(factor), visualization=_NOVIS))
        else:
            spring = mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[prev_rot, rot], stiffness=k, damping=beta * k, offset=0.0, visualization=_NOVIS))
            if stroke_path == "offsets":
                model.offset_items.append(spring)
                model.offset_factors.append(factor)
        prev_pos, prev_rot = mr, rot
    if stroke_path == "prestep":
        # Every joint's rest angle times its stiffness is the same moment, EI kappa (clamp:
        # 2EI/L_c * theta_c/2, inside: EI/L_c * theta_c).  The spring moment k (dphi - theta0)
        # splits into k dphi plus the pair +k theta0 / -k theta0 on the two bodies; the pairs
        # cancel on every body but the last.  So rest angles following the stroke are exactly
        # one torque EI kappa(strain) = a_eff e strain on the last body: one call per step
        # instead of one per joint.  Tested against the rest-angle paths.
        m_last = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=bd, localPosition=[0.0, 0.0, 0.0]))
        model.torque_load = mbs.AddLoad(ii.LoadTorqueVector(markerNumber=m_last, loadVector=[0.0, 0.0, 0.0]))
        model.torque_per_strain = act.bending_stiffness * act.curvature_per_strain
    model._tip_marker = prev_pos
    model._tip_node = nodes[-1]
    model._cell_nodes = nodes
    model.tip_local_x = 0.0
    model.tip_rotation_per_strain = 0.5 * rot_per_strain
    return model


def _finish_indices(model: BuiltModel) -> None:
    # ODE2 indices are known once nodes exist (nodes are numbered in creation order)
    mbs = model.mbs
    tip = mbs.GetNodeODE2Index(model._tip_node)
    model.tip_indices = np.array([tip, tip + 1, tip + 2])
    model.cell_angle_indices = np.array([mbs.GetNodeODE2Index(nd) + 2 for nd in model._cell_nodes])


# ---------------------------------------------------------------------------- settings

def apply_user_settings(settings, user: Any) -> None:
    """Apply a user's adjustment: a callable receiving the settings, or a dict of dotted names."""
    if user is None:
        return
    if callable(user):
        user(settings)
        return
    if not isinstance(user, dict):
        raise ValueError(
            f"settings must be None, a callable receiving exudyn.SimulationSettings, or a dict of "
            f"dotted names such as {{'timeIntegration.newton.maxIterations': 10}}; got {user!r}")
    for key, value in user.items():
        if not isinstance(key, str) or not key:
            raise ValueError(f"settings keys must be dotted attribute names, got {key!r}")
        obj = settings
        parts = key.split(".")
        for part in parts[:-1]:
            if not hasattr(obj, part):
                raise ValueError(f"settings has no attribute {part!r} (in {key!r})")
            obj = getattr(obj, part)
        if not hasattr(obj, parts[-1]):
            raise ValueError(f"settings has no attribute {parts[-1]!r} (in {key!r})")
        try:
            setattr(obj, parts[-1], value)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"settings[{key!r}] = {value!r} was refused by Exudyn: {exc}") from exc


def base_settings():
    """Settings shared by the static and the dynamic solve (SI units, sparse, quiet)."""
    s = exu.SimulationSettings()
    s.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    s.solution.file.write = False
    s.solution.file.writeInitialValues = False
    s.solution.sensors.writePeriod = 1e30
    s.show.computationTime = False
    s.show.statistics = False
    s.timeIntegration.verboseMode = 0
    s.staticSolver.verboseMode = 0
    s.timeIntegration.newton.absoluteTolerance = NEWTON_ABSOLUTE_TOLERANCE
    s.staticSolver.newton.absoluteTolerance = NEWTON_ABSOLUTE_TOLERANCE
    s.parallel.numberOfThreads = 1
    return s


def dynamic_settings(t_end: float, step: float):
    s = base_settings()
    ti = s.timeIntegration
    ti.endTime = t_end
    ti.numberOfSteps = max(1, int(math.ceil(t_end / step - 1e-9)))
    ti.minimumStepSize = step * 1e-4
    ti.adaptiveStep = True
    ti.generalizedAlpha.spectralRadius = 0.8
    ti.newton.useModifiedNewton = True
    # measured on REF-A chains driven by the stroke: Exudyn's Jacobian misses the derivative
    # of the (large, ~100 N) internal constraint forces, so a stale Jacobian contracts only
    # ~0.5 per iteration; renewing it below contraction 0.2 and skipping the analytic
    # connector derivative cut the cost per step by ~35 % (results unchanged to 1e-10 m)
    ti.newton.modifiedNewtonContractivity = 0.2
    ti.newton.numericalDifferentiation.jacobianConnectorDerivative = False
    return s


def static_settings(load_steps: int):
    s = base_settings()
    st = s.staticSolver
    st.numberOfLoadSteps = load_steps
    st.loadStepDuration = 1.0
    st.loadStepGeometric = False
    st.adaptiveStep = True
    st.minimumStepSize = 1e-3
    st.newton.maxIterations = 25
    st.newton.useModifiedNewton = False
    st.newton.numericalDifferentiation.jacobianConnectorDerivative = False
    st.useLoadFactor = True
    return s


# ---------------------------------------------------------------------------- solves

class ExudynFailure(RuntimeError):
    """Exudyn's solver stopped; carries the time / load factor reached."""

    def __init__(self, message: str, time: float):
        super().__init__(message)
        self.time = time


def _quiet():
    exu.config.printToConsole = False


def _loud():
    exu.config.printToConsole = True


def _apply_tolerance_floor(model: BuiltModel, newton) -> None:
    if newton.absoluteTolerance < model.newton_tolerance_floor:
        newton.absoluteTolerance = model.newton_tolerance_floor


def run_static(model: BuiltModel, settings, strain_at_factor: Callable[[float], float]) -> None:
    """Solve statically; the strain follows the load factor ``f`` in [0, 1] via ``strain_at_factor``."""
    mbs = model.mbs

    def pre(mbs_, t):
        model.set_strain(strain_at_factor(min(max(t, 0.0), 1.0)))
        return True

    _apply_tolerance_floor(model, settings.staticSolver.newton)
    if model.static_relative_tolerance is not None:
        settings.staticSolver.newton.relativeTolerance = model.static_relative_tolerance
    mbs.SetPreStepUserFunction(pre)
    model.set_strain(strain_at_factor(0.0))
    saved_uf = model.uf_strain
    model.uf_strain = lambda t: strain_at_factor(min(max(t, 0.0), 1.0))
    solver = exu.MainSolverStatic()
    _quiet()
    try:
        ok = solver.SolveSystem(mbs, settings)
    except Exception as exc:  # noqa: BLE001 - any Exudyn failure is reported with context
        t = _solver_time(solver)
        raise ExudynFailure(f"{type(exc).__name__}: {exc}", t) from exc
    finally:
        _loud()
        mbs.SetPreStepUserFunction(0)
        model.uf_strain = saved_uf
    if not ok:
        raise ExudynFailure("static Newton iteration did not converge", _solver_time(solver))
    # the static solver ends at load factor 1: make sure the final strain is exact
    model.set_strain(strain_at_factor(1.0))


def _solver_time(solver) -> float:
    try:
        return float(solver.it.currentTime)
    except Exception:  # noqa: BLE001
        return float("nan")


def set_current_as_initial(model: BuiltModel, zero_velocity: bool = False) -> None:
    mbs = model.mbs
    state = mbs.systemData.GetSystemState()
    mbs.systemData.SetSystemState(systemStateList=state, configuration=exu.ConfigurationType.Initial)
    if zero_velocity:
        n = len(mbs.systemData.GetODE2Coordinates_t())
        zeros = np.zeros(n)
        mbs.systemData.SetODE2Coordinates_t(zeros, configuration=exu.ConfigurationType.Initial)
        mbs.systemData.SetODE2Coordinates_tt(zeros, configuration=exu.ConfigurationType.Initial)


def reset_to_reference(model: BuiltModel) -> None:
    """Put the undeformed state back as initial and current state."""
    mbs = model.mbs
    sd = mbs.systemData
    n = len(sd.GetODE2Coordinates())
    zeros = np.zeros(n)
    for cfg in (exu.ConfigurationType.Initial, exu.ConfigurationType.Current):
        sd.SetODE2Coordinates(zeros, configuration=cfg)
        sd.SetODE2Coordinates_t(zeros, configuration=cfg)
        sd.SetODE2Coordinates_tt(zeros, configuration=cfg)


def run_relaxation(model: BuiltModel, strain: float, omega1: float, damping_factor: float,
                   periods_ramp: float = 2.0, periods_total: float = 10.0,
                   steps_per_period: int = 60) -> float:
    """Static equilibrium by dynamic relaxation (fallback when the static Newton iteration fails).

    Exudyn's static solver leaves out the constraint forces' derivative in its Jacobian
    (measured: linear convergence whose rate tends to 1 under large tip forces).  The
    implicit dynamic solver adds ``M/(beta h²)`` to the Jacobian, which keeps it contractive.
    Strain and loads (``model.scale_loads``) are ramped smoothly over ``periods_ramp`` periods of the first mode,
    with every spring damped at ``damping_factor * k`` (critical damping of the first mode for
    ``2/omega1``), then held until ``periods_total``.  Returns the largest coordinate change
    over the last period (a measure of the remaining motion).
    """
    mbs = model.mbs
    period = 2.0 * math.pi / omega1
    t_ramp = periods_ramp * period
    t_end = periods_total * period
    h = period / steps_per_period
    tail = {"q": None, "t_mark": t_end - period, "change": 0.0}

    def ramp(t):
        x = min(max(t / t_ramp, 0.0), 1.0)
        return x * x * (3.0 - 2.0 * x)

    def pre(mbs_, t):
        f = ramp(t)
        model.set_strain(f * strain)
        model.scale_loads(f)
        return True

    def post(mbs_, t):
        if t >= tail["t_mark"]:
            q = np.array(mbs_.systemData.GetODE2Coordinates(copy=False))
            if tail["q"] is None:
                tail["q"] = q
            else:
                tail["change"] = max(tail["change"], float(np.max(np.abs(q - tail["q"]))))
        return True

    saved = [(item, name, mbs.GetObjectParameter(item, name)) for item, _, name in model.springs]
    for item, k, name in model.springs:
        mbs.SetObjectParameter(item, name, damping_factor * k)
    settings = dynamic_settings(t_end, h)
    _apply_tolerance_floor(model, settings.timeIntegration.newton)
    settings.timeIntegration.newton.useModifiedNewton = False
    settings.timeIntegration.newton.maxIterations = 25
    mbs.SetPreStepUserFunction(pre)
    mbs.SetPostStepUserFunction(post)
    solver = exu.MainSolverImplicitSecondOrder()
    saved_uf = model.uf_strain
    model.uf_strain = lambda t: ramp(t) * strain
    _quiet()
    try:
        ok = solver.SolveSystem(mbs, settings)
    except Exception as exc:  # noqa: BLE001
        raise ExudynFailure(f"{type(exc).__name__}: {exc}", _solver_time(solver) / t_end) from exc
    finally:
        _loud()
        mbs.SetPreStepUserFunction(0)
        mbs.SetPostStepUserFunction(0)
        model.uf_strain = saved_uf
        for item, name, d in saved:
            mbs.SetObjectParameter(item, name, d)
        model.scale_loads(1.0)
    if not ok:
        raise ExudynFailure("dynamic relaxation did not converge", _solver_time(solver) / t_end)
    model.set_strain(strain)
    return tail["change"]


def run_dynamic(model: BuiltModel, settings, pre_step: Callable[[float], None] | None,
                post_step: Callable[[float], None]) -> dict:
    """Integrate in time; ``pre_step(t)`` before each attempted step, ``post_step(t)`` after each accepted one.

    A hook returning ``False`` stops the integration cleanly (Exudyn ends the run).

    Returns solver statistics.
    """
    mbs = model.mbs
    counts = {"attempts": 0}

    if pre_step is not None:
        def pre(mbs_, t):
            counts["attempts"] += 1
            return pre_step(t) is not False  # False: stop the run (e.g. Ctrl-C caught in the hook)
    else:
        def pre(mbs_, t):
            counts["attempts"] += 1
            return True

    def post(mbs_, t):
        return post_step(t) is not False

    _apply_tolerance_floor(model, settings.timeIntegration.newton)
    mbs.SetPreStepUserFunction(pre)
    mbs.SetPostStepUserFunction(post)
    solver = exu.MainSolverImplicitSecondOrder()
    _quiet()
    try:
        ok = solver.SolveSystem(mbs, settings)
    except Exception as exc:  # noqa: BLE001
        raise ExudynFailure(f"{type(exc).__name__}: {exc}", _solver_time(solver)) from exc
    finally:
        _loud()
        mbs.SetPreStepUserFunction(0)
        mbs.SetPostStepUserFunction(0)
    if not ok:
        raise ExudynFailure("Newton iteration did not converge even at the minimum step size",
                            _solver_time(solver))
    it = solver.it
    return {
        "pre_step_calls": counts["attempts"],
        "newton_steps": int(it.newtonStepsCount),
        "rejected_steps": int(getattr(it, "rejectedModifiedNewtonSteps", 0)),
        "discontinuous_iterations": int(it.discontinuousIterationsCount),
    }


def eigenfrequencies(model: BuiltModel, n: int) -> np.ndarray:
    """Lowest ``n`` undamped eigenfrequencies [Hz] about the model's current (equilibrium) state.

    Includes the constraint forces' geometric stiffness, which Exudyn's
    ``ComputeODE2Eigenvalues`` leaves out (see :mod:`exudyn_atcm._eigen`).
    """
    return constrained_eigenfrequencies(model.mbs, n)


def exudyn_version() -> str:
    return str(exu.__version__)
