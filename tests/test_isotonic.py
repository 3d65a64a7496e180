"""The branch averaging of from_loop is scipy's isotonic regression (issue 14, part 5).

Reference: the least-squares non-decreasing fit written as a bound-constrained least-squares
problem, ``y = c + cumsum(d)`` with increments ``d >= 0`` (scipy.optimize.lsq_linear), which
shares no code with the pool-adjacent-violators algorithm behind ``isotonic_regression``.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import lsq_linear

from exudyn_atcm.hysteresis.loop_identification import isotonic


def _reference(values: np.ndarray) -> np.ndarray:
    n = values.size
    # columns: the offset c, then the increments d_1..d_{n-1} (lower triangular ones)
    a = np.ones((n, n))
    a[:, 1:] = np.tril(np.ones((n, n)), -1)[:, :-1]
    lower = np.r_[-np.inf, np.zeros(n - 1)]
    sol = lsq_linear(a, values, bounds=(lower, np.full(n, np.inf)), tol=1e-14, lsmr_tol="auto", max_iter=10_000)
    return a @ sol.x


@pytest.mark.parametrize("seed", range(5))
def test_isotonic_is_the_least_squares_non_decreasing_fit(seed):
    rng = np.random.default_rng(seed)
    values = np.cumsum(rng.normal(0.0, 0.1, 60)) + rng.normal(0.0, 1.0, 60)
    fit = isotonic(values)
    assert np.all(np.diff(fit) >= 0.0)
    np.testing.assert_allclose(fit, _reference(values), atol=1e-8)


def test_isotonic_of_sorted_values_is_the_identity_and_of_reversed_is_the_mean():
    values = np.linspace(-1.0, 2.0, 7)
    np.testing.assert_array_equal(isotonic(values), values)
    np.testing.assert_allclose(isotonic(values[::-1]), np.full(7, values.mean()), rtol=0, atol=1e-15)
