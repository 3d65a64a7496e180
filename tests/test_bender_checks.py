"""Every bender's cell-kind run checks, wherever the bender sits (issue 30, part 1).

The ``ritz`` kind linearises the dynamics about the quasi-static arc and warns when the tip
rotation leaves it by more than :data:`~exudyn_atcm.theory.ritz_beam.DYNAMIC_ROTATION_LIMIT`
(0.05 rad).  Before issue 30 the check ran for a lone ``BendingActuator`` only: the same bender
inside a ``Mechanism`` was silent.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm import Bender, Layer, Mechanism, PiezoDrive, simulate
from exudyn_atcm.signals import PiecewiseLinear
from exudyn_atcm.solve.bender_checks import bender_view
from exudyn_atcm.theory import ritz_beam as rb

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
L = 0.087  # the paper actuator's length [m] (3 x 29 mm), 28 mm wide: f1 about 36 Hz


def _ritz_cantilever(ramp: float, angle: float, side: str) -> tuple[Mechanism, Bender]:
    drive = PiezoDrive(PiecewiseLinear([0.0, ramp], [0.0, 1500.0]))
    b = Bender("b", width=28e-3, passive=CFC, active=MFC, length=L, n_cells=4, drive=drive, cell="ritz",
               angle=angle, active_side=side)
    return Mechanism("m").add(b).ground(b.base), b


@pytest.mark.parametrize("angle, side", [(0.0, "right"), (0.7, "left")])
def test_a_ritz_bender_in_a_mechanism_gets_its_large_rotation_warning(angle, side):
    # 0 -> 1500 V in 1 ms (a step for the 36 Hz bender): the tip overshoots the arc by ~0.28 rad
    # (as the lone actuator of test_actuator_ritz), whatever the bender's direction and active side
    mech, _ = _ritz_cantilever(1e-3, angle, side)
    with pytest.warns(RuntimeWarning, match=r"deviates by up to 0\.2\d* rad.*cell='beam'") as caught:
        simulate(mech, 0.1)
    assert any(w.filename == __file__ for w in caught)  # the warning points at the caller's line


@pytest.mark.parametrize("angle, side", [(0.0, "right"), (0.7, "left")])
def test_a_slow_ramp_stays_silent_and_the_view_is_in_the_benders_frame(angle, side):
    # over 50 ms the deviation from the arc is ~0.02 rad: below the limit, no warning
    mech, b = _ritz_cantilever(0.05, angle, side)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        r = simulate(mech, 0.1)
    view = bender_view(r, b)
    # the view's tip angle is the rotation against the base, in the bending sense of the strain:
    # the quasi-static arc's tip angle kappa L at the end (dynamic part small), independent of the pose
    kappa_l = b.laminate.curvature_per_strain * view["strain"][-1] * L
    assert kappa_l > 0.3
    np.testing.assert_allclose(view["tip_angle"], b.curvature_sign * (r["b.tip_angle"] - angle), atol=1e-15)
    assert view["tip_angle"][-1] == pytest.approx(kappa_l, abs=0.03)  # the dynamic part, < 0.05 rad
    delta = rb.dynamic_rotation(view["tip_angle"], view["strain"], b.laminate.curvature_per_strain, L)
    assert 0.005 < delta < rb.DYNAMIC_ROTATION_LIMIT
    assert math.isclose(b.curvature_sign, 1.0 if side == "right" else -1.0)


def test_a_built_system_runs_the_same_cell_checks():
    """BuiltSystem.simulate checks every bender's cell kind as simulate does (the ritz overshoot of the first test)."""
    mech, _ = _ritz_cantilever(1e-3, 0.0, "right")
    built = atcm.BuiltSystem(mech)
    with pytest.warns(RuntimeWarning, match=r"deviates by up to 0\.2\d* rad.*cell='beam'") as caught:
        built.simulate(0.1)
    assert any(w.filename == __file__ for w in caught)
