"""Closed-form reference formulas for the two-layer piezo bending actuator.

These functions are the independent references the validation tests compare the multibody
model against.  They are plain formulas of classical beam theory (Euler-Bernoulli,
perfectly bonded layers, small strains) and deliberately share no code with the model
(:mod:`exudyn_atcm.mechanism.actuator`, :mod:`exudyn_atcm.mbs.actuator_chains`).

Layer 1 is the passive layer (CFC), layer 2 the active layer (MFC).  All quantities in SI
units: m, N, Pa, kg/m³; strains are unit-free.

References
----------
S. Timoshenko, "Analysis of bi-metal thermostats", J. Opt. Soc. Am. 11:233-255, 1925.
K. E. Bisshopp, D. C. Drucker, "Large deflection of cantilever beams",
Q. Appl. Math. 3:272-275, 1945.
"""

from __future__ import annotations

import math

import numpy as np

#: First root of ``1 + cos(x) cosh(x) = 0`` (clamped-free Euler-Bernoulli beam).
BETA1_L = 1.8751040687119611

#: Elastica of a cantilever under a tip force perpendicular to the undeformed axis
#: (Bisshopp & Drucker, Q. Appl. Math. 3:272, 1945): alpha = F L²/EI -> (y/L, 1 - x/L).
ELASTICA_TIP_FORCE = {
    1.0: (0.30172, 0.05643),
    2.0: (0.49346, 0.16064),
    5.0: (0.71379, 0.38763),
}


def second_moment(width: float, thickness: float) -> float:
    """Second moment of area ``b h³ / 12`` of a rectangular layer [m⁴] (Eq. 6)."""
    return width * thickness**3 / 12.0


def axial_rigidity(youngs_modulus: float, width: float, thickness: float) -> float:
    """Axial rigidity ``a = E b h`` of a layer [N]."""
    return youngs_modulus * width * thickness


def layer_offset(h1: float, h2: float) -> float:
    """Distance ``e = (h1 + h2) / 2`` between the mid-planes of the two layers [m]."""
    return 0.5 * (h1 + h2)


def series_axial_rigidity(E1: float, h1: float, E2: float, h2: float, width: float) -> float:
    """``a1 a2 / (a1 + a2)`` [N]: the two layers' axial rigidities in series."""
    a1 = axial_rigidity(E1, width, h1)
    a2 = axial_rigidity(E2, width, h2)
    return a1 * a2 / (a1 + a2)


def composite_bending_stiffness(E1: float, h1: float, E2: float, h2: float, width: float) -> float:
    """Bending stiffness of the bonded two-layer laminate (lamination theory) [N m²].

    ``EI = E1 I1 + E2 I2 + [a1 a2 / (a1 + a2)] e²``.
    """
    e = layer_offset(h1, h2)
    return (
        E1 * second_moment(width, h1)
        + E2 * second_moment(width, h2)
        + series_axial_rigidity(E1, h1, E2, h2, width) * e**2
    )


def paper_bending_stiffness(E1: float, h1: float, E2: float, h2: float, width: float) -> float:
    """Bending stiffness of the paper's cell as printed (rigid passive bar, ``k1 = E2 b h2/L``) [N m²].

    ``EI = E1 I1 + E2 I2 + E2 A2 e²`` (the passive layer taken as axially rigid), with the torsion springs doubled as the
    paper's text says.
    """
    e = layer_offset(h1, h2)
    return (
        E1 * second_moment(width, h1)
        + E2 * second_moment(width, h2)
        + axial_rigidity(E2, width, h2) * e**2
    )


def free_curvature(E1: float, h1: float, E2: float, h2: float, width: float, strain: float) -> float:
    """Free curvature of the laminate under an active-layer strain mismatch ``strain`` [1/m].

    ``kappa = [a1 a2/(a1 + a2)] e strain / EI`` (Timoshenko's bimetal formula).
    """
    e = layer_offset(h1, h2)
    return (
        series_axial_rigidity(E1, h1, E2, h2, width)
        * e
        * strain
        / composite_bending_stiffness(E1, h1, E2, h2, width)
    )


