"""The ``"beam"`` cell inside a mechanism: a chain of geometrically exact 2-D beam elements.

One ``ObjectBeamGeometricallyExact2D`` element per cell (Simo-Reissner beam, linear
interpolation of position and rotation between two ``NodeRigidBody2D`` nodes) along the
passive layer's mid-plane, with the laminate's numbers of
:class:`~exudyn_atcm.model.laminate.Laminate` exactly as the lone actuator's beam cell
: bending stiffness ``EI``, axial and shear stiffness
``a1 + a2`` (a practically inextensible, shear-rigid axis: the closed forms are
Euler-Bernoulli's), mass per length, rotary inertia about the passive mid-plane, and
stiffness-proportional damping ``beta`` times each stiffness (the bender's ``beta``: its
laminate's material damping, or ``2 zeta / omega_1`` of the whole bender as a cantilever for a
damping ratio, as for the other cells; a beam bender refuses mass-proportional damping).

The nodes are the bender's *bodies*: node ``i`` (``i = 0 .. N``) sits at the ``i``-th cell
boundary with the bender's direction as reference angle, so a bender end is a real node
with position and rotation.  It joins the rest of the mechanism (see
:mod:`exudyn_atcm.mbs.layout`) as

* the body of its rigid group when the group holds only bender ends (a free end, a pin, two
  ends welded together): the other parts join the node itself;
* welded to the group's body otherwise: clamped by three coordinate constraints when the
  group is the ground (as the lone actuator's clamp), a revolute joint and a rotation
  constraint on a link or an interface body.

Actuation: for a segment ``k`` of uniform laminate the free curvature ``kappa_k(t)`` enters
as two end torques, ``+EI kappa_k`` on its end node and ``-EI kappa_k`` on its start node (the
element's bending moment is ``EI (k - kappa)``; the virtual work of ``EI kappa`` integrates to
``EI kappa (phi_end - phi_start)``, the same equations as a reference curvature ``kappa`` in
every element, which the ``"offsets"`` stroke path writes instead).  The torques of
all segments meeting at a node are summed per drive: one ``LoadTorqueVector`` per segment
boundary, written per step.  A node clamped to the ground gets none (its torque goes into
the clamp).
"""

from __future__ import annotations

import math

import numpy as np
from exudyn import itemInterface as ii

from ..cells import BeamCell
from ..mechanism.bender import Bender
from .cells import add_mechanism_bender
from .items import NOVIS, position_marker, rotation_marker
from .model import Body, MechanismModel

_BEAM_COLOR = [0.2, 0.45, 0.8, 1.0]


def beam_node_key(bender: Bender, i: int) -> str:
    """Body key of node ``i`` (0: base, ``N``: tip) of a beam bender."""
    return f"{bender.name}/node{i}"


def beam_end_key(bender: Bender, end: str) -> str:
    """Body key of the node at ``end`` (``"base"`` or ``"tip"``)."""
    return beam_node_key(bender, 0 if end == "base" else bender.n_cells)


def node_positions(bender: Bender) -> list[np.ndarray]:
    """The reference positions [m] of the cell boundaries of ``bender``, base first; the end nodes
    exactly at the bender's base and tip points."""
    d = bender.direction
    x0 = np.array(bender.base_position, dtype=float)
    s = np.concatenate([[0.0], np.cumsum(bender.cell_lengths)])
    return [x0 + si * d for si in s[:-1]] + [np.array(bender.points["tip"], dtype=float)]


def add_beam_chain(mbs, model: MechanismModel, bender: Bender) -> list[str]:
    """Add the nodes and beam elements of ``bender``; returns the node keys (base first).

    The nodes are registered in ``model.bodies`` (``node_only``); the actuation torques per
    node and drive are given by :func:`actuation_torques`.
    """
    lam = bender.laminate
    ei = lam.bending_stiffness
    ea = lam.axial_rigidity
    mu = lam.mass_per_length
    rho_i = lam.rotary_inertia_per_length
    thick = lam.passive.thickness + (lam.active.thickness if lam.active is not None else 0.0)
    beta = bender.stiffness_damping_factor
    lengths = bender.cell_lengths
    keys = []
    for i, pos in enumerate(node_positions(bender)):
        node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[float(pos[0]), float(pos[1]), bender.angle],
                                              visualization=NOVIS))
        key = beam_node_key(bender, i)
        model.bodies[key] = Body(key, node, -1, np.array([pos[0], pos[1], bender.angle], dtype=float),
                                 node_only=True)
        keys.append(key)
    items = []
    for j, lc in enumerate(lengths):
        a, b = model.bodies[keys[j]], model.bodies[keys[j + 1]]
        item = mbs.AddObject(ii.ObjectBeamGeometricallyExact2D(
            nodeNumbers=[a.node, b.node], length=float(lc), massPerLength=mu, crossSectionInertia=rho_i,
            bendingStiffness=ei, axialStiffness=ea, shearStiffness=ea,
            bendingDamping=beta * ei, axialDamping=beta * ea, shearDamping=beta * ea,
            referenceCurvature=0.0,
            visualization={'show': True, 'drawHeight': float(thick), 'color': _BEAM_COLOR}))
        model.springs.append((item, ei, "bendingDamping"))
        items.append(item)
    for i, key in enumerate(keys):  # a node's "body": the element ending there (the first for the base)
        model.bodies[key].item = items[max(i - 1, 0)]
    register_element_chain(model, bender, keys, items)
    return keys


