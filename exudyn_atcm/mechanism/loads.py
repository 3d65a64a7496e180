"""Loads of a mechanism: point forces, torques, springs between points and one-sided stops.

Each implements the connection protocol (:mod:`exudyn_atcm.mechanism.connection`): it adds its
items through the build context (:class:`exudyn_atcm.mbs.build_context.BuildContext`), names its recorded
columns, its parameters and draws itself.  Forces and torques are numbers or callables of time
``t`` [s].
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Union

import numpy as np

from .connection import ConnectionBase, Readout
from .points import PointRef

ForceValue = Union[tuple[float, float], Callable[[float], tuple[float, float]]]
TorqueValue = Union[float, Callable[[float], float]]

_SPRING_COLOR = "#8c510a"


@dataclass(frozen=True)
class Force(ConnectionBase):
    """Point force ``(Fx, Fy)`` [N] (or a callable of t): dead (global) or follower (turns with the body)."""

    point: PointRef
    force: ForceValue
    follower: bool = False
    name: str = ""

    def points(self) -> tuple[PointRef, ...]:
        """The loaded point."""
        return (self.point,)

    def parameters(self) -> dict[str, Any]:
        """``{"name [N]": "point value [follower]"}``."""
        return {f"{self.name} [N]": f"{self.point} {self.force!r}{' follower' if self.follower else ''}"}

    def realise(self, context: Any) -> None:
        """A force load at the point, written per step."""
        context.add_force(self.point, self.force, follower=self.follower, name=self.name)


@dataclass(frozen=True)
class Torque(ConnectionBase):
    """Torque [N m] (or a callable of t) on a component's body, counter-clockwise positive."""

    component: str
    torque: TorqueValue
    name: str = ""

    def components(self) -> tuple[str, ...]:
        """The loaded component."""
        return (self.component,)

    def parameters(self) -> dict[str, Any]:
        """``{"name [N m]": "component value"}``."""
        return {f"{self.name} [N m]": f"{self.component} {self.torque!r}"}

    def realise(self, context: Any) -> None:
        """A torque load on the component's body, written per step."""
        context.add_torque(self.component, self.torque, name=self.name)


@dataclass(frozen=True)
class Spring(ConnectionBase):
    """Linear spring-damper between two points; tension positive (column ``{name}.force [N]``)."""

    p: PointRef
    q: PointRef
    stiffness: float
    damping: float = 0.0
    rest_length: float | None = None
    name: str = ""

    def points(self) -> tuple[PointRef, ...]:
        """Both ends."""
        return (self.p, self.q)

    def parameters(self) -> dict[str, Any]:
        """Ends, stiffness, damping and rest length with units."""
        return {self.name: (f"{self.p}-{self.q} stiffness={self.stiffness!r} N/m damping={self.damping!r} N s/m "
                            f"rest_length={self.rest_length!r} m")}

    def readouts(self) -> tuple[Readout, ...]:
        """The force, tension positive [N]."""
        return (Readout(f"{self.name}.force", "N"),)

    def realise(self, context: Any) -> None:
        """A spring-damper between the points and its force read-out."""
        item = context.add_spring_damper(self.p, self.q, self.stiffness, self.damping, self.rest_length, self.name)
        context.add_readout(self.readouts()[0], context.output(item, "ForceLocal"))

    def draw(self, canvas: Any) -> None:
        """A zigzag between the points."""
        canvas.zigzag(canvas.position(self.p), canvas.position(self.q), color=_SPRING_COLOR,
                      label="springs (objects)")


@dataclass(frozen=True)
class Stop(ConnectionBase):
    """One-sided contact: force ``k pen`` along ``normal`` when ``(x_p - position) . normal < 0``
    (column ``{name}.force [N]``, compression positive)."""

    point: PointRef
    position: tuple[float, float]
    normal: tuple[float, float]
    stiffness: float
    damping: float = 0.0
    name: str = ""

    def points(self) -> tuple[PointRef, ...]:
        """The point that touches the wall."""
        return (self.point,)

    def parameters(self) -> dict[str, Any]:
        """Point, wall, stiffness and damping with units."""
        return {self.name: (f"{self.point} position={self.position!r} m normal={self.normal!r} "
                            f"stiffness={self.stiffness!r} N/m damping={self.damping!r} N s/m")}

    def readouts(self) -> tuple[Readout, ...]:
        """The contact force, compression positive [N]."""
        return (Readout(f"{self.name}.force", "N"),)

    def realise(self, context: Any) -> None:
        """The contact connector and its force read-out (the force along the normal)."""
        item = context.add_contact(self.point, self.position, self.normal, self.stiffness, self.damping, self.name)
        force = context.output(item, "Force")
        nx, ny = float(self.normal[0]), float(self.normal[1])

        def compression() -> float:
            f = force().tolist()  # Python floats: cheaper than numpy for 3 components
            return -(f[0] * nx + f[1] * ny)

        context.add_readout(self.readouts()[0], compression)

    def draw(self, canvas: Any) -> None:
        """A hatched wall through ``position``, hatched on the side away from ``normal``."""
        normal = np.array(self.normal, dtype=float)
        canvas.wall(np.array(self.position, dtype=float), np.array([-normal[1], normal[0]]),
                    0.06 * canvas.size, -normal)
