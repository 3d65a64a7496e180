"""DiscretePreisach against a plain relay-by-relay simulation, and its identification."""

from unittest import mock

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from exudyn_atcm.hysteresis import ContinuousPreisach, DiscretePreisach, _dominance
from exudyn_atcm.hysteresis._dominance import DominanceSums

from relays import equal_gain_relays, relay_outputs


@st.composite
def relay_sets(draw):
    n = draw(st.integers(1, 30))
    grid = st.sampled_from([-2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0])  # shared values: ties
    anywhere = st.floats(-3, 3, allow_nan=False)
    alpha, beta = [], []
    for _ in range(n):
        a = draw(st.one_of(grid, anywhere))
        b = a - draw(st.one_of(st.just(0.0), st.floats(0, 3), st.sampled_from([0.5, 1.0])))
        alpha.append(a)
        beta.append(b)
    # dyadic gains: every partial sum is exact, so outputs can be compared for equality
    weights = [draw(st.integers(-16, 16)) / 16.0 for _ in range(n)]
    offset = draw(st.integers(-8, 8)) / 4.0
    return np.array(alpha), np.array(beta), np.array(weights), offset


inputs = st.lists(
    st.one_of(st.floats(-4, 4, allow_nan=False), st.sampled_from([-2.0, -1.0, 0.0, 0.5, 1.0, 2.0])),
    min_size=1,
    max_size=60,
)


def build(alpha, beta, weights, offset, kernel):
    """A model with the kernel asked for: "auto" (prefix sums or Everett table), or the
    dominance-sum table with two or three levels (forced for any relay set)."""
    if kernel == "auto":
        return DiscretePreisach(alpha, beta, weights, offset)
    two_level_entries = 1 << 62 if kernel == "dominance2" else 0
    with mock.patch.object(_dominance, "TWO_LEVEL_ENTRIES", two_level_entries):
        model = DiscretePreisach(alpha, beta, weights, offset, max_table_entries=0)
    assert model.kernel in ("prefix", "dominance")
    return model


KERNELS = ["auto", "dominance2", "dominance3"]


@given(relay_sets(), inputs, st.sampled_from(KERNELS))
def test_identical_to_relay_by_relay_simulation(relays, u, kernel):
    """Every kernel (prefix sums, Everett table, dominance sums) gives the relays' output."""
    alpha, beta, weights, offset = relays
    model = build(alpha, beta, weights, offset, kernel)
    np.testing.assert_array_equal(model.apply(u), relay_outputs(alpha, beta, weights, offset, u))


@st.composite
def weighted_points(draw):
    n = draw(st.integers(1, 80))
    grid = st.sampled_from([-1.0, 0.0, 0.25, 1.0])  # duplicates and ties alpha == beta
    coordinate = st.one_of(grid, st.floats(-2, 2, allow_nan=False))
    alpha = [draw(coordinate) for _ in range(n)]
    beta = [draw(st.one_of(st.just(a), coordinate)) for a in alpha]  # beta > alpha allowed here
    weights = [draw(st.integers(-8, 8)) / 8.0 for _ in range(n)]
    return np.array(alpha), np.array(beta), np.array(weights)


@given(weighted_points(), st.sampled_from([2, 3]), st.lists(st.floats(-3, 3, allow_nan=False), max_size=8))
def test_dominance_sums_equal_the_direct_sum(points, levels, extra):
    """K(a, b) at every threshold, between them and beyond (±inf too) is the direct sum of
    the weights with alpha <= a and beta >= b (exact: dyadic weights)."""
    alpha, beta, weights = points
    structure = DominanceSums(alpha, beta, weights, levels)
    probes = sorted({*alpha.tolist(), *beta.tolist(), *extra, -np.inf, np.inf, -5.0, 5.0})
    for a in probes:
        for b in probes:
            assert structure.query(a, b) == weights[(alpha <= a) & (beta >= b)].sum(), (a, b)


def test_dominance_sums_refuse_bad_levels():
    with pytest.raises(ValueError, match="levels must be 2, 3"):
        DominanceSums(np.zeros(3), np.zeros(3), np.ones(3), levels=4)


