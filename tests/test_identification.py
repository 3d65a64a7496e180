"""Identification of hysteresis operators from records (fits, from_loop on measured data, FitReport)."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest

from exudyn_atcm.hysteresis import ContinuousPreisach, DiscretePreisach, PrandtlIshlinskii
from exudyn_atcm.hysteresis.identification import relay_grid

from relays import equal_gain_relays, relay_outputs

PAPER = ContinuousPreisach.from_points(-500, 1500, -4e-6, 40e-6, 500, 12e-6, 28e-6)


def corners_path(corners, step):
    """Input through the corner values with increments of at most ``step``."""
    out = [corners[0]]
    for a, b in zip(corners[:-1], corners[1:]):
        n = max(1, int(math.ceil(abs(b - a) / step)))
        out.extend(np.linspace(a, b, n + 1)[1:])
    return np.array(out)


def known_grid_model(n_levels=10):
    """A non-uniform density on the fit grid over [-1, 1]: weights depend on (alpha, beta)."""
    alpha, beta, _ = relay_grid(-1.0, 1.0, n_levels)
    weights = 0.2 + np.exp(-((alpha - beta - 0.6) ** 2) / 0.2) * (1.0 + alpha)
    return alpha, beta, weights, 0.5


# history used to fit: major loops and first-order reversal curves
FIT_CORNERS = [-1, 1, -1, 0.6, -1, 0.2, -1, -0.2, -1, 1, 0.4, 1, -0.3, 1, -0.7, 1, -1]
# history held out: minor loops inside the range, not in the fitted history
TEST_CORNERS = [-1, 0.75, -0.45, 0.5, -0.1, 0.35, -0.65, 0.9, 0.15, 0.6, -1]


# ----------------------------------------------------------------------------- DiscretePreisach.fit
def test_fit_recovers_known_density_and_predicts_unseen_minor_loops():
    alpha, beta, weights, offset = known_grid_model()
    u_fit = corners_path(FIT_CORNERS, 0.02)
    u_test = corners_path(TEST_CORNERS, 0.02)
    u = np.r_[u_fit, u_test]
    # independent reference: the relays simulated one by one (tests/relays.py)
    clean = relay_outputs(alpha, beta, weights, offset, u)
    sigma = 0.01 * np.ptp(clean)
    noisy = clean + sigma * np.random.default_rng(3).standard_normal(u.size)
    model, report = DiscretePreisach.fit(u, noisy, 10, n_fit=u_fit.size, input_range=(-1.0, 1.0))
    predicted = model.apply(u)
    held = slice(u_fit.size, None)
    # fitted on noisy data: the residual is the noise (1 % of the range); the model itself is
    # closer to the truth, its error from the noise on 55 weights fitted on ~1100 samples being
    # about sigma * sqrt(55 / 1100) = 0.22 sigma (twice that allowed), on minor loops never seen
    assert report.model_errors["fit"]["rms"] == pytest.approx(sigma, rel=0.15)
    assert np.sqrt(np.mean((predicted[held] - clean[held]) ** 2)) < 0.45 * sigma
    assert report.model_errors["held_out"]["rms"] < 1.2 * sigma
    # the linear model cannot follow the loops: far worse than the noise level
    assert report.linear_errors["held_out"]["rms"] > 5 * sigma


def test_fit_predicts_sloped_minor_loops():
    """After a reversal inside the range the fitted model's output moves at once (no flat part)."""
    alpha, beta, weights, offset = known_grid_model()
    u_fit = corners_path(FIT_CORNERS, 0.02)
    clean = relay_outputs(alpha, beta, weights, offset, u_fit)
    model, _ = DiscretePreisach.fit(u_fit, clean, 10, input_range=(-1.0, 1.0))
    # rise to 0.5 from negative saturation, then fall by one and by two grid cells (0.2 each)
    path = [-1.0, 0.5, 0.3, 0.1]
    truth = relay_outputs(alpha, beta, weights, offset, path)
    got = model.apply(path)
    assert truth[1] - truth[2] > 0.05  # the true minor loop is sloped
    np.testing.assert_allclose(got, truth, atol=0.02 * np.ptp(clean))
    # the equal-gain model of the major loop holds the output flat after this reversal
    # (the grid model's major loop is a staircase: its top level is reached at u = 0.9 rising
    # but left at u = 1 falling, so the two crossings are merged, with a warning)
    loop = corners_path([-1, 1, -1], 0.002)
    with pytest.warns(RuntimeWarning, match="cross"):
        eq12 = DiscretePreisach.from_loop(loop, relay_outputs(alpha, beta, weights, offset, loop), 10,
                                          reversal_tolerance=0.06)
    y_eq = eq12.apply(path)
    assert y_eq[1] - y_eq[2] < 0.5 * (truth[1] - truth[2])


