"""The ``rod`` cell's one-call-per-hook kernels (issue 31, part 3) against plain numpy.

``rod_kernels.predicted_items`` (pre-step) and ``rod_kernels.solved_check`` (post-Newton) replace the
calls of ``moving`` + ``linearisation`` and ``step_check`` with the rod's constants packed into two
arrays (``pack_rod``) and the actuation folded into the force vector.  Here they are checked against a
plain numpy evaluation of the rod on a moving base written out in the test from the formulas (the
positions of the quadrature points ``r_j = (X, Y) + L sum_k I_jk (cos, sin) theta_k``, their Jacobians
and convective terms), and against the kernels they replace: the same numbers to round-off.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.theory import rod_kernels as rk
from exudyn_atcm.theory import rotation_rod as rr

L, MU, RHO_I, EI_KAPPA = 0.06, 0.2, 1.5e-8, 0.37  # m, kg/m, kg m, N m per unit strain
BASE, ROD, TIP, TIE = 4, 10, 1, 2  # indices of the rod's coordinates in made-up system arrays


def _numpy_items(shapes, z, z_dot):
    """Mass matrix, -g, the tie's x1 and offset of the rod on the base z[:3], in plain numpy."""
    phi, integ, w = shapes.phi_hat, shapes.integration, shapes.weights
    size = z.size
    theta, rate = phi @ z[2:], phi @ z_dot[2:]
    c, s = np.cos(theta), np.sin(theta)
    mass, g = np.zeros((size, size)), np.zeros(size)
    for j in range(len(w)):
        jac = np.zeros((2, size))
        jac[0, 0] = jac[1, 1] = 1.0
        jac[0, 2:] = -L * (integ[j] * s) @ phi
        jac[1, 2:] = L * (integ[j] * c) @ phi
        b = -L * np.array([(integ[j] * c) @ rate**2, (integ[j] * s) @ rate**2])
        e = np.zeros(size)
        e[2:] = phi[j]
        mass += L * w[j] * (MU * jac.T @ jac + RHO_I * np.outer(e, e))
        g += L * w[j] * MU * jac.T @ b
    tip = np.array([z[0] + L * w @ c, z[1] + L * w @ s, shapes.phi_hat_tip @ z[2:]])
    x1 = np.zeros((3, size))
    x1[0, 0] = x1[1, 1] = 1.0
    x1[0, 2:] = -L * (w * s) @ phi
    x1[1, 2:] = L * (w * c) @ phi
    x1[2, 2:] = shapes.phi_hat_tip
    return mass, -g, x1, x1 @ z - tip


def _setup(n_modes, rng, segments=None):
    shapes = rr.rod_shapes(n_modes, L) if segments is None else rr.rod_shapes(n_modes, L, *segments)
    size = 3 + n_modes
    reference = np.array([0.01, -0.02, 0.4])
    tip_reference = np.array([0.05, 0.03])
    limits = np.array([1e-8 * L] * 2 + [1e-7] * (size - 2))
    stiffness = np.zeros((size, size))
    stiffness[3:, 3:] = shapes.stiffness_matrix(0.02)
    actuation = [(3 + first, k) for k, first in enumerate(shapes.first_modes)]
    ints, consts, out = rk.pack_rod(reference, tip_reference, [L, MU, RHO_I], limits, 1e-8 * L, stiffness,
                                    shapes.phi_hat, shapes.integration, shapes.weights, shapes.phi_hat_tip, actuation,
                                    EI_KAPPA)
    ints[:4] = [BASE, ROD, TIP, TIE]
    n_sys = ROD + n_modes + 2
    q, v, a = (rng.normal(scale=0.3, size=n_sys) for _ in range(3))
    strains = rng.normal(scale=1e-3, size=len(actuation))
    return shapes, size, reference, tip_reference, limits, stiffness, actuation, ints, consts, out, q, v, a, strains


