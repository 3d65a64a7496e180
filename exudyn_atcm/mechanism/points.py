"""Named points of mechanism components and the names they are referred to by."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from .._checks import shown
from ..suggestions import close_names

#: Reserved component name of the ground (the fixed frame).
GROUND = "ground"

_FORBIDDEN = set(".,[]#\n ")


class MechanismError(ValueError):
    """A mechanism description that cannot be built; the message names the parts involved."""


def closest(name: str, candidates: Iterable[str]) -> str:
    """A ``"; did you mean 'x'?"`` hint for a misspelt name (empty if nothing is close)."""
    matches = close_names(name, candidates, cutoff=0.5)
    return f"; did you mean {matches[0]!r}?" if matches else ""


def check_name(kind: str, name: object) -> str:
    """Return ``name`` if it is a valid component or point name, else raise :class:`MechanismError`.

    Names are non-empty strings without ``.``, ``,``, ``[``, ``]``, ``#``, spaces or newlines
    (they become parts of result column names such as ``coupler.P_x [m]``).
    """
    if not isinstance(name, str) or not name or any(c in _FORBIDDEN for c in name):
        raise MechanismError(
            f"{kind} must be a non-empty string without '.', ',', '[', ']', '#' or spaces, got {shown(name)}")
    return name


@dataclass(frozen=True)
class PointRef:
    """A named point of a named component, e.g. ``PointRef("crank", "tip")`` (written ``"crank.tip"``).

    Parameters
    ----------
    component : str
        Component name.
    point : str
        Point name on that component.
    """

    component: str
    point: str

    def __str__(self) -> str:
        return f"{self.component}.{self.point}"

    @classmethod
    def parse(cls, value: "PointRef | str") -> "PointRef":
        """A :class:`PointRef` from itself or from a string ``"component.point"``."""
        if isinstance(value, PointRef):
            return value
        if isinstance(value, str) and value.count(".") == 1 and all(value.split(".")):
            component, point = value.split(".")
            return cls(component, point)
        raise MechanismError(
            f"a point must be a PointRef (e.g. bender.tip, link.point('P')) or a string 'component.point', "
            f"got {shown(value)}")


def unknown_point(component: str, point: str, names: Iterable[str]) -> MechanismError:
    """The error for a point name that ``component`` does not have (lists its points)."""
    names = list(names)
    return MechanismError(
        f"component {component!r} has no point {point!r}{closest(point, names)} "
        f"(its points: {', '.join(names)})")
