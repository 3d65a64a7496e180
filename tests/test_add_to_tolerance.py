"""add_to with beam cells in a user's own solve: Newton's absolute tolerance raised to the cells' floor.

A 24-cell beam bender welded to a lever, solved with ``exudyn.SolveDynamic`` and Exudyn's default
settings (absolute Newton tolerance 1e-10).  Without the package's pre-step function
(:class:`~exudyn_atcm.mbs.tolerance_floor.ToleranceFloor`) Exudyn stops with its generic
``SolveDynamic terminated``; with it the solve runs and gives the same lever motion as the
same model solved with the tolerance set to the floor by hand.
"""

from __future__ import annotations

import warnings

import exudyn as exu
import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm import Bender, Layer, Link, Mechanism, PiezoDrive
from exudyn_atcm.mbs import hooks
from exudyn_atcm.mbs.tolerance_floor import ToleranceFloor
from exudyn_atcm.model.signals import Triangle

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
WIDTH, LENGTH, CELLS = 10e-3, 0.03, 24


def _system(with_floor: bool = True):
    b = Bender("crank", width=WIDTH, passive=CFC, active=MFC, length=LENGTH, n_cells=CELLS,
               drive=PiezoDrive(Triangle(750.0, 750.0, 0.1)), cell="beam")
    lever = Link("lever", {"A": (LENGTH, 0.0), "E": (LENGTH + 0.02, 0.0)}, mass=2e-4, inertia=1e-8)
    mech = Mechanism("m").add(b, lever).ground(b.base).weld(b.tip, lever.point("A"))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    handle = atcm.add_to(mbs, mech)
    if not with_floor:  # the state before the fix: no tolerance check among the pre-step functions
        step_functions = hooks.step_hooks(mbs).pre
        step_functions[:] = [f for f in step_functions if not isinstance(f, ToleranceFloor)]
    mbs.Assemble()
    settings = exu.SimulationSettings()  # Exudyn's defaults: absolute Newton tolerance 1e-10
    settings.timeIntegration.endTime = 0.05
    settings.timeIntegration.numberOfSteps = 50
    settings.solution.file.write = False  # no solution/ folder in the working directory
    return SC, mbs, handle, settings


@pytest.fixture(autouse=True)
def _quiet_exudyn():
    exu.config.printToConsole = False
    yield
    exu.config.printToConsole = True


def test_the_floor_is_the_round_off_of_the_stiff_axis():
    # 10 eps EA / L_c * L with EA = width (E1 t1 + E2 t2) (beam_chain's rule, computed here by hand)
    ea = WIDTH * (70e9 * 0.2e-3 + 30.336e9 * 0.3e-3)
    expected = 10.0 * np.finfo(float).eps * ea / (LENGTH / CELLS) * LENGTH
    _, _, handle, settings = _system()
    assert handle.newton_tolerance_floor == pytest.approx(expected, rel=1e-12)
    assert settings.timeIntegration.newton.absoluteTolerance == 1e-10 < expected  # the default is below it


def test_without_the_check_exudyn_fails_generically():
    _, mbs, handle, settings = _system(with_floor=False)
    with pytest.raises(exu.SolverError, match="SolveDynamic terminated"):
        exu.SolveDynamic(mbs, settings)
    assert handle.result()["time"][-1] < 0.01  # stopped in the first steps


def test_default_settings_are_raised_to_the_floor_and_match_the_floor_set_by_hand():
    _, mbs, handle, settings = _system()
    with pytest.warns(RuntimeWarning) as record:
        assert exu.SolveDynamic(mbs, settings)
    floor = handle.newton_tolerance_floor
    messages = [str(w.message) for w in record if "newton_tolerance_floor" in str(w.message)]
    assert len(messages) == 1
    assert f"tolerance 1e-10 of this solve is below {floor:.3g}" in messages[0]
    assert f"raised to {floor:.3g}" in messages[0]
    assert settings.timeIntegration.newton.absoluteTolerance == 1e-10  # the user's object is untouched
    checks = [f for f in hooks.step_hooks(mbs).pre if isinstance(f, ToleranceFloor)]
    assert [c.raised for c in checks] == [[("dynamicSolver", 1e-10, floor)]]
    got = handle.result()

    _, mbs2, handle2, settings2 = _system()
    settings2.timeIntegration.newton.absoluteTolerance = handle2.newton_tolerance_floor
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # nothing to raise: no warning
        assert exu.SolveDynamic(mbs2, settings2)
    ref = handle2.result()
    np.testing.assert_array_equal(got["time"], ref["time"])
    assert got["time"][-1] == pytest.approx(0.05)
    travel = np.ptp(ref["lever.E_y"])
    assert travel > 1e-3
    for name in ("lever.E_x", "lever.E_y", "crank.tip_y"):
        np.testing.assert_allclose(got[name], ref[name], rtol=0, atol=1e-9 * travel, err_msg=name)


def test_a_second_solve_is_checked_again_and_the_static_solver_too():
    _, mbs, handle, settings = _system()
    with pytest.warns(RuntimeWarning, match="newton_tolerance_floor"):
        assert exu.SolveStatic(mbs, settings)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # warned once per handle: the second solve is raised silently
        assert exu.SolveDynamic(mbs, settings)
    (check,) = [f for f in hooks.step_hooks(mbs).pre if isinstance(f, ToleranceFloor)]
    floor = handle.newton_tolerance_floor
    assert check.raised == [("staticSolver", 1e-10, floor), ("dynamicSolver", 1e-10, floor)]


def test_an_unreachable_solver_is_said_and_a_bad_floor_refused():
    _, mbs, handle, settings = _system()
    settings.timeIntegration.newton.absoluteTolerance = handle.newton_tolerance_floor
    with pytest.warns(RuntimeWarning, match=r"not stored in mbs.sys \(storeSolver=False\?\)"):
        assert exu.SolveDynamic(mbs, settings, storeSolver=False)
    with pytest.raises(ValueError, match="floor must be a positive tolerance"):
        ToleranceFloor(0.0)
