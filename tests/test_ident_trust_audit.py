"""Findings of the identification audit: fitted-range inverses, one warning per series, options, units, short records.

The independent reference throughout is a Prandtl-Ishlinskii operator written out in this file
(``play_sum``: the play recursion ``z = max(v - r, min(v + r, z))`` summed by hand), not the
package's operator.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from exudyn_atcm.errors import OutOfReachWarning, SetupWarning
from exudyn_atcm.hysteresis import PrandtlIshlinskii, identify
from exudyn_atcm.hysteresis.identify_options import IdentifyOptions
from exudyn_atcm.model.feedforward import feedforward_program

RADII = np.array([0.0, 100.0, 250.0, 400.0])  # [V]
WEIGHTS = np.array([1.0, 1.5, 1.0, 0.5]) * 1e-9  # [m/V]
P0 = 2e-9  # [m/V]


def play_sum(u, radii, weights, p0, offset=0.0, input_offset=0.0, z0=None):
    """Output of ``offset + p0 v + sum_j w_j z_j`` along ``v = u - input_offset``, plays from ``z0`` (default 0)."""
    z = np.zeros(len(radii)) if z0 is None else np.array(z0, dtype=float)
    out = []
    for x in np.asarray(u, dtype=float) - input_offset:
        z = np.maximum(x - radii, np.minimum(x + radii, z))
        out.append(offset + p0 * x + weights @ z)
    return np.array(out)


def audit_record():
    """The audit's record: growing cosine bursts 0 ... 1000 V [V], displacement [m] with 2 nm noise."""
    t = np.arange(5401) / 2000
    c = np.clip(((t - 0.2) / 0.5).astype(int), 0, 4)
    u = np.where(t < 0.2, 0.0, np.linspace(0.2, 1, 5)[c] * 500 * (1 - np.cos(2 * np.pi * (t - 0.2) / 0.5)))
    y = play_sum(u, RADII, WEIGHTS, P0, z0=np.zeros(4)) + np.random.default_rng(0).normal(0, 2e-9, u.size)
    return u, y


def by_hand(model, u):
    """The fitted PI model evaluated by the hand-written operator of this file."""
    return play_sum(u, model.radii, model.weights, model.p0, model.offset, model.input_offset)


def _out_of_reach(caught):
    return [w for w in caught if issubclass(w.category, OutOfReachWarning)]


