"""Joints of a mechanism (weld, pin, slider): connections that hold parts together.

A joint's second point ``q`` is ``None`` for a connection to the ground (at ``p``'s reference
position).  Welds fuse the parts they join into one rigid group (:mod:`exudyn_atcm.mbs.layout`);
pins and sliders are realised through the build context's
:meth:`~exudyn_atcm.mbs.build_context.BuildContext.add_pin` and
:meth:`~exudyn_atcm.mbs.build_context.BuildContext.add_slider`.  Each draws its ground symbol.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Union

import numpy as np

from .connection import ConnectionBase
from .points import GROUND, PointRef


@dataclass(frozen=True)
class JointBase(ConnectionBase):
    """Common part of the joints: points ``p`` and ``q`` (``None``: the ground)."""

    p: PointRef
    q: PointRef | None
    holds: ClassVar[bool] = True
    loads_points: ClassVar[bool] = False
    #: True if it fuses the joined parts into one rigid group (a weld)
    fuses: ClassVar[bool] = False
    kind: ClassVar[str] = "joint"

    def points(self) -> tuple[PointRef, ...]:
        """``p`` and, unless the ground, ``q``."""
        return (self.p,) if self.q is None else (self.p, self.q)

    def describe(self) -> str:
        """``"pin(crank.base, ground)"``."""
        return joint_label(self)

    def details(self) -> str:
        """What :meth:`parameters` adds to the label (springs, axis)."""
        return ""

    def assembly_gap(self, xp: np.ndarray, xq: np.ndarray) -> tuple[float, str]:
        """How far [m] the reference positions ``xp``, ``xq`` of ``p``, ``q`` are from assembled, and what is wrong."""
        return float(np.linalg.norm(xq - xp)), "the joined points do not coincide"

    def parameters(self) -> dict[str, Any]:
        """``{name: label and details}`` (``name`` is ``joint_k``, given by the mechanism)."""
        return {self.name: joint_label(self) + self.details()}

    def draw(self, canvas: Any) -> None:
        """A ground joint's symbol at ``p`` (joints between parts are drawn by the parts)."""
        if self.q is None:
            self.draw_ground(canvas, np.asarray(canvas.reference(self.p)), canvas.inward(self.p), 0.06 * canvas.size)

    def draw_ground(self, canvas: Any, x: np.ndarray, inward: np.ndarray, size: float) -> None:
        """The ground symbol at ``x`` [m] for a part lying towards ``inward`` (unit vector)."""


@dataclass(frozen=True)
class Weld(JointBase):
    """Rigid connection: positions and relative angle of ``p`` and ``q`` fixed."""

    name: str = ""
    fuses: ClassVar[bool] = True
    kind: ClassVar[str] = "weld"

    def draw_ground(self, canvas: Any, x: np.ndarray, inward: np.ndarray, size: float) -> None:
        """A hatched wall behind ``x``."""
        canvas.wall(x, np.array([-inward[1], inward[0]]), size, -inward)


@dataclass(frozen=True)
class Pin(JointBase):
    """Revolute joint at ``p`` = ``q`` with an optional torsion spring [N m/rad] and damper [N m s/rad]."""

    stiffness: float = 0.0
    damping: float = 0.0
    name: str = ""
    kind: ClassVar[str] = "pin"

    def details(self) -> str:
        """The spring and damper, if any."""
        return f" stiffness={self.stiffness!r} damping={self.damping!r}" if self.stiffness or self.damping else ""

    def realise(self, context: Any) -> None:
        """A hinge with the pin's spring and damper."""
        context.add_pin(self.p, self.q, self.stiffness, self.damping, self.describe())

    def draw_ground(self, canvas: Any, x: np.ndarray, inward: np.ndarray, size: float) -> None:
        """A triangle on a hatched wall."""
        normal = np.array([-inward[1], inward[0]])
        canvas.line(np.array([x, x + size * (-0.35 * normal - 0.5 * inward),
                              x + size * (0.35 * normal - 0.5 * inward), x]), color="k", lw=1.2)
        canvas.wall(x - 0.5 * size * inward, normal, size, -inward)


@dataclass(frozen=True)
class Slider(JointBase):
    """Prismatic joint: ``q`` moves along ``axis`` (global, reference pose) relative to ``p``'s body,
    no relative rotation; optional axial spring [N/m] and damper [N s/m]."""

    axis: tuple[float, float] = (1.0, 0.0)
    stiffness: float = 0.0
    damping: float = 0.0
    name: str = ""
    kind: ClassVar[str] = "slider"

    def details(self) -> str:
        """The spring and damper, if any, and the axis."""
        spring = f" stiffness={self.stiffness!r} damping={self.damping!r}" if self.stiffness or self.damping else ""
        return spring + f" axis={self.axis!r}"

    def assembly_gap(self, xp: np.ndarray, xq: np.ndarray) -> tuple[float, str]:
        """Distance [m] of ``q`` from the axis line through ``p``."""
        d = xq - xp
        return abs(float(d[0] * self.axis[1] - d[1] * self.axis[0])), \
            f"{self.q} lies off the slider axis {self.axis} through {self.p}"

    def realise(self, context: Any) -> None:
        """A prismatic joint with the slider's spring and damper."""
        context.add_slider(self.p, self.q, self.axis, self.stiffness, self.damping, self.describe())

    def draw_ground(self, canvas: Any, x: np.ndarray, inward: np.ndarray, size: float) -> None:
        """A rail along the axis."""
        axis = np.array(self.axis, dtype=float)
        normal = np.array([-axis[1], axis[0]])
        canvas.wall(x + 0.15 * size * normal, axis, 2 * size, -normal)


Joint = Union[Weld, Pin, Slider]


def joint_label(joint: Any) -> str:
    """``"weld(crank.tip, coupler.A)"`` - how a joint is named in messages."""
    q = GROUND if joint.q is None else str(joint.q)
    return f"{joint.kind}({joint.p}, {q})"