def test_fit_leaves_out_samples_before_the_memory_is_known():
    alpha, beta, weights, offset = known_grid_model()
    u = corners_path([0.3, 1, -1, 1, -1], 0.02)
    y = relay_outputs(alpha, beta, weights, offset, u)
    _, report = DiscretePreisach.fit(u, y, 10, input_range=(-1.0, 1.0))
    first_low = int(np.argmax(u <= -0.9))  # lowest grid threshold: -1 + 0.1
    assert report.fit_start == first_low
    assert "left out" in report.notes[0]


# ----------------------------------------------------------------------------- PI and continuous
def test_pi_fit_recovers_known_operator_with_nonnegative_weights():
    n = 8
    radii = 2.0 * np.arange(1, n) / (2.0 * n)  # the fit's radii for an input range of 2
    truth = PrandtlIshlinskii(radii, [0.3, 0.0, 0.2, 0.4, 0.1, 0.0, 0.2], 0.5, offset=0.1)
    u = corners_path(FIT_CORNERS + TEST_CORNERS[1:], 0.02)
    clean = truth.apply(u)
    sigma = 0.005 * np.ptp(clean)
    noisy = clean + sigma * np.random.default_rng(5).standard_normal(u.size)
    n_fit = corners_path(FIT_CORNERS, 0.02).size
    model, report = PrandtlIshlinskii.fit(u, noisy, n, n_fit=n_fit)
    assert (model.weights >= 0).all() and model.p0 > 0
    np.testing.assert_allclose(model.radii, radii)
    assert np.sqrt(np.mean((model.apply(u)[n_fit:] - clean[n_fit:]) ** 2)) < 0.3 * sigma
    assert report.model_errors["fit"]["rms"] == pytest.approx(sigma, rel=0.15)


def test_continuous_fit_recovers_exponents():
    u = corners_path([-500, 1500, -500, 1500, 300, 1100, -500], 10.0)
    clean = PAPER.apply(u)
    sigma = 0.2e-6
    noisy = clean + sigma * np.random.default_rng(11).standard_normal(u.size)
    model, report = ContinuousPreisach.fit(u, noisy)
    # ~1000 samples with 0.5 % noise: the exponents come back to about 1 %
    assert model.r1 == pytest.approx(PAPER.r1, rel=0.02)
    assert model.r2 == pytest.approx(PAPER.r2, rel=0.02)
    assert model.y_max == pytest.approx(40e-6, abs=0.1e-6)
    assert report.model_errors["fit"]["rms"] == pytest.approx(sigma, rel=0.15)


