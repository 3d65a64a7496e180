"""External loads of a mechanism model: point forces, torques, springs between points, stops."""

from __future__ import annotations

import warnings

import numpy as np
from exudyn import itemInterface as ii

from ..mechanism.assembly import Mechanism
from ..mechanism.points import GROUND
from .items import NOVIS, position_marker, rigid_marker
from .model import LoadRecord, MechanismModel
from ..errors import SetupWarning


def add_loads(mbs, mech: Mechanism, model: MechanismModel) -> None:
    """Add the forces, torques, springs and stops of ``mech`` at the model's anchored points.

    Force and torque values are written per step by :meth:`MechanismModel.set_strains` /
    :meth:`MechanismModel.set_time` (they may be callables of time); a follower force is given
    in the reference pose and turns with its body (on a free bender end: with the end's interface).
    """
    for f in mech.forces:
        key, local = model.anchors[str(f.point)]
        body = model.bodies[key]
        if body.node is None:
            warnings.warn(f"force {f.name!r} acts at {f.point}, which is welded to the ground: it has no effect",
                          SetupWarning, stacklevel=4)
            continue
        if f.follower:  # a body-fixed load needs the marker's orientation
            marker = rigid_marker(mbs, body, local)
        else:
            marker = position_marker(mbs, body, local)
        load = mbs.AddLoad(ii.LoadForceVector(markerNumber=marker, loadVector=[0.0, 0.0, 0.0], bodyFixed=f.follower))
        end = model.ends.get(str(f.point))
        free = end if (f.follower and end is not None and end.kind == "free") else None
        model.loads.append(LoadRecord(load, "force", f.force, f.follower, float(body.reference[2]), free, f.name))
    for t in mech.torques:
        key = model.group_of_component[t.component]
        body = model.bodies[key]
        if body.node is None:
            warnings.warn(f"torque {t.name!r} acts on {t.component!r}, which is welded to the ground: no effect",
                          SetupWarning, stacklevel=4)
            continue
        marker = rigid_marker(mbs, body, (0.0, 0.0))
        load = mbs.AddLoad(ii.LoadTorqueVector(markerNumber=marker, loadVector=[0.0, 0.0, 0.0]))
        model.loads.append(LoadRecord(load, "torque", t.torque, name=t.name))
    for s in mech.springs:
        ka, la = model.anchors[str(s.p)]
        kb, lb = model.anchors[str(s.q)]
        length = float(np.linalg.norm(mech.position(s.p) - mech.position(s.q)))
        rest = length if s.rest_length is None else s.rest_length
        ma = position_marker(mbs, model.bodies[ka], la)
        mb = position_marker(mbs, model.bodies[kb], lb)
        model.spring_items[s.name] = mbs.AddObject(ii.ObjectConnectorSpringDamper(
            markerNumbers=[ma, mb], referenceLength=rest, stiffness=s.stiffness, damping=s.damping,
            visualization={'show': True, 'drawSize': -1.0, 'color': [0.1, 0.6, 0.1, 1.0]}))
    for s in mech.stops:
        key, local = model.anchors[str(s.point)]
        ground_marker = position_marker(mbs, model.bodies[GROUND], s.position)
        mp = position_marker(mbs, model.bodies[key], local)
        model.spring_items[s.name] = mbs.AddObject(ii.ObjectConnectorCartesianSpringDamper(
            markerNumbers=[ground_marker, mp], stiffness=[0.0, 0.0, 0.0], damping=[0.0, 0.0, 0.0],
            springForceUserFunction=_stop_force(s.normal, s.stiffness, s.damping), visualization=NOVIS))


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
