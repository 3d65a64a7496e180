"""The mass-proportional part ``alpha M`` of Rayleigh damping on planar rigid bodies.

For a rigid body of mass ``m`` and inertia ``J`` about its centre of mass, the kinetic energy
is ``m v_c²/2 + J omega²/2`` (``v_c`` the velocity of the centre of mass); the damping
``alpha M`` of its mass matrix is therefore exactly the force ``-alpha m v_c`` at the centre of
mass and the torque ``-alpha J omega``.  Both are measured against the ground (the inertial
frame), so they also damp rigid-body motion.  A body that carries several parts (a rigid
group in a mechanism) gets one such pair per damped part, at the part's own centre, with
that part's mass and inertia about its centre: the sum is ``alpha`` times the part's share of
the body's mass matrix.

Each pair is a zero-stiffness ``ObjectConnectorCartesianSpringDamper`` (damping ``alpha m`` in
``x`` and ``y``) from a ground marker to a marker at the centre, and a zero-stiffness
``ObjectConnectorCoordinateSpringDamper`` (damping ``alpha J``) on the body's rotation
coordinate.  Static solves and eigenfrequencies do not see them.
"""

from __future__ import annotations

from .exudyn_items import ii

from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..mechanism.flexure import Flexure
from ..mechanism.points import GROUND
from .items import NOVIS
from .items import rotation_marker as body_rotation_marker
from .model import Body


def ground_position_marker(mbs, ground_item: int) -> int:
    """A position marker on the ground object (the fixed end of the mass dampers)."""
    return mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=ground_item, localPosition=[0.0, 0.0, 0.0]))


def add_mass_damper(mbs, *, body_item: int, rotation_marker: int, ground_position: int, ground_rotation: int,
                    alpha: float, mass: float, inertia: float, center) -> tuple[int, int]:
    """Damp a rigid body's mass ``mass`` [kg] and inertia ``inertia`` [kg m²] (about ``center``) with ``alpha`` [1/s].

    Parameters
    ----------
    body_item : int
        The ``ObjectRigidBody2D``.
    rotation_marker : int
        Marker of the body node's rotation coordinate.
    ground_position, ground_rotation : int
        A position marker on the ground object and a fixed coordinate marker.
    alpha : float
        Mass-proportional coefficient [1/s], > 0.
    mass, inertia : float
        The damped mass [kg] and its inertia about its own centre [kg m²].
    center : (float, float)
        The mass's centre in the body frame [m] (relative to the body's node).

    Returns
    -------
    (int, int)
        The translational and the rotational damper items.
    """
    at_center = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=body_item,
                                                    localPosition=[float(center[0]), float(center[1]), 0.0]))
    translation = mbs.AddObject(ii.ObjectConnectorCartesianSpringDamper(
        markerNumbers=[ground_position, at_center], stiffness=[0.0, 0.0, 0.0],
        damping=[alpha * mass, alpha * mass, 0.0], visualization=NOVIS))
    rotation = mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
        markerNumbers=[ground_rotation, rotation_marker], stiffness=0.0, damping=alpha * inertia,
        visualization=NOVIS))
    return translation, rotation


def part_mass_damping_factor(mech: Mechanism, part: str) -> float:
    """``alpha`` [1/s] of the component owning the rigid part ``part`` (0 for the ground and links)."""
    if part == GROUND:
        return 0.0
    comp = mech.components[part.partition("#")[0]]
    return comp.mass_damping_factor if isinstance(comp, (Bender, Flexure)) else 0.0


class MassDampers:
    """The mass dampers of one mechanism system (the ground marker is made on first use).

    Parameters
    ----------
    mbs : exudyn MainSystem
    ground_item : int
        The ground object.
    ground_rotation : int
        A fixed coordinate marker (the ground's rotation for the torque dampers).
    """

    def __init__(self, mbs, ground_item: int, ground_rotation: int) -> None:
        self.mbs = mbs
        self.ground_item = ground_item
        self.ground_rotation = ground_rotation
        self.ground_position: int | None = None

    def add(self, body: Body, alpha: float, mass: float, inertia: float, center) -> None:
        """Damp ``mass`` [kg] / ``inertia`` [kg m²] at ``center`` (body frame) on ``body`` with ``alpha`` (0: nothing)."""
        if alpha == 0.0:
            return
        if self.ground_position is None:
            self.ground_position = ground_position_marker(self.mbs, self.ground_item)
        add_mass_damper(self.mbs, body_item=body.item,
                        rotation_marker=body_rotation_marker(self.mbs, body, self.ground_rotation),
                        ground_position=self.ground_position, ground_rotation=self.ground_rotation,
                        alpha=alpha, mass=mass, inertia=inertia, center=center)