def _z(reference, arrays, n_modes, with_reference=True):
    return np.concatenate([(reference if with_reference else 0.0) + arrays[BASE:BASE + 3], arrays[ROD:ROD + n_modes]])


@pytest.mark.parametrize("n_modes, segments", [(3, None), (4, None), (4, ((2, 2), (0.03, 0.03)))])
def test_predicted_items_are_the_numpy_rod_at_the_predicted_state(n_modes, segments):
    rng = np.random.default_rng(n_modes)
    shapes, size, reference, _, _, stiffness, actuation, ints, consts, out, q, v, a, strains = _setup(
        n_modes, rng, segments)
    h = 3e-4
    assert rk.predicted_items(q, v, a, h, strains, ints, consts, out)
    z = _z(reference, q, n_modes) + h * _z(reference, v, n_modes, False) + 0.5 * h * h * _z(reference, a, n_modes, False)
    z_dot = _z(reference, v, n_modes, False) + h * _z(reference, a, n_modes, False)
    mass, force, x1, offset = _numpy_items(shapes, z, z_dot)
    for coordinate, source in actuation:  # EI kappa on each driven segment's first mode
        force[coordinate] += EI_KAPPA * strains[source]
    m_out, f_out, x1_out, off_out, tangent = rk.unpack_out(out, size)
    # plain numpy sums in another order: equal to round-off (1e-13 of each array's largest entry)
    for got, want in ((m_out, mass), (f_out, force), (x1_out, x1), (off_out, offset)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-13 * np.max(np.abs(want)))
    np.testing.assert_array_equal(tangent, stiffness)  # no geometric stiffness in a time step
    assert np.max(np.abs(f_out - force)) < 1e-3 * EI_KAPPA * np.max(np.abs(strains))  # the actuation is in


def test_predicted_items_refuse_a_static_step_and_a_rod_at_rest():
    rng = np.random.default_rng(0)
    *_, ints, consts, out, q, v, a, strains = _setup(3, rng)
    before = out.copy()
    for h in (0.0, np.inf):  # a static solver's load step: no finite time step
        assert not rk.predicted_items(q, v, a, h, strains, ints, consts, out)
    assert not rk.predicted_items(q, np.zeros_like(v), np.zeros_like(a), 1e-4, strains, ints, consts, out)
    np.testing.assert_array_equal(out, before)


