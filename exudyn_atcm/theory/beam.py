"""Closed-form reference formulas for the two-layer piezo bending actuator: the laminate and the cantilever.

These functions are the independent references the validation tests compare the multibody
model against.  They are plain formulas of classical beam theory (Euler-Bernoulli,
perfectly bonded layers, small strains) and deliberately share no code with the model
(:mod:`exudyn_atcm.mechanism.actuator`, :mod:`exudyn_atcm.mbs.builder`).  The
references of the mechanism cases are in :mod:`exudyn_atcm.theory.beam_mechanisms`, the
dynamic ones in :mod:`exudyn_atcm.theory.beam_dynamics`; all of them are exported by
:mod:`exudyn_atcm.theory`.

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
from .._checks import shown

__all__ = [
    "ELASTICA_TIP_FORCE",
    "second_moment",
    "axial_rigidity",
    "layer_offset",
    "series_axial_rigidity",
    "composite_bending_stiffness",
    "paper_bending_stiffness",
    "free_curvature",
    "paper_free_curvature",
    "piezo_strain",
    "linear_tip_deflection",
    "arc_point",
    "chain_polygon",
    "blocked_force",
    "tip_compliance",
    "rigid_chain_compliance_factor",
    "six_bar_chain_compliance_factor",
    "beam_element_compliance_factor",
    "mass_per_length",
    "actuator_work",
    "optimal_thickness_ratio",
]

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


def mass_per_length(rho1: float, h1: float, rho2: float, h2: float, width: float) -> float:
    """Mass per unit length ``b (rho1 h1 + rho2 h2)`` of the laminate [kg/m]."""
    return width * (rho1 * h1 + rho2 * h2)


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
        raise ValueError(f"modulus_ratio must be a finite number > 0, got {shown(modulus_ratio)}")
    roots = np.roots([n * n, 3.0 * n * n - 2.0 * n, -3.0 * n, -5.0 * n, -2.0])
    positive = [r.real for r in roots if abs(r.imag) <= 1e-9 * max(1.0, abs(r)) and r.real > 0.0]
    t = max(positive)
    # one Newton step on the quartic polishes the root to machine precision
    p = np.polynomial.Polynomial([-2.0, -5.0 * n, -3.0 * n, 3.0 * n * n - 2.0 * n, n * n])
    return float(t - p(t) / p.deriv()(t))
