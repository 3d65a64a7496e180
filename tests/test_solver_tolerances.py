"""Solver tolerances: static solves as accurate at small voltages as at large ones (rigid cells), and the dynamic settings of mechanisms.

A chain of rigid cells actuated by joint torques is nearly linear in its rotations: with an
absolute Newton tolerance of 1e-8 (SI) Exudyn accepted the first Newton step at small voltages,
and a 60 mm bender of 16 rigid cells at 20 V missed about 19 % of its second-order shortening
``L - x_tip``.  The rigid cell now asks for a tolerance relative to the step's first residual
(:attr:`exudyn_atcm.cells.CellKind.static_tolerances`).  Reference: the exact static shape of
a chain of N rigid cells bent by the free curvature is the chain polygon inscribed in the arc
(:func:`exudyn_atcm.theory.chain_polygon`), whatever the voltage.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

import exudyn_atcm as atcm
from exudyn_atcm import theory

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import bench_systems as bm  # noqa: E402 - the four-bar and the gripper of the mechanism benchmarks

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
W, L = 28e-3, 0.06


def _polygon_tip(strain: float, n: int) -> tuple[float, float]:
    kappa = theory.free_curvature(CFC.youngs_modulus, CFC.thickness, MFC.youngs_modulus, MFC.thickness, W, strain)
    x, y = theory.chain_polygon(float(kappa), L, n)
    return float(x[-1]), float(y[-1])


@pytest.mark.parametrize("n", [16, 40])
@pytest.mark.parametrize("voltage", [20.0, 200.0, 1500.0])
@pytest.mark.parametrize("system", ["actuator", "mechanism"])
def test_rigid_chain_shortening_is_exact_at_any_voltage(system, voltage, n):
    if system == "actuator":
        r = atcm.solve_static(atcm.BendingActuator(n, L / n, W, CFC, MFC, atcm.PiezoDrive(0.0), cell="rigid"),
                              voltage=voltage)
        x, y, strain = r["actuator.tip_x"][-1], r["actuator.tip_y"][-1], r["actuator.strain"][-1]
    else:
        b = atcm.Bender("b", width=W, passive=CFC, active=MFC, length=L, n_cells=n, cell="rigid",
                        drive=atcm.PiezoDrive(0.0))
        r = atcm.solve_static(atcm.Mechanism("m").add(b).ground(b.base), voltage=voltage)
        x, y, strain = r["b.tip_x"][-1], r["b.tip_y"][-1], r["b.strain"][-1]
    px, py = _polygon_tip(strain, n)
    shortening = L - px
    # was 0.19 of the shortening at 20 V; now round-off of the tip position (1e-16 m) against a
    # shortening of 1.1e-7 m at 20 V
    assert abs(x - px) <= 1e-6 * shortening
    assert y == pytest.approx(py, rel=1e-12)


@pytest.mark.parametrize("name", ["four_bar", "gripper"])
def test_rigid_mechanisms_still_converge_statically(name):
    """The relative tolerance keeps the closed loops on Exudyn's static solver (no relaxation fallback)."""
    mech = bm.MECHANISMS[name](8, "rigid")
    r = atcm.static_sweep(mech, [0.0, 20.0, 500.0, 1500.0, 20.0])
    assert r.info["methods"] == "static"


@pytest.mark.parametrize("name, bound", [("four_bar", 1e-5), ("gripper", 2e-5)])
def test_dynamic_newton_settings_keep_mechanism_paths_accurate(name, bound):
    """The package's dynamic settings (modified Newton, absolute 1e-8) against full Newton at 1e-12.

    Measured over 0.1 s (``benchmarks/bench_solver_settings.py``): 3.9e-7 (four-bar) and 1.9e-6
    (gripper) of the tracked point's travel, far below the 1e-4 the finest accuracy target of the
    mechanism benchmark asks; the bound leaves a factor of 10-25 for other machines' round-off.
    """
    tight = {"timeIntegration.newton.useModifiedNewton": False, "timeIntegration.newton.absoluteTolerance": 1e-12,
             "timeIntegration.newton.relativeTolerance": 1e-12}
    reference = atcm.simulate(bm.MECHANISMS[name](8, "rigid"), 0.1, step=1e-4, settings=tight)
    result = atcm.simulate(bm.MECHANISMS[name](8, "rigid"), 0.1, step=1e-4)
    assert bm.path_error(result, reference, bm.TRACKED[name]) < bound