def test_fitted_pi_inverse_and_feedforward_stay_in_the_fitted_range():
    u, y = audit_record()
    model, _ = PrandtlIshlinskii.fit(u, y, 20, output_unit="m")
    top = float(u.max())  # 1000 V: the fitted input range is the record's
    tt = np.linspace(0.0, 1.0, 100)
    wanted = 9e-6 * np.sin(np.pi * tt)  # needs about 1600 V at its peak, beyond the fitted 1000 V
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        volts = model.inverse().apply(wanted)
    assert len(_out_of_reach(caught)) == 1  # one warning for the series
    assert volts.max() == top and volts.min() >= float(u.min())
    achieved = by_hand(model, volts)
    reached = np.abs(achieved - wanted) <= 1e-12 * np.ptp(wanted)
    clipped = int((~reached).sum())
    assert 0 < clipped < wanted.size
    # the unreached samples are exactly the ones held at a limit of the fitted range (at the end, back at
    # 0 V after the peak, the descending branch stays above the wanted 0 m)
    assert np.all((volts[~reached] == top) | (volts[~reached] == float(u.min())))
    assert f"{clipped} of {wanted.size} wanted outputs" in str(_out_of_reach(caught)[0].message)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        program, info = feedforward_program(model, tt, wanted)
    assert len(_out_of_reach(caught)) == 1
    assert info["clipped_samples"] == clipped
    assert info["largest_clip"] == pytest.approx(float(np.max(np.abs(achieved - wanted))), rel=1e-9)
    np.testing.assert_array_equal(program(tt), volts)
    # a PI operator built by hand (not fitted) keeps its unbounded analytic inverse
    hand = PrandtlIshlinskii(RADII[1:], WEIGHTS[1:], P0 + WEIGHTS[0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        free = hand.inverse().apply(wanted)
    assert free.max() > 1500.0
    np.testing.assert_allclose(play_sum(free, RADII[1:], WEIGHTS[1:], P0 + WEIGHTS[0]), wanted, rtol=0, atol=1e-20)


def test_bounded_inverse_apply_warns_once_with_the_count_and_the_worst_value():
    radii, weights, p0 = np.array([0.2, 0.5]), np.array([0.5, 0.25]), 1.0
    model = PrandtlIshlinskii(radii, weights, p0)
    u_true = np.linspace(0.0, 2.0, 101)  # rising from rest: the input that gives each wanted output
    wanted = play_sum(u_true, radii, weights, p0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        volts = model.inverse(input_range=(-1.0, 1.0)).apply(wanted)
    found = _out_of_reach(caught)
    assert len(found) == 1
    n_beyond = int((u_true > 1.0).sum())  # 50: rising, everything needing more than 1 is out of reach
    message = str(found[0].message)
    assert f"{n_beyond} of 101 wanted outputs" in message
    assert repr(float(wanted[-1])) in message  # the worst: the last, largest wanted output
    np.testing.assert_allclose(volts, np.minimum(u_true, 1.0), rtol=0, atol=1e-12)


@pytest.mark.parametrize("options, name, value", [
    (dict(n_levels=500), "n_levels", 500), (dict(n_levels=1), "n_levels", 1),
    (dict(n_plays=1), "n_plays", 1), (dict(prior="flat"), "prior", "'flat'"),
    (dict(smoothing=-1.0), "smoothing", -1.0)])
def test_bad_identify_options_are_refused_up_front(options, name, value):
    u, y = audit_record()
    with pytest.raises(ValueError, match=rf"IdentifyOptions\.{name} must be .* got {value}"):
        identify(u[::10], y[::10], options=IdentifyOptions(**options))


def test_n_levels_limit_is_the_grid_fits_limit():
    from exudyn_atcm.hysteresis.identification import MAX_FIT_LEVELS
    u, y = audit_record()
    with pytest.raises(ValueError, match=rf"n_levels must be an integer <= {MAX_FIT_LEVELS}, got {MAX_FIT_LEVELS + 1} \(allowed: 2 \.\.\. {MAX_FIT_LEVELS}\)"):
        identify(u[::10], y[::10], options=IdentifyOptions(n_levels=MAX_FIT_LEVELS + 1))


def test_unknown_output_quantity_is_refused_and_unknown_unit_warned():
    u, y = audit_record()
    with pytest.raises(ValueError, match=r"output_quantity must be None or one of 'strain', 'displacement'.*'strian'"):
        identify(u[::5], y[::5], output_quantity="strian")
    with pytest.warns(SetupWarning, match=r"output_unit 'meters' is not a unit.*'m'"):
        choice = identify(u[::5], y[::5], output_unit="meters")
    assert choice.output_quantity is None


def test_short_record_is_refused_once_with_the_counts():
    u, y = audit_record()
    n = 12
    fitted = int(round(0.6 * n))  # the default split fits the first 60 % of the samples
    with pytest.raises(ValueError, match=rf"record has {n} samples .* fits {fitted} of them.* at least 10 fitted") as err:
        identify(u[1000:1000 + n], y[1000:1000 + n])
    assert "n_fit (samples fitted" not in str(err.value)  # not one message per family


def test_strain_far_beyond_an_mfc_is_warned():
    from exudyn_atcm.errors import InputRangeWarning
    from exudyn_atcm.model.strain_conversion import model_to_strain

    u, y = audit_record()
    model, _ = PrandtlIshlinskii.fit(u, y * 1e6, 20, output_unit="m")  # µm values declared as m
    # by hand: the truth's displacement at 1000 V from rest is 5.4e-6 m, here 5.4 "m"; over 0.06 m: a strain of 90
    peak = play_sum([0.0, 1000.0], RADII, WEIGHTS, P0)[-1] * 1e6 / 0.06
    with pytest.warns(InputRangeWarning, match=r"reaches a strain of (89\.\d|90\.\d*|90) .*more than 0\.01"):
        strain = model_to_strain(model, gauge_length=0.06)
    assert float(strain.apply([0.0, 1000.0])[-1]) == pytest.approx(peak, rel=0.02)


def test_a_gauge_length_in_millimetres_is_warned():
    """60 for 60 mm: the strains come out 1000 times too small (9e-8 at 1000 V by the hand model), silently before."""
    from exudyn_atcm.errors import InputRangeWarning
    from exudyn_atcm.model.strain_conversion import model_to_strain

    u, y = audit_record()
    model, _ = PrandtlIshlinskii.fit(u, y, 20, output_unit="m")
    with pytest.warns(InputRangeWarning, match=r"model_to_strain: gauge_length = 60\.0 m is outside the plausible range"):
        strain = model_to_strain(model, gauge_length=60.0)
    peak = play_sum([0.0, 1000.0], RADII, WEIGHTS, P0)[-1] / 60.0
    assert float(strain.apply([0.0, 1000.0])[-1]) == pytest.approx(peak, rel=0.02)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        model_to_strain(model, gauge_length=0.06)  # a plausible length: silent
