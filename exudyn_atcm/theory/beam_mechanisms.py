"""Closed-form and shooting references for the mechanism cases.

The guided S-shaped blade (parallel guide), the bender with a rigid extension (lever, gripper
jaw), and the curved cantilever under an end force in large deflection (Kirchhoff rod with a
free curvature, solved by shooting).  Like :mod:`exudyn_atcm.theory.beam`, on which they build,
they share no code with the model.  SI units throughout.
"""

from __future__ import annotations

import math

import numpy as np

from .._checks import shown
from .beam import arc_point

__all__ = [
    "s_blade_deflection_linear",
    "s_blade_end",
    "extension_free_deflection",
    "extension_compliance",
    "rigid_chain_extension_compliance",
    "extension_blocked_force",
    "spring_contact_force",
    "rigid_extension_point",
    "curved_cantilever_end_load",
    "curved_cantilever_spring_force",
]



def s_blade_deflection_linear(curvature: float, length: float) -> float:
    r"""Small-deflection end deflection ``kappa L² / 4`` of a guided blade bent into an S [m].

    The blade of length ``L`` is clamped at ``s = 0``; its first half has the free curvature
    ``+kappa``, its second half ``-kappa``; its end is guided (rotation held at zero,
    translation free) and carries no other load.

    Derivation (Euler-Bernoulli, small slopes): with the bending moment ``M(s)`` the
    curvature is :math:`w'' = \kappa_0(s) + M/EI`.  The free curvature integrates to zero,
    :math:`\int_0^L \kappa_0\,ds = \kappa L/2 - \kappa L/2 = 0`, so the *unloaded* blade
    already ends with zero slope: the guide needs no end moment and, as the translation is
    free, no end force; ``M = 0`` throughout.  Then

    .. math:: w(L) = \int_0^L (L - s)\,\kappa_0(s)\,ds
              = \kappa\left[\tfrac{3L^2}{8} - \tfrac{L^2}{8}\right] = \frac{\kappa L^2}{4}.

    This is half the free deflection ``kappa L²/2`` of a uniformly curved cantilever of the
    same length.  The large-deflection value is :func:`s_blade_end`.
    """
    return 0.25 * curvature * length**2


def s_blade_end(curvature: float, length: float) -> tuple[float, float]:
    r"""Exact end position ``(x, y)`` of the guided S-blade of :func:`s_blade_deflection_linear` [m].

    .. math:: x = \frac{2 \sin(\kappa L/2)}{\kappa}, \qquad
              y = \frac{2\,(1 - \cos(\kappa L/2))}{\kappa} = \frac{4 \sin^2(\kappa L/4)}{\kappa},

    base at the origin, blade along ``x``; end rotation exactly zero.

    Derivation (inextensible Kirchhoff rod, any deflection): the unloaded blade's shape is
    its free shape, two circular arcs of radius ``1/kappa`` turning by ``+kappa L/2`` and back
    by ``-kappa L/2``.  Its end slope is zero, so the guide (rotation fixed, translation free)
    is satisfied without any end load, and the free shape is the equilibrium for every
    ``kappa``.  The second arc is the first rotated by 180° about the inflection point, so the
    end displacement is twice the first arc's chord vector
    ``(sin(kappa L/2), 1 - cos(kappa L/2))/kappa``.

    Conditions: no load on the guided end (in a parallel guide, two identical blades welded
    to one rigid coupler: each blade's free end pose is the same translation with zero
    rotation, so the coupler fits both without any force); halves of equal length and equal
    ``|kappa|``; the bending stiffness drops out.  For small ``kappa L`` the deflection is
    :math:`y = \frac{\kappa L^2}{4}\,\mathrm{sinc}^2(\kappa L/4)
    \approx \frac{\kappa L^2}{4}\,(1 - (\kappa L)^2/48)` and the end moves back by
    :math:`L - x \approx \kappa^2 L^3 / 24`.

    A chain of rigid cells with joint rest angles equal to the cells' free rotations has its
    joints on the same two arcs' inscribed polygons: its end lies at ``(x, y)`` times
    ``(kappa L_c/2) / sin(kappa L_c/2) ~ 1 + (kappa L_c)²/24`` (cell length ``L_c``).
    """
    if curvature == 0.0:
        return float(length), 0.0
    half = 0.5 * curvature * length
    return 2.0 * math.sin(half) / curvature, 2.0 * (1.0 - math.cos(half)) / curvature


