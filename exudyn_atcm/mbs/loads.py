"""The Exudyn items of the package's loads: point forces, torques, springs between points, stops.

Called through the public build context (:class:`~exudyn_atcm.mbs.build_context.BuildContext`)
by the loads' ``realise`` (:mod:`exudyn_atcm.mechanism.loads`).
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
from .exudyn_items import ii

from ..mechanism.points import PointRef
from .items import NOVIS, position_marker, rigid_marker
from .model import LoadRecord, MechanismModel
from ..errors import SetupWarning


def add_force(mbs, model: MechanismModel, point: PointRef, value: Any, follower: bool, name: str) -> int | None:
    """A force load at ``point`` (written per step by the model); ``None`` (and a warning) on the ground.

    A follower force is given in the reference pose and turns with its body (on a free bender
    end: with the end's interface).
    """
    key, local = model.anchors[str(point)]
    body = model.bodies[key]
    if body.node is None:
        warnings.warn(f"force {name!r} acts at {point}, which is welded to the ground: it has no effect",
                      SetupWarning, stacklevel=5)
        return None
    marker = rigid_marker(mbs, body, local) if follower else position_marker(mbs, body, local)
    load = mbs.AddLoad(ii.LoadForceVector(markerNumber=marker, loadVector=[0.0, 0.0, 0.0], bodyFixed=follower))
    end = model.ends.get(str(point))
    free = end if (follower and end is not None and end.kind == "free") else None
    model.loads.append(LoadRecord(load, "force", value, follower, float(body.reference[2]), free, name))
    return load


def add_torque(mbs, model: MechanismModel, component: str, value: Any, name: str) -> int | None:
    """A torque load on ``component``'s body (written per step); ``None`` (and a warning) on the ground."""
    body = model.bodies[model.group_of_component[component]]
    if body.node is None:
        warnings.warn(f"torque {name!r} acts on {component!r}, which is welded to the ground: no effect",
                      SetupWarning, stacklevel=5)
        return None
    marker = rigid_marker(mbs, body, (0.0, 0.0))
    load = mbs.AddLoad(ii.LoadTorqueVector(markerNumber=marker, loadVector=[0.0, 0.0, 0.0]))
    model.loads.append(LoadRecord(load, "torque", value, name=name))
    return load


def add_spring_damper(mbs, model: MechanismModel, markers: list[int], stiffness: float, damping: float,
                      rest_length: float, name: str) -> int:
    """A spring-damper [N/m], [N s/m] of rest length [m] between two position ``markers``; its object number."""
    item = model.spring_items[name] = mbs.AddObject(ii.ObjectConnectorSpringDamper(
        markerNumbers=list(markers), referenceLength=rest_length, stiffness=stiffness, damping=damping,
        visualization={'show': True, 'drawSize': -1.0, 'color': [0.1, 0.6, 0.1, 1.0]}))
    return item


def add_contact(mbs, model: MechanismModel, markers: list[int], normal: Any, stiffness: float, damping: float,
                name: str) -> int:
    """A one-sided contact between a ground marker and a point's marker (``markers``): the wall through the
    ground marker, free side ``normal``, stiffness [N/m] and damping [N s/m]; its object number."""
    item = model.spring_items[name] = mbs.AddObject(ii.ObjectConnectorCartesianSpringDamper(
        markerNumbers=list(markers), stiffness=[0.0, 0.0, 0.0], damping=[0.0, 0.0, 0.0],
        springForceUserFunction=_stop_force(normal, stiffness, damping), visualization=NOVIS))
    return item


def reference_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Distance [m] of two reference positions."""
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b)))


def _stop_force(normal, stiffness: float, damping: float):
    nx, ny = float(normal[0]), float(normal[1])

    def force(mbs, t, item, displacement, velocity, k, d, offset):
        gap = displacement[0] * nx + displacement[1] * ny
        if gap >= 0.0:
            return [0.0, 0.0, 0.0]
        rate = velocity[0] * nx + velocity[1] * ny
        # connector force convention: f acts on marker 1 as -f; push the point out along the normal
        magnitude = stiffness * gap + damping * rate
        return [magnitude * nx, magnitude * ny, 0.0]

    return force
