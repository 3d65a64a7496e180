"""Exudyn system of the ``"beam"`` cell: geometrically exact 2-D beam elements.

Each cell is one ``ObjectBeamGeometricallyExact2D`` element (Simo-Reissner beam with linear
interpolation of position and rotation between two ``NodeRigidBody2D`` nodes) along the passive
layer's mid-plane ``y = 0``, with the laminate's bending stiffness ``EI``, mass per length and
rotary inertia.  Node 0 is clamped by three coordinate constraints; the tip is node ``N``.

The piezo layer's free curvature ``kappa`` enters as one tip torque ``EI kappa(t)`` written in
the pre-step hook: for a laminate that is uniform along the beam, a prescribed reference
curvature ``kappa`` in every element and the end torque ``EI kappa`` give the same equations
(the element's bending moment is ``EI (k - kappa)``; its virtual work ``EI kappa dk``
integrates to ``EI kappa (phi_N - phi_0)``, the work of the end torque, because the element's
curvature is the rotation difference of its nodes over its length).  The ``"offsets"`` stroke
path writes the reference curvature into every element instead; the tests compare the two.

The axis is modelled as practically inextensible and shear-rigid (axial and shear stiffness
``a1 + a2``, the layers' summed axial rigidity), as the passive bar of the other two cells is:
the closed forms the model is validated against are Euler-Bernoulli's.  Damping is
stiffness-proportional, ``beta`` times each stiffness, as in the other cells.

The stiff axis limits the Newton residual that round-off allows (about ``eps EA L / L_c``);
the absolute Newton tolerance is raised to ten times that where it is tighter (from about 50
cells of the reference bender of the actuator docs on).
"""

from __future__ import annotations

import numpy as np
from exudyn import itemInterface as ii

from .actuator_items import NOVIS, add_ground
from .actuator_model import BuiltModel

_BEAM_VIS = {'show': False, 'drawHeight': 0., 'color': [-1., -1., -1., -1.]}


def build_beam(SC, mbs, act, stroke_path) -> BuiltModel:
    """Add the beam-cell actuator to ``mbs``; returns the model handles (not yet assembled)."""
    if stroke_path not in ("prestep", "offsets"):
        raise ValueError(f"stroke_path must be 'prestep' or 'offsets' for the beam cell, got {stroke_path!r}")
    n, lc = act.n_cells, act.cell_length
    beta = act.stiffness_damping_factor
    w = act.width
    EI = act.bending_stiffness
    EA = act.passive.axial_rigidity(w) + act.active.axial_rigidity(w)
    mu = act.mass_per_length
    # rotary inertia per length about the passive mid-plane (active layer at y = -e)
    rho_i = act.laminate.rotary_inertia_per_length

    ground, gcoord = add_ground(mbs)
    model = BuiltModel(SC=SC, mbs=mbs, cell="beam", n_cells=n, cell_length=lc)
    nodes = [mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[j * lc, 0.0, 0.0], visualization=NOVIS))
             for j in range(n + 1)]
    for k in range(3):  # clamp node 0
        mk = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=k))
        mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[gcoord, mk], visualization=NOVIS))
    for j in range(n):
        beam = mbs.AddObject(ii.ObjectBeamGeometricallyExact2D(
            nodeNumbers=[nodes[j], nodes[j + 1]], length=lc, massPerLength=mu, crossSectionInertia=rho_i,
            bendingStiffness=EI, axialStiffness=EA, shearStiffness=EA,
            bendingDamping=beta * EI, axialDamping=beta * EA, shearDamping=beta * EA,
            referenceCurvature=0.0, visualization=_BEAM_VIS))
        model.springs.append((beam, EI, "bendingDamping"))
        if stroke_path == "offsets":
            model.offset_items.append(beam)
            model.offset_factors.append(act.curvature_per_strain)
    model.offset_parameter = "referenceCurvature"
    # an axial force EA/L_c * du resolves positions only to round-off eps * L: its residual
    # floor is ~eps (EA/L_c) L, 9e-9 N at 64 cells of the reference bender; 10x that is the smallest reachable
    # Newton tolerance (moment residuals of that size move the tip by < 1e-8 rad)
    # the first residual of a static load step carries the stiff axis's forces: 1e-8 of it
    # left 8e-6 N m at the tip (8 cells, 1500 V and a tip load); 1e-10 reaches ~1e-9
    model.static_relative_tolerance = 1e-10
    model.newton_tolerance_floor = 10.0 * np.finfo(float).eps * EA / lc * act.length
    tip_node = nodes[-1]
    if stroke_path == "prestep":
        m_tip = mbs.AddMarker(ii.MarkerNodeRigid(nodeNumber=tip_node))
        model.torque_load = mbs.AddLoad(ii.LoadTorqueVector(markerNumber=m_tip, loadVector=[0.0, 0.0, 0.0]))
        model.torque_per_strain = EI * act.curvature_per_strain
    model._tip_marker = mbs.AddMarker(ii.MarkerNodePosition(nodeNumber=tip_node))
    model._tip_node = tip_node
    model._cell_nodes = nodes
    model.cell_angles_from_nodes = True
    model.tip_local_x = 0.0
    model.tip_rotation_per_strain = 0.0
    return model
