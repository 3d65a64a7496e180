"""Issue 3, part 4 (statics and eigenfrequencies): the multibody model against beam theory.

References are the closed-form formulas of docs/theory.rst (``exudyn_atcm.theory.beam``) on
the paper's actuator and two other geometries; each tolerance says what makes the comparison approximate.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm import theory as bt
from exudyn_atcm.mechanism.actuator import BendingActuator
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.solve import eigenfrequencies, solve_static

from _actuator_geometries import GEOMETRIES, REF_A

CELLS = ("rigid", "six-bar")


def composite_kappa(g, strain):
    return bt.free_curvature(g.E1, g.h1, g.E2, g.h2, g.width, strain)


def composite_EI(g):
    return bt.composite_bending_stiffness(g.E1, g.h1, g.E2, g.h2, g.width)


def six_bar_rel_bound(theta_c, rho_s):
    """Bound on the six-bar cell's relative deviation from linear curvature.

    In one cell the active layer's length is ``L + 2 e sin(theta/2)`` and its lever arm
    ``e cos(theta/2)``; expanding the cell's equilibrium gives a relative error of the cell
    rotation ``theta_c² ((1 - rho_s)/6 - 1/8) + O(theta_c⁴)``.  Bound: 1.5x the leading term
    plus theta_c⁴/10 plus round-off.
    """
    return 1.5 * theta_c**2 * abs((1 - rho_s) / 6 - 1 / 8) + theta_c**4 / 10 + 1e-9


# ----------------------------------------------------------------------------- free actuation

@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: g.name)
@pytest.mark.parametrize("cell", CELLS)
@pytest.mark.parametrize("voltage", [100.0, 1500.0])
def test_free_actuation_tip_angle_is_kappa_L_and_tip_on_chain_polygon(geometry, cell, voltage):
    g = geometry
    act = g.actuator(PiezoDrive(voltage), cell=cell)
    r = solve_static(act)
    strain = bt.piezo_strain(voltage)
    kappa = composite_kappa(g, strain)
    angle_ref = kappa * g.length
    theta_c = kappa * act.cell_length
    if cell == "rigid":
        # the rigid chain's rest angles are the linear free rotation: exact up to Newton tolerance
        rel = 1e-9
    else:
        rel = six_bar_rel_bound(theta_c, act.spring_share)
    assert r["actuator.tip_angle"][0] == pytest.approx(angle_ref, rel=rel)
    # tip = last vertex of the chain of rigid passive bars (length L_c) turning theta_c each;
    # an angle error d(theta) moves it by at most L * d(theta_total)
    px, py = bt.chain_polygon(kappa, g.length, g.n_cells)
    tol = g.length * rel * angle_ref + 1e-12
    assert r["actuator.tip_x"][0] == pytest.approx(px[-1], abs=tol)
    assert r["actuator.tip_y"][0] == pytest.approx(py[-1], abs=tol)
    # each cell's passive bar lies at the mean of its interfaces: (j + 1/2) theta_c
    cell_angles = np.array([r[f"actuator.cell_angle_{j + 1}"][0] for j in range(g.n_cells)])
    np.testing.assert_allclose(cell_angles, (np.arange(g.n_cells) + 0.5) * theta_c, rtol=rel, atol=1e-12)


def test_chain_polygon_converges_to_the_arc_of_model_md():
    # docs/theory.rst: the paper's actuator arc tip (85.131, 15.499) mm.  A chain vertex lies within
    # L theta_c² / 12 of the arc (chord vs arc length of each cell), for both cell types.
    for cell in CELLS:
        for n in (3, 24):
            act = REF_A.actuator(PiezoDrive(1500.0), n_cells=n, cell=cell)
            r = solve_static(act)
            theta_c = 4.13984 * act.cell_length
            bound = REF_A.length * theta_c**2 / 12 + 0.5e-6  # + docs/theory.rst rounding
            assert r["actuator.tip_x"][0] == pytest.approx(85.131e-3, abs=bound)
            assert r["actuator.tip_y"][0] == pytest.approx(15.499e-3, abs=bound)


@pytest.mark.parametrize("cell", CELLS)
def test_large_actuation_rotation_beyond_90_degrees_converges(cell):
    # 16 the paper's actuator cells (464 mm) at 1500 V: kappa L = 1.92 rad (110 degrees)
    g = REF_A
    ref = g.actuator(PiezoDrive(1500.0), cell=cell)
    act = BendingActuator(16, 29e-3, g.width, ref.passive, ref.active, ref.drive, cell=cell)
    r = solve_static(act)
    kappa = composite_kappa(g, bt.piezo_strain(1500.0))
    L = 16 * 29e-3
    assert kappa * L > math.pi / 2
    rel = 1e-9 if cell == "rigid" else six_bar_rel_bound(kappa * 29e-3, act.spring_share)
    assert r["actuator.tip_angle"][0] == pytest.approx(kappa * L, rel=rel)
    px, py = bt.chain_polygon(kappa, L, 16)
    assert r["actuator.tip_x"][0] == pytest.approx(px[-1], abs=L * rel * kappa * L + 1e-12)
    assert r["actuator.tip_y"][0] == pytest.approx(py[-1], abs=L * rel * kappa * L + 1e-12)


# ----------------------------------------------------------------------------- paper calibration

@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: g.name)
@pytest.mark.parametrize("cell", CELLS)
def test_paper_stiffness_curvature_ratio(geometry, cell):
    g = geometry
    strain = bt.piezo_strain(500.0)
    ratio_ref = bt.paper_free_curvature(g.E1, g.h1, g.E2, g.h2, g.width, strain) / composite_kappa(g, strain)
    if g is REF_A:
        assert ratio_ref == pytest.approx(1.11, abs=0.005)  # docs/theory.rst
    comp = solve_static(g.actuator(PiezoDrive(500.0), cell=cell, stiffness="composite"))
    paper = solve_static(g.actuator(PiezoDrive(500.0), cell=cell, stiffness="paper"))
    # six-bar: both runs carry the cell's O(theta_c²) kinematic deviation (see six_bar_rel_bound)
    theta_c = 1.2 * composite_kappa(g, strain) * g.cell_length
    rel = 1e-9 if cell == "rigid" else 2 * six_bar_rel_bound(theta_c, 0.2)
    assert paper["actuator.tip_angle"][0] / comp["actuator.tip_angle"][0] == pytest.approx(ratio_ref, rel=rel)


# ----------------------------------------------------------------------------- tip force, small

@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: g.name)
@pytest.mark.parametrize("cell", CELLS)
@pytest.mark.parametrize("n_cells", [1, 2, 5])
def test_small_tip_force_compliance_with_chain_factor(geometry, cell, n_cells):
    g = geometry
    act = g.actuator(PiezoDrive(0.0), n_cells=n_cells, cell=cell)
    EI = composite_EI(g)
    c0 = bt.tip_compliance(EI, g.length)
    F = 1e-3 * g.length / c0  # tip deflection 0.1 % of L: geometric nonlinearity ~1e-6 relative
    r = solve_static(act, tip_force=(0.0, F))
    if cell == "rigid":
        factor = bt.rigid_chain_compliance_factor(n_cells)
    else:
        rho_s = (g.E1 * g.h1**3 + g.E2 * g.h2**3) * g.width / 12 / EI
        factor = bt.six_bar_chain_compliance_factor(n_cells, rho_s)
    # tolerance: the chain factors are exact in linear theory; what remains is the geometric
    # nonlinearity of a deflection of 1e-3 L (relative ~ (1e-3)² x O(1)) -> 1e-5
    assert r["actuator.tip_y"][0] / F == pytest.approx(c0 * factor, rel=1e-5)
    assert act.spring_share == pytest.approx(
        (g.E1 * g.h1**3 + g.E2 * g.h2**3) * g.width / 12 / EI, rel=1e-12)


# ----------------------------------------------------------------------------- tip force, large

@pytest.mark.parametrize("alpha", [1.0, 2.0, 5.0])
def test_large_tip_force_matches_elastica(alpha):
    g = REF_A
    EI = composite_EI(g)
    y_ref, dx_ref = bt.ELASTICA_TIP_FORCE[alpha]
    errors = []
    for n in (16, 32):
        act = g.actuator(PiezoDrive(0.0), n_cells=n, cell="rigid")
        r = solve_static(act, tip_force=(0.0, alpha * EI / g.length**2))
        err_y = r["actuator.tip_y"][0] / g.length - y_ref
        err_x = (1 - r["actuator.tip_x"][0] / g.length) - dx_ref
        # the chain of N rigid cells differs from the continuum by O(1/N²) (its small-deflection
        # compliance factor is 1 + 1/(2N²)); bound 0.5/N², plus the table's rounding (5 digits)
        assert abs(err_y) <= 0.5 / n**2 + 1e-5
        assert abs(err_x) <= 0.5 / n**2 + 1e-5
        errors.append(max(abs(err_y), abs(err_x)))
    # second-order convergence: doubling N cuts the error by ~4 (at least 3)
    assert errors[1] < errors[0] / 3


# ----------------------------------------------------------------------------- eigenfrequencies

@pytest.mark.parametrize("cell", CELLS)
def test_first_eigenfrequency_converges_to_beam_f1(cell):
    g = REF_A
    mu = bt.mass_per_length(g.rho1, g.h1, g.rho2, g.h2, g.width)
    f1 = bt.first_bending_frequency(composite_EI(g), mu, g.length)
    assert f1 == pytest.approx(35.97, abs=0.005)  # docs/theory.rst
    ns = (4, 8, 16)
    errors = []
    for n in ns:
        f = eigenfrequencies(g.actuator(PiezoDrive(0.0), n_cells=n, cell=cell), n=2)
        assert f[0] < f[1]
        errors.append(f[0] / f1 - 1)
    errors = np.array(errors)
    # lumped chains are softer (compliance factors > 1): they approach f1 from below,
    # at second order in 1/N (ratio of successive errors ~4, at least 3)
    assert np.all(errors < 0)
    assert np.all(np.abs(errors[1:]) < np.abs(errors[:-1]) / 3)
    # at 16 cells: rigid -0.18 %, six-bar -0.9 % (measured; bound set by the 1/N² trend)
    assert abs(errors[-1]) < (0.005 if cell == "rigid" else 0.015)


def test_second_eigenfrequency_of_fine_rigid_chain_near_beam_f2():
    # clamped-free beam: f2/f1 = (4.694091/1.875104)² = 6.2669
    g = REF_A
    f = eigenfrequencies(g.actuator(PiezoDrive(0.0), n_cells=32, cell="rigid"), n=2)
    assert f[1] / f[0] == pytest.approx(6.2669, rel=0.01)  # 32 cells: O(1/N²) ~ 0.5 %


@pytest.mark.parametrize("cell", CELLS)
def test_static_with_hysteresis_follows_the_rising_branch_from_reset(cell):
    # from the reset state (negative saturation) a monotone ramp to 500 V ends on the rising
    # branch, which passes through 12 um per 29 mm cell at 500 V (docs/theory.rst, exact exponents)
    H = paper_strain_preisach()
    H.commit(1000.0)  # some history: solve_static must start from the reset state anyway
    before = H.checkpoint()
    output_before = H.output
    act = REF_A.actuator(PiezoDrive(0.0, hysteresis=H), cell=cell)
    r = solve_static(act, voltage=500.0)
    strain = 12e-6 / 29e-3
    assert r["actuator.strain"][0] == pytest.approx(strain, rel=1e-9)
    assert r["actuator.stroke"][0] == pytest.approx(12e-6, rel=1e-9)
    kappa = composite_kappa(REF_A, strain)
    rel = 1e-9 if cell == "rigid" else six_bar_rel_bound(kappa * REF_A.cell_length, act.spring_share)
    assert r["actuator.tip_angle"][0] == pytest.approx(kappa * REF_A.length, rel=rel)
    # the operator's own memory is untouched by the static solve
    assert H.output == output_before
    H.restore(before)
    assert H.evaluate(500.0) != pytest.approx(strain)  # with that history 500 V gives another strain
