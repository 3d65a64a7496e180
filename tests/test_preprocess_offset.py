"""The output offset of a record: taken from the rest before the excitation, before the start is trimmed (issue 28, part 3).

Synthetic records whose true offset is known: 0.2 s at rest (input 0 V, output = offset +
white noise), then a 5 Hz excitation from 0 to 1000 V whose output is a known curve plus the
offset and the same noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm.errors import AccuracyWarning
from exudyn_atcm.io.measurements import Record, preprocess

OFFSET = 3.7e-6  # [m]: the sensor's zero
NOISE = 0.05e-6  # [m]: standard deviation of the sensor noise
REST = 0.2  # [s]: at rest before the excitation


def record(seed=1, noise=NOISE, filtered=False):
    t = np.arange(0.0, 1.0, 1e-3)
    phase = np.clip(t - REST, 0.0, None)
    u = 500.0 * (1.0 - np.cos(2.0 * math.pi * 5.0 * phase))  # starts at rest, 0 V
    clean = 20e-6 * (u / 1000.0) ** 1.3
    rng = np.random.default_rng(seed)
    e = rng.normal(0.0, noise, t.size)
    if filtered:  # low-pass noise (an instrument's filter): successive samples correlated
        e = np.convolve(rng.normal(0.0, noise * math.sqrt(10.0), t.size + 9), np.ones(10) / 10.0, mode="valid")
    rec = Record(t, u, clean + OFFSET + e, units={"time": "s", "input": "V", "output": "m"})
    return rec, clean, e


def test_offset_samples_are_the_rest_before_the_trimmed_start():
    """The issue's case: trim the rest, take the offset from it (main took the sine after the trim)."""
    rec, clean, e = record()
    n = 150  # all at rest (t < 0.15 s)
    out = preprocess(rec, trim_start=REST, offset_samples=n)
    # the plain reference: the mean of the first n samples of the record as given
    removed = float(np.mean(rec.output[:n]))
    assert removed == pytest.approx(OFFSET, abs=4 * NOISE / math.sqrt(n))  # 4 standard errors of a mean
    kept = rec.time >= rec.time[0] + REST
    np.testing.assert_allclose(out.output, rec.output[kept] - removed, rtol=0, atol=1e-18)
    np.testing.assert_allclose(out.output - e[kept], clean[kept], atol=4 * NOISE / math.sqrt(n))
    assert out.processing[-2:] == (f"removed an output offset of {removed:.6g} m (mean of the first {n} samples)",
                                   "trimmed 200 samples of the first 0.2 s (settling)")


def test_offset_window_on_the_record_time_axis():
    rec, _, _ = record(seed=2)
    out = preprocess(rec, offset_window=(0.05, 0.15), trim_start=REST)
    inside = (rec.time >= 0.05) & (rec.time <= 0.15)
    removed = float(np.mean(rec.output[inside]))
    assert removed == pytest.approx(OFFSET, abs=4 * NOISE / math.sqrt(inside.sum()))
    np.testing.assert_allclose(out.output, rec.output[rec.time >= REST] - removed, rtol=0, atol=1e-18)
    assert f"(mean of the {int(inside.sum())} samples in t = 0.05 ... 0.15 s)" in out.processing[-2]


@pytest.mark.parametrize("kwargs", [{"offset_samples": 400}, {"offset_window": (0.1, 0.5)}])
def test_offset_samples_reaching_into_the_excitation_warn(kwargs):
    rec, _, _ = record(seed=3)
    with pytest.warns(AccuracyWarning, match=r"offset samples \(.*\) are not at rest: the input spreads by .* V .*; "
                                             r"the output spreads by .* m .*Give offset_window=\(t0, t1\)"):
        preprocess(rec, **kwargs)


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("filtered", [False, True])
def test_noise_at_rest_does_not_warn(seed, filtered):
    # pytest turns every AtcmWarning into an error: a warning here fails the test.  Filtered
    # noise understates the sample-to-sample noise (about 1/3 here); the 1 % range floor holds it.
    rec, _, _ = record(seed=seed, filtered=filtered)
    out = preprocess(rec, offset_window=(0.0, 0.19))
    assert out.output[0] == pytest.approx(rec.output[0] - np.mean(rec.output[rec.time <= 0.19]), abs=1e-18)


def test_a_small_offset_count_is_not_judged():
    rec, _, _ = record()
    preprocess(rec, offset_window=(0.4, 0.401))  # two samples moving: too few to tell noise from motion


@pytest.mark.parametrize("kwargs, pattern", [
    ({"offset_samples": 5, "offset_window": (0.0, 0.1)}, r"offset_samples or by offset_window, not both"),
    ({"offset_window": 0.1}, r"offset_window must be a pair \(t0, t1\) of times \[s\], got 0.1"),
    ({"offset_window": (0.2, 0.1)}, r"offset_window must have t0 < t1, got \(0.2, 0.1\)"),
    ({"offset_window": (2.0, 3.0)}, r"offset_window = \(2, 3\) s holds no sample of the record \(its times run "
                                    r"from 0 to 0.999 s"),
    ({"offset_window": (0.0, float("nan"))}, r"offset_window\[1\] must be a finite real number"),
])
def test_bad_offset_arguments(kwargs, pattern):
    rec, _, _ = record()
    with pytest.raises(ValueError, match=pattern):
        preprocess(rec, **kwargs)


def test_drift_is_measured_after_the_settling_start_and_removed_from_the_record_start():
    # triangle cycles after a settling start whose output creeps (a transient at t < 1 s);
    # drift 0.5 per second from t = 0: with trim_start=1 the drift comes from the minima
    # after the settling, the offset from the first sample of the record
    t = np.linspace(0.0, 9.0, 901)
    u = 1.0 - np.abs(((t - 1.0) % 2.0) - 1.0)
    u[t < 1.0] = 0.0
    settling = np.where(t < 1.0, 0.3 * np.sin(math.pi * t), 0.0)
    rec = Record(t, u, u**2 + 3.0 + 0.5 * t + settling, units={"time": "s", "input": "V", "output": "m"})
    out = preprocess(rec, drift=True, offset_samples=1, trim_start=1.0)
    np.testing.assert_allclose(out.output, (u**2)[t >= 1.0], atol=1e-12)
