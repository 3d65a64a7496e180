"""Small Exudyn item helpers of the builder and the cells' realisations (bodies, markers, hidden items)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from .exudyn_items import ii

from .model import Body

#: Visualisation settings of items that are not drawn.
NOVIS = {'show': False, 'drawSize': -1., 'color': [-1., -1., -1., -1.]}


def body_position_marker(mbs, body: int, local) -> int:
    """A ``MarkerBodyPosition`` at ``local`` [m] in the frame of the body with item number ``body``."""
    return mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=body, localPosition=[float(local[0]), float(local[1]), 0.0]))


def _at_node(body: Body, local) -> bool:
    """True for a beam node (markers at the node itself; refuses a point elsewhere)."""
    if not body.node_only:
        return False
    # points joined to a node coincide with it to the assembly check's 1e-9 of the mechanism size
    if math.hypot(float(local[0]), float(local[1])) > 1e-6 * (1.0 + math.hypot(*body.reference[:2])):
        raise ValueError(f"internal: a marker at {tuple(local)} off the beam node {body.key!r}; "
                         "beam nodes carry points only at the node")
    return True


def position_marker(mbs, body: Body, local) -> int:
    """A ``MarkerBodyPosition`` at ``local`` [m] in ``body``'s frame (a ``MarkerNodePosition`` at a beam node)."""
    if _at_node(body, local):
        return mbs.AddMarker(ii.MarkerNodePosition(nodeNumber=body.node))
    return body_position_marker(mbs, body.item, local)


def rigid_marker(mbs, body: Body, local) -> int:
    """A ``MarkerBodyRigid`` at ``local`` [m] in ``body``'s frame (a ``MarkerNodeRigid`` at a beam node)."""
    if _at_node(body, local):
        if body.slope_at is not None:  # an ANCF node has no rotation coordinate: the element's frame there
            return mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=body.item, localPosition=[body.slope_at, 0.0, 0.0]))
        return mbs.AddMarker(ii.MarkerNodeRigid(nodeNumber=body.node))
    return mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=body.item, localPosition=[float(local[0]), float(local[1]), 0.0]))


def rotation_marker(mbs, body: Body, ground_coordinate: int) -> int:
    """The marker of ``body``'s rotation coordinate (created once; the ground's fixed coordinate for the ground)."""
    if body.node is None:
        return ground_coordinate
    if body.rot_marker is None:
        body.rot_marker = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=body.node, coordinate=2))
    return body.rot_marker


def add_body(mbs, key, position, angle, mass, inertia_com, com_local, graphics) -> Body:
    """A 2D rigid body: node at ``position`` [m] with reference ``angle`` [rad], centre of mass at
    ``com_local`` in the body frame, ``inertia_com`` [kg m²] about the centre of mass (Exudyn takes
    the inertia about the node: the parallel-axis term is added here)."""
    inertia = inertia_com + mass * (com_local[0] ** 2 + com_local[1] ** 2)
    node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[float(position[0]), float(position[1]), float(angle)],
                                          visualization=NOVIS))
    item = mbs.AddObject(ii.ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=inertia,
                                              centerOfMass=[float(com_local[0]), float(com_local[1])],
                                              visualization={'show': True, 'graphicsDataUserFunction': 0,
                                                             'graphicsData': graphics}))
    return Body(key, node, item, np.array([position[0], position[1], angle], dtype=float))


def local_point(body: Body, position: Any) -> np.ndarray:
    """The global reference-pose ``position`` [m] in ``body``'s frame."""
    x, y, a = body.reference
    dx, dy = position[0] - x, position[1] - y
    c, s = math.cos(a), math.sin(a)
    return np.array([c * dx + s * dy, -s * dx + c * dy])
