"""The mode the drives ring (``solve.rung_mode``): the step choice's stand-in for symmetric mechanisms.

References: the modes themselves (``modes``: the lowest mode of the micro gripper moves its jaws
antisymmetrically, the second symmetrically, and the mirrored drives' modal forces on the first are
equal and opposite), and runs at a quarter of the chosen step (the time-converged solution within a
sixteenth of the run's error for the second-order integration).
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.casework import Parameters, case_module
from exudyn_atcm.model import Constant, Triangle
from exudyn_atcm.solve import rung_mode, step_choice

from _choice_spy import spy_frequency_error_share

CASES = Path(__file__).resolve().parents[1] / "cases"


def gripper(upper, lower=None, object_stiffness: float | None = 200.0) -> atcm.Mechanism:
    """The micro_gripper case's gripper with 4-mode rod benders holding an object of 200 N/m between its jaws (which
    couples the benders: ``None``, two free benders); ``lower``: another program below."""
    case = case_module(CASES / "micro_gripper.py")
    values = {p.name: p.default for p in case.PARAMETERS}
    values.update(n_cells=4, cell="rod")
    mech = case.build_mechanism(Parameters(case.PARAMETERS, values), object_stiffness, upper)
    if lower is not None:
        mech.drives["lower"].voltage = lower
    return mech


def test_the_gripper_rings_its_symmetric_mode_when_both_benders_are_driven_alike():
    mech = gripper(Triangle(500.0, 1000.0, 0.5))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        modes = atcm.modes(mech, 2, voltage={name: d.voltage_at(0.0) for name, d in mech.drives.items()})
    upper, lower = modes.shape("upper_jaw.jaw"), modes.shape("lower_jaw.jaw")
    assert upper[0, 1] == pytest.approx(lower[0, 1], rel=1e-6)    # mode 1: both jaws move the same way (y)
    assert upper[1, 1] == pytest.approx(-lower[1, 1], rel=1e-6)   # mode 2: they close and open (the object)
    forces = modes.modal_forces
    assert abs(forces[0].sum()) < 1e-6 * np.abs(forces[0]).max()   # the drives' forces on mode 1 cancel
    assert rung_mode.strain_groups(mech, 0.5) == [["upper", "lower"]]
    f, zeta, source = rung_mode.rung_mode(mech, 0.5)
    assert f == pytest.approx(modes.frequencies[1], rel=1e-9) and "cancel" in source
    assert zeta > 0.0


def test_drives_with_different_programs_ring_the_lowest_mode():
    mech = gripper(Triangle(500.0, 1000.0, 0.5), lower=Constant(500.0))
    assert rung_mode.strain_groups(mech, 0.5) == [["upper"], ["lower"]]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        lowest = atcm.eigenfrequencies(mech, n=1, voltage={"upper": -500.0, "lower": 500.0})[0]
    f, _, source = rung_mode.rung_mode(mech, 0.5)
    assert f == pytest.approx(lowest, rel=1e-9) and "lowest" in source


def test_the_gripper_meets_its_target_without_a_refinement():
    # with the antisymmetric 113 Hz mode the stand-in missed the symmetric 211 Hz mode's error: the check failed
    # and the run was refined (the benchmark's triangle: 1.09e-4 s after a refinement, now 1.3e-4 s at once)
    mech = gripper(Triangle(500.0, 1000.0, 0.5))
    run = atcm.simulate(mech, 0.3, accuracy=1e-3)
    assert run.info["accuracy"]["refined"] is False
    assert run.info["accuracy"]["mode_frequency [Hz]"] == pytest.approx(211.5, rel=1e-2)
    reference = atcm.simulate(gripper(Triangle(500.0, 1000.0, 0.5)), 0.3, step=run.info["step [s]"] / 4)
    assert step_choice.position_error(reference, run, run.info["step [s]"]) <= 1e-3


def test_a_failed_analysis_falls_back_to_the_clamped_free_estimate(monkeypatch):
    def failing(*args, **kwargs):
        raise RuntimeError("no equilibrium")
    monkeypatch.setattr(rung_mode, "modes_state", failing)
    mech = gripper(Triangle(500.0, 1000.0, 0.5))
    f, zeta, source = rung_mode.rung_mode(mech, 0.5)
    assert "clamped-free" in source and math.isfinite(f) and f > 0.0
    assert zeta == pytest.approx(rung_mode.lowest_damping_ratio(mech, 2.0 * math.pi * f))


def test_two_free_benders_ring_their_common_lowest_mode():
    # without the object the benders are not coupled: one frequency twice (113 Hz), in a basis the eigensolver
    # chooses; each bender rings at it, and so does the stand-in
    mech = gripper(Triangle(500.0, 1000.0, 0.5), object_stiffness=None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        lowest = atcm.eigenfrequencies(mech, n=2, voltage={"upper": -500.0, "lower": -500.0})
    assert lowest[1] == pytest.approx(lowest[0], rel=1e-9)
    f, _, _ = rung_mode.rung_mode(mech, 0.5)
    assert f == pytest.approx(lowest[0], rel=1e-9)


def test_a_drives_program_set_after_construction_reaches_the_run():
    # PiezoDrive.voltage was a plain attribute and voltage_at kept the program given at construction: a program set
    # afterwards reached the step choice's stand-in (which reads .voltage) but not the run (until 2026-11-29)
    drive = atcm.PiezoDrive(0.0)
    drive.voltage = Triangle(500.0, 500.0, 0.1)
    assert drive.voltage_at(0.05) == pytest.approx(1000.0) and drive.controller is None
    with pytest.raises(ValueError, match="voltage must be a finite number"):
        drive.voltage = "500"
    assert drive.voltage_at(0.05) == pytest.approx(1000.0)  # a refused program leaves the last one
    b = atcm.Bender("b", width=28e-3, passive=atcm.Layer(0.2e-3, 70e9, 1550.0),
                    active=atcm.Layer(0.3e-3, 30.336e9, 5440.0), length=0.087, n_cells=3, cell="rod", drive=drive)
    run = atcm.simulate(atcm.Mechanism("m").add(b).ground(b.base), 0.1, step=1e-3)
    assert run["b.voltage"][50] == pytest.approx(1000.0)


def test_the_cell_choice_follows_the_mode_the_drives_ring(monkeypatch):
    # the gripper's benders with their counts left open: the frequency whose convergence the choice turns into a
    # position error is the symmetric mode's (about 211 Hz), not the antisymmetric lowest's (113 Hz)
    from exudyn_atcm.solve import cell_choice
    case = case_module(CASES / "micro_gripper.py")
    values = {p.name: p.default for p in case.PARAMETERS}
    values.update(n_cells="auto", cell="rod")
    mech = case.build_mechanism(Parameters(case.PARAMETERS, values), 200.0, Triangle(500.0, 1000.0, 0.5))
    calls = spy_frequency_error_share(monkeypatch)
    choice = atcm.choose_cells(mech, 0.5, 1e-3)
    n = choice.cells["upper"][1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        modes = atcm.modes(cell_choice.with_cells(mech, {"upper": ("rod", n), "lower": ("rod", n)}), 2)
    seen = [frequency for frequency, _ in calls]
    assert seen and seen[-1] == pytest.approx(modes.frequencies[1], rel=1e-9)
    assert modes.frequencies[1] > 1.5 * modes.frequencies[0]
