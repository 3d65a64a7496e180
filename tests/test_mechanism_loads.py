"""Issue 7, part 1 (connections and loads): sliders, stops, follower and dead forces, torques,
linear springs, PRBM flexures; each against a closed-form equilibrium of rigid links.

References: Hooke's law, moment balance about a pin solved independently (scipy.optimize),
Howell's pseudo-rigid-body model (a pin with K = gamma k_theta EI/L at the characteristic pivot).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import exudyn_atcm as atcm
from exudyn_atcm import Bender, Flexure, Layer, Link, Mechanism, MechanismError, simulate, solve_static

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)


def block(name="block", at=(0.0, 0.0)):
    return Link(name, {"C": at, "F": (at[0] + 0.01, at[1])}, mass=1e-3, inertia=1e-7, center_of_mass=at)


def test_slider_with_spring_follows_hookes_law_and_blocks_the_normal_direction():
    k, f = 200.0, (0.3, -0.7)
    m = Mechanism().add(block()).ground("block.C", joint="slider", axis=(1.0, 0.0), stiffness=k)
    m.force("block.C", f)
    r = solve_static(m)
    assert r["block.C_x"][0] == pytest.approx(f[0] / k, rel=1e-9)
    assert r["block.C_y"][0] == pytest.approx(0.0, abs=1e-12)
    assert r["block.angle"][0] == pytest.approx(0.0, abs=1e-12)


def test_inclined_slider_between_two_links():
    axis = np.array([math.cos(0.5), math.sin(0.5)])
    base = Link("base", {"O": (0.0, 0.0), "S": (0.02, 0.0)}, mass=1e-3, inertia=1e-7)
    slide = Link("slide", {"S": (0.02, 0.0), "P": (0.03, 0.0)}, mass=1e-3, inertia=1e-7)
    m = Mechanism().add(base, slide).ground("base.O").slider("base.S", "slide.S", axis=tuple(axis), stiffness=50.0)
    m.force("slide.S", (1.0, 0.0))
    r = solve_static(m)
    # the axial component of the force against the spring: displacement (F . a)/k along a
    d = np.array([r["slide.S_x"][0] - 0.02, r["slide.S_y"][0]])
    np.testing.assert_allclose(d, axis * (axis @ [1.0, 0.0]) / 50.0, rtol=1e-9, atol=1e-15)


def test_stop_pushes_back_with_its_stiffness_and_reports_compression():
    # a block held by a slider spring k1 and pushed by f towards a floor 1 mm below; alone the spring
    # would give 2 mm: with the floor f = k1 |y| + k_stop (|y| - 1 mm)
    k1, k_stop, f = 1e3, 1e4, 2.0
    m = Mechanism().add(block()).ground("block.C", joint="slider", axis=(0.0, 1.0), stiffness=k1)
    m.force("block.C", (0.0, -f)).stop("block.C", position=(0.0, -1e-3), normal=(0.0, 1.0), stiffness=k_stop,
                                       name="floor")
    r = solve_static(m)
    y = (f + k_stop * 1e-3) / (k1 + k_stop)
    assert r["block.C_y"][0] == pytest.approx(-y, rel=1e-9)
    assert r["floor.force"][0] == pytest.approx(k_stop * (y - 1e-3), rel=1e-8)
    assert r.unit("floor.force") == "N"


def pinned_arm(k_pin=0.05):
    arm = Link("arm", {"O": (0.0, 0.0), "P": (0.02, 0.0)}, mass=1e-4, inertia=1e-8)
    return Mechanism().add(arm).ground("arm.O", joint="pin", stiffness=k_pin)


def test_follower_force_keeps_its_moment_and_dead_force_does_not():
    k, r_arm, f = 0.05, 0.02, 2.0
    follower = solve_static(pinned_arm(k).force("arm.P", (0.0, f), follower=True))
    dead = solve_static(pinned_arm(k).force("arm.P", (0.0, f)))
    # follower: the moment f r stays -> theta = f r / k; dead: f r cos(theta) = k theta.
    # Newton stops at a residual of 1e-8 N m: 2e-7 rad on this 0.05 N m/rad spring
    assert follower["arm.angle"][0] == pytest.approx(f * r_arm / k, abs=4e-7)
    theta_dead = brentq(lambda t: f * r_arm * math.cos(t) - k * t, 0.0, 1.5)
    assert dead["arm.angle"][0] == pytest.approx(theta_dead, abs=4e-7)
    assert follower["arm.angle"][0] > dead["arm.angle"][0] + 0.1


def test_torque_against_a_linear_spring_between_points():
    """Arm pinned at O; spring from P = (r, 0) to an anchor Q = (r, -d) welded to the ground."""
    r_arm, d, k, torque = 0.02, 0.01, 100.0, 5e-3
    anchor = Link("anchor", {"Q": (r_arm, -d)}, mass=1e-4, inertia=1e-8)
    m = pinned_arm(0.0).add(anchor).ground("anchor.Q").spring("arm.P", "anchor.Q", k, name="spring")
    m.torque("arm", torque)
    res = solve_static(m)

    def moment(theta):
        p = r_arm * np.array([math.cos(theta), math.sin(theta)])
        v = p - np.array([r_arm, -d])
        length = np.linalg.norm(v)
        force_on_p = -k * (length - d) * v / length
        return torque + p[0] * force_on_p[1] - p[1] * force_on_p[0]

    theta = brentq(moment, 0.0, 1.0)
    # Newton stops at a residual of 1e-8 N m; the spring's rotational stiffness is about k r^2 = 0.04 N m/rad
    assert res["arm.angle"][0] == pytest.approx(theta, abs=5e-7)
    p = r_arm * np.array([math.cos(theta), math.sin(theta)])
    tension = k * (np.linalg.norm(p - [r_arm, -d]) - d)
    assert res["spring.force"][0] == pytest.approx(tension, rel=1e-5)
    assert tension > 0.1


def test_time_dependent_force_acts_at_the_step_time():
    # a slow ramp on a stiff slider: quasi-static, x(t) = F(t)/k
    m = Mechanism().add(block()).ground("block.C", joint="slider", axis=(1.0, 0.0), stiffness=1e4, damping=5.0)
    m.force("block.C", lambda t: (100.0 * t, 0.0))
    r = simulate(m, 0.2, step=1e-3)
    i = r.n_rows - 1
    # inertia lag of a 1 kg/m^2... mass 1e-3 kg on 1e4 N/m (50 Hz... 500 Hz): the ramp 100 N/s lags by c/k
    assert r["block.C_x"][i] == pytest.approx(100.0 * r["time"][i] / 1e4 - 100.0 * 5.0 / 1e4**2, rel=1e-3)


def test_prbm_flexure_tip_under_end_moment_turns_by_m_over_k():
    """Howell's PRBM: the tip segment turns about the characteristic pivot by M/K."""
    fx = Flexure("hinge", base=(0.0, 0.0), tip=(0.02, 0.0), width=5e-3, layer=Layer(0.1e-3, 70e9, 1550.0))
    lever = Link("lever", {"A": (0.02, 0.0), "B": (0.03, 0.0)}, mass=1e-4, inertia=1e-8)
    m = Mechanism().add(fx, lever).ground(fx.base).weld(fx.tip, "lever.A").torque("lever", 1e-4)
    r = solve_static(m)
    theta = 1e-4 / fx.torsion_stiffness
    assert r["hinge.tip_angle"][0] == pytest.approx(theta, rel=1e-9)
    assert r["hinge.base_angle"][0] == pytest.approx(0.0, abs=1e-12)
    pivot = np.array(fx.pivot)
    tip = pivot + fx.segment_lengths[1] * np.array([math.cos(theta), math.sin(theta)])
    np.testing.assert_allclose([r["hinge.tip_x"][0], r["hinge.tip_y"][0]], tip, rtol=0, atol=1e-12)
    np.testing.assert_allclose([r["lever.B_x"][0], r["lever.B_y"][0]],
                               tip + 0.01 * np.array([math.cos(theta), math.sin(theta)]), rtol=0, atol=1e-12)


