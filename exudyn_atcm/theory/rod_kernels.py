"""Compiled kernels of the ``rod`` cell's step (numba): the formulas of :mod:`.rotation_rod` on a moving base.

The rod's coordinates are ``z = (X, Y, Phi, q_1 .. q_n)``: the base point ``(X, Y)`` [m] and the
base's rotation ``Phi`` [rad] (total values: reference plus displacement, the rod's frame is a
rigid node), and the mode amplitudes ``q`` [rad].  The absolute rotation is
``theta(s) = Phi + sum_i q_i phi_i(s/L)``: ``p = (Phi, q)`` against the shapes ``(1, phi_1 .. phi_n)``
(``phi_hat``), so the clamped rod of :mod:`.rotation_rod` is the case ``X = Y = Phi = 0``.

The ``rod`` cell evaluates its mass matrix, quadratic velocity vector and the linearisation of
its tip pose once per attempted step (:func:`linearisation`, at the state predicted for the
step's end) and once after every Newton solve (:func:`step_check`, at the solved state, which
also tells whether to solve again; see :mod:`exudyn_atcm.mbs.chains.rod`).  In numpy that is some 35 small array operations (about
75 µs on the development machine); compiled, about 2 µs per evaluation of the items (3 modes) plus
numba's call overhead, about 0.05 µs per argument: the package's hooks therefore call
:func:`predicted_items` and :func:`solved_check`, nine arguments each, on the constants packed once
by :func:`pack_rod`.  Compiled on first use and cached on disk (numba's ``cache=True``); imported
only when a ``rod`` bender is built.

May import: numpy, numba, :mod:`.cholesky_kernel`.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .cholesky_kernel import cholesky_in_place

__all__ = ["rod_matrices", "tip_pose", "geometric_stiffness", "linearisation", "step_check", "moving", "tip_gap",
           "unpack_out", "predicted_items", "solved_check"]


@numba.njit(cache=True)
def _rotations(z, phi_hat):  # pragma: no cover - compiled
    """``phi_hat @ z[2:]``: the absolute rotation at the quadrature points (of ``z_dot``: its rate)."""
    n_points, m = phi_hat.shape
    theta = np.empty(n_points)
    for k in range(n_points):
        th = 0.0
        for i in range(m):
            th += phi_hat[k, i] * z[2 + i]
        theta[k] = th
    return theta


@numba.njit(cache=True)
def _tip(z, theta, phi_hat, weights, length, phi_hat_tip):  # pragma: no cover - compiled
    n_points, m = phi_hat.shape
    x = z[0]
    y = z[1]
    jac = np.zeros((2, 2 + m))
    jac[0, 0] = 1.0
    jac[1, 1] = 1.0
    for k in range(n_points):
        lw = length * weights[k]
        c = math.cos(theta[k])
        s = math.sin(theta[k])
        x += lw * c
        y += lw * s
        for i in range(m):
            jac[0, 2 + i] -= lw * s * phi_hat[k, i]
            jac[1, 2 + i] += lw * c * phi_hat[k, i]
    angle = 0.0
    for i in range(m):
        angle += phi_hat_tip[i] * z[2 + i]
    return x, y, angle, jac


@numba.njit(cache=True)
def tip_pose(z, phi_hat, weights, length, phi_hat_tip):  # pragma: no cover - compiled
    """Tip ``(x, y, theta)`` (global) and the Jacobian rows of ``x`` and ``y`` (2 x (2 + m))."""
    return _tip(z, _rotations(z, phi_hat), phi_hat, weights, length, phi_hat_tip)


@numba.njit(cache=True)
def rod_matrices(z, z_dot, phi_hat, integration, weights, length, mass_per_length, rotary_inertia,
                 phi_hat_tip):  # pragma: no cover - compiled
    """Mass matrix ``M(z)``, force ``-g(z, z_dot)``, and the tip constraint linearised at ``z``.

    Returns ``(mass, force, x1, offset)``: Exudyn's ``ObjectConnectorCoordinateVector``
    equation ``x1 z - q_tip - offset = 0`` with ``q_tip`` the tip node's ``(x, y, angle)``:
    ``x1`` the tip pose's Jacobian, ``offset = x1 z - tip(z)``.
    """
    return _matrices(z, z_dot, _rotations(z, phi_hat), phi_hat, integration, weights, length, mass_per_length,
                     rotary_inertia, phi_hat_tip)


@numba.njit(cache=True)
def _matrices(z, z_dot, theta, phi_hat, integration, weights, length, mass_per_length, rotary_inertia,
              phi_hat_tip):  # pragma: no cover - compiled
    # the sums of issue 29's form, ordered for the compiler (issue 31): sin, cos and the rate once per point,
    # the running integrals as dot products accumulated in registers, the tip in the same pass
    n_points, m = phi_hat.shape
    size = 2 + m
    rate = _rotations(z_dot, phi_hat)  # the absolute rotation's rate at the points
    # columns: sin(theta_k) phi_hat[k, i] (m), cos(theta_k) phi_hat[k, i] (m), cos(theta_k) rate_k^2, sin(...) rate_k^2
    t = np.empty((n_points, 2 * m + 2))
    x1 = np.zeros((3, size))
    x1[0, 0] = 1.0
    x1[1, 1] = 1.0
    x = z[0]
    y = z[1]
    for k in range(n_points):
        c = math.cos(theta[k])
        s = math.sin(theta[k])
        r2 = rate[k] * rate[k]
        t[k, 2 * m] = c * r2
        t[k, 2 * m + 1] = s * r2
        lw = length * weights[k]
        x += lw * c
        y += lw * s
        for i in range(m):
            t[k, i] = s * phi_hat[k, i]
            t[k, m + i] = c * phi_hat[k, i]
            x1[0, 2 + i] -= lw * t[k, i]
            x1[1, 2 + i] += lw * t[k, m + i]
    # the integrals from the base to each point: integration @ t, summed over k in order, all columns at once
    u = np.zeros((n_points, 2 * m + 2))
    for j in range(n_points):
        for k in range(n_points):
            w = integration[j, k]
            for col in range(2 * m + 2):
                u[j, col] += w * t[k, col]
    ax = np.empty((n_points, m))
    ay = np.empty((n_points, m))
    bx = np.empty(n_points)
    by = np.empty(n_points)
    for j in range(n_points):
        bx[j] = -length * u[j, 2 * m]
        by[j] = -length * u[j, 2 * m + 1]
        for i in range(m):
            ax[j, i] = -length * u[j, i]
            ay[j, i] = length * u[j, m + i]
    mass = np.zeros((size, size))
    force = np.zeros(size)
    mass[0, 0] = mass_per_length * length
    mass[1, 1] = mass_per_length * length
    for j in range(n_points):
        lw = length * weights[j]
        ml = mass_per_length * lw
        force[0] -= ml * bx[j]
        force[1] -= ml * by[j]
        for i in range(m):
            mass[0, 2 + i] += ml * ax[j, i]
            mass[1, 2 + i] += ml * ay[j, i]
            force[2 + i] -= ml * (ax[j, i] * bx[j] + ay[j, i] * by[j])
            for r in range(i, m):
                mass[2 + i, 2 + r] += (ml * (ax[j, i] * ax[j, r] + ay[j, i] * ay[j, r])
                                       + lw * rotary_inertia * phi_hat[j, i] * phi_hat[j, r])
    for i in range(size):
        for r in range(i):
            mass[i, r] = mass[r, i]
    angle = 0.0
    for i in range(m):
        angle += phi_hat_tip[i] * z[2 + i]
        x1[2, 2 + i] = phi_hat_tip[i]
    offset = np.zeros(3)
    offset[0] = -x
    offset[1] = -y
    offset[2] = -angle
    for r in range(3):
        for i in range(size):
            offset[r] += x1[r, i] * z[i]
    return mass, force, x1, offset


@numba.njit(cache=True)
def geometric_stiffness(z, phi_hat, weights, length, lam_x, lam_y):  # pragma: no cover - compiled
    """``lam . d^2 P / dz^2`` ((2 + m) x (2 + m)): the curvature of the tip position times ``lam_x``,
    ``lam_y`` [N] (the tip position is linear in ``X``, ``Y``, its rotation linear in ``z``)."""
    return _geometric(_rotations(z, phi_hat), phi_hat, weights, length, lam_x, lam_y)


@numba.njit(cache=True)
def _geometric(theta, phi_hat, weights, length, lam_x, lam_y):  # pragma: no cover - compiled
    n_points, m = phi_hat.shape
    out = np.zeros((2 + m, 2 + m))
    for k in range(n_points):
        lw = length * weights[k]
        factor = -lw * (lam_x * math.cos(theta[k]) + lam_y * math.sin(theta[k]))
        for i in range(m):
            for r in range(m):
                out[2 + i, 2 + r] += factor * phi_hat[k, i] * phi_hat[k, r]
    return out


@numba.njit(cache=True)
def _gather(coordinates, reference, base_start, rod_start, size):  # pragma: no cover - compiled
    z = np.empty(size)
    for i in range(3):
        z[i] = reference[i] + coordinates[base_start + i]
    for i in range(size - 3):
        z[3 + i] = coordinates[rod_start + i]
    return z


@numba.njit(cache=True)
def linearisation(coordinates, velocities, accelerations, base_start, rod_start, reference, h, lam, stiffness,
                  phi_hat, integration, weights, phi_hat_tip, parameters, mass, tangent, force, x1,
                  offset):  # pragma: no cover - compiled
    """Everything the rod's items need for one step or Newton pass, written into the last five arrays.

    ``coordinates`` / ``velocities`` / ``accelerations``: the system's ODE2 arrays; the base node's
    three coordinates start at ``base_start`` (displacements from ``reference``), the modes at
    ``rod_start``.  The state of linearisation is the second-order prediction of a step ``h`` [s]:
    ``z + h z_dot + h^2 / 2 z_ddot`` with the rates ``z_dot + h z_ddot`` (``h = 0``: the state itself;
    an empty ``accelerations``: ``z + h z_dot`` and ``z_dot``).  ``lam``: the tie's current
    multipliers, or an empty array to leave out the geometric stiffness.  ``parameters``: length,
    mass per length, rotary inertia.  Writes ``mass``, ``tangent = stiffness + kg``,
    ``force = -g + kg u`` (``u``: ``z`` as Exudyn's coordinates, the base's displacements from
    ``reference``), ``x1`` and ``offset`` (see :func:`rod_matrices`; ``kg`` =
    :func:`geometric_stiffness` at ``-lam``).
    """
    size = mass.shape[0]
    z = _gather(coordinates, reference, base_start, rod_start, size)
    z_dot = _gather(velocities, np.zeros(3), base_start, rod_start, size)
    if h != 0.0 and accelerations.shape[0] > 0:
        z_ddot = _gather(accelerations, np.zeros(3), base_start, rod_start, size)
        for i in range(size):
            z[i] += h * z_dot[i] + 0.5 * h * h * z_ddot[i]
            z_dot[i] += h * z_ddot[i]
    else:
        for i in range(size):
            z[i] += h * z_dot[i]
    theta = _rotations(z, phi_hat)
    m_, f_, x1_, off_ = _matrices(z, z_dot, theta, phi_hat, integration, weights, parameters[0], parameters[1],
                                  parameters[2], phi_hat_tip)
    mass[:, :] = m_
    force[:] = f_
    x1[:, :] = x1_
    offset[:] = off_
    tangent[:, :] = stiffness
    if lam.shape[0] >= 2:
        # Exudyn's stiffness acts on the coordinates (the base node's: displacements from its reference)
        kg = _geometric(theta, phi_hat, weights, parameters[0], -lam[0], -lam[1])
        for i in range(size):
            for r in range(size):
                tangent[i, r] += kg[i, r]
                force[i] += kg[i, r] * (z[r] - reference[r] if r < 3 else z[r])


@numba.njit(cache=True)
def _cholesky_solve(a, b):  # pragma: no cover - compiled
    """Solve ``a x = b`` in place for a small symmetric positive definite ``a`` (overwritten by its factor)."""
    size = a.shape[0]
    cholesky_in_place(a)
    for i in range(size):
        v = b[i]
        for k in range(i):
            v -= a[i, k] * b[k]
        b[i] = v / a[i, i]
    for i in range(size - 1, -1, -1):
        v = b[i]
        for k in range(i + 1, size):
            v -= a[k, i] * b[k]
        b[i] = v / a[i, i]


@numba.njit(cache=True)
def moving(velocities, accelerations, base_start, rod_start, n_modes):  # pragma: no cover - compiled
    """Whether any of the rod's coordinates (the base node's three, the ``n_modes`` modes) has a non-zero rate
    or acceleration: a time step of a rod in motion or starting to move."""
    for i in range(3):
        if velocities[base_start + i] != 0.0 or accelerations[base_start + i] != 0.0:
            return True
    for i in range(n_modes):
        if velocities[rod_start + i] != 0.0 or accelerations[rod_start + i] != 0.0:
            return True
    return False


@numba.njit(cache=True)
def step_check(coordinates, velocities, accelerations, base_start, rod_start, tip_start, reference, tip_reference,
               multipliers, tie_start, phi_hat, integration, weights, phi_hat_tip, parameters, factor, limits, tip_limit, mass, force, x1,
               offset):  # pragma: no cover - compiled
    """After a dynamic step's Newton solve: how far its state is from the solution of the exact equations.

    The step was solved with the items ``mass``, ``force`` (``-g``) and the tie ``x1``, ``offset``
    evaluated at a predicted state (:func:`linearisation`, without the geometric stiffness).  At the
    solved state ``z``, ``z_dot``, ``z_ddot`` (the system's ODE2 arrays, as in :func:`linearisation`;
    the tip node's coordinates from ``tip_start``, plus ``tip_reference``):

    * the tip node's distance from the exact tip position ``P(z)``, over ``tip_limit`` [m];
    * the equations of motion evaluated there differ from the solved ones by
      ``dr = (M(z) - mass) z_ddot - (-g(z, z_dot) - force) - (x1(z) - x1)^T lam`` (``lam``: the tie's
      multipliers, ``multipliers[tie_start:tie_start + 2]`` of the system's algebraic coordinates, Exudyn's
      sign, the tie's force output); Newton's correction of the accelerations is about ``M^-1 dr``,
      of the coordinates ``factor M^-1 dr`` (``factor``: the integrator's ``beta' h^2``): its
      largest ``|factor (M^-1 dr)_i| / limits_i`` (``limits``: the allowed change of each coordinate,
      [m] for ``X``, ``Y``, [rad] for the rotations).

    Returns the larger ratio.  Above 1 the items evaluated at the solved state are written into
    ``mass``, ``force``, ``x1`` and ``offset`` (to be handed to Exudyn for another Newton solve);
    else they are left as they were.
    """
    size = mass.shape[0]
    z = _gather(coordinates, reference, base_start, rod_start, size)
    z_dot = _gather(velocities, np.zeros(3), base_start, rod_start, size)
    z_ddot = _gather(accelerations, np.zeros(3), base_start, rod_start, size)
    m_, f_, x1_, off_ = _matrices(z, z_dot, _rotations(z, phi_hat), phi_hat, integration, weights, parameters[0],
                                  parameters[1], parameters[2], phi_hat_tip)
    ratio = 0.0
    for r in range(2):  # the tip position P = x1 z - offset
        p = -off_[r]
        for i in range(size):
            p += x1_[r, i] * z[i]
        ratio = max(ratio, abs(tip_reference[r] + coordinates[tip_start + r] - p) / tip_limit)
    dr = np.zeros(size)
    for i in range(size):
        d = force[i] - f_[i]
        for r in range(size):
            d += (m_[i, r] - mass[i, r]) * z_ddot[r]
        d -= (x1_[0, i] - x1[0, i]) * multipliers[tie_start] + (x1_[1, i] - x1[1, i]) * multipliers[tie_start + 1]
        dr[i] = d
    _cholesky_solve(m_.copy(), dr)  # dr becomes M^-1 dr
    for i in range(size):
        ratio = max(ratio, abs(factor * dr[i]) / limits[i])
    if ratio > 1.0:
        mass[:, :] = m_
        force[:] = f_
        x1[:, :] = x1_
        offset[:] = off_
    return ratio


@numba.njit(cache=True)
def tip_gap(coordinates, velocities, base_start, rod_start, tip_start, reference, tip_reference, phi_hat, weights,
            phi_hat_tip, length, moving_limit, rest_limit):  # pragma: no cover - compiled
    """Distance [m] of the tip node (ODE2 coordinates from ``tip_start``, plus ``tip_reference``) from the
    exact tip position of the rod's coordinates, divided by the allowed distance: ``moving_limit`` if
    any of the rod's velocities is non-zero, else ``rest_limit`` [m]."""
    size = 2 + phi_hat.shape[1]
    z = _gather(coordinates, reference, base_start, rod_start, size)
    moving = False
    for i in range(3):
        if velocities[base_start + i] != 0.0:
            moving = True
    for i in range(size - 3):
        if velocities[rod_start + i] != 0.0:
            moving = True
    x, y, _, _ = tip_pose(z, phi_hat, weights, length, phi_hat_tip)
    gx = abs(tip_reference[0] + coordinates[tip_start] - x)
    gy = abs(tip_reference[1] + coordinates[tip_start + 1] - y)
    return max(gx, gy) / (moving_limit if moving else rest_limit)


# ----------------------------------------------------------------------------- one call per hook
# A compiled function's call costs about 0.05 us per argument (numba's dispatcher types each one):
# linearisation and step_check take some 20, so the package's hooks call these instead, with the
# rod's constants packed into one float and one integer array (pack_rod) and the items' arrays as
# views of one buffer.  They do what moving + linearisation (pre-step) and step_check (post-Newton)
# do, plus the actuation EI kappa folded into the force vector (one Exudyn item write less).

def pack_rod(reference, tip_reference, parameters, limits, tip_limit, stiffness, phi_hat, integration, weights,
             phi_hat_tip, actuation, moment_per_strain):
    """The rod's constants as ``(ints, consts, out)`` for :func:`predicted_items` and :func:`solved_check`.

    ``actuation``: ``(object coordinate of the mode, strain source index)`` per driven segment, each
    loaded by ``moment_per_strain`` [N m] times its source's strain; the other arguments as in
    :func:`linearisation` and :func:`step_check`.  ``ints[0:4]`` are the base's, the modes', the tip's
    ODE2 index and the tie's first algebraic index, to be filled in once the system is assembled.
    ``out`` holds ``mass``, ``force``, ``x1``, ``offset`` and ``tangent`` (:func:`unpack_out`).
    """
    n_points, m = phi_hat.shape
    size = 2 + m
    ints = np.array([-1, -1, -1, -1, size, n_points, len(actuation)] + [v for pair in actuation for v in pair],
                    dtype=np.int64)
    consts = np.concatenate([np.asarray(reference, dtype=float), np.asarray(tip_reference, dtype=float)[:2],
                             np.asarray(parameters, dtype=float), [float(moment_per_strain), float(tip_limit)],
                             np.asarray(limits, dtype=float), np.ravel(stiffness), np.ravel(phi_hat),
                             np.ravel(integration), np.ravel(weights), np.ravel(phi_hat_tip)])
    out = np.zeros(2 * size * size + 4 * size + 3)
    return ints, consts, out


def unpack_out(out, size):
    """Views ``(mass, force, x1, offset, tangent)`` of :func:`pack_rod`'s ``out`` (numpy or compiled)."""
    a = size * size
    return (out[:a].reshape((size, size)), out[a:a + size], out[a + size:a + 4 * size].reshape((3, size)),
            out[a + 4 * size:a + 4 * size + 3], out[a + 4 * size + 3:2 * a + 4 * size + 3].reshape((size, size)))


_unpack_out = numba.njit(cache=True)(unpack_out)


@numba.njit(cache=True)
def _unpack(ints, consts):  # pragma: no cover - compiled
    size, n_points = ints[4], ints[5]
    m = size - 2
    o = 10 + size
    reference, tip_reference, parameters = consts[0:3], consts[3:5], consts[5:8]
    stiffness = consts[o:o + size * size].reshape((size, size))
    o += size * size
    phi_hat = consts[o:o + n_points * m].reshape((n_points, m))
    o += n_points * m
    integration = consts[o:o + n_points * n_points].reshape((n_points, n_points))
    o += n_points * n_points
    weights = consts[o:o + n_points]
    phi_hat_tip = consts[o + n_points:o + n_points + m]
    return reference, tip_reference, parameters, consts[10:10 + size], stiffness, phi_hat, integration, weights, phi_hat_tip


@numba.njit(cache=True)
def _actuate(force, strains, ints, consts, sign):  # pragma: no cover - compiled
    for k in range(ints[6]):
        force[ints[7 + 2 * k]] += sign * consts[8] * strains[ints[8 + 2 * k]]


@numba.njit(cache=True)
def predicted_items(coordinates, velocities, accelerations, h, strains, ints, consts, out):  # pragma: no cover
    """Pre-step: if ``0 < h < inf`` [s] and the rod moves (:func:`moving`), its items linearised at the state
    predicted for the step's end (:func:`linearisation` without the geometric stiffness) with the actuation
    (``strains``) in the force, into ``out``; returns whether it did (else ``out`` is unchanged)."""
    if not (0.0 < h < math.inf) or not moving(velocities, accelerations, ints[0], ints[1], ints[4] - 3):
        return False
    reference, _, parameters, _, stiffness, phi_hat, integration, weights, phi_hat_tip = _unpack(ints, consts)
    mass, force, x1, offset, tangent = _unpack_out(out, ints[4])
    linearisation(coordinates, velocities, accelerations, ints[0], ints[1], reference, h, np.empty(0), stiffness,
                  phi_hat, integration, weights, phi_hat_tip, parameters, mass, tangent, force, x1, offset)
    _actuate(force, strains, ints, consts, 1.0)
    return True


@numba.njit(cache=True)
def solved_check(coordinates, velocities, accelerations, multipliers, strains, factor, ints, consts,
                 out):  # pragma: no cover - compiled
    """Post-Newton of a time step: :func:`step_check` of the items in ``out`` (written by
    :func:`predicted_items`, the actuation of ``strains`` in the force); above 1 the items at the solved
    state, with the actuation, are written into ``out``.  Returns the ratio."""
    reference, tip_reference, parameters, limits, _, phi_hat, integration, weights, phi_hat_tip = _unpack(ints, consts)
    mass, force, x1, offset, _ = _unpack_out(out, ints[4])
    passive = force.copy()
    _actuate(passive, strains, ints, consts, -1.0)
    ratio = step_check(coordinates, velocities, accelerations, ints[0], ints[1], ints[2], reference, tip_reference,
                       multipliers, ints[3], phi_hat, integration, weights, phi_hat_tip, parameters, factor, limits,
                       consts[9], mass, passive, x1, offset)
    if ratio > 1.0:
        force[:] = passive
        _actuate(force, strains, ints, consts, 1.0)
    return ratio
