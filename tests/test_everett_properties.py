"""Preisach properties of EverettPreisach (Mayergoyz 2003): bounds, wiping-out, congruency, continuity."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from exudyn_atcm.hysteresis import EverettPreisach
from exudyn_atcm.hysteresis.identification import relay_grid

N = 12
ALPHA, BETA, _ = relay_grid(-500.0, 1500.0, N)
RNG = np.random.default_rng(4)
WEIGHTS = RNG.uniform(0.0, 1.0, ALPHA.size) * (RNG.uniform(size=ALPHA.size) > 0.3)  # some cells empty
MODEL = EverettPreisach(np.linspace(-500.0, 1500.0, N + 1), ALPHA, BETA, WEIGHTS, offset=-2.0)
LO, HI = -2.0, -2.0 + WEIGHTS.sum()
TOL = 1e-12 * (HI - LO)

values = st.floats(-800.0, 1800.0, allow_nan=False, allow_infinity=False)
histories = st.lists(values, min_size=1, max_size=20)


def run(history):
    MODEL.reset()
    return [MODEL.commit(u) for u in history]


@given(histories)
def test_bounds_and_saturation(history):
    assert all(LO - TOL <= y <= HI + TOL for y in run(history))
    assert abs(MODEL.commit(1500.0) - HI) <= TOL
    assert abs(MODEL.commit(-500.0) - LO) <= TOL


@given(histories, values, st.lists(st.floats(0, 1), max_size=10), st.floats(0.01, 1))
def test_wiping_out(history, u1, wander, depth):
    run(history)
    assume(u1 != history[-1])
    MODEL.commit(u1)
    probes = np.linspace(-600, 1600, 9)
    expected = [MODEL.evaluate(p) for p in probes]
    u2 = u1 + depth * (history[-1] - u1)
    MODEL.commit(u2)
    for s in wander:
        MODEL.commit(u2 + s * (u1 - u2))
    MODEL.commit(u1)
    np.testing.assert_allclose([MODEL.evaluate(p) for p in probes], expected, rtol=0, atol=TOL)


@given(histories, histories, st.floats(-600, 1600), st.floats(-600, 1600))
def test_congruent_minor_loops(history1, history2, ua, ub):
    assume(abs(ua - ub) > 1.0)
    lo, hi = min(ua, ub), max(ua, ub)
    path = np.r_[np.linspace(hi, lo, 31), np.linspace(lo, hi, 31)[1:]]
    loops = []
    for history in (history1, history2):
        run(history)
        MODEL.commit(ua)
        MODEL.commit(ub)
        loops.append(np.array([MODEL.commit(u) for u in path]))
    shift = loops[0] - loops[1]
    np.testing.assert_allclose(shift, shift[0], rtol=0, atol=TOL)


@settings(max_examples=50)
@given(histories, st.floats(-2.0, 2.0), values)
def test_output_is_continuous(history, step, u):
    """An input change du moves the switching line through one column (or row) of at most N
    cells; each cell's share changes by at most 2 w |du| / h (the diagonal cells' w s^2 has
    slope <= 2 w / h; h = 2000/12 V, the cell width): no jumps."""
    run(history)
    y0 = MODEL.commit(u)
    y1 = MODEL.evaluate(u + step)
    h = 2000.0 / N
    assert abs(y1 - y0) <= 2.0 * N * WEIGHTS.max() * abs(step) / h + TOL