def paper_free_curvature(E1: float, h1: float, E2: float, h2: float, width: float, strain: float) -> float:
    """Free curvature of the paper's printed cell: ``a2 e strain / (E1I1 + E2I2 + a2 e²)`` [1/m]."""
    e = layer_offset(h1, h2)
    return (
        axial_rigidity(E2, width, h2)
        * e
        * strain
        / paper_bending_stiffness(E1, h1, E2, h2, width)
    )


def piezo_strain(voltage: float, d33: float = 460e-12, electrode_spacing: float = 0.5e-3) -> float:
    """Linear free strain ``d33 U / t_IDE`` (Eq. 3) [-]."""
    return d33 * voltage / electrode_spacing


def linear_tip_deflection(curvature: float, length: float) -> float:
    """Small-deflection tip deflection ``kappa L² / 2`` of a uniformly curved cantilever [m]."""
    return 0.5 * curvature * length**2


def arc_point(curvature: float, s: float | np.ndarray) -> tuple:
    """Point at arc length ``s`` of a circular arc from the origin, tangent to x [m].

    ``x = sin(kappa s)/kappa``, ``y = (1 - cos(kappa s))/kappa`` (straight line for kappa = 0).
    """
    s = np.asarray(s, dtype=float)
    if curvature == 0.0:
        return s * 1.0, s * 0.0
    return np.sin(curvature * s) / curvature, (1.0 - np.cos(curvature * s)) / curvature


def chain_polygon(curvature: float, length: float, n_segments: int) -> tuple[np.ndarray, np.ndarray]:
    """Vertices of a chain of ``n`` rigid segments of length ``L/n`` bent uniformly [m].

    Segment ``j`` (0-based) makes the angle ``(j + 1/2) kappa L / n`` with x: the polygon of
    a chain of rigid links whose joints sit on a circle and turn by ``kappa L/n`` each, the
    first link starting tangent-symmetric at the clamp (half a cell's turn at the clamp).
    Its vertices lie on a circle of radius ``(L/n) / (2 sin(kappa L / 2n))``, which tends
    to ``1/kappa`` as ``n`` grows.

    Returns
    -------
    x, y : numpy.ndarray
        ``n + 1`` vertex coordinates, the first at the origin.
    """
    lc = length / n_segments
    angles = (np.arange(n_segments) + 0.5) * curvature * lc
    x = np.concatenate([[0.0], np.cumsum(lc * np.cos(angles))])
    y = np.concatenate([[0.0], np.cumsum(lc * np.sin(angles))])
    return x, y


def blocked_force(bending_stiffness: float, curvature: float, length: float) -> float:
    """Force that holds the tip of a freely curving cantilever at y = 0 (slope free) [N]."""
    return 1.5 * bending_stiffness * curvature / length


def tip_compliance(bending_stiffness: float, length: float) -> float:
    """Tip compliance ``L³ / (3 EI)`` of a cantilever under a small tip force [m/N]."""
    return length**3 / (3.0 * bending_stiffness)


def rigid_chain_compliance_factor(n_cells: int) -> float:
    """Compliance factor ``1 + 1/(2 N²)`` of a chain of N rigid cells under a small tip force (derived on the theory page of the documentation).

    Springs ``EI/L_c`` inside and ``2 EI/L_c`` at the clamp.
    """
    return 1.0 + 1.0 / (2.0 * n_cells**2)


def six_bar_chain_compliance_factor(n_cells: int, spring_share: float) -> float:
    """Compliance factor ``1 + (3/(4 rho_s) - 1/4)/N²`` of a chain of six-bar cells under a small tip force (derived on the theory page of the documentation).

    ``spring_share`` is the share ``rho_s`` of the bending stiffness held by the torsion
    springs, ``(E1 I1 + E2 I2) / EI``.
    """
    return 1.0 + (0.75 / spring_share - 0.25) / n_cells**2


