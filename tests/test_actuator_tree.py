"""The rigid chain in minimal coordinates (``ObjectKinematicTree``, issue 9 part 4).

Kept as an internal alternative formulation of ``cell="rigid"`` for the discretisation
benchmark (it was not faster than the rigid bodies with joints, see
``benchmarks/bench_discretisation.py``).  Reference: the existing rigid-body chain, which the
tree must reproduce (same springs, masses and inertias; only the coordinates differ), and beam
theory for the free actuation.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.mbs import actuator_chains as builder
from exudyn_atcm import theory as bt
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.solve import eigenfrequencies, simulate, solve_static

from _actuator_geometries import REF_A


@pytest.fixture
def formulation(monkeypatch):
    def use(name):
        monkeypatch.setattr(builder, "RIGID_FORMULATION", name)
    return use


def test_tree_reproduces_the_rigid_body_chain(formulation):
    out = {}
    for name in ("bodies", "tree"):
        formulation(name)
        act = REF_A.actuator(PiezoDrive(1500.0), n_cells=8, cell="rigid")
        s = solve_static(act, tip_force=(0.0, -0.2))
        f = eigenfrequencies(act, n=3, voltage=1500.0, tip_force=(0.05, 0.1))
        dyn = simulate(REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, 0.05)), n_cells=8, cell="rigid"),
                       0.02, step=1e-4)
        out[name] = (s, f, dyn)
    (sb, fb, db), (st, ft, dt) = out["bodies"], out["tree"]
    # statics with a large tip load (tip turned by 0.06 rad by it): the two formulations agree
    # to 1e-7 rad (1.5e-6 of the load's rotation; both equilibrium residuals < 3e-9 N; the
    # remaining difference was not traced); in the linear range they agree to 3e-10 relative
    # (next test) and under actuation alone to 5e-12 rad
    for name in ("tip_x", "tip_y", "tip_angle", "cell_angle_1", "cell_angle_8"):
        assert st[name][0] == pytest.approx(sb[name][0], abs=2e-7)
    np.testing.assert_allclose(ft, fb, rtol=1e-6)
    # dynamics: the same motion up to the Newton tolerance accumulated over 200 steps
    assert dt.n_rows == db.n_rows
    for name in ("tip_y", "tip_angle"):
        np.testing.assert_allclose(dt[name], db[name], rtol=0, atol=1e-6 * np.max(np.abs(db[name])))


def test_tree_small_tip_force_is_the_chains_linear_compliance(formulation):
    # rigid chain, small deflection: tip angle F L^2 / 2EI exactly (joint moments exact), tip
    # deflection (F L^3 / 3EI)(1 + 1/(2N^2)); force 1e-4 N: nonlinearity ~1e-9 relative
    formulation("tree")
    g = REF_A
    EI = bt.composite_bending_stiffness(g.E1, g.h1, g.E2, g.h2, g.width)
    F = 1e-4
    r = solve_static(REF_A.actuator(PiezoDrive(0.0), n_cells=8, cell="rigid"), tip_force=(0.0, F))
    assert r["tip_angle"][0] == pytest.approx(F * g.length**2 / (2 * EI), rel=1e-8)
    assert r["tip_y"][0] == pytest.approx(F * bt.tip_compliance(EI, g.length) * bt.rigid_chain_compliance_factor(8),
                                          rel=1e-8)


def test_tree_free_actuation_is_kappa_L(formulation):
    formulation("tree")
    act = REF_A.actuator(PiezoDrive(1500.0), n_cells=5, cell="rigid")
    r = solve_static(act)
    kappa = bt.free_curvature(REF_A.E1, REF_A.h1, REF_A.E2, REF_A.h2, REF_A.width, bt.piezo_strain(1500.0))
    assert r["tip_angle"][0] == pytest.approx(kappa * REF_A.length, rel=1e-9)
    px, py = bt.chain_polygon(kappa, REF_A.length, 5)
    assert r["tip_x"][0] == pytest.approx(px[-1], abs=1e-10)
    assert r["tip_y"][0] == pytest.approx(py[-1], abs=1e-10)
