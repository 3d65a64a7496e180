"""Every bad input of the hysteresis layer raises ValueError naming the parameter and the value."""

import math

import numpy as np
import pytest

from exudyn_atcm.hysteresis import ContinuousPreisach, DiscretePreisach, PrandtlIshlinskii

GOOD = dict(u_min=-500, u_max=1500, y_min=-4.0, y_max=40.0, r1=1.5, r2=2.0)


@pytest.mark.parametrize(
    "change, pattern",
    [
        (dict(u_min=math.nan), r"u_min .*nan"),
        (dict(y_max=math.inf), r"y_max .*inf"),
        (dict(u_max=-500), r"u_max must be > u_min = -500.*-500"),
        (dict(u_max=-600), r"u_max must be > u_min.*-600"),
        (dict(y_max=-4.0), r"y_max must be > y_min.*-4.0"),
        (dict(r1=0.8), r"r1 must be >= 1, got 0.8.*ascending branch lies above"),
        (dict(r2=0.5), r"r2 must be >= 1, got 0.5"),
        (dict(r1="a"), r"r1 must be a finite real number, got 'a'"),
    ],
)
def test_continuous_rejects(change, pattern):
    with pytest.raises(ValueError, match=pattern):
        ContinuousPreisach(**{**GOOD, **change})


@pytest.mark.parametrize(
    "args, pattern",
    [
        ((-500, 1500, -4, 40, 1500, 12, 28), r"u_m must lie strictly between.*1500"),
        ((-500, 1500, -4, 40, 500, 40, 28), r"y_m1 must lie strictly between.*40"),
        ((-500, 1500, -4, 40, 500, 12, -5), r"y_m2 must lie strictly between.*-5"),
        # ascending above descending: the straight line at u_m is -4 + 44 * 1000/2000 = 18, y_m1 = 30 lies above it
        ((-500, 1500, -4, 40, 500, 30, 10), r"^y_m1 = 30 lies above the straight line .* at u_m \(18\): its branch's "
                                            r"exponent would be 0\.\d+, below 1"),
        # a stroke in m among points in µm: the hint names the end point in another unit
        ((-500, 1500, -4e-6, 40.0, 500, 12e-6, 28e-6), r"y_m2 = 2\.8e-05 lies below .*is y_min = -4e-06 or y_max = 40 "
                                                       r"in another unit\?$"),
        ((1500, -500, -4, 40, 500, 12, 28), r"u_max must be > u_min"),
        ((-500, 1500, -4, 40, math.nan, 12, 28), r"u_m .*nan"),
    ],
)
def test_from_points_rejects(args, pattern):
    with pytest.raises(ValueError, match=pattern):
        ContinuousPreisach.from_points(*args)


@pytest.mark.parametrize(
    "args, pattern",
    [
        (([1.0, 2.0], [0.0, 3.0], [1, 1]), r"alpha must be >= beta.*alpha\[1\] = 2.0 < beta\[1\] = 3.0"),
        (([1.0, 2.0], [0.0], [1, 1]), r"alpha, beta, weights must have the same length: .*beta has 1"),
        (([1.0, math.nan], [0.0, 0.0], [1, 1]), r"alpha must hold finite numbers only, got nan at index 1"),
        (([], [], []), r"alpha must hold at least 1"),
        (([1.0], [0.0], [math.inf]), r"weights must hold finite"),
        (([1.0], [0.0], [1.0], math.nan), r"offset must be a finite real number, got nan"),
    ],
)
def test_discrete_rejects(args, pattern):
    with pytest.raises(ValueError, match=pattern):
        DiscretePreisach(*args)


def loop():
    u = np.r_[np.linspace(0, 1, 11), np.linspace(1, 0, 11)[1:]]
    y = np.r_[np.linspace(0, 1, 11) ** 2, 1 - (1 - np.linspace(1, 0, 11)[1:]) ** 2]
    return u, y


@pytest.mark.parametrize(
    "args, pattern",
    [
        ((loop()[0], loop()[1], 0), r"n must be an integer >= 1, got 0"),
        ((loop()[0], loop()[1], 2.5), r"n must be an integer >= 1, got 2.5"),
        (([], [], 3), r"u must hold at least 2"),
        ((loop()[0], loop()[1][:-1], 3), r"u, y must have the same length"),
        ((np.r_[loop()[0][:-1], np.nan], loop()[1], 3), r"u must hold finite numbers only, got nan"),
        ((np.linspace(0, 1, 11), np.linspace(0, 1, 11), 3), r"descending \(falling u\) branch is missing"),
        ((np.linspace(1, 0, 11), np.linspace(1, 0, 11), 3), r"ascending \(rising u\) branch is missing"),
        ((loop()[0], np.zeros(21), 3), r"y must vary"),
        ((loop()[0], loop()[1][::-1], 3), r"ascending branch lies above the descending one"),
    ],
)
def test_from_loop_rejects(args, pattern):
    with pytest.raises(ValueError, match=pattern):
        DiscretePreisach.from_loop(*args)


@pytest.mark.parametrize(
    "args, pattern",
    [
        (([0.5, 0.2], [1, 1], 1.0), r"radii must be strictly increasing, got radii\[1\] = 0.2"),
        (([-0.5], [1], 1.0), r"radii must be >= 0, got -0.5"),
        (([0.5], [1, 2], 1.0), r"radii, weights must have the same length"),
        (([0.5], [1], math.inf), r"p0 must be a finite real number, got inf"),
    ],
)
def test_prandtl_ishlinskii_rejects(args, pattern):
    with pytest.raises(ValueError, match=pattern):
        PrandtlIshlinskii(*args)


@pytest.mark.parametrize(
    "model",
    [
        ContinuousPreisach(**GOOD),
        DiscretePreisach([1.0], [0.0], [1.0]),
        PrandtlIshlinskii([0.5], [1.0], 1.0),
    ],
    ids=type,
)
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, "1.0", None, np.nan])
def test_operators_reject_non_finite_inputs(model, bad):
    with pytest.raises(ValueError, match=r"u must be a finite real number"):
        model.evaluate(bad)
    with pytest.raises(ValueError, match=r"u must be a finite real number"):
        model.commit(bad)
    with pytest.raises(ValueError, match=r"u_series"):
        model.apply([0.0, bad] if bad is not None else [0.0, math.nan])


def test_numpy_scalars_are_accepted():
    model = ContinuousPreisach(**GOOD)
    assert model.commit(np.float32(500)) == pytest.approx(model.ascending(500.0))
    assert model.commit(np.int64(1500)) == pytest.approx(40.0)