def test_cells_flexure_equals_a_passive_bender():
    kw = dict(base=(0.0, 0.0), tip=(0.0, 0.02), width=5e-3, layer=Layer(0.1e-3, 70e9, 1550.0))
    fx = Flexure("hinge", model="cells", n_cells=6, **kw)
    b = Bender("hinge", width=5e-3, passive=Layer(0.1e-3, 70e9, 1550.0), length=0.02, n_cells=6, angle=math.pi / 2, cell="rigid")
    r1 = solve_static(Mechanism().add(fx).ground(fx.base).force(fx.tip, (1e-3, 0.0)))
    r2 = solve_static(Mechanism().add(b).ground(b.base).force(b.tip, (1e-3, 0.0)))
    for name in ("hinge.tip_x", "hinge.tip_y", "hinge.tip_angle"):
        assert r1[name][0] == pytest.approx(r2[name][0], abs=1e-12)
    assert r1["hinge.tip_x"][0] > 5e-5


def test_a_passive_six_bar_strip_is_refused_with_the_alternative():
    b = Bender("b", width=1e-2, passive=CFC, length=0.03, n_cells=4, cell="six-bar")
    with pytest.raises(MechanismError, match=r"six-bar cell models two layers.*needs cell='rigid'"):
        solve_static(Mechanism().add(b).ground(b.base))
    assert issubclass(MechanismError, ValueError) and atcm.MechanismError is MechanismError


def test_a_load_function_returning_nonsense_is_reported_with_its_name_and_time():
    m = Mechanism().add(block()).ground("block.C", joint="slider", axis=(1.0, 0.0), stiffness=1e4)
    m.force("block.C", lambda t: (float("nan") if t > 0.005 else 0.0, 0.0), name="push")
    with pytest.raises(ValueError, match=r"force 'push' gave \(nan, 0.0\) at t = 0.006"):
        simulate(m, 0.01, step=1e-3)
    m2 = Mechanism().add(block()).ground("block.C", joint="slider", axis=(1.0, 0.0), stiffness=1e4)
    m2.force("block.C", lambda t: 1.0)
    with pytest.raises(ValueError, match="must give a pair"):
        solve_static(m2)
