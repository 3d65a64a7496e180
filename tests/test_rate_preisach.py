"""A Preisach (Everett) operator with a rate lag from records at several rates (issue 28, part 5).

The truth is known (``exudyn_atcm.model.rate_family``): an Everett density that depends on
``α + β`` as well as ``α − β`` (loops that no Prandtl-Ishlinskii operator follows), the creep law
``Creep((0.02, 0.2) s, (0.03, 0.04))`` and a lag ``T = 1.5 ms``; records of six growing
raised-cosine cycles from -500 V at 20, 40 and 100 Hz, 10 kHz, noise 0.1 % of the range.  The
fits are given the creep law (as from a step record) and find the operator and ``T``.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.errors import OutOfReachWarning
from exudyn_atcm.hysteresis import EverettPreisach, fit_rate_preisach
from exudyn_atcm.hysteresis.creep import Creep
from exudyn_atcm.hysteresis.dynamics import LagSum, RateLag, WithDynamics
from exudyn_atcm.hysteresis.dynamics_fit import fit_rate_lag
from exudyn_atcm.hysteresis.inverse import inverse_operator
from exudyn_atcm.hysteresis.lagged_basis import cell_fraction_columns, lagged_columns, record_rates
from exudyn_atcm.hysteresis.relay_gram import relay_grid
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.rate_family import RATE_FAMILY, growing_cycles, rate_family_records, rate_family_truth
from exudyn_atcm.model.signals import PiecewiseLinear
from exudyn_atcm.solve import simulate

from _actuator_geometries import REF_A

CREEP = Creep(RATE_FAMILY["creep tau [s]"], RATE_FAMILY["creep c [-]"])
T_TRUE = RATE_FAMILY["lag T [s]"]
LEVELS = 12
REJECTING = {"timeIntegration.newton.maxIterations": 2, "timeIntegration.newton.useModifiedNewton": False}


def rms_share(predicted, y):
    """RMS error as a share of the record's output range."""
    return float(np.sqrt(np.mean((predicted - y) ** 2)) / np.ptp(y))


@pytest.fixture(scope="module")
def family():
    return rate_family_records()


@pytest.fixture(scope="module")
def outer_fit(family):
    """Trained on the slowest (20 Hz) and the fastest (100 Hz) record."""
    return fit_rate_preisach([family[0][:3], family[2][:3]], LEVELS, creep=CREEP, output_quantity="strain")


@pytest.fixture(scope="module")
def slow_fit(family):
    """Trained on the two slower records (20 and 40 Hz)."""
    return fit_rate_preisach([family[0][:3], family[1][:3]], LEVELS, creep=CREEP, output_quantity="strain")


# ------------------------------------------------------------------ the linear basis is the model


def test_cell_fractions_times_weights_are_the_everett_output():
    truth = rate_family_truth(lag=False, creep=False)
    t, u = growing_cycles(40.0)
    _, _, index = relay_grid(truth.edges[0], truth.edges[-1], truth.edges.size - 1)
    columns = cell_fraction_columns(u, truth.edges, index)
    np.testing.assert_allclose(columns @ truth.weights + truth.offset, truth.apply(u), rtol=0, atol=1e-15)


@pytest.mark.parametrize("uniform", [True, False])
def test_lagged_columns_are_the_plain_exact_lag_integration(uniform):
    # reference: each column through each lag step by step, z' = (h - z)/tau exact for h linear over the step
    rng = np.random.default_rng(3)
    t = np.arange(200) * 1e-4 if uniform else np.cumsum(rng.uniform(0.5e-4, 1.5e-4, 200))
    columns = rng.standard_normal((200, 4)).cumsum(axis=0)
    rest = rng.standard_normal(4)
    lags = LagSum.series(CREEP, RateLag(T_TRUE))
    expected = np.empty_like(columns)
    for c in range(4):
        z = np.full(lags.tau.size, rest[c])
        expected[0, c] = lags.d * columns[0, c] + lags.g @ z
        for k in range(1, t.size):
            dt, h0, h1 = t[k] - t[k - 1], columns[k - 1, c], columns[k, c]
            a = np.exp(-dt / lags.tau)
            z = a * z + h1 - a * h0 - (h1 - h0) * lags.tau / dt * (1 - a)
            expected[k, c] = lags.d * h1 + lags.g @ z
    np.testing.assert_allclose(lagged_columns(columns, t, lags, rest), expected, rtol=0,
                               atol=1e-12 * np.abs(expected).max())


