"""Compiled kernels of the ``rod`` cell's step (numba): the formulas of :mod:`.rotation_rod`.

The ``rod`` cell re-evaluates its mass matrix, quadratic velocity vector and the linearisation
of its tip pose once per attempted step (and once per extra Newton pass, see
:mod:`exudyn_atcm.mbs.chains.rod`).  In numpy that is some 35 small array operations (about
75 µs on the development machine); compiled, about 10 µs, so the step stays near the cost of
Exudyn's own beam elements.  Compiled on first use and cached on disk (numba's ``cache=True``);
imported only when a ``rod`` bender is built.

May import: numpy, numba.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["step_matrices", "tip_pose", "geometric_stiffness", "linearisation", "tip_gap", "PARAMETERS"]

#: Order of the scalar parameters packed into one array for :func:`linearisation` and :func:`tip_gap`
#: (fewer arguments: numba's dispatch costs about 0.2 µs per argument).
PARAMETERS = ("length", "mass_per_length", "rotary_inertia", "base_x", "base_y", "cos_a", "sin_a", "angle")


@numba.njit(cache=True)
def tip_pose(q, phi, weights, length, phi_tip):  # pragma: no cover - compiled
    """Tip ``(x, y, theta)`` in the rod's frame and the Jacobian rows of ``x`` and ``y`` (2 x n)."""
    n_points, n = phi.shape
    x = 0.0
    y = 0.0
    jac = np.zeros((2, n))
    for k in range(n_points):
        th = 0.0
        for i in range(n):
            th += phi[k, i] * q[i]
        lw = length * weights[k]
        c = math.cos(th)
        s = math.sin(th)
        x += lw * c
        y += lw * s
        for i in range(n):
            jac[0, i] -= lw * s * phi[k, i]
            jac[1, i] += lw * c * phi[k, i]
    theta = 0.0
    for i in range(n):
        theta += phi_tip[i] * q[i]
    return x, y, theta, jac


@numba.njit(cache=True)
def step_matrices(q, q_dot, phi, integration, weights, length, mass_per_length, rotary_inertia, phi_tip,
                  base_x, base_y, cos_a, sin_a, angle):  # pragma: no cover - compiled
    """Mass matrix ``M(q)``, force ``-g(q, q_dot)``, and the tip constraint linearised at ``q``.

    Returns ``(mass, force, x1, offset)``: Exudyn's ``ObjectConnectorCoordinateVector``
    equation ``x1 q - q_tip - offset = 0`` with ``q_tip`` the tip node's ``(x, y, angle)`` in
    global coordinates: ``x1 = R dP/dq``, ``offset = x1 q - (base + R P(q))`` with ``P`` the tip
    pose in the rod's frame and ``R`` the rotation by the bender's angle.
    """
    n_points, n = phi.shape
    theta = np.empty(n_points)
    rate = np.empty(n_points)
    for k in range(n_points):
        th = 0.0
        om = 0.0
        for i in range(n):
            th += phi[k, i] * q[i]
            om += phi[k, i] * q_dot[i]
        theta[k] = th
        rate[k] = om
    c = np.cos(theta)
    s = np.sin(theta)
    ax = np.zeros((n_points, n))
    ay = np.zeros((n_points, n))
    bx = np.zeros(n_points)
    by = np.zeros(n_points)
    for j in range(n_points):
        for k in range(n_points):
            w = length * integration[j, k]
            if w == 0.0:
                continue
            r2 = rate[k] * rate[k]
            bx[j] -= w * c[k] * r2
            by[j] -= w * s[k] * r2
            for i in range(n):
                ax[j, i] -= w * s[k] * phi[k, i]
                ay[j, i] += w * c[k] * phi[k, i]
    mass = np.zeros((n, n))
    force = np.zeros(n)
    for j in range(n_points):
        lw = length * weights[j]
        for i in range(n):
            force[i] -= mass_per_length * lw * (ax[j, i] * bx[j] + ay[j, i] * by[j])
            for m in range(i, n):
                value = lw * (mass_per_length * (ax[j, i] * ax[j, m] + ay[j, i] * ay[j, m])
                              + rotary_inertia * phi[j, i] * phi[j, m])
                mass[i, m] += value
    for i in range(n):
        for m in range(i):
            mass[i, m] = mass[m, i]
    x, y, th_tip, jac = tip_pose(q, phi, weights, length, phi_tip)
    x1 = np.zeros((3, n))
    offset = np.zeros(3)
    for i in range(n):
        x1[0, i] = cos_a * jac[0, i] - sin_a * jac[1, i]
        x1[1, i] = sin_a * jac[0, i] + cos_a * jac[1, i]
        x1[2, i] = phi_tip[i]
    offset[0] = -(base_x + cos_a * x - sin_a * y)
    offset[1] = -(base_y + sin_a * x + cos_a * y)
    offset[2] = -(angle + th_tip)
    for r in range(3):
        for i in range(n):
            offset[r] += x1[r, i] * q[i]
    return mass, force, x1, offset


