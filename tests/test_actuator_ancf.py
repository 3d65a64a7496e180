"""The ``cell="ancf"`` discretisation (issue 9, part 4): ANCF cable elements (cubic Hermite).

Validated like the other cells against beam theory (``exudyn_atcm.theory.beam``: Timoshenko's
bimetal curvature and arc, the cantilever's tip compliance, Bisshopp & Drucker's elastica, the
clamped-free beam's f1) and against the hysteresis operator applied offline.  Cubic elements
converge at higher order than the linear ones: the bounds below scale with 1/N^4.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm import theory as bt
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.solve import eigenfrequencies, simulate, solve_static

from _actuator_geometries import GEOMETRIES, REF_A
from _actuator_runs import (LeakyOperator, check_end_torque_equals_prestep_path, check_in_step_hysteresis_equals_offline_replay,
                            check_run_starts_in_static_equilibrium, coarse_step_expected,
                            fast_triangle_actuator)

REJECTING = {"timeIntegration.newton.maxIterations": 2, "timeIntegration.newton.useModifiedNewton": False}


def composite_kappa(g, strain):
    return bt.free_curvature(g.E1, g.h1, g.E2, g.h2, g.width, strain)


def composite_EI(g):
    return bt.composite_bending_stiffness(g.E1, g.h1, g.E2, g.h2, g.width)


@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: g.name)
@pytest.mark.parametrize("n_cells", [1, 3, 8])
def test_free_actuation_follows_the_arc(geometry, n_cells):
    # uniform moment EI kappa: the continuum bends into the arc of curvature kappa.  A cubic
    # element with reduced integration represents it to O((kappa L_c)^4): measured relative
    # tip-angle error 8.3e-3 (kappa L_c)^4 at 1, 3 and 8 elements of the paper's actuator at 1500 V (1.4e-4,
    # 1.7e-6, 3.4e-8); bound 1.2e-2 (kappa L_c)^4 + 1e-9
    g = geometry
    voltage = 1500.0
    act = g.actuator(PiezoDrive(voltage), n_cells=n_cells, cell="ancf")
    r = solve_static(act)
    kappa = composite_kappa(g, bt.piezo_strain(voltage))
    rel = 1.2e-2 * (kappa * act.cell_length) ** 4 + 1e-9
    assert r["actuator.tip_angle"][0] == pytest.approx(kappa * g.length, rel=rel)
    x, y = bt.arc_point(kappa, g.length)
    assert r["actuator.tip_x"][0] == pytest.approx(float(x), abs=rel * g.length)
    assert r["actuator.tip_y"][0] == pytest.approx(float(y), abs=rel * g.length)
    angles = np.array([r[f"actuator.cell_angle_{j + 1}"][0] for j in range(n_cells)])
    np.testing.assert_allclose(angles, (np.arange(n_cells) + 0.5) * kappa * act.cell_length, rtol=rel)


def test_end_torque_equals_reference_curvature_in_every_element():
    # the same equations up to the element's reduced quadrature of the reference-curvature
    # term, an O((kappa L_c)^4) difference like the arc error above: measured 5e-6 of the
    # largest value (3 cells, up to 1500 V) -> 2e-5
    check_end_torque_equals_prestep_path("ancf", 2e-5)


@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: g.name)
@pytest.mark.parametrize("n_cells", [2, 5])
def test_small_tip_force_compliance_is_the_beams(geometry, n_cells):
    # cubic Hermite elements contain the exact small-deflection cantilever: tip deflection
    # L^3 / 3EI plus the axial compliance's share (~1e-6) and the reduced integration's
    # O(1/N^4) error (measured 2.7e-6 at 3 elements of the paper's actuator, 3.7e-5 at 2 GEO-C elements):
    # tolerance 1e-3 / N^4 + 1e-5
    g = geometry
    act = g.actuator(PiezoDrive(0.0), n_cells=n_cells, cell="ancf")
    EI = composite_EI(g)
    c0 = bt.tip_compliance(EI, g.length)
    F = 1e-3 * g.length / c0
    r = solve_static(act, tip_force=(0.0, F))
    assert r["actuator.tip_y"][0] / F == pytest.approx(c0, rel=1e-3 / n_cells**4 + 1e-5)
    assert r["actuator.tip_angle"][0] == pytest.approx(F * g.length**2 / (2 * EI), rel=1e-3 / n_cells**4 + 1e-5)


@pytest.mark.parametrize("alpha", [1.0, 2.0, 5.0])
def test_large_tip_force_matches_elastica(alpha):
    g = REF_A
    EI = composite_EI(g)
    y_ref, dx_ref = bt.ELASTICA_TIP_FORCE[alpha]
    act = g.actuator(PiezoDrive(0.0), n_cells=16, cell="ancf")
    r = solve_static(act, tip_force=(0.0, alpha * EI / g.length**2))
    # at large rotations per element the cubic element converges only from ~0.2 rad per element
    # on (alpha = 5: errors 1.2e-3 / 4.8e-5 / 9e-6 at 8 / 16 / 32 elements, measured): 16
    # elements, tolerance 1e-4 plus the table's rounding (5 digits)
    assert r["actuator.tip_y"][0] / g.length == pytest.approx(y_ref, abs=1.1e-4)
    assert 1 - r["actuator.tip_x"][0] / g.length == pytest.approx(dx_ref, abs=1.1e-4)


def test_first_eigenfrequency_converges_from_above_at_fourth_order():
    g = REF_A
    mu = bt.mass_per_length(g.rho1, g.h1, g.rho2, g.h2, g.width)
    f1 = bt.first_bending_frequency(composite_EI(g), mu, g.length)
    errors = np.array([eigenfrequencies(g.actuator(PiezoDrive(0.0), n_cells=n, cell="ancf"), n=1)[0] / f1 - 1
                       for n in (1, 2, 4)])
    # consistent cubic mass and stiffness: from above, O(1/N^4) (doubling N divides by ~16,
    # at least 8); measured +0.48 % / +0.048 % / +0.0034 %
    assert np.all(errors > 0)
    assert np.all(errors[1:] < errors[:-1] / 8)
    assert errors[1] < 1e-3


def test_in_step_hysteresis_equals_offline_replay_despite_rejected_steps():
    check_in_step_hysteresis_equals_offline_replay("ancf", REJECTING)
    H2 = paper_strain_preisach()
    with coarse_step_expected():
        r2 = simulate(fast_triangle_actuator("ancf", LeakyOperator(H2)), 0.1, step=2e-3, settings=REJECTING)
    assert np.max(np.abs(r2["actuator.strain"] - H2.apply(r2["actuator.voltage"]))) > 1e-6


@pytest.mark.parametrize("n_cells", [1, 32])
def test_run_starts_in_static_equilibrium(n_cells):
    r, _ = check_run_starts_in_static_equilibrium("ancf", n_cells)
    assert [c for c in r if c.startswith("actuator.cell_angle_")] == [f"actuator.cell_angle_{j + 1}" for j in range(n_cells)]


def test_bent_state_f1_converges_to_the_linear_elements_value_and_locks_when_coarse():
    # About the state bent at 1500 V (kappa L = 0.36 rad) the cubic element's axial constraint
    # locks on coarse meshes: f1 measured +4.5 % / +0.67 % / +0.27 % / +0.26 % above the straight
    # value at 2 / 4 / 8 / 16 elements, while the linear beam elements give +0.27 % at any
    # count (the O((kappa L)^2) change of the pre-curved beam, tests/test_actuator_eigen.py).
    # Checks: at 16 elements the change equals the linear elements' to 2e-4; at 2 elements the
    # locking is there (> 3 %), as the docs state (use >= 8 elements about bent states).
    changes = {}
    for cell, n in (("ancf", 2), ("ancf", 16), ("beam", 16)):
        act = REF_A.actuator(PiezoDrive(0.0), n_cells=n, cell=cell)
        changes[(cell, n)] = eigenfrequencies(act, n=1, voltage=1500.0)[0] / eigenfrequencies(act, n=1)[0] - 1
    assert changes[("ancf", 16)] == pytest.approx(changes[("beam", 16)], abs=2e-4)
    assert changes[("ancf", 2)] > 0.03
