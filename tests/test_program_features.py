"""What counts as a feature of a piecewise-linear voltage program (issue 9, step checks).

A feature is the stretch between corners: reversals (the slope changes sign) or marked kinks
(the slope changes by more than a tenth of the steepest slope).  References: the extrema of
a smooth two-tone wave found from its derivative, the corners of a coarse polygon, and hand-
made ramps.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from exudyn_atcm.errors import AccuracyWarning
from exudyn_atcm import PiezoDrive
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import PiecewiseLinear
from exudyn_atcm.solve import simulate

from _actuator_geometries import REF_A


def two_tone(t):
    return 500.0 + 400.0 * np.sin(2 * math.pi * 0.25 * t) + 200.0 * np.sin(2 * math.pi * 0.75 * t)


def test_densely_sampled_smooth_wave_has_its_monotone_stretches_as_features():
    t = np.arange(0.0, 4.0 + 5e-4, 1e-3)  # breakpoints every 1 ms
    program = PiecewiseLinear(t, two_tone(t))
    # the extrema of the wave: zeros of its derivative on a fine grid (independent of sampling)
    fine = np.linspace(0.0, 4.0, 4_000_001)
    slope = 400.0 * 0.25 * np.cos(2 * math.pi * 0.25 * fine) + 200.0 * 0.75 * np.cos(2 * math.pi * 0.75 * fine)
    extrema = fine[np.flatnonzero(np.sign(slope[1:]) != np.sign(slope[:-1]))]
    stretches = np.diff(np.concatenate([[0.0], extrema, [4.0]]))
    duration, text = program.shortest_feature()
    # the sampled extrema lie on the 1 ms grid: each end of a stretch moves by < 1 ms
    assert duration == pytest.approx(stretches.min(), abs=2e-3)
    assert duration > 0.3 and "reversals or kinks" in text


def test_coarse_polygon_corners_are_features():
    t = np.linspace(0.0, 1.0, 9)  # a sine as an octagon: slope changes of ~0.6 of the steepest
    assert PiecewiseLinear(t, np.sin(2 * math.pi * t)).shortest_feature()[0] == pytest.approx(0.125)


def test_marked_kink_without_reversal_is_a_feature_and_a_slight_one_is_not():
    fast_then_slow = PiecewiseLinear([0.0, 0.01, 1.0], [0.0, 100.0, 110.0])  # slope 1e4 then 10 V/s
    assert fast_then_slow.shortest_feature()[0] == pytest.approx(0.01)
    slight = PiecewiseLinear([0.0, 0.5, 1.0], [0.0, 50.0, 102.0])  # slope 100 then 104 V/s: 4 % change
    assert slight.shortest_feature()[0] == pytest.approx(1.0)


def test_dense_smooth_program_does_not_warn_at_a_step_that_resolves_it():
    t = np.arange(0.0, 0.2 + 5e-4, 1e-3)
    program = PiecewiseLinear(t, 500.0 + 400.0 * np.sin(2 * math.pi * 5.0 * t))  # 0.1 s between extrema
    act = REF_A.actuator(PiezoDrive(program, hysteresis=paper_strain_preisach()), cell="rigid")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        simulate(act, 0.02, step=2e-4)  # 500 steps per feature; before, 5 per 1 ms breakpoint: a warning
    # a step too coarse for the wave itself is still refused
    with pytest.raises(ValueError, match=r"too coarse"):
        simulate(act, 0.2, step=0.05)


def test_program_with_corners_on_the_step_grid_is_sampled_exactly_and_accepted():
    # a 10 ms triangle at a 5 ms step: 2 steps per ramp would be refused, but every corner lies
    # on the grid, so the solver's input is the program itself: the 1000 V peak is not missed
    program = PiecewiseLinear([0.0, 0.01, 0.02, 0.03], [0.0, 1000.0, 0.0, 1000.0])
    act = REF_A.actuator(PiezoDrive(program, hysteresis=paper_strain_preisach()), cell="rigid")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the step vs f1 warning (dynamics) is expected
        r = simulate(act, 0.03, step=0.005)
    np.testing.assert_allclose(r["actuator.voltage"], program(r["time"]), atol=1e-9)
    assert r["actuator.voltage"].max() == pytest.approx(1000.0, abs=1e-9)
    np.testing.assert_allclose(r["actuator.strain"], paper_strain_preisach().apply(r["actuator.voltage"]), atol=1e-15)
    # the same program with a step whose grid misses its corners is refused
    # (0.007 s does not divide 0.03 s: warned, and the step used, 0.03 / 5 s, is quoted with the one given)
    with pytest.warns(AccuracyWarning, match=r"step = 0\.007 s does not divide t_end = 0\.03 s"):
        with pytest.raises(ValueError, match=r"step = 0\.007 s \(used: 0\.006 s, so that it divides t_end = 0\.03 s\) "
                                             r"is too coarse"):
            simulate(act, 0.03, step=0.007)