def extension_free_deflection(curvature: float, length: float, extension: float) -> float:
    r"""Small-deflection deflection of the end of a rigid tip extension under free curvature [m].

    A cantilever of length ``L`` with uniform free curvature ``kappa`` carries a rigid
    extension of length ``a`` welded to its tip along the tip tangent.  The tip deflects
    ``kappa L²/2`` and turns by ``kappa L``, so the extension's end deflects
    ``kappa (L²/2 + L a)``.  (A contact point offset *across* the extension moves the point
    along the axis only, to first order.)
    """
    return curvature * (0.5 * length**2 + length * extension)


def extension_compliance(bending_stiffness: float, length: float, extension: float) -> float:
    r"""Compliance ``(L³/3 + L² a + L a²) / EI`` of the end of a rigid tip extension [m/N].

    A force ``F`` across the axis at distance ``a`` beyond the tip loads the tip with ``F``
    and the moment ``F a``: tip deflection ``F L³/(3EI) + F a L²/(2EI)``, tip rotation
    ``F L²/(2EI) + F a L/EI``; the end of the extension deflects by the tip deflection plus
    ``a`` times the rotation (Euler-Bernoulli cantilever formulas, e.g. Timoshenko & Gere,
    *Mechanics of Materials*, App. G).  Equivalently
    :math:`\int_0^L (L + a - s)^2\,ds / EI`.
    """
    return (length**3 / 3.0 + length**2 * extension + length * extension**2) / bending_stiffness


def rigid_chain_extension_compliance(bending_stiffness: float, length: float, extension: float, n_cells: int) -> float:
    r"""Compliance of the same point for a chain of ``N`` rigid cells [m/N].

    The rigid-cell chain has torsion springs ``2EI/L_c`` at both ends (clamp and tip weld)
    and ``EI/L_c`` between cells: its compliance
    :math:`\sum_j (L + a - s_j)^2 / k_j` is the trapezoidal rule of the integral of
    :func:`extension_compliance` with step ``L_c = L/N``.  For a quadratic integrand the
    trapezoidal rule is exact up to ``L L_c² f''/12`` with ``f'' = 2/EI``, so the chain's
    compliance is the beam's plus ``L L_c² / (6 EI)`` exactly (``a = 0``: the factor
    ``1 + 1/(2 N²)`` of :func:`rigid_chain_compliance_factor`).  The free deflection
    (:func:`extension_free_deflection`) has a linear integrand: the chain gives it exactly.
    """
    cell = length / n_cells
    return extension_compliance(bending_stiffness, length, extension) + length * cell**2 / (6.0 * bending_stiffness)


def extension_blocked_force(bending_stiffness: float, curvature: float, length: float, extension: float) -> float:
    r"""Force across the axis that holds the end of a rigid tip extension in place [N].

    :math:`F_b = \frac{\kappa (L^2/2 + L a)}{(L^3/3 + L^2 a + L a^2)/EI}
    = EI\,\kappa\,\frac{L/2 + a}{L^2/3 + L a + a^2}` (small deflection, slope free).
    For ``a = 0`` this is :func:`blocked_force`, ``3 EI kappa / (2L)``.
    """
    return extension_free_deflection(curvature, length, extension) / extension_compliance(
        bending_stiffness, length, extension
    )


def spring_contact_force(free_deflection: float, compliance: float, stiffness: float) -> float:
    r"""Force on an elastic object of stiffness ``k`` pressed by a point of compliance ``c`` [N].

    The point would move ``delta_free`` without the object; against a linear spring it
    stops where ``F = k delta`` and ``delta = delta_free - c F``:
    :math:`F = \delta_{free} / (c + 1/k)`.  ``k -> inf`` gives the blocked force
    ``delta_free / c``.  For two mirrored jaws squeezing one spring of stiffness ``k``
    between them, each jaw sees a spring ``2k`` to the symmetry plane: pass ``2k``.
    """
    return free_deflection / (compliance + 1.0 / stiffness)


def rigid_extension_point(
    tip_x: float | np.ndarray, tip_y: float | np.ndarray, tip_angle: float | np.ndarray, extension: float
) -> tuple:
    """End ``tip + a (cos theta, sin theta)`` of a rigid extension welded along the tip tangent [m].

    ``tip_angle`` is the absolute angle of the tip tangent [rad]; exact rigid-body kinematics
    (the weld keeps the extension's direction equal to the tip tangent).
    """
    angle = np.asarray(tip_angle, dtype=float)
    return np.asarray(tip_x) + extension * np.cos(angle), np.asarray(tip_y) + extension * np.sin(angle)