# ----------------------------------------------------------------------------- from_loop on measured data
def test_from_loop_on_noisy_multicycle_record():
    u = corners_path([-500, 1500, -500, 1500, -500, 1500, -500], 5.0)
    rng = np.random.default_rng(2)
    sigma = 0.01 * 44e-6  # 1 % of the output range
    y = PAPER.apply(u) + sigma * rng.standard_normal(u.size)
    u_meas = u + 1.0 * rng.standard_normal(u.size)  # 1 V noise on the measured voltage too
    n = 20
    # noise: the averaged ascending branch ends a little below the loop's top (less than half a
    # gain), which is noted, not warned: the top relay switches at the turning point anyway
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        model, report = DiscretePreisach.from_loop(u_meas, y, n, reversal_tolerance=0.02, report=True)
    assert any("below the loop's top" in note for note in report.notes)
    alpha_ref, beta_ref, _, _ = equal_gain_relays(PAPER, n)
    order = np.argsort(model.alpha)
    # threshold error ~ noise / branch slope, the slope being >= ~4 nm/V away from the
    # loop's flat ends: allow 60 V (3 % of the range) inside, ends excluded
    np.testing.assert_allclose(model.alpha[order][2:-2], alpha_ref[2:-2], atol=60.0)
    np.testing.assert_allclose(model.beta[order][2:-2], beta_ref[2:-2], atol=60.0)
    # gain: the range of the averaged branches, within 2 sigma of the true 44 um
    assert model.weights[0] * n == pytest.approx(44e-6, abs=2 * sigma)
    grid = corners_path([-500, 1500, -500, 800, 100, 1500], 5.0)
    error = np.abs(model.apply(grid) - PAPER.apply(grid))
    assert error.max() <= model.weights[0] + 3 * sigma  # Eq. 12's bound (one gain) + noise


def test_from_loop_unreached_level_is_handled_and_said():
    # the descending branch starts higher than the ascending branch ends (creep at the top):
    # the top level is never reached by the ascending branch
    up = np.linspace(0.0, 1.0, 51)
    u = np.r_[up, up[::-1][1:]]
    y = np.r_[0.9 * up**2, 1.0 - (1.0 - up[::-1][1:]) ** 2]
    with pytest.warns(RuntimeWarning, match=r"ascending branch never reaches the level\(s\) y = "):
        model, report = DiscretePreisach.from_loop(u, y, 10, report=True)
    assert model.alpha.max() == 1.0  # switch-on at the branch's highest input
    assert any("never reaches" in n for n in report.notes)


def test_from_loop_top_level_missed_by_noise_is_noted_not_warned():
    # the branches meet at the turning point u = 1; the ascending one ends 0.02 below the
    # descending one's start (noise, a fifth of the relay gain 0.1): the top relay switches at
    # u = 1 either way, so this is a note, not a warning
    up = np.linspace(0.0, 1.0, 51)
    u = np.r_[up, up[::-1][1:]]
    y = np.r_[0.98 * up**2, 1.0 - (1.0 - up[::-1][1:]) ** 2]
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        model, report = DiscretePreisach.from_loop(u, y, 10, report=True)
    assert model.alpha.max() == 1.0
    assert any("below the loop's top" in n for n in report.notes)


def test_from_loop_ignores_minor_loops_and_partial_segments():
    up = np.linspace(-500, 1500, 401)
    major = np.r_[up, up[::-1][1:]]
    minor = corners_path([-500, 600, 200, 800, -500], 5.0)
    clean_model = DiscretePreisach.from_loop(major, PAPER.apply(major), 12)
    u = np.r_[major, minor[1:]]
    model = DiscretePreisach.from_loop(u, PAPER.apply(u), 12)
    np.testing.assert_allclose(np.sort(model.alpha), np.sort(clean_model.alpha))
    np.testing.assert_allclose(np.sort(model.beta), np.sort(clean_model.beta))


# ----------------------------------------------------------------------------- FitReport
def test_report_linear_model_and_output():
    alpha, beta, weights, offset = known_grid_model()
    u = corners_path(FIT_CORNERS, 0.05)
    y = relay_outputs(alpha, beta, weights, offset, u)
    model, report = DiscretePreisach.fit(u, y, 10, n_fit=200, input_range=(-1.0, 1.0), output_unit="m")
    a, b = np.polyfit(u[:200], y[:200], 1)  # independent least-squares line on the fitted part
    assert report.linear_model["a"] == pytest.approx(a, rel=1e-9)
    e = a * u[200:] + b - y[200:]
    assert report.linear_errors["held_out"]["rms"] == pytest.approx(np.sqrt(np.mean(e**2)), rel=1e-9)
    assert report.linear_errors["held_out"]["max_percent"] == pytest.approx(
        100 * np.abs(e).max() / np.ptp(y[:200]), rel=1e-9)
    text = report.table()
    assert "held_out" in text and "RMS [m]" in text
    data = json.loads(json.dumps(report.to_dict()))
    assert data["n_fit"] == 200 and data["model_errors"]["held_out"]["samples"] == u.size - 200


