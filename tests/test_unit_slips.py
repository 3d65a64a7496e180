"""Inputs a careless user gives: lengths in mm, angles in degrees, CSV-style column names, one
mechanism added twice to a user's system.  Each warns or refuses with a message that names the
parameter, the value and what is expected."""

from __future__ import annotations

import warnings

import exudyn as exu
import numpy as np
import pytest

from exudyn_atcm import Bender, BendingActuator, Flexure, Layer, Link, MechanismError, PiezoDrive, Result, add_to

PASSIVE = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
ACTIVE = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)


def _bender(**kw):
    args = dict(width=0.028, passive=PASSIVE, active=ACTIVE, length=0.087, n_cells=3, drive=PiezoDrive(1500.0))
    args.update(kw)
    return Bender("b", **{"cell": "rigid", **args})


def test_plausible_si_geometry_is_quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        _bender(base=(0.01, -0.02), angle=-0.5 * np.pi)
        BendingActuator(3, 29e-3, 28e-3, PASSIVE, ACTIVE, PiezoDrive(1500.0), cell="six-bar")
        Link("L", {"A": (0.087, 0.0), "B": (0.1, 0.0)}, mass=1e-3, inertia=1e-7)
        Flexure("f", base=(0.0, 0.0), tip=(0.01, 0.0), width=5e-3, layer=Layer(0.2e-3, 70e9, 1550.0))


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: _bender(length=87.0), "bender 'b': length = 87.0 m is outside the plausible range 0.0001 ... 2 m; "
                                       "is it a length in mm passed as metres?"),
        (lambda: _bender(width=28.0), "bender 'b': width = 28.0 m"),
        (lambda: _bender(angle=90.0), "bender 'b': angle = 90.0 rad is outside the plausible range |value| <= 6.28319 rad; "
                                      "is it an angle in degrees passed as radians?"),
        (lambda: _bender(base=(0.0, 20.0)), "bender 'b': base y = 20.0 m"),
        (lambda: BendingActuator(3, 29.0, 28e-3, PASSIVE, ACTIVE, PiezoDrive(1500.0), cell="six-bar"), "BendingActuator: cell_length = 29.0 m"),
        (lambda: Link("L", {"A": (87.0, 0.0), "B": (100.0, 0.0)}, mass=1e-3, inertia=1e-7), "link 'L': point A x = 87.0 m"),
        (lambda: Flexure("f", base=(0.0, 0.0), tip=(0.01, 0.0), width=5e-3, layer=Layer(0.2, 70e9, 1550.0)),
         "Layer thickness = 0.2 m is outside the plausible range 1e-05 ... 0.01 m"),  # the layer says it now
        (lambda: Flexure("f", base=(0.0, 0.0), tip=(0.01, 0.0), width=5.0, layer=Layer(0.2e-3, 70e9, 1550.0)),
         "flexure 'f': width = 5.0 m"),
    ],
)
def test_unit_slips_warn(make, message):
    with pytest.warns(RuntimeWarning) as record:
        make()
    assert any(message in str(w.message) for w in record), [str(w.message) for w in record]


def test_result_column_suggestions():
    r = Result({"time": [0.0], "b.tip_y": [1.0], "b.tip_x": [0.0]}, {"time": "s", "b.tip_y": "m", "b.tip_x": "m"})
    with pytest.raises(KeyError, match=r"no series 'tip_y' \(did you mean 'b.tip_y'\?\)"):
        r["tip_y"]
    with pytest.raises(KeyError, match=r"series names carry no unit: use 'b.tip_y'"):
        r["b.tip_y [m]"]
    with pytest.raises(KeyError, match=r"no series 'b.tip_y \[m\]' \(series names carry no unit"):
        r.unit("b.tip_y [m]")
    assert "zzz" not in r and r.get("zzz") is None  # the Mapping protocol still sees a plain KeyError


def test_add_to_refuses_a_second_copy_and_a_non_system():
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    add_to(mbs, _bender())
    with pytest.raises(MechanismError, match=r"add_to: component\(s\) \['b'\] are already in this MainSystem"):
        add_to(mbs, _bender(base=(0.0, 0.05)))
    add_to(mbs, Bender("b2", width=0.028, passive=PASSIVE, active=ACTIVE, length=0.087, n_cells=3,
                       drive=PiezoDrive(1500.0), base=(0.0, 0.05), cell="rigid"))  # another name is fine
    with pytest.raises(ValueError, match="mbs must be an exudyn MainSystem .*got SystemContainer"):
        add_to(sc, _bender())


def _solve(mbs, t_end=0.1, steps=100):
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime = t_end
    settings.timeIntegration.numberOfSteps = steps
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    mbs.Assemble()
    mbs.SolveDynamic(settings)


@pytest.mark.parametrize("which", ["pre", "post"])
def test_replacing_the_package_hooks_after_add_to_is_noticed(which):
    """mbs.SetPre/PostStepUserFunction after add_to silently replaced the package's hooks (benders
    not actuated, or memory never committed); now it warns once, naming the fix."""
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    handle = add_to(mbs, _bender())
    getattr(mbs, f"Set{which.capitalize()}StepUserFunction")(lambda m, t: True)
    with pytest.warns(RuntimeWarning, match=rf"add_to: the package's {which}-step hook is not running .*add_pre_step"):
        _solve(mbs)
    if which == "post":
        with pytest.raises(ValueError, match="a later mbs.SetPostStepUserFunction replaced it"):
            handle.result()


def test_package_hooks_alone_are_quiet():
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    handle = add_to(mbs, _bender())
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        _solve(mbs)
    assert handle.result().n_rows == 101  # t = 0 and every accepted step
