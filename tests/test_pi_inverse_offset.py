"""``PrandtlIshlinskii.inverse()`` of operators with offsets, fitted models included (issue 14, part 5).

The inverse of ``y = c + P[u − d]`` is ``u = d + P⁻¹[y − c]``: a Prandtl-Ishlinskii operator with the
published inverse weights and radii (checked in test_hysteresis_pi.py) and the two offsets swapped.
Both operators are piecewise linear maps of their input histories, so composing them returns the
input up to floating-point rounding only; the tolerances below are a few hundred ulps of the inputs.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.errors import OutOfReachWarning
from exudyn_atcm.hysteresis import ContinuousPreisach, PrandtlIshlinskii, inverse_operator
from exudyn_atcm.hysteresis.prandtl_ishlinskii import ShiftedPIInverse

PAPER = ContinuousPreisach.from_points(-500, 1500, -4e-6, 40e-6, 500, 12e-6, 28e-6)


def _paper_record():
    """A first loading, a full unloading and a decaying sine: inputs [V], the paper loop's strokes [m]."""
    t = np.linspace(0.0, 4.0, 2001)
    u = np.concatenate([np.linspace(0.0, 1500.0, 200), np.linspace(1500.0, -500.0, 300),
                        500.0 + 1000.0 * np.sin(2 * np.pi * t) * np.exp(-0.3 * t)])
    return u, PAPER.apply(u)


def test_offsets_swap_and_the_composition_is_the_identity():
    model = PrandtlIshlinskii([0.5, 1.0, 2.0], [0.3, 0.2, 0.1], 0.4, offset=-1.0, input_offset=0.25)
    inverse = model.inverse()
    assert (inverse.offset, inverse.input_offset) == (0.25, -1.0)
    u = np.array([0.25, 2.0, -1.0, 1.5, 0.0, 3.0, -2.0, 0.7])
    np.testing.assert_allclose(inverse.apply(model.apply(u)), u, rtol=0, atol=1e-12)
    y = np.array([-1.0, 0.5, -0.2, 1.3, 0.1, 2.0, -0.5])  # starting at the output at rest, c
    np.testing.assert_allclose(model.apply(inverse.apply(y)), y, rtol=0, atol=1e-12)


def test_offset_only_shifts_input_and_output():
    """c + P[u - d] is P[u - d] shifted by c: the same play states, outputs differing by exactly c."""
    plain = PrandtlIshlinskii([0.5, 1.0, 2.0], [0.3, 0.2, 0.1], 0.4)
    shifted = PrandtlIshlinskii([0.5, 1.0, 2.0], [0.3, 0.2, 0.1], 0.4, offset=2.0, input_offset=-0.5)
    u = np.array([0.3, 1.9, -1.2, 0.8, 2.5])
    np.testing.assert_allclose(shifted.apply(u - 0.5), plain.apply(u) + 2.0, rtol=0, atol=1e-15)


# the random stroke history below takes the fitted model far beyond the inputs it was fitted on
# (-4100 V): an algebraic identity of the operator, not a use of the fitted model
@pytest.mark.filterwarnings("ignore::exudyn_atcm.errors.InputRangeWarning")
def test_fitted_model_inverts_with_its_offset():
    u, y = _paper_record()
    model, _ = PrandtlIshlinskii.fit(u, y, 10)
    assert model.offset != 0.0  # what inverse() used to refuse
    inverse = model.inverse()
    # inputs span 2000 V: 1e-9 V is 5e-13 of the range (measured 3e-11 V at most)
    np.testing.assert_allclose(inverse.apply(model.apply(u)), u, rtol=0, atol=1e-9)
    # any wanted stroke history from the output at rest through the analytic inverse (a PI operator with p0 > 0
    # reaches every output); a fitted model's inverse() stays in the fitted input range and says what it clipped
    wanted = model.offset + np.cumsum(np.random.default_rng(1).normal(0.0, 3e-6, 400))
    np.testing.assert_allclose(model.apply(ShiftedPIInverse(model).apply(wanted)), wanted, rtol=0, atol=1e-15)
    beyond = np.abs(ShiftedPIInverse(model).apply(wanted) - 0.5 * (u.min() + u.max())) > 0.5 * np.ptp(u)
    assert beyond.any()  # the history leaves the record's range
    with pytest.warns(OutOfReachWarning, match=r"wanted outputs are outside the range reachable"):
        bounded = inverse.apply(wanted)
    assert u.min() <= bounded.min() and bounded.max() <= u.max()


def test_inverse_of_the_inverse_is_the_model():
    u, y = _paper_record()
    model, _ = PrandtlIshlinskii.fit(u, y, 10)
    again = model.inverse().inverse()
    assert (again.offset, again.input_offset) == (model.offset, model.input_offset)
    assert again.p0 == pytest.approx(model.p0, rel=1e-12)
    np.testing.assert_allclose(again.radii, model.radii, rtol=1e-12)
    np.testing.assert_allclose(again.weights, model.weights, rtol=1e-9, atol=1e-12 * model.weights.max())


def test_inverse_operator_is_the_same_inverse():
    u, y = _paper_record()
    model, _ = PrandtlIshlinskii.fit(u, y, 10)
    wanted = model.apply(u[::7])
    general = inverse_operator(model)
    np.testing.assert_array_equal([general.commit(w) for w in wanted], model.inverse().apply(wanted))
    assert general.clip_count == 0


def test_input_offset_must_be_finite():
    with pytest.raises(ValueError, match="input_offset"):
        PrandtlIshlinskii([1.0], [0.5], 1.0, input_offset=float("nan"))