def register_element_chain(model: MechanismModel, bender: Bender, keys: list[str], items: list[int]) -> None:
    """Register a chain of beam or ANCF elements: its node keys as the bender's cells (a cell's angle is
    the mean of its nodes'), its elements, and the Newton tolerances its stiff axis needs."""
    model.cells[bender.name] = keys
    model.elements[bender.name] = items
    model.beam_benders.add(bender.name)
    # an axial force EA/L_c du resolves positions only to round-off eps L: its residual floor is
    # ~eps (EA/L_c) L; 10x that is the smallest reachable Newton tolerance, and the static solves
    # need the relative tolerance 1e-10 there
    ea = bender.laminate.axial_rigidity
    floor = 10.0 * np.finfo(float).eps * ea / float(np.min(bender.cell_lengths)) * bender.length
    model.newton_tolerance_floor = max(model.newton_tolerance_floor, floor)
    model.static_relative_tolerance = 1e-10


def actuation_torques(model: MechanismModel, bender: Bender, zeros) -> dict[str, np.ndarray]:
    """Torque per unit strain of each source on every node of ``bender`` [N m]: ``+EI kappa`` per
    unit strain on each segment's end node, ``-EI kappa`` on its start node (zero entries left out)."""
    lam = bender.laminate
    per_strain = bender.curvature_sign * lam.bending_stiffness * lam.curvature_per_strain
    out: dict[str, np.ndarray] = {}
    first = 0
    for k, seg in enumerate(bender.segments):
        last = first + seg.n_cells
        if seg.drive is not None:
            src = model.drive_source[bender.drive_name(k)]
            for i, sign in ((first, -1.0), (last, 1.0)):
                key = beam_node_key(bender, i)
                out.setdefault(key, zeros())[src] += sign * per_strain
        first = last
    return {key: v for key, v in out.items() if np.any(v != 0.0)}


def reference_curvatures(model: MechanismModel, bender: Bender, zeros) -> list[tuple[int, np.ndarray]]:
    """``(element, free curvature per unit strain of each source [1/m])`` of every actuated element of a
    beam or ANCF ``bender``: the ``"offsets"`` stroke path writes them as the elements' reference curvature."""
    per_strain = bender.curvature_sign * bender.laminate.curvature_per_strain
    out = []
    for item, k in zip(model.elements[bender.name], bender.cell_segments):
        if bender.segments[int(k)].drive is not None:
            coefficient = zeros()
            coefficient[model.drive_source[bender.drive_name(int(k))]] = per_strain
            out.append((item, coefficient))
    return out


def weld_node(mbs, node: Body, body: Body, ground_coordinate: int) -> None:
    """Weld a beam node to ``body`` at the node: clamp it (ground) or a revolute joint plus a rotation constraint."""
    if body.node is None:
        for k in range(3):
            mk = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node.node, coordinate=k))
            mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[ground_coordinate, mk], visualization=NOVIS))
        return
    x, y, a = body.reference
    dx, dy = node.reference[0] - x, node.reference[1] - y
    c, s = math.cos(a), math.sin(a)
    local = (c * dx + s * dy, -s * dx + c * dy)
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[position_marker(mbs, body, local),
                                                          position_marker(mbs, node, (0.0, 0.0))],
                                           visualization=NOVIS))
    mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[rotation_marker(mbs, body, ground_coordinate),
                                                              rotation_marker(mbs, node, ground_coordinate)],
                                               visualization=NOVIS))


@add_mechanism_bender.register
def _beam(cell: BeamCell, builder, bender: Bender) -> None:
    add_beam_chain(builder.mbs, builder.model, bender)