def curved_cantilever_end_load(
    curvature: float,
    bending_stiffness: float,
    length: float,
    force: tuple[float, float] = (0.0, 0.0),
    extension: tuple[float, float] = (0.0, 0.0),
) -> dict[str, float]:
    r"""Large-deflection equilibrium of a cantilever with free curvature and a dead end force.

    The cantilever (length ``L``, bending stiffness ``EI``, uniform free curvature
    ``kappa``) is clamped at the origin along ``x``.  A rigid extension welded to its tip
    carries the load point ``P = r(L) + a t + c n`` (``t`` the tip tangent, ``n`` its left
    normal, ``extension = (a, c)``), where the dead force ``force = (Fx, Fy)`` acts.

    Kirchhoff's inextensible rod with a natural curvature: the moment about ``r(s)`` of the
    load beyond ``s`` is :math:`M(s) = (P_x - x) F_y - (P_y - y) F_x` and the constitutive
    law :math:`EI(\theta' - \kappa) = M` gives the ODE system
    :math:`x' = \cos\theta,\ y' = \sin\theta,\ \theta' = \kappa + M(s)/EI`,
    :math:`\theta(0) = 0`.  ``P`` is unknown beforehand: it is found by shooting (integrate
    with an assumed ``P``, compare with the ``P`` the end state gives, solve with
    ``scipy.optimize.root``; integration with ``DOP853``, relative tolerance 1e-12).
    Without free curvature this is the elastica of Bisshopp & Drucker (1945).

    Returns
    -------
    dict
        ``tip_x``, ``tip_y`` [m], ``tip_angle`` [rad], ``point_x``, ``point_y`` [m].

    Raises
    ------
    RuntimeError
        If the shooting does not converge (a load far beyond the buckling range).
    """
    from scipy.integrate import solve_ivp
    from scipy.optimize import root

    kappa = float(curvature)
    ei = float(bending_stiffness)
    if not ei > 0.0:
        raise ValueError(f"bending_stiffness must be > 0 [N m^2], got {shown(bending_stiffness)}")
    fx, fy = (float(v) for v in force)
    a, c = (float(v) for v in extension)

    def end_state(p: np.ndarray) -> np.ndarray:
        def rhs(_s, z):
            x, y, th = z
            moment = (p[0] - x) * fy - (p[1] - y) * fx
            return [math.cos(th), math.sin(th), kappa + moment / ei]

        sol = solve_ivp(rhs, (0.0, length), [0.0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-15)
        return sol.y[:, -1]

    def point(z: np.ndarray) -> np.ndarray:
        x, y, th = z
        return np.array([x + a * math.cos(th) - c * math.sin(th), y + a * math.sin(th) + c * math.cos(th)])

    guess = point(np.array([*arc_point(kappa, length), kappa * length], dtype=float))
    def residual(p: np.ndarray) -> np.ndarray:
        return (point(end_state(p)) - p) / length

    sol = root(residual, guess, method="hybr", tol=1e-13)
    if float(np.max(np.abs(residual(sol.x)))) > 1e-10:
        raise RuntimeError(f"curved_cantilever_end_load: shooting did not converge ({sol.message}) for force {force!r} N")
    z = end_state(sol.x)
    p = point(z)
    return {"tip_x": float(z[0]), "tip_y": float(z[1]), "tip_angle": float(z[2]),
            "point_x": float(p[0]), "point_y": float(p[1])}


def curved_cantilever_spring_force(
    curvature: float,
    bending_stiffness: float,
    length: float,
    extension: tuple[float, float],
    stiffness: float,
) -> float:
    r"""Large-deflection force [N] on a spring that resists the load point's ``y`` motion.

    The load point of :func:`curved_cantilever_end_load` is tied to a linear spring along
    ``y`` of stiffness ``k`` (``inf``: held in place, the blocked force), unloaded in the
    straight pose.  The equilibrium force ``F`` satisfies
    ``F = k (y_P(F) - y_P0)`` with the spring force ``-F`` acting on the point along ``y``;
    solved by Brent's method.  Returns ``F`` (positive when the point is pushed back towards
    ``-y`` for a positive curvature).
    """
    from scipy.optimize import brentq

    c = float(extension[1])
    free = curved_cantilever_end_load(curvature, bending_stiffness, length, (0.0, 0.0), extension)["point_y"] - c
    if free == 0.0:
        return 0.0
    blocked_guess = abs(extension_blocked_force(bending_stiffness, curvature, length, float(extension[0])))

    def residual(f: float) -> float:
        y = curved_cantilever_end_load(curvature, bending_stiffness, length, (0.0, -f), extension)["point_y"] - c
        return y if math.isinf(stiffness) else f - stiffness * y

    sign = 1.0 if free > 0 else -1.0
    low, high = 0.0, sign * 2.0 * blocked_guess
    while residual(low) * residual(high) > 0.0:
        high *= 2.0
    return float(brentq(residual, min(low, high), max(low, high), xtol=1e-15, rtol=1e-13))
