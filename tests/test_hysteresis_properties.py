"""Property-based tests of the Preisach operators (Mayergoyz 2003, ch. 1).

Wiping-out, congruency of minor loops, rate independence, bounds, continuity, and that
``evaluate`` has no side effect, on random input histories, for every Preisach model:
the continuous model, a discrete model identified from a loop (monotone relay family) and a
discrete model with random relays (general relay family).
"""

from unittest import mock

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st

from exudyn_atcm.hysteresis import ContinuousPreisach, DiscretePreisach, _dominance

U_LO, U_HI = -800.0, 1800.0  # beyond the models' range on both sides, to test saturation


def continuous():
    return ContinuousPreisach.from_points(-500, 1500, -4e-6, 40e-6, 500, 12e-6, 28e-6)


def discrete_from_loop():
    model = continuous()
    u = np.linspace(-500, 1500, 401)
    y = np.r_[[model.ascending(v) for v in u], [model.descending(v) for v in u[::-1]]]
    return DiscretePreisach.from_loop(np.r_[u, u[::-1]], y, 37)


def discrete_random(max_table_entries=1 << 22):
    rng = np.random.default_rng(7)
    n = 60
    a = rng.uniform(-500, 1500, n)
    b = a - rng.uniform(0, 900, n)
    b[:5] = a[:5]  # a few relays with alpha == beta
    w = rng.integers(1, 9, n) / 8.0
    return DiscretePreisach(a, b, w, offset=-1.0, max_table_entries=max_table_entries)


def discrete_random_three_levels():
    with mock.patch.object(_dominance, "TWO_LEVEL_ENTRIES", 0):
        return discrete_random(0)


MODELS = {
    "continuous": continuous,
    "from_loop": discrete_from_loop,  # prefix-sum kernel
    "random": discrete_random,  # Everett-table kernel
    "random_dominance": lambda: discrete_random(0),  # dominance sums, two levels
    "random_dominance3": discrete_random_three_levels,  # dominance sums, three levels
}
model_names = st.sampled_from(sorted(MODELS))
inputs = st.floats(U_LO, U_HI, allow_nan=False, allow_infinity=False)
grid_inputs = st.sampled_from([-500.0, 0.0, 250.0, 500.0, 1000.0, 1500.0])
values = st.one_of(inputs, grid_inputs)
histories = st.lists(values, min_size=1, max_size=25)


def run(model, history):
    model.reset()
    return [model.commit(u) for u in history]


def bounds(model):
    if isinstance(model, ContinuousPreisach):
        return model.y_min, model.y_max
    w = model.weights
    return model.offset + w[w < 0].sum(), model.offset + w[w > 0].sum()


def scale(model):
    lo, hi = bounds(model)
    return hi - lo


@given(model_names, histories, st.lists(values, max_size=5))
def test_evaluate_changes_nothing(name, history, trials):
    model = MODELS[name]()
    run(model, history)
    before = model.checkpoint()
    for u in trials:
        model.evaluate(u)
    assert model.checkpoint() == before
    # and evaluate(u) is exactly what commit(u) would return
    for u in trials:
        assert model.evaluate(u) == model.commit(u)


@given(model_names, histories)
def test_output_stays_within_bounds(name, history):
    model = MODELS[name]()
    lo, hi = bounds(model)
    tol = 1e-12 * scale(model)
    for y in run(model, history):
        assert lo - tol <= y <= hi + tol


@given(model_names, histories, values, st.lists(st.floats(0, 1), max_size=12), st.floats(0.01, 1))
def test_return_point_memory(name, history, u1, wander, depth):
    """The input reaches u1 from the last history value h, turns back to u2 between u1 and h,
    wanders inside [u1, u2]; coming back to u1 wipes out everything since and restores the
    state held at u1 (Mayergoyz's wiping-out property)."""
    model = MODELS[name]()
    run(model, history)
    direction = np.sign(u1 - history[-1])
    assume(direction != 0)
    model.commit(u1)
    at_u1 = model.checkpoint()
    probes = np.linspace(U_LO, U_HI, 13)
    expected = [model.evaluate(p) for p in probes]
    u2 = u1 + depth * (history[-1] - u1)
    model.commit(u2)
    for s in wander:
        model.commit(u2 + s * (u1 - u2))
    model.commit(u1)
    tol = 1e-12 * scale(model)
    np.testing.assert_allclose([model.evaluate(p) for p in probes], expected, rtol=0, atol=tol)
    model.restore(at_u1)


