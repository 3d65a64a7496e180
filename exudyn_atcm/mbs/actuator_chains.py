"""Builds the Exudyn multibody system of a :class:`~exudyn_atcm.mechanism.actuator.BendingActuator`.

:func:`build` adds the chain of cells, the clamp and the tip load to a new ``MainSystem`` and
returns its :class:`~exudyn_atcm.mbs.actuator_model.BuiltModel`.  This module builds the
``"six-bar"`` and ``"rigid"`` cells and dispatches the others (:mod:`~exudyn_atcm.mbs.actuator_beam`,
:mod:`~exudyn_atcm.mbs.actuator_ancf`, :mod:`~exudyn_atcm.mbs.actuator_ritz` (no tip load), and
:mod:`~exudyn_atcm.mbs.actuator_tree` for the rigid chain in minimal coordinates); the solver
runs are in :mod:`~exudyn_atcm.mbs.solver_runs`.  It holds no physics constants of its own (those
come from the actuator) and no file formats.

Model layout (planar, SI units; see :mod:`exudyn_atcm.mechanism.actuator` for the coordinates):

``"six-bar"`` cell j (``x_j = j L_c``), the paper's six-bar cell:
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
    :func:`build_rigid`: the rest-angle moments cancel pairwise on every other body).
``"offsets"``
    As ``"prestep"``, but the rigid cell's rest angles are written into every torsion
    spring's ``offset`` (one call per joint and step).
``"user_function"``
    Offset user functions (six-bar) / spring-force user functions with the rest angle
    (rigid) that call the strain source at their ``t``.

These are the same computation: every hook and user function of one solver step receives
the same ``t`` (the end time of the step being attempted, measured with Exudyn 1.13), and the strain
source evaluates from memory that changes only in the post-step hook, i.e. after the step.
So the offset a user function would return at each Newton iteration is exactly the value the
pre-step hook wrote for that step; the test suite checks the paths against each other.
"""

from __future__ import annotations

import exudyn as exu
import numpy as np
from exudyn import itemInterface as ii

from ..cells import AncfCell, BeamCell, RigidCell, RitzCell, SixBarCell
from .actuator_ancf import build_ancf
from .actuator_beam import build_beam
from .actuator_items import NOVIS, add_ground, hinge_with_spring, body_position_marker, rigid_body_2d, rotation_marker
from .actuator_model import BuiltModel
from .actuator_ritz import build_ritz
from .actuator_tree import build_tree
from .cells import add_actuator_cells
from .mass_damping import add_mass_damper, ground_position_marker

#: How ``cell="rigid"`` is built with the default stroke path: ``"tree"`` (minimal coordinates,
#: one ``ObjectKinematicTree``) or ``"bodies"`` (rigid bodies, revolute joints, springs).
RIGID_FORMULATION = "bodies"


def _zero(t: float) -> float:
    return 0.0


def build(actuator, tip_force=(0.0, 0.0), stroke_path: str = "prestep") -> BuiltModel:
    """Build the Exudyn system of ``actuator`` with a dead tip load ``tip_force`` [N].

    With ``stroke_path="user_function"`` the user functions call ``model.uf_strain(t)``,
    which the caller sets (static solve: strain at load factor ``t``; dynamics: the strain source).
    """
    if stroke_path not in ("prestep", "user_function", "offsets"):
        raise ValueError(f"stroke_path must be 'prestep', 'offsets' or 'user_function', got {stroke_path!r}")
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    model = add_actuator_cells(actuator.cell, SC, mbs, actuator, stroke_path, tip_force)
    model.uf_strain = _zero
    if actuator.cell.carries_tip_load:  # a model without a tip point to load refuses tip loads itself
        fx, fy = float(tip_force[0]), float(tip_force[1])
        model.tip_load = mbs.AddLoad(ii.LoadForceVector(markerNumber=model._tip_marker,
                                                        loadVector=[fx, fy, 0.0], bodyFixed=False))
        model.tip_force = (fx, fy)
    for i in range(mbs.systemData.NumberOfObjects()):
        if mbs.GetObject(i)["objectType"] == "ConnectorCoordinateSpringDamper":
            model.springs.append((i, float(mbs.GetObjectParameter(i, "stiffness")), "damping"))
    mbs.Assemble()
    tolerances = actuator.cell.static_tolerances
    if tolerances is not None and model.static_absolute_tolerance is None:
        model.static_absolute_tolerance, model.static_relative_tolerance = tolerances
    if hasattr(model, "finish_indices"):
        model.finish_indices()
        return model
    _finish_indices(model)
    ref = mbs.systemData.GetODE2Coordinates(configuration=exu.ConfigurationType.Reference)
    model.tip_reference = tuple(float(v) for v in np.asarray(ref)[model.tip_indices])
    return model


