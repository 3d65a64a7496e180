"""The step choice's linear filters (:mod:`exudyn_atcm.solve.linear_recurrence`) against the recurrence
stepped one sample at a time and against ``scipy.signal.lfilter`` (the transfer-function form)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.signal import lfilter

from exudyn_atcm.solve.linear_recurrence import block_length, first_component, first_order


def _stepped(a, b, u):
    """e_0 . z_n, n = 1..N, of z_{n+1} = A z_n + b u_n from z_0 = 0, one sample at a time."""
    z = np.zeros(a.shape[0], dtype=np.result_type(a, b, u, float))
    out = []
    for value in u:
        z = a @ z + b * value
        out.append(z[0])
    return np.array(out)


def _generalized_alpha_like(h: float, omega: float) -> np.ndarray:
    """A 3 x 3 stable, non-normal matrix: a damped rotation with a lagging state (spectral radius < 1)."""
    c, s = math.cos(omega * h), math.sin(omega * h)
    return np.array([[0.99 * c, 0.99 * s, 0.3], [-0.99 * s, 0.99 * c, 0.0], [0.0, 0.0, -0.8]])


@pytest.mark.parametrize("n", [1, 2, 15, 16, 17, 255, 256, 257, 1000, 4099])
def test_first_component_is_the_recurrence_stepped_sample_by_sample(n):
    # lengths at, below and above the block lengths (16 ... 256) and several blocks
    rng = np.random.default_rng(n)
    a = _generalized_alpha_like(1e-3, 300.0)
    b = np.array([0.2, -1.0, 0.5])
    u = rng.standard_normal(n)
    ref = _stepped(a, b, u)
    assert np.max(np.abs(first_component(a, b, u) - ref)) <= 1e-12 * max(1.0, np.max(np.abs(ref)))


def test_first_order_is_lfilter_on_a_long_lightly_damped_complex_record():
    # the stand-in's amplitudes: a complex pole just inside the unit circle over many blocks
    rng = np.random.default_rng(7)
    x = rng.standard_normal(200_000) + 1j * rng.standard_normal(200_000)
    pole = np.exp(complex(-0.01 * 314.0, 314.0) * 1e-5)
    ref = lfilter([1.0], [1.0, -pole], x)
    assert np.max(np.abs(first_order(pole, x) - ref)) <= 1e-12 * np.max(np.abs(ref))


def test_a_marginally_stable_pole_accumulates_exactly():
    # pole 1: the running sum; pole -1: the alternating running sum (integers, exact in floating point)
    x = np.arange(1.0, 1001.0)
    assert np.array_equal(first_order(1.0, x).real, np.cumsum(x))
    assert np.array_equal(first_order(-1.0, x).real, np.array([sum((-1) ** (k - j) * x[j] for j in range(k + 1))
                                                              for k in range(1000)]))


def test_block_lengths_stay_within_bounds():
    assert [block_length(n) for n in (0, 1, 100, 4096, 65536, 10**7)] == [16, 16, 16, 64, 256, 256]


def test_shapes_are_checked():
    with pytest.raises(ValueError, match="a must be square"):
        first_component(np.zeros((2, 3)), np.zeros(2), np.zeros(4))
    with pytest.raises(ValueError, match="shapes"):
        first_component(np.eye(2), np.zeros(3), np.zeros(4))
    assert first_component(np.eye(2), np.ones(2), np.zeros(0)).shape == (0,)
