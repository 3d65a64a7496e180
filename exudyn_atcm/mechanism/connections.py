"""Connections (joints) and loads of a mechanism: plain records, checked by :class:`Mechanism`.

A joint's second point ``q`` is ``None`` for a connection to the ground (at ``p``'s reference
position).  Forces and torques are numbers or callables of time ``t`` [s].
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Union

from .points import GROUND, PointRef

ForceValue = Union[tuple[float, float], Callable[[float], tuple[float, float]]]
TorqueValue = Union[float, Callable[[float], float]]


@dataclass(frozen=True)
class Weld:
    """Rigid connection: positions and relative angle of ``p`` and ``q`` fixed."""

    p: PointRef
    q: PointRef | None

    kind = "weld"


@dataclass(frozen=True)
class Pin:
    """Revolute joint at ``p`` = ``q`` with an optional torsion spring [N m/rad] and damper [N m s/rad]."""

    p: PointRef
    q: PointRef | None
    stiffness: float = 0.0
    damping: float = 0.0

    kind = "pin"


@dataclass(frozen=True)
class Slider:
    """Prismatic joint: ``q`` moves along ``axis`` (global, reference pose) relative to ``p``'s body,
    no relative rotation; optional axial spring [N/m] and damper [N s/m]."""

    p: PointRef
    q: PointRef | None
    axis: tuple[float, float] = (1.0, 0.0)
    stiffness: float = 0.0
    damping: float = 0.0

    kind = "slider"


Joint = Union[Weld, Pin, Slider]


def joint_label(joint: Joint) -> str:
    """``"weld(crank.tip, coupler.A)"`` - how a joint is named in messages."""
    q = GROUND if joint.q is None else str(joint.q)
    return f"{joint.kind}({joint.p}, {q})"


@dataclass(frozen=True)
class Force:
    """Point force ``(Fx, Fy)`` [N] (or a callable of t): dead (global) or follower (turns with the body)."""

    point: PointRef
    force: ForceValue
    follower: bool = False
    name: str = ""


@dataclass(frozen=True)
class Torque:
    """Torque [N m] (or a callable of t) on a component's body, counter-clockwise positive."""

    component: str
    torque: TorqueValue
    name: str = ""


@dataclass(frozen=True)
class Spring:
    """Linear spring-damper between two points; tension positive."""

    p: PointRef
    q: PointRef
    stiffness: float
    damping: float = 0.0
    rest_length: float | None = None
    name: str = ""


@dataclass(frozen=True)
class Stop:
    """One-sided contact: force ``k pen`` along ``normal`` when ``(x_p - position) . normal < 0``."""

    point: PointRef
    position: tuple[float, float]
    normal: tuple[float, float]
    stiffness: float
    damping: float = 0.0
    name: str = ""
