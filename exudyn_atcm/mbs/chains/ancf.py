"""The ``"ancf"`` cell in the one builder: a chain of ANCF cable elements (cubic Hermite beam elements).

One ``ObjectANCFCable2D`` element per cell (Bernoulli-Euler beam in absolute nodal
coordinates: node position and slope vector, cubic interpolation) along the passive layer's
mid-plane, with the laminate's ``EI``, mass per length and axial stiffness ``a1 + a2`` (an axis
that is practically inextensible, as in the other cells) and stiffness-proportional damping
``beta`` times each stiffness.  Cubic elements represent the small-deflection cantilever
exactly under a tip force, so the discretisation error is of higher order than the linear beam
elements' (f1: +0.05 % at 2 elements against +0.70 % at 4 linear ones).  In a strongly bent
state the element's axial constraint locks on coarse meshes (f1 about the state at 1500 V: +4 %
at 2 elements, +0.4 % at 4, 1e-4 at 8).

The nodes are the bender's *bodies* (as a beam bender's, :mod:`exudyn_atcm.mbs.chains.beam`,
with the same keys): their angle is the slope vector's, and orientation markers (torques,
follower forces) sit on the element's frame at the node.  The base is clamped to the ground by
fixing the node's position and the slope's component normal to the bender
(:func:`clamp_slope_node`); the tip is free.  Other end connections are refused by the cell
(:meth:`exudyn_atcm.cells.AncfCell.end_refusal`): joining a slope to a rigid body's rotation is
not modelled.

Actuation: the free curvature enters as the beam chain's end torques ``+-EI kappa`` per
segment (:func:`~exudyn_atcm.mbs.node_chain.actuation_torques`); for a uniform laminate the same
equations as a reference curvature in every element.
"""

from __future__ import annotations

import math

import numpy as np
from ..exudyn_items import ii

from ...cells import AncfCell
from ...mechanism.bender import Bender
from ..node_chain import NodeEnds, beam_node_key, node_positions, register_element_chain
from ..items import NOVIS
from ..model import Body
from ..realisation import register_realisation

__all__ = ["AncfChain", "add_ancf_chain", "clamp_slope_node"]


def add_ancf_chain(ctx, bender: Bender) -> list[str]:
    """Add the nodes and ANCF elements of ``bender`` through the build context ``ctx``; returns the node keys
    (base first)."""
    mbs = ctx.mbs
    lam = bender.laminate
    ei, ea, mu = lam.bending_stiffness, lam.axial_rigidity, lam.mass_per_length
    beta = bender.stiffness_damping_factor
    lengths = bender.cell_lengths
    a = bender.angle
    nodes, keys = [], []
    for i, pos in enumerate(node_positions(bender)):
        nodes.append(mbs.AddNode(ii.NodePoint2DSlope1(
            referenceCoordinates=[float(pos[0]), float(pos[1]), math.cos(a), math.sin(a)], visualization=NOVIS)))
        keys.append(beam_node_key(bender, i))
        ctx.register_body(Body(keys[-1], nodes[-1], -1, np.array([pos[0], pos[1], a], dtype=float),
                               node_only=True))
    items = []
    for j, lc in enumerate(lengths):
        item = mbs.AddObject(ii.ObjectANCFCable2D(
            nodeNumbers=[nodes[j], nodes[j + 1]], length=float(lc), massPerLength=mu, bendingStiffness=ei,
            axialStiffness=ea, bendingDamping=beta * ei, axialDamping=beta * ea, referenceCurvature=0.0,
            useReducedOrderIntegration=True, visualization={'show': False, 'drawHeight': 0.,
                                                            'color': [-1., -1., -1., -1.]}))
        ctx.add_spring(item, ei, "bendingDamping")
        items.append(item)
    for i, key in enumerate(keys):  # orientation at a node: the element ending there (the first for the base)
        body = ctx.body(key)
        body.item = items[max(i - 1, 0)]
        body.slope_at = float(lengths[i - 1]) if i > 0 else 0.0
    # the kind joins mechanisms as a cantilever only (AncfCell.end_refusal): an end welded to its group is
    # the base clamped to the ground
    ctx.body(keys[0]).weld = lambda mbs, body, ground_coordinate, node=ctx.body(keys[0]): \
        clamp_slope_node(mbs, node, ground_coordinate)
    register_element_chain(ctx, bender, keys, items)
    return keys


def clamp_slope_node(mbs, node: Body, ground_coordinate: int) -> None:
    """Clamp an ANCF node to the ground: its position and the slope's component normal to its reference
    direction stay at their reference values (the slope keeps its direction; its length is free)."""
    a = float(node.reference[2])
    if abs(math.sin(a)) < 1e-15 or abs(math.cos(a)) < 1e-15:  # along an axis: fix one slope coordinate
        fixed = (0, 1, 3 if abs(math.sin(a)) < 1e-15 else 2)
        for k in fixed:
            mk = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node.node, coordinate=k))
            mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[ground_coordinate, mk], visualization=NOVIS))
        return
    # three linear equations in the node's coordinates (Exudyn's connector acts on reference plus
    # displacement): position at the base point, slope along the bender; the connector needs two
    # markers: both are the node, the first one weighted by zero
    markers = [mbs.AddMarker(ii.MarkerNodeCoordinates(nodeNumber=node.node)) for _ in range(2)]
    rows = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, -math.sin(a), math.cos(a)]])
    mbs.AddObject(ii.ObjectConnectorCoordinateVector(markerNumbers=markers, scalingMarker0=np.zeros((3, 4)),
                                                     scalingMarker1=rows,
                                                     offset=[float(node.reference[0]), float(node.reference[1]), 0.0],
                                                     visualization=NOVIS))


@register_realisation(AncfCell)
class AncfChain(NodeEnds):
    """ANCF cable elements between nodes; the base clamped by its position and slope, the tip free."""

    def add_cells(self, ctx) -> None:
        add_ancf_chain(ctx, self.bender)
