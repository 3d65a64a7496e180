"""Prandtl-Ishlinskii operator and its analytic inverse (docs/theory.rst test vector:
Al Janaideh et al., IEEE Control Systems Magazine 2023, Ex. 1)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from exudyn_atcm.hysteresis import PrandtlIshlinskii

R = [0, 0.45, 0.9, 1.35, 1.8, 2.25, 2.7]
P = [0.72, 0.6, 0.48, 0.36, 0.24, 0.12, 0.012]


def sine_input():
    t = np.linspace(0, 3, 3001)
    return 4 * np.sin(2 * np.pi * t)


def play_by_hand(v, r):
    z, out = 0.0, []
    for x in v:
        z = max(x - r, min(x + r, z))
        out.append(z)
    return np.array(out)


def test_output_is_the_weighted_sum_of_plays():
    v = sine_input()
    model = PrandtlIshlinskii(R[1:], P[1:], p0=P[0])
    expected = P[0] * v + sum(p * play_by_hand(v, r) for r, p in zip(R[1:], P[1:]))
    np.testing.assert_allclose(model.apply(v), expected, rtol=0, atol=1e-13)


@pytest.mark.parametrize(
    "model",
    [PrandtlIshlinskii(R[1:], P[1:], p0=P[0]), PrandtlIshlinskii(R, P, p0=0.0)],
    ids=["p0-separate", "radius-0-play"],
)
def test_inverse_composed_with_operator_is_identity(model):
    v = sine_input()
    inverse = model.inverse()
    np.testing.assert_allclose(inverse.apply(model.apply(v)), v, rtol=0, atol=1e-12)
    np.testing.assert_allclose(model.apply(inverse.apply(v)), v, rtol=0, atol=1e-12)


def test_inverse_parameters_follow_the_published_formulas():
    inverse = PrandtlIshlinskii(R, P, p0=0.0).inverse()
    p0, r, p = P[0], R[1:], P[1:]
    # the formulas of docs/theory.rst written out term by term
    expected_p, expected_r = [], []
    for j in range(len(r)):
        upto = p0 + sum(p[: j + 1])
        before = p0 + sum(p[:j])
        expected_p.append(-p[j] / (upto * before))
        expected_r.append(p0 * r[j] + sum(p[i] * (r[j] - r[i]) for i in range(j + 1)))
    assert inverse.p0 == pytest.approx(1 / 0.72, rel=1e-15)
    np.testing.assert_allclose(inverse.weights, expected_p, rtol=1e-14)
    np.testing.assert_allclose(inverse.radii, expected_r, rtol=1e-14)
    # a few by hand: r̂1 = .72·.45, r̂2 = .72·.9 + .6·.45, r̂3 = .72·1.35 + .6·.9 + .48·.45,
    # p̂1 = −.6/(1.32·.72)
    np.testing.assert_allclose(inverse.radii[:3], [0.324, 0.918, 1.728], rtol=1e-14)
    assert inverse.weights[0] == pytest.approx(-0.6 / (1.32 * 0.72), rel=1e-14)


@given(
    st.lists(st.floats(0.01, 2), min_size=1, max_size=8, unique=True),
    st.data(),
)
def test_inverse_identity_on_random_operators_and_inputs(radii, data):
    radii = sorted(radii)
    weights = data.draw(st.lists(st.floats(0, 2), min_size=len(radii), max_size=len(radii)))
    p0 = data.draw(st.floats(0.1, 2))
    u = data.draw(st.lists(st.floats(-10, 10), min_size=1, max_size=40))
    model = PrandtlIshlinskii(radii, weights, p0)
    np.testing.assert_allclose(model.inverse().apply(model.apply(u)), u, rtol=0, atol=1e-9)


def test_evaluate_is_side_effect_free_and_checkpoint_restores():
    model = PrandtlIshlinskii(R[1:], P[1:], P[0])
    for u in (1.0, 3.0, -2.0):
        model.commit(u)
    saved = model.checkpoint()
    trial = model.evaluate(0.5)
    assert model.evaluate(0.5) == trial
    assert model.commit(0.5) == trial
    model.commit(4.0)
    model.restore(saved)
    assert model.commit(0.5) == trial


def test_inverse_refused_when_not_invertible():
    with pytest.raises(ValueError, match="p0"):
        PrandtlIshlinskii([1.0], [-2.0], 1.0).inverse()
