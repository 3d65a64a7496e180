r"""Position analysis of the rigid planar four-bar linkage (closed form).

The independent reference for compliant four-bar mechanisms: given where the input crank's
tip is, the rigid four-bar's loop closure fixes the rocker joint and the coupler point.
Pure NumPy; shares no code with the multibody model.

Notation (Norton, *Design of Machinery*, ch. 4; Freudenstein 1955): ground pivots ``A``
(crank) and ``D`` (rocker), crank tip ``B``, rocker joint ``C``; link lengths ``a = |AB|``
(crank), ``b = |BC|`` (coupler), ``c = |DC|`` (rocker), ``d = |AD|`` (ground).  The coupler
point ``P`` is fixed on the coupler, given by its coordinates ``(u, v)`` in the coupler frame
(``u`` along ``B -> C``, ``v`` to the left of it).

Two routes give the same answer and are tested against each other:

* **Circle intersection** (used with a compliant crank, whose tip ``B`` is known but does
  not move on a circle): ``C`` lies on the circle of radius ``b`` about ``B`` and on the
  circle of radius ``c`` about ``D``; of the two intersections the *branch* (assembly mode)
  picks the one on a fixed side of the line ``B -> D``.
* **Freudenstein's equation** (rigid crank at angle :math:`\theta_2`; ground ``A -> D``
  along :math:`\theta_1`): the loop closure
  :math:`a e^{i\theta_2} + b e^{i\theta_3} = d e^{i\theta_1} + c e^{i\theta_4}`, squared to
  remove :math:`\theta_3`, gives

  .. math:: K_1 \cos\varphi_4 - K_2 \cos\varphi_2 + K_3 = \cos(\varphi_2 - \varphi_4),
            \quad K_1 = d/a,\; K_2 = d/c,\; K_3 = \frac{a^2 - b^2 + c^2 + d^2}{2ac},

  with angles :math:`\varphi_k = \theta_k - \theta_1` measured from the ground line.  Written
  as :math:`P\cos\varphi_4 + Q\sin\varphi_4 = -R` with :math:`P = K_1 - \cos\varphi_2`,
  :math:`Q = -\sin\varphi_2`, :math:`R = K_3 - K_2\cos\varphi_2`, its two roots are
  :math:`\varphi_4 = \operatorname{atan2}(Q, P) \pm \arccos(-R/\sqrt{P^2 + Q^2})`, one per
  assembly mode.

References
----------
F. Freudenstein, "Approximate synthesis of four-bar linkages", Trans. ASME 77:853-861, 1955.
R. L. Norton, *Design of Machinery*, 5th ed., McGraw-Hill, 2012, sect. 4.5.
L. L. Howell, *Compliant Mechanisms*, Wiley, 2001, ch. 5 (pseudo-rigid-body four-bars).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._checks import finite_float, positive_float, shown

__all__ = [
    "circle_intersection",
    "branch_of",
    "RigidFourBar",
    "freudenstein_constants",
    "freudenstein_rocker_angle",
    "grashof_type",
]


def _point(name: str, value) -> np.ndarray:
    array = np.asarray(value, dtype=float)
    if array.shape[-1:] != (2,) or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite (x, y) coordinates [m] (shape (..., 2)), got {shown(value)}")
    return array


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def circle_intersection(center1, radius1: float, center2, radius2: float, branch: int) -> np.ndarray:
    """Intersection of two circles on the chosen side of the line ``center1 -> center2`` [m].

    Parameters
    ----------
    center1, center2 : array_like, shape (2,) or (n, 2)
        Circle centres [m]; arrays of centres are handled row by row.
    radius1, radius2 : float
        Radii [m], > 0.
    branch : {+1, -1}
        ``+1``: the intersection to the left of ``center1 -> center2`` (positive cross product
        ``(center2 - center1) x (p - center1)``); ``-1``: to the right.

    Returns
    -------
    numpy.ndarray
        The intersection point(s), same leading shape as the centres.

    Raises
    ------
    ValueError
        If the circles do not intersect (distance between the centres outside
        ``[|r1 - r2|, r1 + r2]``): the message gives the distance and the allowed range.
    """
    c1 = _point("center1", center1)
    c2 = _point("center2", center2)
    r1 = positive_float("radius1", radius1)
    r2 = positive_float("radius2", radius2)
    if branch not in (1, -1):
        raise ValueError(f"branch must be +1 or -1, got {shown(branch)}")
    c1, c2 = np.broadcast_arrays(c1, c2)
    delta = c2 - c1
    dist = np.hypot(delta[..., 0], delta[..., 1])
    low, high = abs(r1 - r2), r1 + r2
    bad = (dist > high * (1 + 1e-12)) | (dist < low * (1 - 1e-12)) | (dist == 0.0)
    if np.any(bad):
        worst = float(np.atleast_1d(dist)[np.argmax(np.atleast_1d(bad))])
        raise ValueError(
            f"the circles do not intersect: distance between the centres {worst!r} m is outside "
            f"[{low!r}, {high!r}] m (|r1 - r2| ... r1 + r2); the loop cannot close at this position"
        )
    along = (dist**2 + r1**2 - r2**2) / (2.0 * dist)
    across = np.sqrt(np.maximum(r1**2 - along**2, 0.0))
    unit = delta / dist[..., None]
    normal = np.stack([-unit[..., 1], unit[..., 0]], axis=-1)
    return c1 + along[..., None] * unit + branch * across[..., None] * normal


def branch_of(center1, center2, point) -> int:
    """Side (``+1`` left, ``-1`` right) of ``point`` relative to the line ``center1 -> center2``.

    Raises
    ------
    ValueError
        If the point lies on the line (a change-point configuration: no branch defined).
    """
    c1, c2, p = (_point(n, v) for n, v in (("center1", center1), ("center2", center2), ("point", point)))
    side = float(_cross(c2 - c1, p - c1))
    scale = float(np.linalg.norm(c2 - c1) * np.linalg.norm(p - c1))
    if abs(side) <= 1e-12 * max(scale, 1e-300):
        raise ValueError(f"point {p.tolist()} lies on the line {c1.tolist()} -> {c2.tolist()}: branch undefined")
    return 1 if side > 0.0 else -1


@dataclass(frozen=True)
class RigidFourBar:
    """A rigid four-bar with a coupler point, for position analysis from the crank tip.

    Parameters
    ----------
    crank_pivot : (float, float)
        Ground pivot ``A`` of the crank [m].
    rocker_pivot : (float, float)
        Ground pivot ``D`` of the rocker [m].
    crank_length, coupler_length, rocker_length : float
        ``a = |AB|``, ``b = |BC|``, ``c = |DC|`` [m], > 0.
    coupler_point : (float, float)
        Coordinates ``(u, v)`` of the coupler point in the coupler frame [m]: ``u`` along
        ``B -> C``, ``v`` to its left.
    branch : {+1, -1}
        Assembly mode: side of ``C`` relative to the line ``B -> D`` (see :func:`branch_of`).

    Examples
    --------
    >>> fb = RigidFourBar.from_points(A=(0, 0), B=(0, 1), C=(2, 1), D=(2, 0), P=(1, 1.5))
    >>> fb.coupler_point_from_crank_tip((0.0, 1.0)).round(12).tolist()
    [1.0, 1.5]
    """

    crank_pivot: tuple[float, float]
    rocker_pivot: tuple[float, float]
    crank_length: float
    coupler_length: float
    rocker_length: float
    coupler_point: tuple[float, float]
    branch: int

    def __post_init__(self) -> None:
        for name in ("crank_length", "coupler_length", "rocker_length"):
            object.__setattr__(self, name, positive_float(name, getattr(self, name)))
        for name in ("crank_pivot", "rocker_pivot", "coupler_point"):
            object.__setattr__(self, name, tuple(float(v) for v in _point(name, getattr(self, name))))
        if self.branch not in (1, -1):
            raise ValueError(f"branch must be +1 or -1, got {self.branch!r}")

    @classmethod
    def from_points(cls, A, B, C, D, P) -> "RigidFourBar":
        """The four-bar through the joint positions of one assembled pose [m].

        Link lengths, the coupler point's coupler-frame coordinates and the branch are read
        from the pose ``A`` (crank pivot), ``B`` (crank tip), ``C`` (rocker joint), ``D``
        (rocker pivot), ``P`` (coupler point).
        """
        A, B, C, D, P = (_point(n, v) for n, v in zip("ABCDP", (A, B, C, D, P)))
        e = (C - B) / np.linalg.norm(C - B)
        n = np.array([-e[1], e[0]])
        return cls(
            crank_pivot=tuple(A),
            rocker_pivot=tuple(D),
            crank_length=float(np.linalg.norm(B - A)),
            coupler_length=float(np.linalg.norm(C - B)),
            rocker_length=float(np.linalg.norm(C - D)),
            coupler_point=(float((P - B) @ e), float((P - B) @ n)),
            branch=branch_of(B, D, C),
        )

    @property
    def ground_length(self) -> float:
        """``d = |AD|`` [m]."""
        return float(np.hypot(self.rocker_pivot[0] - self.crank_pivot[0], self.rocker_pivot[1] - self.crank_pivot[1]))

    def rocker_joint(self, crank_tip) -> np.ndarray:
        """Rocker joint ``C`` [m] for crank tip(s) ``B`` (shape (2,) or (n, 2)) by circle intersection."""
        return circle_intersection(crank_tip, self.coupler_length, self.rocker_pivot, self.rocker_length, self.branch)

    def coupler_point_from_crank_tip(self, crank_tip) -> np.ndarray:
        """Coupler point ``P`` [m] for crank tip(s) ``B``: ``P = B + u e + v n``.

        ``e`` is the unit vector ``B -> C`` with ``C`` from :meth:`rocker_joint`, ``n`` its
        left normal.  The crank tip need not be at distance ``a`` from ``A`` (a compliant
        crank's tip does not move on a circle); only the coupler and rocker are rigid.
        """
        B = _point("crank_tip", crank_tip)
        C = self.rocker_joint(B)
        e = (C - B) / self.coupler_length
        n = np.stack([-e[..., 1], e[..., 0]], axis=-1)
        u, v = self.coupler_point
        return B + u * e + v * n

    def crank_tip(self, crank_angle: float | np.ndarray) -> np.ndarray:
        """Crank tip ``B = A + a (cos theta2, sin theta2)`` [m] of the rigid crank at ``theta2`` [rad]."""
        theta = np.asarray(crank_angle, dtype=float)
        return np.asarray(self.crank_pivot) + self.crank_length * np.stack([np.cos(theta), np.sin(theta)], axis=-1)

    def rocker_angle(self, crank_angle: float | np.ndarray) -> np.ndarray:
        """Absolute rocker angle ``theta4`` [rad] (direction ``D -> C``) by Freudenstein's equation.

        The root is the one of this four-bar's branch (checked against the circle intersection).
        """
        A, D = np.asarray(self.crank_pivot), np.asarray(self.rocker_pivot)
        theta1 = math.atan2(D[1] - A[1], D[0] - A[0])
        theta2 = np.asarray(crank_angle, dtype=float)
        roots = [
            theta1
            + freudenstein_rocker_angle(theta2 - theta1, self.crank_length, self.coupler_length,
                                        self.rocker_length, self.ground_length, sign)
            for sign in (1, -1)
        ]
        # pick the root whose C lies on this four-bar's side of B -> D
        B = self.crank_tip(theta2)
        for root in roots:
            C = D + self.rocker_length * np.stack([np.cos(root), np.sin(root)], axis=-1)
            if np.all(np.sign(_cross(D - B, C - B)) == self.branch):
                return root
        raise ValueError("no Freudenstein root on this four-bar's branch at the given crank angle(s)")


def freudenstein_constants(a: float, b: float, c: float, d: float) -> tuple[float, float, float]:
    """Freudenstein's ``K1 = d/a``, ``K2 = d/c``, ``K3 = (a² - b² + c² + d²)/(2ac)`` [-]."""
    a, b, c, d = (positive_float(n, v) for n, v in zip("abcd", (a, b, c, d)))
    return d / a, d / c, (a * a - b * b + c * c + d * d) / (2.0 * a * c)


def freudenstein_rocker_angle(
    crank_angle: float | np.ndarray, a: float, b: float, c: float, d: float, sign: int
) -> np.ndarray:
    """Rocker angle ``phi4`` [rad] from crank angle ``phi2`` [rad], both from the ground line ``A -> D``.

    Parameters
    ----------
    crank_angle : float or array_like
        ``phi2`` [rad].
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths [m].
    sign : {+1, -1}
        Which of the two roots ``atan2(Q, P) +- arccos(-R / sqrt(P² + Q²))``.

    Raises
    ------
    ValueError
        If the linkage cannot be assembled at ``phi2`` (``|R| > sqrt(P² + Q²)``).
    """
    if sign not in (1, -1):
        raise ValueError(f"sign must be +1 or -1, got {shown(sign)}")
    k1, k2, k3 = freudenstein_constants(a, b, c, d)
    phi2 = np.asarray(crank_angle, dtype=float)
    p = k1 - np.cos(phi2)
    q = -np.sin(phi2)
    r = k3 - k2 * np.cos(phi2)
    ratio = -r / np.hypot(p, q)
    if np.any(np.abs(ratio) > 1.0 + 1e-12):
        raise ValueError(
            f"the four-bar (a={a}, b={b}, c={c}, d={d}) cannot be assembled at crank angle(s) "
            f"{np.asarray(phi2)[np.abs(ratio) > 1.0 + 1e-12]!r} rad"
        )
    return np.arctan2(q, p) + sign * np.arccos(np.clip(ratio, -1.0, 1.0))


def grashof_type(a: float, b: float, c: float, d: float) -> str:
    """Grashof classification: ``"grashof"`` (s + l < p + q), ``"change-point"`` (=), ``"non-grashof"``.

    ``s``, ``l`` shortest and longest of the four lengths [m], ``p``, ``q`` the others.
    """
    lengths = sorted(finite_float(n, v) for n, v in zip("abcd", (a, b, c, d)))
    lhs, rhs = lengths[0] + lengths[3], lengths[1] + lengths[2]
    if math.isclose(lhs, rhs, rel_tol=1e-12):
        return "change-point"
    return "grashof" if lhs < rhs else "non-grashof"
