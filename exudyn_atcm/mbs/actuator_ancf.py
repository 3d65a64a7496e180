"""Exudyn system of the ``"ancf"`` cell: ANCF cable elements (cubic Hermite beam elements).

Each cell is one ``ObjectANCFCable2D`` element (Bernoulli-Euler beam in absolute nodal
coordinates: node position and slope vector, cubic interpolation) along the passive layer's
mid-plane, with the laminate's ``EI``, mass per length and axial stiffness ``a1 + a2`` (an
axis that is practically inextensible, as in the other cells).  Node 0 is clamped (position
and the slope's ``y`` component fixed).  The piezo layer's free curvature enters as one tip
torque ``EI kappa(t)`` written in the pre-step hook (the ``"offsets"`` path writes the
reference curvature into every element instead; for a uniform laminate the two are the same
equations).  Cubic elements represent the small-deflection cantilever exactly under a tip
force, so the discretisation error is of higher order than the linear beam elements' (f1:
+0.05 % at 2 elements against +0.70 % at 4 linear ones).  In a strongly bent state the
element's axial constraint locks on coarse meshes (f1 about the state at 1500 V: +4 % at 2
elements, +0.4 % at 4, 1e-4 at 8).

Angles are not coordinates here: a node's rotation is the angle of its slope vector, and a
cell's angle is the mean of its two nodes' rotations.
"""

from __future__ import annotations

import numpy as np
from exudyn import itemInterface as ii

from .actuator_items import NOVIS, add_ground
from .actuator_model import BuiltModel


class AncfModel(BuiltModel):
    """Handles of the ANCF-cable model (internal)."""

    node_indices: np.ndarray | None = None  # ODE2 index of each node's first coordinate

    @property
    def record_indices(self) -> np.ndarray:
        return (self.node_indices[:, None] + np.arange(4)[None, :]).ravel()

    def _from_records(self, records: np.ndarray) -> tuple:
        r = records.reshape(records.shape[0], self.n_cells + 1, 4)
        phi = np.unwrap(np.arctan2(r[:, :, 3], 1.0 + r[:, :, 2]), axis=1)
        x = self.length + r[:, -1, 0]
        y = r[:, -1, 1]
        return x, y, phi[:, -1], 0.5 * (phi[:, :-1] + phi[:, 1:])

    def read_state(self, q: np.ndarray, strain: float) -> tuple:
        x, y, a, cells = self._from_records(np.asarray(q)[self.record_indices][None, :])
        return float(x[0]), float(y[0]), float(a[0]), cells[0]

    def states_from_records(self, records: np.ndarray, strains: np.ndarray) -> tuple:
        return self._from_records(records)

    def finish_indices(self) -> None:
        self.node_indices = np.array([self.mbs.GetNodeODE2Index(nd) for nd in self._cell_nodes])
        self.tip_indices = self.node_indices[-1] + np.arange(4)

    @property
    def length(self) -> float:
        return self.n_cells * self.cell_length


def build_ancf(SC, mbs, act, stroke_path) -> AncfModel:
    """Add the ANCF-cable actuator to ``mbs``; returns the model handles (not yet assembled)."""
    if stroke_path not in ("prestep", "offsets"):
        raise ValueError(f"stroke_path must be 'prestep' or 'offsets' for the ancf cell, got {stroke_path!r}")
    n, lc = act.n_cells, act.cell_length
    beta = act.stiffness_damping_factor
    w = act.width
    EI = act.bending_stiffness
    EA = act.passive.axial_rigidity(w) + act.active.axial_rigidity(w)
    mu = act.mass_per_length

    ground, gcoord = add_ground(mbs)
    model = AncfModel(SC=SC, mbs=mbs, cell="ancf", n_cells=n, cell_length=lc)
    nodes = [mbs.AddNode(ii.NodePoint2DSlope1(referenceCoordinates=[j * lc, 0.0, 1.0, 0.0], visualization=NOVIS))
             for j in range(n + 1)]
    for k in (0, 1, 3):  # clamp: position and the slope's y component of node 0
        mk = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=k))
        mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[gcoord, mk], visualization=NOVIS))
    elements = []
    for j in range(n):
        el = mbs.AddObject(ii.ObjectANCFCable2D(
            nodeNumbers=[nodes[j], nodes[j + 1]], length=lc, massPerLength=mu, bendingStiffness=EI,
            axialStiffness=EA, bendingDamping=beta * EI, axialDamping=beta * EA, referenceCurvature=0.0,
            useReducedOrderIntegration=True, visualization={'show': False, 'drawHeight': 0.,
                                                            'color': [-1., -1., -1., -1.]}))
        elements.append(el)
        model.springs.append((el, EI, "bendingDamping"))
        if stroke_path == "offsets":
            model.offset_items.append(el)
            model.offset_factors.append(act.curvature_per_strain)
    model.offset_parameter = "referenceCurvature"
    if stroke_path == "prestep":
        m_tip = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=elements[-1], localPosition=[lc, 0.0, 0.0]))
        model.torque_load = mbs.AddLoad(ii.LoadTorqueVector(markerNumber=m_tip, loadVector=[0.0, 0.0, 0.0]))
        model.torque_per_strain = EI * act.curvature_per_strain
    model._tip_marker = mbs.AddMarker(ii.MarkerNodePosition(nodeNumber=nodes[-1]))
    model._tip_node = nodes[-1]
    model._cell_nodes = nodes
    model.static_relative_tolerance = 1e-10
    # round-off floor of the stiff axis's forces, as for the linear beam elements
    model.newton_tolerance_floor = 10.0 * np.finfo(float).eps * EA / lc * act.length
    return model