def test_record_rates_are_the_cycle_frequencies_for_full_cycles():
    t = np.arange(4001) / 10e3
    u = np.cos(2 * np.pi * 25.0 * t)  # 10 full cycles
    rates = record_rates([(t, u, u), (t, u[::-1].copy(), u)])
    np.testing.assert_allclose(rates, 25.0, rtol=1e-3)


def test_family_truth_is_scaled_and_its_loops_are_not_point_symmetric():
    op = rate_family_truth(lag=False, creep=False)
    assert op.apply([-500.0, 1500.0])[-1] == pytest.approx(-1.5e-4 + 1.2e-3, rel=1e-12)
    # a Prandtl-Ishlinskii major loop is point-symmetric about its centre: up(u) + down(u_lo + u_hi - u) = y_lo + y_hi
    u = np.linspace(-500.0, 1500.0, 201)
    branches = op.apply(np.concatenate([u, u[::-1]]))
    up, down = branches[:201], branches[201:]  # down[k] is at u[::-1][k] = u_lo + u_hi - u[k]
    asymmetry = np.max(np.abs(up + down - (up[0] + up[-1]))) / np.ptp(up)
    assert asymmetry > 0.05  # measured 0.14 of the range


def test_growing_cycles_start_and_end_at_rest_at_the_lowest_voltage():
    t, u = growing_cycles(40.0, peaks=[0.5, 1.0])
    assert t.size == 501 and t[1] == pytest.approx(1e-4)
    assert u[0] == u[-1] == -500.0 and u[250] == pytest.approx(-500.0)
    assert u[:250].max() == pytest.approx(500.0) and u.max() == pytest.approx(1500.0)
    with pytest.raises(ValueError, match=r"peaks must lie in \(0, 1\], got \[0.5, 1.5\]"):
        growing_cycles(40.0, peaks=[0.5, 1.5])


# ------------------------------------------------------------------ identification on the known family


def test_known_lag_is_recovered(outer_fit, slow_fit):
    # measured: relative error 2.3e-4 (20 + 100 Hz) and 1.4e-5 (20 + 40 Hz); stated tolerance 2 %
    for _, info in (outer_fit, slow_fit):
        assert info["T"] == pytest.approx(T_TRUE, rel=0.02)
        # the fitted records are followed to about the noise (0.1 % of the range; measured 0.105 to 0.118 %)
        for rms, (t, u, y, _) in zip(info["rms"], rate_family_records()):
            assert rms < 1.5e-3 * np.ptp(y)
        # without the lag the same operator cannot follow both rates (measured 22 to 123 times the fit's RMS)
        assert max(info["rms_rate_independent"]) > 10 * max(info["rms"])


def test_middle_rate_is_predicted_from_the_slowest_and_fastest(family, outer_fit):
    # goal: within 0.8 % RMS of the range; measured 0.108 % against the noisy record (noise 0.1 %), 0.024 % against
    # the noise-free truth
    model, _ = outer_fit
    t, u, y, clean = family[1]
    assert rms_share(model.apply(u, t), y) < 0.008
    assert rms_share(model.apply(u, t), clean) < 0.001


def test_fastest_rate_is_predicted_from_the_two_slower(family, slow_fit):
    # goal: within 1.5 % RMS of the range; measured 0.119 % (0.016 % against the noise-free truth)
    model, _ = slow_fit
    t, u, y, clean = family[2]
    assert rms_share(model.apply(u, t), y) < 0.015
    assert rms_share(model.apply(u, t), clean) < 0.001


def test_a_play_operator_with_the_same_lag_cannot_follow_the_asymmetric_loops(family):
    # the reason for the Everett operator: fit_rate_lag (PI + creep + lag) on the same training predicts 40 Hz
    # at 1.9 % and 100 Hz at 3.0 % (measured), beyond both goals
    pi_outer, _ = fit_rate_lag([family[0][:3], family[2][:3]], LEVELS, creep=CREEP)
    pi_slow, _ = fit_rate_lag([family[0][:3], family[1][:3]], LEVELS, creep=CREEP)
    assert rms_share(pi_outer.apply(family[1][1], family[1][0]), family[1][2]) > 0.008
    assert rms_share(pi_slow.apply(family[2][1], family[2][0]), family[2][2]) > 0.015