@pytest.mark.parametrize("kernel", ["dominance2", "dominance3"])
def test_scattered_relays_with_duplicates_and_ties_under_a_noisy_input(kernel):
    """400 relays on a coarse grid (many duplicate relays, 1 in 8 with alpha == beta) and an
    input that reverses at nearly every step, landing on thresholds often: the dominance
    kernel equals the relay-by-relay simulation exactly (dyadic gains) and the Everett-table
    kernel exactly."""
    rng = np.random.default_rng(11)
    n = 400
    alpha = rng.integers(-40, 40, n) / 8.0
    beta = alpha - rng.integers(0, 30, n) / 8.0
    beta[::8] = alpha[::8]
    weights = rng.integers(-32, 64, n) / 64.0
    u = np.round(np.cumsum(rng.normal(scale=0.8, size=600)) * (1 - 2 * (np.arange(600) % 2)), 1)
    model = build(alpha, beta, weights, 0.5, kernel)
    assert model.kernel == "dominance" and model._has_ties
    table = DiscretePreisach(alpha, beta, weights, 0.5)
    assert table.kernel == "table"
    expected = relay_outputs(alpha, beta, weights, 0.5, u)
    np.testing.assert_array_equal(model.apply(u), expected)
    np.testing.assert_array_equal(table.apply(u), expected)


def test_preisach_grid_uses_the_everett_table_and_matches_relays():
    levels = np.linspace(-1, 1, 9)
    alpha, beta = np.meshgrid(levels, levels, indexing="ij")
    keep = alpha >= beta
    alpha, beta = alpha[keep], beta[keep]
    weights = np.exp(-(alpha - 0.2) ** 2 - (beta + 0.1) ** 2)
    model = DiscretePreisach(alpha, beta, weights)
    assert model.kernel == "table"
    rng = np.random.default_rng(5)
    u = np.r_[np.cumsum(rng.normal(scale=0.25, size=300)), levels]
    np.testing.assert_allclose(model.apply(u), relay_outputs(alpha, beta, weights, 0.0, u), rtol=0, atol=1e-12)


def test_random_relays_with_random_float_gains():
    rng = np.random.default_rng(3)
    for n, limit, kernel in ((1, 1 << 22, "prefix"), (10, 1 << 22, "table"), (200, 1 << 22, "table"), (200, 100, "dominance")):
        alpha = rng.uniform(-1, 1, n)
        beta = alpha - rng.exponential(0.4, n)
        weights = rng.normal(size=n)
        model = DiscretePreisach(alpha, beta, weights, 0.25, max_table_entries=limit)
        assert model.kernel == kernel
        u = np.cumsum(rng.normal(scale=0.3, size=400))
        expected = relay_outputs(alpha, beta, weights, 0.25, u)
        # float sums in another order: equal to round-off of sum(|w|)
        np.testing.assert_allclose(model.apply(u), expected, rtol=0, atol=1e-12 * np.abs(weights).sum())


def test_monotone_family_is_detected_and_matches_relays():
    alpha = np.array([0.0, 1.0, 2.0, 3.0])
    beta = np.array([-1.0, -0.5, 1.0, 3.0])
    model = DiscretePreisach(alpha[::-1], beta[::-1], [1, 2, 3, 4])
    assert model.monotone and model.kernel == "prefix"
    u = [3, -1, 2, 0.5, 1, -0.7, 2.5, 0.99, 4, -3]
    np.testing.assert_array_equal(model.apply(u), relay_outputs(alpha[::-1], beta[::-1], [1, 2, 3, 4], 0.0, u))


def continuous_loop(model, samples=2001):
    u = np.linspace(model.u_min, model.u_max, samples)
    y_up = np.array([model.ascending(v) for v in u])
    y_down = np.array([model.descending(v) for v in u[::-1]])
    return np.r_[u, u[::-1]], np.r_[y_up, y_down]


PAPER = ContinuousPreisach.from_points(-500, 1500, -4e-6, 40e-6, 500, 12e-6, 28e-6)