@numba.njit(cache=True)
def geometric_stiffness(q, phi, weights, length, lam_x, lam_y, cos_a, sin_a):  # pragma: no cover - compiled
    """``lam . d^2 (R P(q)) / dq^2`` (n x n): the curvature of the tip constraint times its multipliers
    ``lam_x``, ``lam_y`` [N] (the rotation row is linear in ``q``)."""
    n_points, n = phi.shape
    out = np.zeros((n, n))
    for k in range(n_points):
        th = 0.0
        for i in range(n):
            th += phi[k, i] * q[i]
        lw = length * weights[k]
        hx = -lw * math.cos(th)  # d2x/dq2 = -sum lw cos(theta) phi phi^T
        hy = -lw * math.sin(th)
        factor = lam_x * (cos_a * hx - sin_a * hy) + lam_y * (sin_a * hx + cos_a * hy)
        for i in range(n):
            for m in range(n):
                out[i, m] += factor * phi[k, i] * phi[k, m]
    return out


@numba.njit(cache=True)
def linearisation(coordinates, velocities, start, h, lam, stiffness, phi, integration, weights, phi_tip, parameters,
                  mass, tangent, force, x1, offset):  # pragma: no cover - compiled
    """Everything the rod's items need for one step or Newton pass, written into the last five arrays.

    ``coordinates`` / ``velocities``: the system's ODE2 arrays; the rod's ``n`` coordinates start at
    ``start``; the state of linearisation is ``q + h q_dot``.  ``lam``: the tie's current
    multipliers, or an empty array to leave out the geometric stiffness.  Writes ``mass``,
    ``tangent = stiffness + kg``, ``force = -g + kg q``, ``x1`` and ``offset`` (see
    :func:`step_matrices`; ``kg`` = :func:`geometric_stiffness` at ``-lam``).
    """
    n = phi.shape[1]
    q = np.empty(n)
    q_dot = np.empty(n)
    for i in range(n):
        q_dot[i] = velocities[start + i]
        q[i] = coordinates[start + i] + h * q_dot[i]
    m_, f_, x1_, off_ = step_matrices(q, q_dot, phi, integration, weights, parameters[0], parameters[1],
                                      parameters[2], phi_tip, parameters[3], parameters[4], parameters[5],
                                      parameters[6], parameters[7])
    mass[:, :] = m_
    force[:] = f_
    x1[:, :] = x1_
    offset[:] = off_
    tangent[:, :] = stiffness
    if lam.shape[0] >= 2:
        kg = geometric_stiffness(q, phi, weights, parameters[0], -lam[0], -lam[1], parameters[5], parameters[6])
        for i in range(n):
            for m in range(n):
                tangent[i, m] += kg[i, m]
                force[i] += kg[i, m] * q[m]


@numba.njit(cache=True)
def tip_gap(coordinates, velocities, start, tip_start, tip_reference, phi, weights, phi_tip, parameters, moving_limit,
            rest_limit):  # pragma: no cover - compiled
    """Distance [m] of the tip node (ODE2 coordinates from ``tip_start``, plus ``tip_reference``) from the
    exact tip position of the rod's coordinates (from ``start``), divided by the allowed distance:
    ``moving_limit`` if any of the rod's velocities is non-zero, else ``rest_limit`` [m]."""
    n = phi.shape[1]
    q = np.empty(n)
    moving = False
    for i in range(n):
        q[i] = coordinates[start + i]
        if velocities[start + i] != 0.0:
            moving = True
    x, y, _, _ = tip_pose(q, phi, weights, parameters[0], phi_tip)
    cos_a, sin_a = parameters[5], parameters[6]
    gx = abs(tip_reference[0] + coordinates[tip_start] - (parameters[3] + cos_a * x - sin_a * y))
    gy = abs(tip_reference[1] + coordinates[tip_start + 1] - (parameters[4] + sin_a * x + cos_a * y))
    return max(gx, gy) / (moving_limit if moving else rest_limit)