@given(model_names, histories, histories, st.floats(-600, 1600), st.floats(-600, 1600))
def test_minor_loops_between_same_extrema_are_congruent(name, history1, history2, ua, ub):
    assume(abs(ua - ub) > 1.0)
    lo, hi = min(ua, ub), max(ua, ub)
    model = MODELS[name]()
    path = np.r_[np.linspace(hi, lo, 41), np.linspace(lo, hi, 41)[1:]]
    loops = []
    for history in (history1, history2):
        run(model, history)
        model.commit(ua)
        model.commit(ub)
        loops.append(np.array([model.commit(u) for u in path]))
    shift = loops[0] - loops[1]
    np.testing.assert_allclose(shift, shift[0], rtol=0, atol=1e-12 * scale(model))


@given(model_names, histories, st.lists(st.floats(0.001, 0.999), min_size=1, max_size=4))
def test_rate_independence(name, history, fractions):
    """Re-sampling each monotone segment (extra points strictly inside it) changes nothing."""
    model = MODELS[name]()
    original = run(model, history)
    refined, keep = [], []
    previous = None
    for u in history:
        if previous is not None:
            for f in sorted(fractions):
                refined.append(previous + f * (u - previous))
        refined.append(u)
        keep.append(len(refined) - 1)
        previous = u
    outputs = run(model, refined)
    np.testing.assert_allclose(
        [outputs[k] for k in keep], original, rtol=0, atol=1e-12 * scale(model)
    )


@given(histories, st.floats(-5, 5), values)
def test_continuous_model_is_lipschitz_continuous(history, step, u):
    """From any committed state the output is Lipschitz in the next input, with the branches'
    steepest slope Δy·max(r1, r2)/Δu as constant."""
    model = continuous()
    run(model, history)
    lip = (model.y_max - model.y_min) * max(model.r1, model.r2) / (model.u_max - model.u_min)
    assert abs(model.evaluate(u + step) - model.evaluate(u)) <= lip * abs(step) * (1 + 1e-9) + 1e-20


@given(st.sampled_from(["from_loop", "random", "random_dominance", "random_dominance3"]), histories, values)
def test_discrete_output_jumps_only_by_relays_crossed(name, history, u):
    """A discrete model's output changes only by the weights of relays whose thresholds lie
    between the last input and the new one (its form of continuity)."""
    model = MODELS[name]()
    run(model, history)
    c = model.last_input
    lo, hi = min(c, u), max(c, u)
    crossed = ((model.alpha >= lo) & (model.alpha <= hi)) | ((model.beta >= lo) & (model.beta <= hi))
    assert abs(model.evaluate(u) - model.output) <= np.abs(model.weights[crossed]).sum() + 1e-12


@given(histories, st.floats(1501, 5000), st.floats(-5000, -501))
def test_inputs_beyond_the_bounds_saturate(history, above, below):
    model = continuous()
    run(model, history)
    # equal up to the round-off of y_max - (y_max - y_min)
    tol = 1e-12 * (model.y_max - model.y_min)
    assert abs(model.commit(above) - model.y_max) <= tol
    assert abs(model.commit(below) - model.y_min) <= tol
    # and the state is negative saturation again: the next rise follows Eq. 8
    assert abs(model.commit(500.0) - model.ascending(500.0)) <= tol


@given(model_names, histories, histories)
def test_checkpoint_and_restore_replay_exactly(name, history, continuation):
    model = MODELS[name]()
    run(model, history)
    saved = model.checkpoint()
    first = [model.commit(u) for u in continuation]
    model.restore(saved)
    assert [model.commit(u) for u in continuation] == first


@given(model_names, histories, st.lists(st.tuples(st.lists(values, max_size=3), st.integers(0, 3), values),
                                         min_size=1, max_size=20))
def test_commit_after_trials_equals_commit_alone(name, history, steps):
    """A solver step's pattern: trials (``evaluate``, any number), then ``commit`` of the last trial's
    input, of an earlier one, or of another input (a trial of an earlier step: a stale one).  The
    commit takes the matching trial's output instead of evaluating ``K`` again; outputs and memory
    must equal those of a twin that only commits, bit for bit."""
    model, twin = MODELS[name](), MODELS[name]()
    run(model, history)
    run(twin, history)
    earlier = list(history)
    for trials, pick, other in steps:
        for u in trials:
            model.evaluate(u)
        pool = trials + earlier[-2:] + [other]
        u = pool[-1 - pick] if pick < len(trials) else pool[pick % len(pool)]
        assert model.commit(u) == twin.commit(u)
        assert model.checkpoint() == twin.checkpoint()
        earlier += trials
    for a, b in ((700.0, -200.0), (-200.0, 700.0)):  # a trial, another input committed, then the trial's input
        model.evaluate(a)
        assert model.commit(b) == twin.commit(b)
        assert model.commit(a) == twin.commit(a)
    twin.reset()
    for u in (1500.0, -500.0, 300.0):
        twin.commit(u)
    model.reset()
    model.evaluate(700.0)
    model.restore(twin.checkpoint())  # a restored memory forgets the trial
    assert model.commit(700.0) == twin.commit(700.0)
