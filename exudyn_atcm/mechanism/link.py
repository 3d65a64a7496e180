"""A rigid planar link with named points."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._checks import finite_float, positive_float, shown, warn_implausible
from .points import PointRef, check_name, unknown_point


def point_pair(name: str, value: Any) -> tuple[float, float]:
    try:
        x, y = value
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (x, y) of finite numbers [m], got {shown(value)}") from None
    return finite_float(f"{name}[0]", x), finite_float(f"{name}[1]", y)


class Link:
    """A rigid planar body with named points.

    Parameters
    ----------
    name : str
        Component name.
    points : mapping of str to (float, float)
        Named points in global coordinates of the reference pose [m]; at least one.
    mass : float
        Mass [kg], > 0.
    inertia : float
        Moment of inertia about the centre of mass [kg m²], > 0.
    center_of_mass : (float, float), optional
        Centre of mass in the reference pose [m]; default: the mean of the points.

    Examples
    --------
    >>> coupler = Link("coupler", {"A": (0.0, 0.05), "B": (0.06, 0.05), "P": (0.03, 0.08)},
    ...                mass=2e-3, inertia=1e-6)
    >>> coupler.point("P")
    PointRef(component='coupler', point='P')
    """

    def __init__(self, name: str, points: Mapping[str, tuple[float, float]], *, mass: float, inertia: float,
                 center_of_mass: tuple[float, float] | None = None) -> None:
        self.name = check_name("Link name", name)
        if not isinstance(points, Mapping) or not points:
            raise ValueError(f"points of link {name!r} must be a non-empty mapping name -> (x, y) [m], got {shown(points)}")
        self.points: dict[str, tuple[float, float]] = {
            check_name(f"point name of link {name!r}", k): point_pair(f"points[{k!r}]", v) for k, v in points.items()}
        self.mass = positive_float("mass", mass)
        self.inertia = positive_float("inertia", inertia)
        for pname, xy in self.points.items():
            for axis, value in zip("xy", xy):
                warn_implausible(f"point {pname} {axis}", value, "position", f"link {name!r}")
        if center_of_mass is None:
            c = np.mean(np.array(list(self.points.values())), axis=0)
            center_of_mass = (float(c[0]), float(c[1]))
        self.center_of_mass = point_pair("center_of_mass", center_of_mass)

    @classmethod
    def from_outline(cls, name: str, points: Mapping[str, tuple[float, float]], outline: Sequence[tuple[float, float]],
                     density: float, thickness: float) -> "Link":
        """A link cut from a plate: mass, centre of mass and inertia of a polygon.

        Parameters
        ----------
        name, points
            As for :class:`Link`.
        outline : sequence of (float, float)
            Polygon vertices in the reference pose [m], in order (either sense), >= 3.
        density : float
            Plate density [kg/m³], > 0.
        thickness : float
            Plate thickness [m], > 0.
        """
        density = positive_float("density", density)
        thickness = positive_float("thickness", thickness)
        vertices = np.array([point_pair(f"outline[{k}]", v) for k, v in enumerate(outline)], dtype=float) \
            if isinstance(outline, Sequence) or isinstance(outline, np.ndarray) else None
        if vertices is None or len(vertices) < 3:
            raise ValueError(f"outline of link {name!r} must be a sequence of >= 3 vertices (x, y) [m], got {shown(outline)}")
        x, y = vertices[:, 0], vertices[:, 1]
        xn, yn = np.roll(x, -1), np.roll(y, -1)
        cross = x * yn - xn * y
        area = 0.5 * float(np.sum(cross))
        if abs(area) <= 1e-12 * float(np.ptp(x) + np.ptp(y)) ** 2:
            raise ValueError(f"outline of link {name!r} encloses no area (degenerate polygon): {outline!r}")
        cx = float(np.sum((x + xn) * cross)) / (6.0 * area)
        cy = float(np.sum((y + yn) * cross)) / (6.0 * area)
        # polar second moment of area about the origin, then about the centroid
        jz = float(np.sum((x * x + x * xn + xn * xn + y * y + y * yn + yn * yn) * cross)) / 12.0
        jz_c = abs(jz) - abs(area) * (cx * cx + cy * cy)
        mass = density * thickness * abs(area)
        return cls(name, points, mass=mass, inertia=density * thickness * jz_c, center_of_mass=(cx, cy))

    def point(self, name: str) -> PointRef:
        """The named point as a :class:`PointRef`."""
        if name not in self.points:
            raise unknown_point(self.name, name, self.points)
        return PointRef(self.name, name)

    def parameters(self) -> dict[str, Any]:
        """Parameters with units, for result headers."""
        p = self.name
        out: dict[str, Any] = {f"{p}.type": "Link", f"{p}.mass [kg]": self.mass,
                               f"{p}.inertia [kg m^2]": self.inertia,
                               f"{p}.center_of_mass [m]": self.center_of_mass}
        for k, v in self.points.items():
            out[f"{p}.{k} [m]"] = v
        return out

    def __repr__(self) -> str:
        return (f"Link({self.name!r}, {self.points!r}, mass={self.mass!r}, inertia={self.inertia!r}, "
                f"center_of_mass={self.center_of_mass!r})")