@pytest.mark.parametrize("scale, above", [(1e-9, False), (1e-2, True)])
def test_solved_check_is_the_numpy_residual_change_and_replaces_the_items_above_one(scale, above):
    rng = np.random.default_rng(7)
    n_modes = 3
    shapes, size, reference, tip_reference, limits, stiffness, actuation, ints, consts, out, q, v, a, strains = \
        _setup(n_modes, rng)
    h = 2e-4
    assert rk.predicted_items(q, v, a, h, strains, ints, consts, out)
    mass_p, force_p, x1_p, off_p, _ = (x.copy() for x in rk.unpack_out(out, size))
    # the solved state: the prediction plus a change of size `scale`
    z_p = _z(reference, q, n_modes) + h * _z(reference, v, n_modes, False) + 0.5 * h * h * _z(reference, a, n_modes, False)
    q2, v2, a2 = q.copy(), v.copy(), a.copy()
    q2[BASE:BASE + 3] = z_p[:3] - reference + scale * rng.normal(size=3)
    q2[ROD:ROD + n_modes] = z_p[3:] + scale * rng.normal(size=n_modes)
    z = _z(reference, q2, n_modes)
    _, _, x1_z, off_z = _numpy_items(shapes, z, _z(reference, v2, n_modes, False))
    tip = x1_z @ z - off_z
    q2[TIP:TIP + 2] = tip[:2] - tip_reference + 1e-9 * L * scale  # the tip node near the exact tip
    multipliers = rng.normal(size=TIE + 3)
    factor = 0.25 * h * h
    ratio = rk.solved_check(q2, v2, a2, multipliers, strains, factor, ints, consts, out)
    # numpy: the equations evaluated at the solved state minus the solved ones, M^-1, over the limits
    mass, force, x1, offset = _numpy_items(shapes, z, _z(reference, v2, n_modes, False))
    passive = force_p.copy()
    for coordinate, source in actuation:
        passive[coordinate] -= EI_KAPPA * strains[source]
    lam = multipliers[TIE:TIE + 2]
    dr = (mass - mass_p) @ _z(reference, a2, n_modes, False) - (force - passive) - (x1[:2] - x1_p[:2]).T @ lam
    gap = np.max(np.abs(tip_reference + q2[TIP:TIP + 2] - (x1 @ z - offset)[:2])) / (1e-8 * L)
    want = max(gap, np.max(np.abs(factor * np.linalg.solve(mass, dr)) / limits))
    # dr is a difference of nearby values: with a change of 1e-9 rad its round-off is about 1e-16 / 1e-9 of it,
    # amplified by M^-1 (condition ~1e4 here): 1e-3 relative; with 1e-2 rad round-off is far below 1e-9
    assert ratio == pytest.approx(want, rel=1e-3 if scale < 1e-6 else 1e-9)
    assert (ratio > 1.0) is above
    m_out, f_out, x1_out, off_out, _ = rk.unpack_out(out, size)
    if above:  # the items at the solved state, the actuation in the force
        for coordinate, source in actuation:
            force[coordinate] += EI_KAPPA * strains[source]
        for got, want_ in ((m_out, mass), (f_out, force), (x1_out, x1), (off_out, offset)):
            np.testing.assert_allclose(got, want_, rtol=0, atol=1e-13 * np.max(np.abs(want_)))
    else:  # left as predicted
        for got, want_ in ((m_out, mass_p), (f_out, force_p), (x1_out, x1_p), (off_out, off_p)):
            np.testing.assert_array_equal(got, want_)


def test_the_new_kernels_equal_the_ones_they_replace():
    """predicted_items = moving + linearisation (+ the actuation), solved_check = step_check, to round-off."""
    rng = np.random.default_rng(3)
    n_modes = 4
    shapes, size, reference, tip_reference, limits, stiffness, actuation, ints, consts, out, q, v, a, strains = \
        _setup(n_modes, rng)
    h = 1e-4
    assert rk.predicted_items(q, v, a, h, strains, ints, consts, out)
    mass, tangent, force, x1, offset = (np.empty((size, size)), np.empty((size, size)), np.empty(size),
                                        np.empty((3, size)), np.empty(3))
    params = np.array([L, MU, RHO_I])
    rk.linearisation(q, v, a, BASE, ROD, reference, h, np.empty(0), stiffness, shapes.phi_hat, shapes.integration,
                     shapes.weights, shapes.phi_hat_tip, params, mass, tangent, force, x1, offset)
    for coordinate, source in actuation:
        force[coordinate] += EI_KAPPA * strains[source]
    got = rk.unpack_out(out, size)
    for g, w in zip(got, (mass, force, x1, offset, tangent)):
        np.testing.assert_allclose(g, w, rtol=0, atol=1e-15 * max(1.0, np.max(np.abs(w))))
    multipliers = rng.normal(size=TIE + 3)
    q2 = q + 1e-3 * rng.normal(size=q.size)
    passive = force.copy()
    for coordinate, source in actuation:
        passive[coordinate] -= EI_KAPPA * strains[source]
    want = rk.step_check(q2, v, a, BASE, ROD, TIP, reference, tip_reference, multipliers, TIE, shapes.phi_hat,
                         shapes.integration, shapes.weights, shapes.phi_hat_tip, params, 1e-8, limits, 1e-8 * L,
                         mass, passive, x1, offset)
    assert rk.solved_check(q2, v, a, multipliers, strains, 1e-8, ints, consts, out) == pytest.approx(want, rel=1e-12)
