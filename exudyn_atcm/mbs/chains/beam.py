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

from ..exudyn_items import ii
import numpy as np

from ...cells import BeamCell
from ...mechanism.bender import Bender
from ..items import NOVIS
from ..model import Body
from ..node_chain import NodeEnds, beam_node_key, node_positions, register_element_chain
from ..realisation import register_realisation

__all__ = ["BeamChain", "add_beam_chain"]

_BEAM_COLOR = [0.2, 0.45, 0.8, 1.0]


def add_beam_chain(ctx, bender: Bender) -> list[str]:
    """Add the nodes and beam elements of ``bender`` through the build context ``ctx``; returns the node keys
    (base first).

    The nodes are registered as bodies (``node_only``); the actuation torques per node and drive are
    given by :func:`~exudyn_atcm.mbs.node_chain.actuation_torques`.
    """
    mbs = ctx.mbs
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
        ctx.register_body(Body(key, node, -1, np.array([pos[0], pos[1], bender.angle], dtype=float),
                               node_only=True))
        keys.append(key)
    items = []
    for j, lc in enumerate(lengths):
        a, b = ctx.body(keys[j]), ctx.body(keys[j + 1])
        item = mbs.AddObject(ii.ObjectBeamGeometricallyExact2D(
            nodeNumbers=[a.node, b.node], length=float(lc), massPerLength=mu, crossSectionInertia=rho_i,
            bendingStiffness=ei, axialStiffness=ea, shearStiffness=ea,
            bendingDamping=beta * ei, axialDamping=beta * ea, shearDamping=beta * ea,
            referenceCurvature=0.0,
            visualization={'show': True, 'drawHeight': float(thick), 'color': _BEAM_COLOR}))
        ctx.add_spring(item, ei, "bendingDamping")
        items.append(item)
    for i, key in enumerate(keys):  # a node's "body": the element ending there (the first for the base)
        ctx.body(key).item = items[max(i - 1, 0)]
    register_element_chain(ctx, bender, keys, items)
    return keys


@register_realisation(BeamCell)
class BeamChain(NodeEnds):
    """Geometrically exact beam elements between nodes; the end nodes join the mechanism."""

    def add_cells(self, ctx) -> None:
        add_beam_chain(ctx, self.bender)
