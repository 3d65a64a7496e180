"""The closed-form references of the mechanism cases, checked against hand calculations,
the literature's tabulated values and each other (no multibody model involved)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm import theory as bt
from exudyn_atcm.theory.four_bar import (
    RigidFourBar,
    branch_of,
    circle_intersection,
    freudenstein_constants,
    freudenstein_rocker_angle,
    grashof_type,
)

EI = 1.28699e-2  # N m^2, the paper's three-cell laminate (composite theory)
L = 0.087  # m
KAPPA = 4.13984  # 1/m at 1500 V


# ----------------------------------------------------------------------------- four-bar
def test_circle_intersection_hand_values():
    # A=(0,0), D=(2,0), a=1, b=2, c=1, crank at 90 deg: B=(0,1); by hand 5x^2-16x+12=0,
    # so C = (2, 1) (open, parallelogram) or C = (1.2, -0.6) (crossed)
    B, D = (0.0, 1.0), (2.0, 0.0)
    open_ = circle_intersection(B, 2.0, D, 1.0, branch=+1)
    crossed = circle_intersection(B, 2.0, D, 1.0, branch=-1)
    np.testing.assert_allclose(open_, [2.0, 1.0], atol=1e-15)
    np.testing.assert_allclose(crossed, [1.2, -0.6], atol=1e-15)
    assert branch_of(B, D, open_) == 1 and branch_of(B, D, crossed) == -1


def test_circle_intersection_vectorised_and_errors():
    centers = np.array([[0.0, 1.0], [0.0, 1.0]])
    out = circle_intersection(centers, 2.0, (2.0, 0.0), 1.0, branch=1)
    assert out.shape == (2, 2)
    with pytest.raises(ValueError, match="do not intersect.*outside"):
        circle_intersection((0.0, 0.0), 1.0, (5.0, 0.0), 1.0, 1)
    with pytest.raises(ValueError, match="branch must be"):
        circle_intersection((0.0, 0.0), 1.0, (1.0, 0.0), 1.0, 0)
    with pytest.raises(ValueError, match="radius1 must be > 0"):
        circle_intersection((0.0, 0.0), -1.0, (1.0, 0.0), 1.0, 1)


def test_parallelogram_coupler_translates_with_the_crank_tip():
    # a parallelogram four-bar (a = c, b = d, open branch): the coupler translates, so the
    # coupler point moves exactly as the crank tip does (theta4 = theta2)
    fb = RigidFourBar.from_points(A=(0, 0), B=(0, 1), C=(2, 1), D=(2, 0), P=(1.0, 1.5))
    for theta in np.linspace(0.3, 2.8, 7):
        B = fb.crank_tip(theta)
        P = fb.coupler_point_from_crank_tip(B)
        np.testing.assert_allclose(P - B, [1.0, 0.5], atol=1e-13)
        assert fb.rocker_angle(theta) == pytest.approx(theta, abs=1e-12)


def test_freudenstein_and_circle_intersection_agree():
    # a general crank-rocker (Grashof): check both routes give the same rocker joint and
    # that the loop-closure lengths hold
    A, D = np.array([0.0, 0.0]), np.array([0.05, 0.01])
    B0, C0, P0 = np.array([0.0, 0.02]), np.array([0.055, 0.045]), np.array([0.03, 0.06])
    fb = RigidFourBar.from_points(A, B0, C0, D, P0)
    assert grashof_type(fb.crank_length, fb.coupler_length, fb.rocker_length, fb.ground_length) == "grashof"
    thetas = np.linspace(0.0, 2 * math.pi, 37)
    B = fb.crank_tip(thetas)
    C = fb.rocker_joint(B)
    theta4 = fb.rocker_angle(thetas)
    np.testing.assert_allclose(C, D + fb.rocker_length * np.stack([np.cos(theta4), np.sin(theta4)], -1), atol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(C - B, axis=1), fb.coupler_length, rtol=1e-13)
    P = fb.coupler_point_from_crank_tip(B)
    # the coupler point keeps its distances to B and C (rigid coupler)
    np.testing.assert_allclose(np.linalg.norm(P - B, axis=1), np.linalg.norm(P0 - B0), rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(P - C, axis=1), np.linalg.norm(P0 - C0), rtol=1e-12)
    # and in the reference pose the construction returns the given points
    np.testing.assert_allclose(fb.rocker_joint(B0), C0, atol=1e-15)
    np.testing.assert_allclose(fb.coupler_point_from_crank_tip(B0), P0, atol=1e-15)


def test_freudenstein_constants_and_assembly_error():
    assert freudenstein_constants(1.0, 2.0, 1.0, 2.0) == pytest.approx((2.0, 2.0, (1 - 4 + 1 + 4) / 2))
    # square four-bar a=b=c=d=1 at phi2 = 90 deg: C=(1,1), phi4 = 90 deg on one root
    roots = {round(float(freudenstein_rocker_angle(math.pi / 2, 1, 1, 1, 1, s)), 12) for s in (1, -1)}
    assert round(math.pi / 2, 12) in roots
    with pytest.raises(ValueError, match="cannot be assembled"):
        freudenstein_rocker_angle(math.pi, 1.0, 0.5, 0.5, 3.0, 1)
    assert grashof_type(1, 2, 1, 2) == "change-point"
    assert grashof_type(1, 2, 2, 4) == "non-grashof"  # 1 + 4 > 2 + 2


# ----------------------------------------------------------------------------- S-blade
def test_s_blade_small_deflection_limit():
    # kappa L^2/4: half the free deflection of a uniformly curved cantilever
    assert bt.s_blade_deflection_linear(KAPPA, L) == pytest.approx(0.5 * bt.linear_tip_deflection(KAPPA, L))
    x, y = bt.s_blade_end(1e-4, L)
    assert y == pytest.approx(1e-4 * L**2 / 4, rel=1e-8)
    assert x == pytest.approx(L, rel=1e-9)


def test_s_blade_is_two_arcs_and_series_expansion():
    x, y = bt.s_blade_end(KAPPA, L)
    ax, ay = bt.arc_point(KAPPA, L / 2)  # first arc's end = inflection point, half the displacement
    assert (x, y) == pytest.approx((2 * float(ax), 2 * float(ay)), rel=1e-14)
    z = KAPPA * L
    assert y == pytest.approx(KAPPA * L**2 / 4 * (1 - z**2 / 48), rel=z**4 / 1000)
    assert L - x == pytest.approx(KAPPA**2 * L**3 / 24, rel=z**2 / 10)
    # the S-blade obtained by integrating the free curvature +kappa / -kappa numerically
    s = np.linspace(0.0, L, 200001)
    theta = np.where(s <= L / 2, KAPPA * s, KAPPA * (L - s))
    xs = np.trapezoid(np.cos(theta), s)
    ys = np.trapezoid(np.sin(theta), s)
    assert (xs, ys) == pytest.approx((x, y), rel=1e-9)


def test_rigid_chain_s_blade_polygon_scaling():
    # chain of rigid cells with rest angles = the cells' free rotations: vertices on the
    # inscribed polygons of the two arcs, scaled by (k Lc/2)/sin(k Lc/2)
    n = 6  # cells per half
    lc = L / (2 * n)
    angles = KAPPA * lc * np.concatenate([np.arange(n) + 0.5, (np.arange(n) + 0.5)[::-1]])
    end = np.array([np.sum(lc * np.cos(angles)), np.sum(lc * np.sin(angles))])
    scale = (KAPPA * lc / 2) / math.sin(KAPPA * lc / 2)
    np.testing.assert_allclose(end, np.array(bt.s_blade_end(KAPPA, L)) * scale, rtol=1e-13)


# ----------------------------------------------------------------------------- extension / blocked force
def test_extension_formulas_reduce_to_cantilever():
    assert bt.extension_compliance(EI, L, 0.0) == pytest.approx(bt.tip_compliance(EI, L))
    assert bt.extension_blocked_force(EI, KAPPA, L, 0.0) == pytest.approx(bt.blocked_force(EI, KAPPA, L))
    assert bt.extension_blocked_force(EI, KAPPA, L, 0.0) == pytest.approx(0.9186, abs=1e-4)  # paper laminate
    # compliance as the integral of (L + a - s)^2 / EI
    a = 0.03
    s = np.linspace(0.0, L, 100001)
    assert bt.extension_compliance(EI, L, a) == pytest.approx(np.trapezoid((L + a - s) ** 2, s) / EI, rel=1e-9)


def test_rigid_chain_compliance_is_the_trapezoidal_rule():
    a, n = 0.02, 5
    lc = L / n
    s = np.arange(n + 1) * lc
    k = np.full(n + 1, EI / lc)
    k[[0, -1]] = 2 * EI / lc
    chain = np.sum((L + a - s) ** 2 / k)
    assert bt.rigid_chain_extension_compliance(EI, L, a, n) == pytest.approx(chain, rel=1e-13)
    assert bt.rigid_chain_extension_compliance(EI, L, 0.0, n) == pytest.approx(
        bt.tip_compliance(EI, L) * bt.rigid_chain_compliance_factor(n), rel=1e-13
    )


def test_spring_contact_force_limits():
    free, c = 1e-3, 2e-2
    assert bt.spring_contact_force(free, c, 1e12) == pytest.approx(free / c, rel=1e-9)
    assert bt.spring_contact_force(free, c, 1.0) == pytest.approx(free / (c + 1.0))


def test_rigid_extension_point():
    x, y = bt.rigid_extension_point(1.0, 2.0, math.pi / 2, 0.5)
    assert (float(x), float(y)) == pytest.approx((1.0, 2.5))


# ----------------------------------------------------------------------------- large deflection
@pytest.mark.parametrize("alpha", sorted(bt.ELASTICA_TIP_FORCE))
def test_elastica_matches_bisshopp_drucker(alpha):
    r = bt.curved_cantilever_end_load(0.0, EI, L, (0.0, alpha * EI / L**2))
    y_ref, dx_ref = bt.ELASTICA_TIP_FORCE[alpha]
    assert r["tip_y"] / L == pytest.approx(y_ref, abs=6e-6)  # table has 5 decimals
    assert 1 - r["tip_x"] / L == pytest.approx(dx_ref, abs=6e-6)


def test_curved_cantilever_unloaded_is_an_arc_with_a_rigid_extension():
    r = bt.curved_cantilever_end_load(KAPPA, EI, L, (0.0, 0.0), (0.02, 0.0))
    ax, ay = bt.arc_point(KAPPA, L)
    assert (r["tip_x"], r["tip_y"], r["tip_angle"]) == pytest.approx((float(ax), float(ay), KAPPA * L), rel=1e-10)
    px, py = bt.rigid_extension_point(ax, ay, KAPPA * L, 0.02)
    assert (r["point_x"], r["point_y"]) == pytest.approx((float(px), float(py)), rel=1e-10)


def test_large_deflection_blocked_force_tends_to_closed_form():
    # small curvature: small deflection holds -> closed form to O((kappa L)^2)
    k = KAPPA * 1e-3
    for a in (0.0, 0.02):
        f = bt.curved_cantilever_spring_force(k, EI, L, (a, 0.0), math.inf)
        assert f == pytest.approx(bt.extension_blocked_force(EI, k, L, a), rel=1e-6)
    # finite spring: F = free/(c + 1/k)
    f = bt.curved_cantilever_spring_force(k, EI, L, (0.02, 0.0), 50.0)
    ref = bt.spring_contact_force(bt.extension_free_deflection(k, L, 0.02), bt.extension_compliance(EI, L, 0.02), 50.0)
    assert f == pytest.approx(ref, rel=1e-6)
    # at the paper's 1500 V curvature the geometric nonlinearity is below 1e-2 but not zero
    f = bt.curved_cantilever_spring_force(KAPPA, EI, L, (0.0, 0.0), math.inf)
    assert 1e-4 < f / bt.blocked_force(EI, KAPPA, L) - 1 < 1e-2
