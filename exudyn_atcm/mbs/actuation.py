"""How the drives' strains reach a built mechanism: the hinges' springs and the actuation.

:func:`realise_actuation` gives every hinge of the builder its series spring-damper and
realises the free curvature of the benders along one of the stroke paths
(:attr:`exudyn_atcm.cells.CellKind.stroke_paths`):

``"prestep"`` (default)
    Every spring's rest angle ``theta0(strains)`` is the free rotation of the half cells it
    stands for.  The rest-angle moment ``k theta0`` splits into ``k dphi`` plus the pair
    ``+k theta0 / -k theta0`` on the spring's two bodies; the pairs are summed per body and
    drive, giving one ``LoadTorqueVector`` per body whose net torque is not identically zero
    (for a uniform cantilever the pairs cancel on every cell but the last: one torque
    ``EI kappa``).  Beam and ANCF benders get the end torques ``+-EI kappa`` of each segment
    on their nodes (:func:`~exudyn_atcm.mbs.node_chain.actuation_torques`).  The model writes
    them in the pre-step hook (:meth:`~exudyn_atcm.mbs.model.MechanismModel.set_strains`).
``"offsets"``
    The rest angles are written into every spring's ``offset``; beam and ANCF elements get
    the free curvature as their ``referenceCurvature``.  The same equations, one call per
    spring or element and step.
``"user_function"``
    Spring-force user functions with the rest angle at the solver's ``t`` (six-bar motors:
    offset user functions, :mod:`~exudyn_atcm.mbs.chains.six_bar`).

These are the same computation: every hook and user function of one solver step receives the
same ``t`` (the end time of the step being attempted, measured with Exudyn 1.13), and the
strain sources evaluate from memory that changes only in the post-step hook, after the step.
The tests compare the paths run against run (``tests/test_actuator_dynamics.py``).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np
from .exudyn_items import ii

from ..mechanism.assembly import Mechanism
from .node_chain import actuation_torques, reference_curvatures
from .items import NOVIS, rigid_marker, rotation_marker
from .model import MechanismModel

__all__ = ["realise_actuation"]


def realise_actuation(mbs, mech: Mechanism, model: MechanismModel, ground_coordinate: int,
                      zeros: Callable[[], np.ndarray], clamped: set[str]) -> None:
    """Add every hinge's spring-damper and the actuation along ``model.stroke_path``.

    ``zeros()`` is a vector per strain source; ``clamped`` names the beam nodes clamped to the ground
    (their end torques go into the clamp).
    """
    per_body: dict[str, np.ndarray] = {}
    for h in model.hinges:
        if len(h.elements) == 1:
            e = h.elements[0]
            h.stiffness, damping, h.moment = e.stiffness, e.damping, e.moment
        else:
            finite = [e for e in h.elements if math.isfinite(e.stiffness)]
            if any(e.stiffness == 0.0 for e in finite):
                h.stiffness, h.moment = 0.0, zeros()
                damping = sum(e.damping for e in finite if e.stiffness == 0.0)
            else:
                h.stiffness = 1.0 / sum(1.0 / e.stiffness for e in finite)
                h.moment = h.stiffness * sum((e.theta for e in h.elements), zeros())
                # series Kelvin-Voigt elements with equal beta = d/k give beta k_s; in general
                # k_s^2 sum(d_i / k_i^2) (exact for equal beta, an approximation otherwise)
                damping = h.stiffness**2 * sum(e.damping / e.stiffness**2 for e in finite)
        # the rest angle per unit strain of each source, for the "offsets" and "user_function" paths
        rest = sum((e.theta for e in h.elements if math.isfinite(e.stiffness)), zeros())
        actuated = bool(np.any(h.moment != 0.0))
        if h.stiffness > 0.0 or damping > 0.0:
            ra = rotation_marker(mbs, model.bodies[h.a], ground_coordinate)
            rb = rotation_marker(mbs, model.bodies[h.b], ground_coordinate)
            extra = {}
            if actuated and model.stroke_path == "user_function":
                extra["springForceUserFunction"] = _rest_angle_spring(model, rest)
            h.spring_item = mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[ra, rb], stiffness=h.stiffness, damping=damping, visualization=NOVIS, **extra))
            model.springs.append((h.spring_item, h.stiffness, "damping"))
            if actuated and model.stroke_path == "offsets":
                model.offset_items.append((h.spring_item, "offset", rest))
        if actuated and model.stroke_path == "prestep":
            per_body[h.b] = per_body.get(h.b, zeros()) + h.moment
            per_body[h.a] = per_body.get(h.a, zeros()) - h.moment
    for bender in mech.benders:
        if bender.name in model.beam_benders and model.stroke_path == "offsets":
            model.offset_items += [(item, "referenceCurvature", coef)
                                   for item, coef in reference_curvatures(model, bender, zeros)]
        elif bender.name in model.beam_benders:  # the segments' end torques EI kappa on the beam nodes
            for key, coef in actuation_torques(model, bender, zeros).items():
                if key not in clamped:
                    per_body[key] = per_body.get(key, zeros()) + coef
    scale = max((float(np.max(np.abs(v))) for v in per_body.values()), default=0.0)
    for key, coef in per_body.items():
        body = model.bodies[key]
        if body.node is None or float(np.max(np.abs(coef))) <= 1e-12 * scale:
            continue  # ground, or moments that cancel (inner cells of one drive)
        marker = rigid_marker(mbs, body, (0.0, 0.0))
        load = mbs.AddLoad(ii.LoadTorqueVector(markerNumber=marker, loadVector=[0.0, 0.0, 0.0]))
        model.torque_loads.append((load, coef))


def _rest_angle_spring(model: MechanismModel, rest: np.ndarray):
    """A torsion spring's force user function whose rest angle follows the strains at the solver's ``t``."""
    def force(mbs_, t, item_number, displacement, velocity, stiffness, damping, offset):
        return stiffness * (displacement - float(rest @ model.strains_at(t))) + damping * velocity
    return force