@pytest.mark.parametrize("n", [1, 6, 25, 100])
def test_from_loop_error_at_most_one_gain_step(n):
    u, y = continuous_loop(PAPER)
    model = DiscretePreisach.from_loop(u, y, n)
    gain = (PAPER.y_max - PAPER.y_min) / n
    np.testing.assert_allclose(model.weights, gain)
    assert model.offset == PAPER.y_min
    assert model.monotone
    # two cycles over the loop, sampled more finely than the identification data
    grid = np.linspace(-500, 1500, 3001)
    path = np.r_[grid, grid[::-1], grid, grid[::-1]]
    reference = PAPER.apply(path)
    error = np.abs(model.apply(path) - reference)
    # the thresholds are interpolated in the identification samples: allow that error too
    assert error.max() <= gain * (1 + 1e-3)


def test_from_loop_error_shrinks_as_n_grows():
    u, y = continuous_loop(PAPER)
    grid = np.linspace(-500, 1500, 1501)
    path = np.r_[grid, grid[::-1], grid[:800], grid[800:300:-1], grid[300:1200]]
    reference = PAPER.apply(path)
    errors = []
    for n in (6, 24, 96, 384):
        errors.append(np.abs(DiscretePreisach.from_loop(u, y, n).apply(path) - reference).max())
    assert all(later < 0.6 * earlier for earlier, later in zip(errors, errors[1:])), errors


def test_from_loop_thresholds_are_the_branch_crossings():
    u, y = continuous_loop(PAPER, samples=20001)
    model = DiscretePreisach.from_loop(u, y, 6)
    alpha_ref, beta_ref, _, _ = equal_gain_relays(PAPER, 6)
    order = np.argsort(model.alpha)
    np.testing.assert_allclose(model.alpha[order], alpha_ref, atol=0.05)  # V, sample spacing 0.1 V
    np.testing.assert_allclose(model.beta[order], beta_ref, atol=0.05)


@given(
    st.lists(
        st.one_of(st.floats(-700, 1700, allow_nan=False), st.sampled_from([-500.0, 500.0, 1500.0])),
        min_size=1,
        max_size=20,
    )
)
def test_continuous_model_is_the_limit_of_eq_12_relays(history):
    """The continuous model against an independent relay-by-relay simulation of the paper's
    equal-gain construction with n = 3000 relays built from the analytic branch inverses.

    The relays count levels where the continuous model measures them; the set of 'on'
    levels is a union of at most len(history) + 1 intervals, each of which can be off by
    one gain step: tolerance (len(history) + 1) * dy."""
    n = 3000
    alpha, beta, weights, offset = equal_gain_relays(PAPER, n)
    relays = relay_outputs(alpha, beta, weights, offset, history)
    dy = (PAPER.y_max - PAPER.y_min) / n
    np.testing.assert_allclose(PAPER.apply(history), relays, rtol=0, atol=(len(history) + 1) * dy)


def test_scattered_relays_select_the_dominance_kernel_by_default():
    """3000 random relays (a 9-million-cell Everett grid) get the dominance kernel without
    any option, and follow the relay-by-relay simulation on an input that reverses at every
    step (float gains: equal to the round-off of sum |w|)."""
    rng = np.random.default_rng(21)
    n = 3000
    alpha = rng.uniform(-500, 1500, n)
    beta = alpha - rng.uniform(0, 1000, n)
    weights = rng.uniform(0, 1e-6, n)
    model = DiscretePreisach(alpha, beta, weights, offset=-1e-4)
    assert model.kernel == "dominance"
    steps = np.arange(250)
    u = 500 + 900 * np.sin(steps / 20.0) + 40 * (1 - 2 * (steps % 2))  # zigzag: always a reversal
    assert np.all(np.diff(u)[1:] * np.diff(u)[:-1] < 0)
    expected = relay_outputs(alpha, beta, weights, -1e-4, u)
    np.testing.assert_allclose(model.apply(u), expected, rtol=0, atol=1e-12 * weights.sum())