def beam_element_compliance_factor(n_elements: int) -> float:
    """Compliance factor ``1 - 1/(4 N²)`` of N linear shear-rigid beam elements under a small tip force.

    Two-node elements with one-point (mid-element) integration, as Exudyn's
    ``ObjectBeamGeometricallyExact2D``: the rotation is linear in each element and the
    deflection follows the element's mid rotation (trapezoidal rule over the node
    rotations), so ``y = (F L³ / 3EI)(1 - 1/(4 N²))`` exactly (N = 1: ``F L³ / 4EI``).
    Cubic (Hermite / ANCF cable) elements reproduce the cubic deflection exactly: factor 1.
    """
    return 1.0 - 1.0 / (4.0 * n_elements**2)


def first_bending_frequency(bending_stiffness: float, mass_per_length: float, length: float) -> float:
    """First bending eigenfrequency of a clamped-free beam [Hz].

    ``f1 = 1.875104² / (2 pi L²) sqrt(EI / mu)``.
    """
    return BETA1_L**2 / (2.0 * math.pi * length**2) * math.sqrt(bending_stiffness / mass_per_length)


def mass_per_length(rho1: float, h1: float, rho2: float, h2: float, width: float) -> float:
    """Mass per unit length ``b (rho1 h1 + rho2 h2)`` of the laminate [kg/m]."""
    return width * (rho1 * h1 + rho2 * h2)


# ----------------------------------------------------------------------------- mechanisms
# References for the mechanism cases: the guided S-shaped blade (parallel guide), the bender
# with a rigid extension (lever, gripper jaw), and the curved cantilever under an end force
# in large deflection (Kirchhoff rod with a free curvature, solved by shooting).


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
        raise ValueError(f"bending_stiffness must be > 0 [N m^2], got {bending_stiffness!r}")
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


def actuator_work(E1: float, h1: float, E2: float, h2: float, width: float, strain: float, length: float) -> float:
    """Product of free tip deflection and blocked tip force, ``delta_free F_b`` [J].

    With ``delta_free = kappa L²/2`` (:func:`linear_tip_deflection`) and
    ``F_b = 1.5 EI kappa / L`` (:func:`blocked_force`), ``W = 0.75 L EI kappa²``, and with
    Timoshenko's curvature ``kappa = a_s e strain / EI`` (:func:`free_curvature`,
    ``a_s = a1 a2/(a1 + a2)``)::

        W = 0.75 L (a_s e strain)² / EI = 2.25 L strain² E2 b h2 g(n, t),
        g(n, t) = n² t² (1 + t)² / [(1 + n t)(1 + 4nt + 6nt² + 4nt³ + n²t⁴)]

    with ``n = E1/E2`` and ``t = h1/h2``.
    """
    kappa = free_curvature(E1, h1, E2, h2, width, strain)
    return linear_tip_deflection(kappa, length) * blocked_force(composite_bending_stiffness(E1, h1, E2, h2, width), kappa, length)


def optimal_thickness_ratio(modulus_ratio: float) -> float:
    """Passive-to-active thickness ratio ``t = h1/h2`` that maximises :func:`actuator_work` [-].

    For a given active layer (``E2``, ``h2``, strain) and modulus ratio ``n = E1/E2``,
    ``d ln g / dt = 0`` factors into ``(n t² + 2t + 1)(n² t⁴ + (3n² - 2n) t³ - 3n t² - 5n t - 2) = 0``;
    the first factor is positive, and the quartic has exactly one positive root
    (one sign change, Descartes), the optimum.  For ``n = 1`` the quartic is
    ``(t - 2)(t + 1)³``: the passive layer twice as thick as the active one.

    Raises
    ------
    ValueError
        If ``modulus_ratio`` is not a finite positive number.
    """
    n = float(modulus_ratio)
    if not (math.isfinite(n) and n > 0.0):
        raise ValueError(f"modulus_ratio must be a finite number > 0, got {modulus_ratio!r}")
    roots = np.roots([n * n, 3.0 * n * n - 2.0 * n, -3.0 * n, -5.0 * n, -2.0])
    positive = [r.real for r in roots if abs(r.imag) <= 1e-9 * max(1.0, abs(r)) and r.real > 0.0]
    t = max(positive)
    # one Newton step on the quartic polishes the root to machine precision
    p = np.polynomial.Polynomial([-2.0, -5.0 * n, -3.0 * n, 3.0 * n * n - 2.0 * n, n * n])
    return float(t - p(t) / p.deriv()(t))


