"""Exact time integration of the ``rod`` cell's Ritz space: the reference for its dynamics.

A clamped rod of :mod:`.rotation_rod` (base fixed, ``n`` modes ``q`` [rad]) obeys

    M(q) q_ddot + g(q, q_dot) + K q + beta K q_dot = Q(q),

with the exact mass matrix and quadratic velocity vector of :mod:`.rotation_rod` (numpy), ``K`` the
modes' stiffness and ``Q`` the generalised force of a tip force ``F`` [N] (dead: ``J(q)^T F``;
follower: ``J(q)^T R(theta_tip) F``, the force given in the reference pose and turned with the tip),
of a tip moment ``m`` [N m] (``phi(1) m``: ``q_1`` only) and of a free curvature, which loads
``q_1`` alike (``EI kappa``).  :func:`integrate_clamped_rod` integrates this system of ordinary
differential equations with scipy's ``solve_ivp`` at tight tolerances: an independent check of the
Exudyn realisation's time integration (:mod:`exudyn_atcm.mbs.chains.rod`, which uses the compiled
kernels, a moving base node and a tied tip node), not of the Ritz discretisation itself.

Without damping the energy ``E = 1/2 q_dot^T M q_dot + 1/2 q^T K q - F . r_tip - m theta_tip``
(dead force and moment) is conserved; :func:`energy` evaluates it.

May import: numpy, scipy (and :mod:`.rotation_rod`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from . import rotation_rod

__all__ = ["ClampedRod", "RodMotion", "integrate_clamped_rod", "tip_position", "energy"]


@dataclass(frozen=True)
class ClampedRod:
    """A clamped rod of ``n`` modes under constant tip loads (from rest, released at ``t = 0``).

    Attributes
    ----------
    n : int
        Modes.
    length : float
        ``L`` [m].
    bending_stiffness : float
        ``EI`` [N m^2].
    mass_per_length : float
        ``mu`` [kg/m].
    rotary_inertia : float
        ``rho_I`` [kg m].
    tip_force : (float, float)
        Tip force [N] (global components; a follower force: in the reference pose).
    follower : bool
        The tip force turns with the tip's rotation.
    tip_moment : float
        Moment on ``q_1`` [N m] (a tip moment, or ``EI kappa`` of a free curvature ``kappa``).
    beta : float
        Stiffness-proportional damping factor [s] (0: undamped).
    onset : float
        The loads rise over ``onset`` [s] as ``(1 - cos(pi t / onset)) / 2`` (continuous force and
        rate, so that an integrator started at rest with zero acceleration is consistent); 0: a step
        at ``t = 0``.
    """

    n: int
    length: float
    bending_stiffness: float
    mass_per_length: float
    rotary_inertia: float
    tip_force: tuple[float, float] = (0.0, 0.0)
    follower: bool = False
    tip_moment: float = 0.0
    beta: float = 0.0
    onset: float = 0.0

    def load_factor(self, t: float) -> float:
        """The loads' fraction at time ``t`` [s]."""
        if t >= self.onset:
            return 1.0
        return 0.5 * (1.0 - math.cos(math.pi * max(t, 0.0) / self.onset))

    @property
    def shapes(self) -> rotation_rod.RodShapes:
        return rotation_rod.rod_shapes(self.n, self.length)

    @functools.cached_property
    def _arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        shapes = self.shapes
        lw = shapes.length * shapes.weights
        rotary = self.rotary_inertia * (shapes.phi.T * lw) @ shapes.phi
        return shapes.phi, shapes.length * shapes.integration, lw, rotary, shapes.stiffness_matrix(self.bending_stiffness)

    @property
    def stiffness(self) -> np.ndarray:
        """``K`` [N m / rad]."""
        return self._arrays[4]

    def tip_jacobian(self, q: np.ndarray) -> np.ndarray:
        """``d r_tip / d q`` (2 x n) [m/rad]."""
        phi, _, lw, _, _ = self._arrays
        theta = phi @ q
        return np.stack([-(lw * np.sin(theta)) @ phi, (lw * np.cos(theta)) @ phi])

    def generalised_force(self, q: np.ndarray, t: float = math.inf) -> np.ndarray:
        """``Q(q)`` [N m] of the tip force and moment at time ``t`` [s]."""
        f = np.asarray(self.tip_force, dtype=float)
        if self.follower:
            a = float(q[0])  # the tip's rotation: phi_1(1) = 1, the other shapes vanish at the tip
            f = np.array([math.cos(a) * f[0] - math.sin(a) * f[1], math.sin(a) * f[0] + math.cos(a) * f[1]])
        out = self.tip_jacobian(q).T @ f
        out[0] += self.tip_moment
        return self.load_factor(t) * out

    def inertia(self, q: np.ndarray, q_dot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Mass matrix ``M(q)`` [kg m^2] and quadratic velocity vector ``g(q, q_dot)`` [N m].

        From the velocity of the points of the quadrature rule, ``r_dot = A(q) q_dot`` with
        ``A = d r / d q`` (``r`` the integral of ``(cos theta, sin theta)`` from the base), and its
        time derivative ``A_dot q_dot = b`` (the integral of ``-(cos theta, sin theta) theta_dot^2``):
        ``M = int mu A^T A + rho_I phi phi^T``, ``g = int mu A^T b``.
        """
        phi, s, lw, rotary, _ = self._arrays
        theta = phi @ q
        rate2 = (phi @ q_dot) ** 2
        c, sn = np.cos(theta), np.sin(theta)
        ax = -s @ (sn[:, None] * phi)
        ay = s @ (c[:, None] * phi)
        bx = -s @ (c * rate2)
        by = -s @ (sn * rate2)
        mu = self.mass_per_length
        mass = mu * ((ax.T * lw) @ ax + (ay.T * lw) @ ay) + rotary
        return mass, mu * ((ax.T * lw) @ bx + (ay.T * lw) @ by)

    def acceleration(self, q: np.ndarray, q_dot: np.ndarray, t: float = math.inf) -> np.ndarray:
        """``q_ddot`` [rad/s^2] of the equations of motion at time ``t`` [s]."""
        k = self.stiffness
        mass, g = self.inertia(q, q_dot)
        return np.linalg.solve(mass, self.generalised_force(q, t) - g - k @ q - self.beta * (k @ q_dot))


class RodMotion:
    """The reference motion of :func:`integrate_clamped_rod`: ``motion(t)`` is ``(q, q_dot)`` stacked (2 n,
    or 2 n x len(t)) from scipy's dense output of each piece (before and after the loads' onset)."""

    def __init__(self, pieces: list, n: int) -> None:
        self.pieces = pieces
        self.n = n
        self.evaluations = sum(int(p.nfev) for p in pieces)

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        if len(self.pieces) == 1:
            return self.pieces[0].sol(t)
        first, second = self.pieces
        boundary = first.t[-1]
        out = np.empty((2 * self.n,) + t.shape)
        early = t <= boundary
        if np.any(early):
            out[..., early] = first.sol(t[early])
        if np.any(~early):
            out[..., ~early] = second.sol(t[~early])
        return out


def integrate_clamped_rod(rod: ClampedRod, t_end: float, rtol: float = 1e-11, method: str = "DOP853") -> RodMotion:
    """Integrate ``rod`` from rest in the straight pose over ``[0, t_end]`` [s].

    Returns the :class:`RodMotion`: ``(q, q_dot)`` at any time, from scipy's dense output (one
    integration before the loads' onset ends, one after, so that the kink of the loads' rate is a
    step boundary).  The absolute tolerance is ``rtol`` times 1e-3 rad (and rad/s).
    """
    n = rod.n

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        return np.concatenate([y[n:], rod.acceleration(y[:n], y[n:], t)])

    pieces = []
    y0 = np.zeros(2 * n)
    bounds = [0.0, float(t_end)] if not 0.0 < rod.onset < t_end else [0.0, rod.onset, float(t_end)]
    for start, end in zip(bounds, bounds[1:]):
        out = solve_ivp(rhs, (start, end), y0, method=method, rtol=rtol, atol=rtol * 1e-3, dense_output=True)
        if not out.success:
            raise RuntimeError(f"the reference integration failed between t = {start} and {end} s: {out.message}")
        pieces.append(out)
        y0 = out.y[:, -1]
    return RodMotion(pieces, n)


def tip_position(rod: ClampedRod, q: np.ndarray) -> np.ndarray:
    """Tip ``(x, y)`` [m] in the rod's frame."""
    return rotation_rod.tip_pose(rod.shapes, q)[:2]


def energy(rod: ClampedRod, q: np.ndarray, q_dot: np.ndarray) -> float:
    """Total energy [J] of a dead tip force and moment: kinetic plus elastic minus the loads' potential
    (conserved without damping once the loads are constant, ``t >= onset``)."""
    if rod.follower:
        raise ValueError("energy: a follower force has no potential (follower must be False)")
    mass, _ = rod.inertia(q, q_dot)
    pose = rotation_rod.tip_pose(rod.shapes, q)
    # the load's potential counted from the straight reference pose (tip at (L, 0), angle 0)
    work = (rod.tip_force[0] * (pose[0] - rod.length) + rod.tip_force[1] * pose[1] + rod.tip_moment * pose[2])
    return float(0.5 * q_dot @ mass @ q_dot + 0.5 * q @ rod.stiffness @ q - work)
