"""Small Exudyn item helpers of the actuator chains: planar rigid bodies, markers, the clamp and
hinges with torsion springs; and :data:`NOVIS`, the hidden visualisation shared with the
mechanism builders (:mod:`exudyn_atcm.mbs.items`)."""

from __future__ import annotations

from exudyn import itemInterface as ii

#: Visualisation settings of items that are not drawn.
NOVIS = {'show': False, 'drawSize': -1., 'color': [-1., -1., -1., -1.]}


def rigid_body_2d(mbs, position, mass, inertia, com=(0.0, 0.0)):
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


def body_position_marker(mbs, body: int, local) -> int:
    """A ``MarkerBodyPosition`` at ``local`` [m] in the frame of the body with item number ``body``."""
    return mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=body, localPosition=[float(local[0]), float(local[1]), 0.0]))


def rotation_marker(mbs, node):
    """The marker of node ``node``'s rotation coordinate."""
    return mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node, coordinate=2))


def add_ground(mbs):
    """The clamp: a ground object and a fixed coordinate marker for the first joint's spring."""
    ground = mbs.AddObject(ii.ObjectGround(visualization={'show': False, 'graphicsDataUserFunction': 0,
                                                          'graphicsData': []}))
    gnode = mbs.AddNode(ii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0], visualization=NOVIS))
    return ground, mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=gnode, coordinate=0))


def hinge_with_spring(mbs, positions, rotations, stiffness: float, beta: float) -> None:
    """A revolute joint between two position markers and a torsion spring-damper between the
    rotation coordinates of the joined bodies (damping ``beta * stiffness``)."""
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=list(positions), visualization=NOVIS))
    mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(markerNumbers=list(rotations), stiffness=stiffness,
                                                          damping=beta * stiffness, visualization=NOVIS))
