"""Inverse operators, feedforward programs and identification from first-order reversal curves."""

from __future__ import annotations


import numpy as np
import pytest

from exudyn_atcm.model.feedforward import feedforward_program
from exudyn_atcm.hysteresis import ContinuousPreisach, DiscretePreisach, EverettPreisach, PrandtlIshlinskii
from exudyn_atcm.hysteresis.identification import relay_grid
from exudyn_atcm.hysteresis.inverse import BisectionInverse, inverse_operator
from exudyn_atcm.model.signals import ForcProgram

from relays import relay_outputs

PAPER = ContinuousPreisach.from_points(-500, 1500, -4e-6, 40e-6, 500, 12e-6, 28e-6)
WANTED = np.array([0.0, 30e-6, 10e-6, 25e-6, -2e-6, 39e-6, 20e-6, 22e-6, 5e-6])


def test_continuous_inverse_reaches_every_reachable_output():
    inverse = inverse_operator(PAPER)
    forward = PAPER.apply(np.array([inverse.commit(y) for y in WANTED]))
    # bisection to 1e-9 of the 2000 V range: 2e-6 V times a slope below 0.1 um/V
    np.testing.assert_allclose(forward, WANTED, atol=1e-12)


def test_pi_inverse_is_analytic_with_offset():
    model = PrandtlIshlinskii([0.5, 1.0, 2.0], [0.3, 0.2, 0.1], 0.4, offset=-1.0)
    wanted = np.array([-1.0, 0.5, -0.2, 1.3, 0.1, 2.0, -0.5])
    inverse = inverse_operator(model)
    u = np.array([inverse.commit(y) for y in wanted])
    np.testing.assert_allclose(model.apply(u), wanted, atol=1e-12)
    # inverse() includes the offset too (it used to refuse every model with an offset)
    np.testing.assert_allclose(model.apply(model.inverse().apply(wanted)), wanted, atol=1e-12)


def test_discrete_inverse_hits_reachable_steps_and_stays_within_a_gain():
    alpha, beta, _ = relay_grid(-1.0, 1.0, 8)
    weights = 1.0 + alpha - beta
    model = DiscretePreisach(alpha, beta, weights)
    inverse = inverse_operator(model)
    history = [-1.0, 0.7, -0.3, 0.45, 0.05]
    # reachable values: the outputs the model itself produces along a history
    reachable = relay_outputs(alpha, beta, weights, 0.0, history)
    u = [inverse.commit(y) for y in reachable]
    np.testing.assert_allclose(relay_outputs(alpha, beta, weights, 0.0, u), reachable, atol=1e-12)
    # values between steps: the nearest step, within the largest weight
    inverse.reset()
    targets = np.array([3.3, 1.7, 6.1, 0.2])
    u = [inverse.commit(y) for y in targets]
    assert np.abs(model.apply(u) - targets).max() <= weights.max()


def test_unreachable_output_is_clipped_with_the_amount():
    inverse = BisectionInverse(PAPER, input_range=(-500.0, 1000.0))
    reachable_top = PAPER.ascending(1000.0)
    with pytest.warns(RuntimeWarning, match=r"clipped by 5e-06 \(output units\) to the input 1000.0"):
        u = inverse.commit(reachable_top + 5e-6)
    assert u == 1000.0 and inverse.clip_count == 1
    assert inverse.largest_clip == pytest.approx(5e-6, rel=1e-9)


def test_inverse_evaluate_does_not_change_memory():
    inverse = inverse_operator(PAPER)
    inverse.commit(30e-6)
    saved = inverse.checkpoint()
    trial = inverse.evaluate(10e-6)
    assert inverse.checkpoint() == saved
    assert inverse.commit(10e-6) == trial


def test_feedforward_program_makes_the_model_follow():
    t = np.linspace(0.0, 1.0, WANTED.size)
    program, info = feedforward_program(PAPER, t, WANTED)
    # the program sampled finely, through the model: at the sample times it hits the wanted values
    fine = np.linspace(0.0, 1.0, 801)
    y = PAPER.apply(program(fine))
    np.testing.assert_allclose(y[::100], WANTED, atol=1e-12)
    assert info["clipped_samples"] == 0
    with pytest.warns(RuntimeWarning, match=r"1 of 2 wanted outputs are not reachable"):
        feedforward_program(PAPER, [0.0, 1.0], [0.0, 50e-6])


