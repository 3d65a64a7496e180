"""Dynamic references of the clamped-free bender: its first bending frequency and the modal
solution under a time-varying end moment.  They share no code with the model; SI units.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "BETA1_L",
    "first_bending_frequency",
    "end_moment_tip_rotation",
]

#: First root of ``1 + cos(x) cosh(x) = 0`` (clamped-free Euler-Bernoulli beam).
BETA1_L = 1.8751040687119611

def first_bending_frequency(bending_stiffness: float, mass_per_length: float, length: float) -> float:
    """First bending eigenfrequency of a clamped-free beam [Hz].

    ``f1 = 1.875104² / (2 pi L²) sqrt(EI / mu)``.
    """
    return BETA1_L**2 / (2.0 * math.pi * length**2) * math.sqrt(bending_stiffness / mass_per_length)


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
