"""The third discretisation, ``cell="beam"`` (issue 9, part 4): geometrically exact beam elements.

Validated like the six-bar and rigid cells: against beam theory (``exudyn_atcm.theory.beam``:
Timoshenko's bimetal curvature, the cantilever's tip compliance, Bisshopp & Drucker's elastica,
the clamped-free beam's f1) and against the hysteresis operator applied offline.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.errors import InputRangeWarning

from exudyn_atcm import theory as bt
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.solve import eigenfrequencies, simulate, solve_static

from _actuator_geometries import GEOMETRIES, REF_A
from _actuator_runs import (LeakyOperator, check_end_torque_equals_prestep_path, check_in_step_hysteresis_equals_offline_replay,
                            check_run_starts_in_static_equilibrium, coarse_step_expected,
                            fast_triangle_actuator)

# Newton limited to 2 full iterations: Exudyn rejects and repeats steps (measured 54 in 0.1 s)
REJECTING = {"timeIntegration.newton.maxIterations": 2, "timeIntegration.newton.useModifiedNewton": False}


def composite_kappa(g, strain):
    return bt.free_curvature(g.E1, g.h1, g.E2, g.h2, g.width, strain)


def composite_EI(g):
    return bt.composite_bending_stiffness(g.E1, g.h1, g.E2, g.h2, g.width)


@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: g.name)
@pytest.mark.parametrize("voltage", [100.0, 1500.0])
def test_free_actuation_tip_angle_is_kappa_L_and_nodes_on_the_chain_polygon(geometry, voltage):
    # The end torque EI kappa bends every element to the curvature kappa exactly (uniform
    # moment).  With linear elements the nodes then lie on the chain polygon of chords L_c turning
    # kappa L_c each (no axial or shear strain: chord length L_c, chord along the mean node
    # rotation), and the element angle (mean of its nodes) is (j + 1/2) kappa L_c.
    g = geometry
    act = g.actuator(PiezoDrive(voltage), cell="beam")
    r = solve_static(act)
    kappa = composite_kappa(g, bt.piezo_strain(voltage))
    assert r["actuator.tip_angle"][0] == pytest.approx(kappa * g.length, rel=1e-9)
    px, py = bt.chain_polygon(kappa, g.length, g.n_cells)
    # Newton tolerance 1e-8 N on axial stiffness ~1e5-1e6 N: chord lengths exact to ~1e-13 m
    assert r["actuator.tip_x"][0] == pytest.approx(px[-1], abs=1e-9 * g.length)
    assert r["actuator.tip_y"][0] == pytest.approx(py[-1], abs=1e-9 * g.length)
    angles = np.array([r[f"actuator.cell_angle_{j + 1}"][0] for j in range(g.n_cells)])
    np.testing.assert_allclose(angles, (np.arange(g.n_cells) + 0.5) * kappa * act.cell_length, rtol=1e-9)


def test_end_torque_equals_reference_curvature_in_every_element():
    # the default path (one end torque EI kappa) against Exudyn's prescribed reference curvature
    # written into every element in each pre-step: the same equations (see exudyn_atcm.mbs.actuator_beam), identical
    # runs up to round-off
    check_end_torque_equals_prestep_path("beam", 1e-9)


@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: g.name)
@pytest.mark.parametrize("n_cells", [1, 2, 5])
def test_small_tip_force_compliance_with_element_factor(geometry, n_cells):
    # Linear elements with one-point integration under a tip force F: the element moment is the
    # exact moment at its midpoint, the node rotations are exact, and the tip deflection is the
    # trapezoidal rule over the node rotations: y = (F L^3 / 3EI) (1 - 1/(4 N^2)) exactly in
    # linear theory, plus the shear compliance F L / GA of the (stiff, GA = a1 + a2) axis.
    # Remaining: geometric nonlinearity of a deflection 1e-3 L (relative ~1e-6) -> 1e-5.
    g = geometry
    act = g.actuator(PiezoDrive(0.0), n_cells=n_cells, cell="beam")
    EI = composite_EI(g)
    c0 = bt.tip_compliance(EI, g.length)
    F = 1e-3 * g.length / c0
    r = solve_static(act, tip_force=(0.0, F))
    ga = (g.E1 * g.h1 + g.E2 * g.h2) * g.width
    expected = c0 * (1 - 1 / (4 * n_cells**2)) + g.length / ga
    assert r["actuator.tip_y"][0] / F == pytest.approx(expected, rel=1e-5)
    # the tip rotation is exact at the nodes: F L^2 / 2EI
    assert r["actuator.tip_angle"][0] == pytest.approx(F * g.length**2 / (2 * EI), rel=1e-5)


@pytest.mark.parametrize("alpha", [1.0, 2.0, 5.0])
def test_large_tip_force_matches_elastica(alpha):
    g = REF_A
    EI = composite_EI(g)
    y_ref, dx_ref = bt.ELASTICA_TIP_FORCE[alpha]
    errors = []
    for n in (8, 16):
        act = g.actuator(PiezoDrive(0.0), n_cells=n, cell="beam")
        r = solve_static(act, tip_force=(0.0, alpha * EI / g.length**2))
        err_y = r["actuator.tip_y"][0] / g.length - y_ref
        err_x = (1 - r["actuator.tip_x"][0] / g.length) - dx_ref
        # O(1/N^2) like the small-deflection factor 1/(4N^2): bound 0.5/N^2 plus the table's
        # rounding (5 digits)
        assert abs(err_y) <= 0.5 / n**2 + 1e-5
        assert abs(err_x) <= 0.5 / n**2 + 1e-5
        errors.append(max(abs(err_y), abs(err_x)))
    assert errors[1] < errors[0] / 3  # second order


def test_first_eigenfrequency_converges_to_beam_f1_from_above():
    g = REF_A
    mu = bt.mass_per_length(g.rho1, g.h1, g.rho2, g.h2, g.width)
    f1 = bt.first_bending_frequency(composite_EI(g), mu, g.length)
    assert f1 == pytest.approx(35.97, abs=0.005)
    errors = np.array([eigenfrequencies(g.actuator(PiezoDrive(0.0), n_cells=n, cell="beam"), n=1)[0] / f1 - 1
                       for n in (4, 8, 16)])
    # the element's (lumped-at-midpoint) stiffness is exact in rotation but its consistent mass
    # with linear shape functions over-estimates the frequency: from above, second order (ratio
    # ~4, at least 3); measured +0.70 % at 4 elements.  The rotary inertia of the cross section
    # lowers f1 by ~(h/L)^2 ~ 1e-5, far below these errors.
    assert np.all(errors > 0)
    assert np.all(errors[1:] < errors[:-1] / 3)
    assert errors[-1] < 0.001


def test_bent_beam_f1_changes_at_second_order():
    # as the chains (test_actuator_eigen): the beam's mass line is its reference line, so it has
    # only the even, O((kappa L)^2) change (the chains' even part measured +0.27 % at 1500 V)
    act = REF_A.actuator(PiezoDrive(0.0), n_cells=8, cell="beam")
    f0 = eigenfrequencies(act, n=1)[0]
    d = {v: eigenfrequencies(act, n=1, voltage=v)[0] / f0 - 1 for v in (750.0, 1500.0)}
    with pytest.warns(InputRangeWarning, match="rated range"):  # below the MFC's rated -500 V: computed all the same
        d[-1500.0] = eigenfrequencies(act, n=1, voltage=-1500.0)[0] / f0 - 1
    assert d[1500.0] == pytest.approx(d[-1500.0], rel=1e-3)
    assert d[1500.0] / d[750.0] == pytest.approx(4.0, rel=0.05)
    assert d[1500.0] == pytest.approx(0.0027, abs=0.0003)


def test_in_step_hysteresis_equals_offline_replay_despite_rejected_steps():
    r = check_in_step_hysteresis_equals_offline_replay("beam", REJECTING)
    assert np.diff(r["time"]).min() < 2e-3 * 0.75
    # negative control: committing inside trials drifts once steps are repeated
    H2 = paper_strain_preisach()
    with coarse_step_expected():
        r2 = simulate(fast_triangle_actuator("beam", LeakyOperator(H2)), 0.1, step=2e-3, settings=REJECTING)
    assert np.max(np.abs(r2["actuator.strain"] - H2.apply(r2["actuator.voltage"]))) > 1e-6


@pytest.mark.parametrize("n_cells", [1, 64])
def test_run_starts_in_static_equilibrium(n_cells):
    r, _ = check_run_starts_in_static_equilibrium("beam", n_cells)
    assert [c for c in r if c.startswith("actuator.cell_angle_")] == [f"actuator.cell_angle_{j + 1}" for j in range(n_cells)]


def test_beam_and_rigid_chain_agree_in_a_slow_dynamic_run():
    # a 2 Hz voltage triangle (f1 = 36 Hz: quasi-static up to the 2 % viscous lag), 16 cells:
    # both discretisations follow the same arc; they differ by their O(1/N^2) dynamic errors
    # and the rigid chain's mass-centre offset (~0.2 %), so 1 % of the tip-y range
    from exudyn_atcm.model.signals import Triangle
    runs = {}
    for cell in ("beam", "rigid"):
        act = REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, 0.5)), n_cells=16, cell=cell)
        runs[cell] = simulate(act, 0.5, step=5e-4)
    y_b, y_r = runs["beam"]["actuator.tip_y"], runs["rigid"]["actuator.tip_y"]
    assert y_b.shape == y_r.shape
    assert np.max(np.abs(y_b - y_r)) < 0.01 * np.ptp(y_r)