# ----------------------------------------------------------------------------- FORC
def test_forc_program_corners():
    forc = ForcProgram(-1.0, 1.0, 4, rate=2.0)
    np.testing.assert_allclose(forc.values, [-1, 1, 0.5, 1, 0, 1, -0.5, 1, -1, 1, -1])
    assert forc.duration == pytest.approx(sum(abs(np.diff(forc.values))) / 2.0)
    with pytest.raises(ValueError, match="n_curves must be an integer >= 1"):
        ForcProgram(-1, 1, 0, 1.0)


def test_fit_from_forc_record_identifies_the_density():
    """With reversal inputs on the grid, a FORC record identifies every relay weight."""
    n = 10
    alpha, beta, _ = relay_grid(-1.0, 1.0, n)
    weights = np.exp(-((alpha + beta) ** 2)) * (alpha - beta + 0.3)
    forc = ForcProgram(-1.0, 1.0, n, rate=1.0)
    t = np.linspace(0.0, forc.duration, 4001)
    u = forc(t)
    y = relay_outputs(alpha, beta, weights, 0.0, u)
    # no regularisation at all (prior="smooth" with smoothing 0): the plain least squares
    model, report = DiscretePreisach.fit(u, y, n, input_range=(-1.0, 1.0), smoothing=0.0, prior="smooth")
    np.testing.assert_allclose(model.weights, weights, atol=1e-6 * weights.max())
    assert report.model_errors["fit"]["max"] < 1e-6 * np.ptp(y)



def test_everett_inverse_is_exact_for_reachable_outputs():
    from exudyn_atcm.hysteresis import EverettPreisach

    alpha, beta, _ = relay_grid(-1.0, 1.0, 6)
    model = EverettPreisach(np.linspace(-1.0, 1.0, 7), alpha, beta, 1.0 + alpha - beta)
    total = float(np.sum(1.0 + alpha - beta))
    wanted = total * np.array([0.1, 0.8, 0.35, 0.6, 0.05, 0.95, 0.5])
    inverse = inverse_operator(model)
    u = [inverse.commit(y) for y in wanted]
    # continuous output: bisection to 2e-9 of the input range, slope at most ~6 per input unit
    np.testing.assert_allclose(model.apply(u), wanted, atol=1e-7 * total)


def _everett_with_offset():
    """An Everett model on a 6-cell grid with a positive density and an offset (as a fit gives)."""
    edges = np.linspace(-1.0, 1.0, 7)
    alpha, beta, _ = relay_grid(-1.0, 1.0, 6)
    return EverettPreisach(edges, alpha, beta, 0.5 + alpha - beta, offset=-2.0)


@pytest.mark.parametrize("make, wanted, tolerance", [
    # continuous: bisection to 1e-9 of the input range (see above)
    (lambda: PAPER, WANTED, 1e-12),
    # Everett: piecewise-bilinear, continuous in the input: reached to the bisection's tolerance
    (_everett_with_offset, -2.0 + np.array([0.0, 2.0, 0.5, 1.5, 0.2, 3.0, 1.0]), 1e-8),
])
def test_every_preisach_model_has_an_inverse_method(make, wanted, tolerance):
    """``model.inverse()`` (issue 14 part 5) is the bisection inverse, offset included."""
    model = make()
    u = model.inverse().apply(wanted)
    np.testing.assert_allclose(model.apply(u), wanted, rtol=0, atol=tolerance)
    np.testing.assert_array_equal(u, inverse_operator(model).apply(wanted))


def test_discrete_inverse_method_equals_the_bisection_inverse():
    alpha, beta, _ = relay_grid(-1.0, 1.0, 8)
    model = DiscretePreisach(alpha, beta, 1.0 + alpha - beta, offset=3.0)
    wanted = 3.0 + np.array([0.0, 20.0, 5.0, 15.0, 1.0, 30.0])
    inverse = model.inverse(input_range=(-1.5, 1.5))
    assert isinstance(inverse, BisectionInverse)
    np.testing.assert_array_equal(inverse.apply(wanted), BisectionInverse(model, (-1.5, 1.5)).apply(wanted))
    # the staircase output is reached to within one relay weight (the largest is 1 + 2 = 3)
    assert np.max(np.abs(model.apply(inverse.apply(wanted)) - wanted)) <= 3.0