def _mass_damping(mbs, act, ground, gcoord):
    """``damp(node, body, mass, inertia, com)``: the mass dampers of ``act.mass_damping_factor`` on a
    rigid body (nothing for ``alpha = 0``); see :mod:`exudyn_atcm.mbs.mass_damping`."""
    alpha = act.mass_damping_factor
    if alpha == 0.0:
        return lambda node, body, mass, inertia, com=(0.0, 0.0): None
    gpos = ground_position_marker(mbs, ground)

    def damp(node, body, mass, inertia, com=(0.0, 0.0)):
        add_mass_damper(mbs, body_item=body, rotation_marker=rotation_marker(mbs, node), ground_position=gpos,
                        ground_rotation=gcoord, alpha=alpha, mass=mass, inertia=inertia, center=com)
    return damp


def build_six_bar(SC, mbs, act, stroke_path) -> BuiltModel:
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

    ground, gcoord = add_ground(mbs)
    damp = _mass_damping(mbs, act, ground, gcoord)
    model = BuiltModel(SC=SC, mbs=mbs, cell="six-bar", n_cells=n, cell_length=lc)

    def motor_uf_factory(factor):
        return lambda mbs_, t, itemNumber, lOffset: factor * model.uf_strain(t)

    # previous interface: markers (lower, upper) and rotation-coordinate marker
    prev_lower = body_position_marker(mbs, ground, (0.0, 0.0))
    prev_upper = body_position_marker(mbs, ground, (0.0, -e))
    prev_rot = gcoord
    passive_nodes = []
    last_if_node = None
    for j in range(n):
        x0 = j * lc
        # passive bar
        mp = m1_cell * keep
        npb, bp = rigid_body_2d(mbs, (x0 + 0.5 * lc, 0.0), mp, mp * (lc**2 + h1**2) / 12.0)
        damp(npb, bp, mp, mp * (lc**2 + h1**2) / 12.0)
        passive_nodes.append(npb)
        # active bodies A1, A2, A3
        ma = m2_cell * keep / 3.0
        la = lc / 3.0
        ja = ma * (la**2 + h2**2) / 12.0
        nodes_a = []
        bodies_a = []
        for k in range(3):
            nd, bd = rigid_body_2d(mbs, (x0 + (k + 0.5) * la, -e), ma, ja)
            damp(nd, bd, ma, ja)
            nodes_a.append(nd)
            bodies_a.append(bd)
        # next interface element (reference point on the passive layer)
        # interface j+1 takes half its lumped mass from cell j and half from cell j+1
        share = 1.0 if j < n - 1 else 0.5
        nif, bif = rigid_body_2d(mbs, (x0 + lc, 0.0), share * m_if, share * j_if, com=(0.0, -0.5 * e))
        damp(nif, bif, share * m_if, share * j_if, (0.0, -0.5 * e))
        last_if_node = nif
        if_lower = body_position_marker(mbs, bif, (0.0, 0.0))
        if_upper = body_position_marker(mbs, bif, (0.0, -e))
        if_rot = rotation_marker(mbs, nif)
        p_rot = rotation_marker(mbs, npb)
        a1_rot = rotation_marker(mbs, nodes_a[0])
        a3_rot = rotation_marker(mbs, nodes_a[2])
        # lower revolute joints + torsion springs (passive layer)
        mpl = body_position_marker(mbs, bp, (-0.5 * lc, 0.0))
        mpr = body_position_marker(mbs, bp, (0.5 * lc, 0.0))
        hinge_with_spring(mbs, (prev_lower, mpl), (prev_rot, p_rot), k_p, beta)
        hinge_with_spring(mbs, (mpr, if_lower), (p_rot, if_rot), k_p, beta)
        # upper revolute joints + torsion springs (active layer)
        ma1 = body_position_marker(mbs, bodies_a[0], (-0.5 * la, 0.0))
        ma3 = body_position_marker(mbs, bodies_a[2], (0.5 * la, 0.0))
        hinge_with_spring(mbs, (prev_upper, ma1), (prev_rot, a1_rot), k_a, beta)
        hinge_with_spring(mbs, (ma3, if_upper), (a3_rot, if_rot), k_a, beta)
        # prismatic joints A1-A2 (motor) and A2-A3 (spring k1)
        for left, right in ((0, 1), (1, 2)):
            mr0 = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=bodies_a[left], localPosition=[0.5 * la, 0.0, 0.0]))
            mr1 = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=bodies_a[right], localPosition=[-0.5 * la, 0.0, 0.0]))
            mbs.AddObject(ii.ObjectJointPrismatic2D(markerNumbers=[mr0, mr1], axisMarker0=[1.0, 0.0, 0.0],
                                                    normalMarker1=[0.0, 1.0, 0.0], constrainRotation=True,
                                                    visualization=NOVIS))
        m_motor = mbs.AddMarker(ii.MarkerBodiesRelativeTranslationCoordinate(
            bodyNumbers=[bodies_a[0], bodies_a[1]], localPosition0=[0.5 * la, 0.0, 0.0],
            localPosition1=[-0.5 * la, 0.0, 0.0], axis0=[1.0, 0.0, 0.0]))
        m_spring = mbs.AddMarker(ii.MarkerBodiesRelativeTranslationCoordinate(
            bodyNumbers=[bodies_a[1], bodies_a[2]], localPosition0=[0.5 * la, 0.0, 0.0],
            localPosition1=[-0.5 * la, 0.0, 0.0], axis0=[1.0, 0.0, 0.0]))
        if stroke_path == "user_function":
            motor = mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[gcoord, m_motor],
                                                               offsetUserFunction=motor_uf_factory(lc),
                                                               visualization=NOVIS))
        else:
            motor = mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[gcoord, m_motor], offset=0.0,
                                                               visualization=NOVIS))
            model.offset_items.append(motor)
            model.offset_factors.append(lc)
        mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(markerNumbers=[gcoord, m_spring], stiffness=k1,
                                                              damping=beta * k1, visualization=NOVIS))
        prev_lower, prev_upper, prev_rot = if_lower, if_upper, if_rot
    model._tip_marker = prev_lower
    model._tip_node = last_if_node
    model._cell_nodes = passive_nodes
    model.tip_local_x = 0.0
    model.tip_rotation_per_strain = 0.0
    return model


