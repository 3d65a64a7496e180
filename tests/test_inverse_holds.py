"""A wanted output that holds keeps its input (the bisection inverse of a Preisach model).

The paper's continuous Preisach loop leaves a reversal horizontally: after a rise from the reset state
to -149.36 V its output stays within 1e-12 of its value down to about -414 V.  Bisection for that same
output then picked either end of the flat stretch by the last bit of rounding: a constant wanted
strain committed three times gave -149.36 V, -414.33 V, -149.36 V (until 2026-11-29), a 265 V pulse of
one sample at the start of every feedforward program whose wanted path starts at rest.

References: rate independence (re-applying the last input leaves a Preisach memory as it was, so the
input that reached an output reaches it again), and the forward model evaluated at the inputs found.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.hysteresis.inverse import inverse_operator
from exudyn_atcm.model.feedforward import feedforward_program
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.sampled_program import reversal_times

RANGE = (-500.0, 1500.0)


def rest_strain() -> float:
    """The paper operator's strain at -149.36 V from its reset state (the rest of the synthesise_compensated case)."""
    model = paper_strain_preisach()
    return float(model.evaluate(-149.36))


def test_a_constant_wanted_strain_keeps_one_voltage():
    inverse = inverse_operator(paper_strain_preisach(), RANGE)
    y = rest_strain()
    volts = [inverse.commit(y) for _ in range(4)]
    assert volts[1:] == volts[:1] * 3  # the same input, not an end of the flat stretch below it
    assert volts[0] == pytest.approx(-149.36, abs=1e-3)
    forward = paper_strain_preisach()
    for v in volts:
        assert float(forward.commit(v)) == pytest.approx(y, rel=1e-9)


def test_a_feedforward_program_does_not_move_while_the_wanted_strain_holds():
    # rest, a rise, a hold at the top, a fall, a hold: the voltages move only where the strain does, and the
    # program's features are its real reversal (one), not a one-sample pulse at the start
    y0, y1 = rest_strain(), float(paper_strain_preisach().evaluate(1000.0))
    times = np.arange(0.0, 1.0 + 5e-4, 1e-3)
    wanted = np.interp(times, [0.0, 0.1, 0.4, 0.6, 0.9, 1.0], [y0, y0, y1, y1, y0 + 0.3 * (y1 - y0),
                                                                y0 + 0.3 * (y1 - y0)])
    program, info = feedforward_program(paper_strain_preisach(), times, wanted, RANGE)
    assert info["clipped_samples"] == 0
    v = program.values
    for a, b in ((0.0, 0.1), (0.4, 0.6), (0.9, 1.0)):
        hold = (times >= a - 1e-9) & (times <= b + 1e-9)
        assert np.ptp(v[hold]) == 0.0, (a, b)
    np.testing.assert_allclose(reversal_times(program.times, v), [0.6], atol=1.5e-3)  # after the top hold only
    duration, _ = program.shortest_feature(1.0)
    assert duration == pytest.approx(0.4, abs=2e-3)  # the fall and the last hold (the first stretch: 0.6 s)
    forward = paper_strain_preisach()
    strain = np.array([float(forward.commit(u)) for u in v])
    # the bisection stops at 1e-9 of the input range (2e-6 V); at the loop's steepest (about 5e-7 per V) that is
    # 1e-12 of strain, 4e-9 of the travel
    np.testing.assert_allclose(strain, wanted, rtol=0.0, atol=1e-8 * abs(y1 - y0))


def test_a_trial_after_a_restore_holds_the_input_too():
    inverse = inverse_operator(paper_strain_preisach(), RANGE)
    y = rest_strain()
    u = inverse.commit(y)
    snapshot = inverse.checkpoint()
    inverse.commit(float(paper_strain_preisach().evaluate(500.0)))
    inverse.restore(snapshot)
    assert inverse.evaluate(y) == u
    inverse.reset()
    assert inverse.evaluate(y) == u  # from the reset state bisection finds the same input as the first time
