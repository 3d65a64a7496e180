"""Chains whose ends are nodes (beam, ANCF, assumed-mode and rod benders: :class:`NodeEnds`): what the builder
and the kinds' realisations share.

The bender's nodes are registered in the model's bodies under :func:`beam_node_key`; an end node
joins the rest of the mechanism welded to its group's body (:func:`weld_node`) or as that body
itself.  Actuation by end torques per node (:func:`actuation_torques`, the ``"prestep"`` stroke
path) or by every element's reference curvature (:func:`reference_curvatures`, ``"offsets"``);
see :mod:`exudyn_atcm.mbs.chains.beam` for why the two are the same equations.
"""

from __future__ import annotations

import math

import numpy as np
from .exudyn_items import ii

from ..mechanism.bender import Bender
from .items import NOVIS, position_marker, rotation_marker
from .model import Body, EndReadout, MechanismModel
from .realisation import CellRealisation

__all__ = ["NodeEnds", "beam_node_key", "beam_end_key", "node_positions", "register_element_chain",
           "actuation_torques", "reference_curvatures", "weld_node"]


class NodeEnds(CellRealisation):
    """Ends that are nodes of the bender (keys :func:`beam_end_key`): welded to the body of their group, or
    that body themselves (a group of bender ends only); a node clamped to the ground gets no actuation torque."""

    ends_are_nodes = True

    def end_body_key(self, end: str) -> str | None:
        return beam_end_key(self.bender, end)

    def connect_end(self, ctx, end: str) -> None:
        key = beam_end_key(self.bender, end)
        node, body = ctx.body(key), ctx.group_body(self.bender, end)
        if body is not node:
            ctx.weld_node(node, body)
        ctx.set_end_readout(self.bender, end, EndReadout("body", body=key))


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


def register_element_chain(ctx, bender: Bender, keys: list[str], items: list[int]) -> None:
    """Register a chain of beam or ANCF elements through the build context ``ctx``: its node keys as the bender's
    cells (a cell's angle is the mean of its nodes'), its elements, and the Newton tolerances its stiff axis needs."""
    ctx.add_element_chain(bender, keys, items)
    # an axial force EA/L_c du resolves positions only to round-off eps L: its residual floor is
    # ~eps (EA/L_c) L; 10x that is the smallest reachable Newton tolerance, and the static solves
    # need the relative tolerance 1e-10 there
    ea = bender.laminate.axial_rigidity
    floor = 10.0 * np.finfo(float).eps * ea / float(np.min(bender.cell_lengths)) * bender.length
    ctx.raise_newton_tolerance_floor(floor)
    ctx.set_static_relative_tolerance(1e-10)


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