def build_rigid(SC, mbs, act, stroke_path) -> BuiltModel:
    n, lc = act.n_cells, act.cell_length
    beta = act.stiffness_damping_factor
    m, com_offset, j_com = act.laminate.rigid_cell(lc)
    y_com = -com_offset  # active layer at y = -e
    k_in, k_end = act.joint_stiffness_inside, act.joint_stiffness_end
    rot_per_strain = act.curvature_per_strain * lc  # free rotation of one cell per unit strain

    ground, gcoord = add_ground(mbs)
    damp = _mass_damping(mbs, act, ground, gcoord)
    model = BuiltModel(SC=SC, mbs=mbs, cell="rigid", n_cells=n, cell_length=lc)

    def spring_uf_factory(factor):
        def uf(mbs_, t, itemNumber, displacement, velocity, stiffness, damping, offset):
            return stiffness * (displacement - factor * model.uf_strain(t)) + damping * velocity
        return uf

    prev_pos = body_position_marker(mbs, ground, (0.0, 0.0))
    prev_rot = gcoord
    nodes = []
    for j in range(n):
        # node (reference point) at the cell's end joint: the tip load then acts at a node
        # and its generalized force does not depend on the body's rotation
        nd, bd = rigid_body_2d(mbs, ((j + 1.0) * lc, 0.0), m, j_com, com=(-0.5 * lc, y_com))
        damp(nd, bd, m, j_com, (-0.5 * lc, y_com))
        nodes.append(nd)
        ml = body_position_marker(mbs, bd, (-lc, 0.0))
        mr = body_position_marker(mbs, bd, (0.0, 0.0))
        rot = rotation_marker(mbs, nd)
        mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[prev_pos, ml], visualization=NOVIS))
        k = k_end if j == 0 else k_in
        factor = 0.5 * rot_per_strain if j == 0 else rot_per_strain
        if stroke_path == "user_function":
            mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[prev_rot, rot], stiffness=k, damping=beta * k,
                springForceUserFunction=spring_uf_factory(factor), visualization=NOVIS))
        else:
            spring = mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[prev_rot, rot], stiffness=k, damping=beta * k, offset=0.0, visualization=NOVIS))
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


# ------------------------------------------------------------------------------ cell kinds
@add_actuator_cells.register
def _six_bar(cell: SixBarCell, SC, mbs, actuator, stroke_path, tip_force) -> BuiltModel:
    return build_six_bar(SC, mbs, actuator, stroke_path)


@add_actuator_cells.register
def _rigid(cell: RigidCell, SC, mbs, actuator, stroke_path, tip_force) -> BuiltModel:
    if RIGID_FORMULATION == "tree" and stroke_path == "prestep" and actuator.mass_damping_factor == 0.0:
        # the minimal-coordinate tree has no bodies to hang the mass dampers on: with alpha > 0
        # the rigid chain is built from bodies (the same model in other coordinates)
        return build_tree(SC, mbs, actuator, stroke_path)
    return build_rigid(SC, mbs, actuator, stroke_path)


@add_actuator_cells.register
def _beam(cell: BeamCell, SC, mbs, actuator, stroke_path, tip_force) -> BuiltModel:
    return build_beam(SC, mbs, actuator, stroke_path)


@add_actuator_cells.register
def _ancf(cell: AncfCell, SC, mbs, actuator, stroke_path, tip_force) -> BuiltModel:
    return build_ancf(SC, mbs, actuator, stroke_path)


@add_actuator_cells.register
def _ritz(cell: RitzCell, SC, mbs, actuator, stroke_path, tip_force) -> BuiltModel:
    return build_ritz(SC, mbs, actuator, stroke_path, tip_force)