def test_fitted_model_carries_its_metadata(outer_fit):
    model, info = outer_fit
    assert isinstance(model, WithDynamics) and isinstance(model.operator, EverettPreisach)
    assert model.fitted_range == (RATE_FAMILY["u_min [V]"], RATE_FAMILY["u_max [V]"])
    assert model.output_quantity == "strain" and model.operator.output_quantity == "strain"
    assert model.output_unit == ""
    assert model.fit_info is info and info["fit_start"] == [0, 0]
    assert model.lag.T == info["T"] and model.creep is CREEP
    assert (model.operator.weights >= 0).all()


def test_unknown_memory_before_the_first_visit_of_the_lowest_input_is_left_out(family):
    # a record that starts at 700 V on an unknown branch (the truth was driven to 1500 V and back first): the fit
    # leaves out the samples before the input first comes down to -500 V and still predicts the clean record
    truth = rate_family_truth()
    t, u = growing_cycles(20.0)
    t0 = np.arange(101) / 10e3
    prefix = 700.0 - 1200.0 * t0 / t0[-1]  # 700 V down to -500 V in 10 ms
    u_all = np.concatenate([prefix, u[1:]])
    t_all = np.arange(u_all.size) / 10e3
    history = np.concatenate([np.linspace(-500.0, 1500.0, 50), np.linspace(1500.0, 700.0, 50)])
    truth.reset()
    for v in history:
        truth.commit_held(v)  # held: lags settled, memory at 700 V on the descending branch
    y_all = np.array([truth.commit(v, tk) for v, tk in zip(u_all, t_all + 1.0)])
    model, info = fit_rate_preisach([(t_all, u_all, y_all), family[2][:3]], LEVELS, creep=CREEP, T=T_TRUE,
                                    prior_weight=0.1)
    # the first sample within 1 % of the range (20 V) of -500 V: -488 V at sample 99
    assert info["fit_start"] == [99, 0]
    assert "samples 0..98 left out" in info["notes"][0]
    t, u, _, clean = family[1]
    assert rms_share(model.apply(u, t), clean) < 0.003  # measured 0.022 %; with the lag states not freed 1.3 %


# ------------------------------------------------------------------ in the solver step and the inverse


def test_in_step_strain_is_the_offline_apply_despite_rejected_steps(outer_fit):
    model, _ = outer_fit
    t, u = growing_cycles(40.0)
    drive = PiezoDrive(PiecewiseLinear(t[::10], u[::10]), hysteresis=model)
    r = simulate(REF_A.actuator(drive, cell="rigid"), 0.1, step=1e-3, settings=REJECTING)
    assert r.info["rejected_steps"] > 0
    assert np.diff(r["time"]).min() < 0.75e-3  # the retried steps are in the record
    replay = model.apply(r["actuator.voltage"], r["time"])
    np.testing.assert_allclose(r["actuator.strain"], replay, rtol=0, atol=1e-12 * np.ptp(replay))
    assert np.ptp(r["actuator.strain"]) > 0.5 * RATE_FAMILY["strain_range [-]"]


def test_inverse_of_the_forward_output_is_the_input(family, outer_fit):
    # the record starts and peaks at the grid's edges, where the Everett output saturates: the lag block's inverse
    # returns those outputs to rounding (1e-17 of the output beyond them), which the bisection inverse takes as
    # reached, not clipped (on main it warned OutOfReachWarning "clipped by 8e-19")
    model, _ = outer_fit
    t, u, _, _ = family[1]
    y = model.apply(u, t)
    inverse = model.inverse()  # the one convention (was model.inverse_apply(y, t, inverse_operator(model.operator)))
    u_back = inverse.apply(y, t)
    assert inverse.clip_count == 0
    # measured 2.1e-3 V over 2000 V (the Everett inverse's bisection, flat spots of the fitted density)
    np.testing.assert_allclose(u_back, u, rtol=0, atol=1e-5 * np.ptp(u))
    np.testing.assert_allclose(model.apply(u_back, t), y, rtol=0, atol=1e-9 * np.ptp(y))


def test_bisection_inverse_takes_an_output_beyond_saturation_by_rounding_as_reached():
    operator = rate_family_truth(lag=False, creep=False)
    top = float(operator.apply([1500.0])[-1])
    inverse = inverse_operator(operator)
    assert inverse.commit(top * (1 + 4e-16)) == 1500.0 and inverse.clip_count == 0
    # beyond it by more than rounding (1e-9 of the range): clipped and said
    with pytest.warns(OutOfReachWarning, match="clipped by 1.2e-12"):
        inverse.commit(top + 1.2e-12)
    assert inverse.clip_count == 1