def end_moment_tip_rotation(bending_stiffness: float, mass_per_length: float, length: float,
                            damping_factor: float, times: np.ndarray, moments: np.ndarray,
                            n_modes: int = 30) -> np.ndarray:
    r"""Tip rotation [rad] of the Euler-Bernoulli cantilever under a time-varying end moment.

    Modal solution (mode-acceleration form) of the clamped-free beam with stiffness-proportional
    damping, loaded at the tip by the moment ``M(t)`` [N m], piecewise linear between ``times``,
    starting at rest in the static state of ``M(times[0])``.

    Parameters
    ----------
    bending_stiffness : float
        ``EI`` [N m²].
    mass_per_length : float
        ``mu`` [kg/m] (rotary inertia neglected).
    length : float
        ``L`` [m].
    damping_factor : float
        ``beta`` [s]: damping ``beta K``, modal damping ratio ``zeta_r = beta omega_r / 2``.
    times : numpy.ndarray
        Increasing times [s].
    moments : numpy.ndarray
        End moment [N m] at ``times``.
    n_modes : int, optional
        Number of modes (default 30; the remainder is static, see Notes).

    Returns
    -------
    numpy.ndarray
        Tip rotation [rad] at ``times``.

    Notes
    -----
    With the mass-normalised modes ``phi_r`` (``int mu phi_r² = 1``, ``omega_r = (beta_r L)²
    sqrt(EI/mu)/L²``, ``1 + cos(beta_r L) cosh(beta_r L) = 0``) the end moment's generalised force
    is ``M phi_r'(L)``, so the modal coordinates obey ``y_r'' + 2 zeta_r omega_r y_r' + omega_r² y_r =
    omega_r² M`` for ``eta_r = phi_r'(L) y_r / omega_r²``.  The tip rotation ``sum phi_r'(L) eta_r``
    is written in mode-acceleration form: the static part ``M L / EI`` (all modes) plus the
    dynamic parts ``w_r (y_r - M)``, ``w_r = phi_r'(L)² / omega_r²``, of the first ``n_modes``
    modes, whose weights fall like ``1/r²``, so the truncation leaves only the fast dynamics of the
    higher modes out.  With ``phi = cosh - cos - sigma (sinh - sin)`` of ``beta x``
    (``int_0^L phi² = L``), ``sigma = (cosh + cos)/(sinh + sin)`` of ``beta_r L``, the weight is
    ``phi'(L)² / (mu L omega_r²)``.  Each modal equation is integrated exactly for the piecewise
    linear input (``scipy.signal.lsim``).
    """
    from scipy.optimize import brentq  # noqa: PLC0415 - only this reference needs scipy
    from scipy.signal import lsim  # noqa: PLC0415

    EI, mu, L = bending_stiffness, mass_per_length, length
    times = np.asarray(times, dtype=float)
    moments = np.asarray(moments, dtype=float)
    theta = moments * L / EI
    for r in range(1, n_modes + 1):
        guess = (r - 0.5) * math.pi
        bl = BETA1_L if r == 1 else brentq(lambda x: 1.0 + math.cos(x) * math.cosh(x), guess - 0.3, guess + 0.3)
        sigma = (math.cosh(bl) + math.cos(bl)) / (math.sinh(bl) + math.sin(bl))
        dphi = bl / L * (math.sinh(bl) + math.sin(bl) - sigma * (math.cosh(bl) - math.cos(bl)))
        omega = bl**2 / L**2 * math.sqrt(EI / mu)
        weight = dphi**2 / (mu * L * omega**2)
        zeta = 0.5 * damping_factor * omega
        a = np.array([[0.0, 1.0], [-omega**2, -2.0 * zeta * omega]])
        b = np.array([[0.0], [omega**2]])
        c = np.array([[1.0, 0.0]])
        d = np.array([[0.0]])
        _, y, _ = lsim((a, b, c, d), moments, times, X0=[moments[0], 0.0], interp=True)
        theta = theta + weight * (y - moments)
    return theta

