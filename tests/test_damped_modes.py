"""The lowest mode's damping ratio of a whole mechanism (``mbs.linear.damped_modes``), as the step choice uses it.

References: the closed form ``zeta = beta omega / 2`` of stiffness-proportional damping on a lone bender (every
mode of ``C = beta K`` has it), and the poles of the linear state-space model (``linearise``: the damped
eigenvalues of ``A``, ``zeta = -Re(p) / |p|``) of the ``compliant_four_bar`` case, whose flexures and bender
damp at different ratios.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.casework import case_module
from exudyn_atcm.model import Triangle
from exudyn_atcm.solve import mechanism_solve, step_choice

from _choice_spy import spy_frequency_error_share

CASES = Path(__file__).resolve().parents[1] / "cases"
CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)


def compliant_four_bar(period: float = 0.5) -> atcm.Mechanism:
    four_bar = case_module(CASES / "compliant_four_bar.py")
    p = four_bar.CASE.resolve({})
    return four_bar.build_mechanism(p, four_bar.strain_laws(p.exponents)["hysteresis"], Triangle(500.0, 1000.0, period))


def pole_damping(mech: atcm.Mechanism, output: str) -> tuple[float, float]:
    """Frequency [Hz] and damping ratio of the lowest oscillating pole of the linear model about the start state."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        poles = atcm.linearise(mech, outputs=[output]).poles
    oscillating = poles[np.abs(poles.imag) > 0.0]
    pole = oscillating[np.argmin(np.abs(oscillating))]
    return abs(pole) / (2.0 * math.pi), -pole.real / abs(pole)


@pytest.mark.parametrize("cell", ["rod", "rigid"])
def test_a_lone_bender_with_stiffness_proportional_damping_has_beta_omega_over_two(cell):
    beta = 2e-4  # s
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=4, cell=cell,
                    damping=atcm.RayleighDamping(beta=beta), drive=atcm.PiezoDrive(0.0))
    mech = atcm.Mechanism("lone").add(b).ground(b.base)
    freqs, zetas = mechanism_solve.eigenfrequencies(mech, 2, damping=True)
    np.testing.assert_allclose(zetas, beta * 2.0 * math.pi * freqs / 2.0, rtol=1e-6)
    np.testing.assert_allclose(freqs, mechanism_solve.eigenfrequencies(mech, 2), rtol=1e-9)


def test_the_compliant_four_bars_lowest_mode_is_damped_as_its_linear_models_pole():
    # the flexures' Rayleigh ratio at the mode's 55 Hz is 1.6e-4, the bender's 0.02: the mode's is neither
    mech = compliant_four_bar()
    f_pole, zeta_pole = pole_damping(mech, "coupler.P_x")
    start = {name: drive.voltage_at(0.0) for name, drive in mech.drives.items()}  # where linearise takes the state
    freqs, zetas = mechanism_solve.eigenfrequencies(mech, 1, start, damping=True)
    assert freqs[0] == pytest.approx(f_pole, rel=1e-3)
    assert zetas[0] == pytest.approx(zeta_pole, rel=0.02)  # the diagonal approximation of non-proportional damping
    smallest = step_choice.lowest_damping_ratio(mech, 2.0 * math.pi * freqs[0])
    assert smallest < 0.05 * zetas[0]


def test_the_step_choice_takes_the_modes_damping_and_meets_the_target():
    # with the parts' smallest ratio (1.6e-4) the stand-in rang on for the whole run and missed 3.5 times the
    # run's error: 1.43e-4 s where 2.5e-4 s meets 1e-3 (0.39 s of CPU per case run against 0.22 s).  Reference:
    # the same mechanism at an eighth of the chosen step
    mech = compliant_four_bar()
    run = atcm.simulate(mech, 0.5, accuracy=1e-3)
    info = run.info["accuracy"]
    assert info["damping_ratio"] == pytest.approx(pole_damping(mech, "coupler.P_x")[1], rel=0.02)
    assert run.info["step [s]"] >= 2e-4
    reference = atcm.simulate(compliant_four_bar(), 0.5, step=run.info["step [s]"] / 8)
    assert step_choice.position_error(reference, run, run.info["step [s]"]) <= 1e-3


def test_the_cell_choice_rings_its_stand_in_with_the_modes_damping_too(monkeypatch):
    # the compliant four-bar with its crank's rod modes left open: each count's frequency error is turned into a
    # position error by the stand-in, damped as the count's lowest mode (the flexures' 1.6e-4 before 2026-11-29)
    from exudyn_atcm.casework import Parameters
    from exudyn_atcm.solve import cell_choice
    four_bar = case_module(CASES / "compliant_four_bar.py")
    values = {p.name: p.default for p in four_bar.PARAMETERS}
    values.update(n_cells="auto", cell="rod")
    mech = four_bar.build_mechanism(Parameters(four_bar.PARAMETERS, values), four_bar.strain_laws("exact")["hysteresis"],
                                    Triangle(500.0, 1000.0, 0.5))
    calls = spy_frequency_error_share(monkeypatch)
    choice = atcm.choose_cells(mech, 0.5, 1e-3)
    n = choice.cells["crank"][1]
    reference = mechanism_solve.eigenfrequencies(cell_choice.with_cells(mech, {"crank": ("rod", n)}), 1, None,
                                                 damping=True)[1][0]
    seen = [zeta for _, zeta in calls]
    assert seen and seen[-1] == pytest.approx(reference, rel=1e-6)
    assert seen[-1] > 20.0 * step_choice.lowest_damping_ratio(mech, 2.0 * math.pi * 55.0)