def test_feedforward_through_the_fitted_inverse_drives_the_truth_to_the_wanted_output(outer_fit):
    # wanted: the truth's own 40 Hz output (reachable), shifted by 3.4e-4 of the range to start at the model's rest
    model, _ = outer_fit
    truth = rate_family_truth()
    t, u = growing_cycles(40.0)
    wanted = truth.apply(u, t)
    wanted = wanted + (model.lags.static_gain * model.operator.offset - wanted[0])
    u_ff = model.inverse().apply(wanted, t)
    # measured 0.023 % of the range; the Everett inverse alone (creep and lag ignored): 9.4 %
    assert rms_share(truth.apply(u_ff, t), wanted) < 0.005
    u_plain = inverse_operator(model.operator).apply(wanted / model.lags.static_gain)
    assert rms_share(truth.apply(u_plain, t), wanted) > 0.03


# ------------------------------------------------------------------ bad inputs


@pytest.fixture(scope="module")
def two(family):
    return [family[0][:3], family[2][:3]]


def test_records_of_different_lengths_are_refused(two):
    t, u, y = two[1]
    with pytest.raises(ValueError, match=r"records\[1\]: t, u and y must have the same length, got 601, 601 and 600"):
        fit_rate_preisach([two[0], (t, u, y[:-1])], LEVELS)
    with pytest.raises(ValueError, match=r"records\[0\] must be a \(t, u, y\) triple"):
        fit_rate_preisach([(t, u), two[1]], LEVELS)
    with pytest.raises(ValueError, match=r"records\[1\].t must be strictly increasing"):
        fit_rate_preisach([two[0], (t[::-1].copy(), u, y)], LEVELS)


def test_one_record_or_one_rate_is_refused_when_T_is_searched(family, two):
    with pytest.raises(ValueError, match="at least 2 .* got 1"):
        fit_rate_preisach([two[0]], LEVELS)
    t, u, y, _ = family[0]
    with pytest.raises(ValueError, match=r"differ by 1x, less than 1.5x: records at one rate .* or give T"):
        fit_rate_preisach([(t, u, y), (t, u, y + 1e-6)], LEVELS)
    # with T given, one record is enough
    model, info = fit_rate_preisach([two[0]], LEVELS, creep=CREEP, T=T_TRUE, prior_weight=0.1)
    assert info["T"] == T_TRUE and info["search"] == []


@pytest.mark.parametrize("bounds, message", [
    ((0.1, 0.01), r"0 < low < high \[s\], got \(0.1, 0.01\)"),
    ((-1.0, 1.0), r"0 < low < high"),
    ((0.0, float("nan")), r"T_bounds\[1\] must be a finite real number"),
    ("fast", r"T_bounds must be a pair \(low, high\) \[s\], got 'fast'"),
])
def test_bad_T_bounds_are_refused(two, bounds, message):
    with pytest.raises(ValueError, match=message):
        fit_rate_preisach(two, LEVELS, T_bounds=bounds)


def test_other_bad_arguments_are_refused(family, two):
    with pytest.raises(ValueError, match=r"n_levels must be an integer in \[2, 100\], got 1"):
        fit_rate_preisach(two, 1)
    with pytest.raises(ValueError, match=r"n_levels must be an integer in \[2, 100\], got 12.0"):
        fit_rate_preisach(two, 12.0)
    with pytest.raises(ValueError, match="T must be > 0, got -0.001"):
        fit_rate_preisach(two, LEVELS, T=-1e-3)
    with pytest.raises(ValueError, match="lag T = 0.02 s equals the creep time constant"):
        fit_rate_preisach(two, LEVELS, creep=CREEP, T=0.02)
    with pytest.raises(ValueError, match="creep must be a Creep or None, got tuple"):
        fit_rate_preisach(two, LEVELS, creep=(0.02, 0.03))
    with pytest.raises(ValueError, match="cv_folds must be an integer >= 2, got 1"):
        fit_rate_preisach(two, LEVELS, cv_folds=1)
    with pytest.raises(ValueError, match="prior_weight must be >= 0, got -1.0"):
        fit_rate_preisach(two, LEVELS, prior_weight=-1.0)
    t, u, y, _ = family[1]
    with pytest.raises(ValueError, match=r"records\[1\] never comes down to the lowest input -500.0 .*its lowest "
                                         r"is -400.0"):
        fit_rate_preisach([two[0], (t, np.maximum(u, -400.0), y)], LEVELS)
    with pytest.raises(ValueError, match="the output must vary"):
        fit_rate_preisach([(two[0][0], two[0][1], np.zeros(two[0][0].size)), (t, u, np.zeros(t.size))], LEVELS)