# ----------------------------------------------------------------------------- bad input
GOOD_U = corners_path([-1, 1, -1, 1], 0.1)
GOOD_Y = GOOD_U**2


@pytest.mark.parametrize(
    "fit",
    [
        lambda u, y, n=5: DiscretePreisach.fit(u, y, n),
        lambda u, y, n=5: PrandtlIshlinskii.fit(u, y, n),
        lambda u, y, n=5: ContinuousPreisach.fit(u, y),
    ],
    ids=["discrete", "pi", "continuous"],
)
@pytest.mark.parametrize(
    "args, pattern",
    [
        ((GOOD_U[:5], GOOD_Y[:5]), r"at least 10 samples to identify a model, got 5"),
        ((np.full(30, 2.0), np.linspace(0, 1, 30)), r"u must vary over the fitted samples, got a constant input 2.0"),
        ((GOOD_U, GOOD_Y[:-1]), r"u, y must have the same length: u has 61, y has 60"),
        ((np.r_[GOOD_U[:-1], np.inf], GOOD_Y), r"u must hold finite numbers only, got inf at index 60"),
        ((GOOD_U, np.r_[np.nan, GOOD_Y[1:]]), r"y must hold finite numbers only, got nan at index 0"),
        ((GOOD_U, np.zeros(61)), r"y must vary over the fitted samples"),
    ],
)
def test_fits_reject_bad_records(fit, args, pattern):
    with pytest.raises(ValueError, match=pattern):
        fit(*args)


@pytest.mark.parametrize("n", [1, 0, 2.5, True])
def test_fits_reject_too_few_levels(n):
    with pytest.raises(ValueError, match=r"n_levels must be an integer >= 2"):
        DiscretePreisach.fit(GOOD_U, GOOD_Y, n)
    with pytest.raises(ValueError, match=r"n must be an integer >= 2"):
        PrandtlIshlinskii.fit(GOOD_U, GOOD_Y, n)


def test_fit_refuses_a_grid_too_large_for_memory():
    """500 levels = 125250 relays: dense normal equations of 117 GiB; refused before allocating."""
    with pytest.raises(ValueError, match=r"n_levels must be <= 100, got 500: 125250 relays .*\(117 GiB\)"):
        DiscretePreisach.fit(GOOD_U, GOOD_Y, 500)


def test_fit_rejects_bad_options():
    with pytest.raises(ValueError, match=r"smoothing must be a finite number >= 0, got -1"):
        DiscretePreisach.fit(GOOD_U, GOOD_Y, 4, smoothing=-1)
    with pytest.raises(ValueError, match=r"n_fit .* must be an integer in \[10, 61\], got 5"):
        DiscretePreisach.fit(GOOD_U, GOOD_Y, 4, n_fit=5)
    with pytest.raises(ValueError, match=r"input_range must be finite with u_hi > u_lo"):
        DiscretePreisach.fit(GOOD_U, GOOD_Y, 4, input_range=(1, 0))


def test_report_without_held_out_part_is_strict_json():
    alpha, beta, weights, offset = known_grid_model()
    u = corners_path(FIT_CORNERS, 0.05)
    y = relay_outputs(alpha, beta, weights, offset, u)
    _, report = DiscretePreisach.fit(u, y, 10, input_range=(-1.0, 1.0))
    data = report.to_dict()
    assert data["model_errors"]["held_out"]["rms"] is None
    json.dumps(data, allow_nan=False)  # raises on NaN
    assert math.isnan(report.improvement_over_linear("held_out"))
