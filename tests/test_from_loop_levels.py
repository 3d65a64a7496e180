"""``DiscretePreisach.from_loop(levels=...)``: the paper's levels and centred levels (issue 16,
part 2): the held-out RMS error of each against its analytic value for a uniformly
distributed error."""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm.hysteresis import ContinuousPreisach, DiscretePreisach
from exudyn_atcm.hysteresis.fit_report import make_report

TRUTH = ContinuousPreisach.from_points(-500, 1500, -4e-6, 40e-6, 500, 12e-6, 28e-6)


def uniform_in_output_cycle(fractions):
    """Inputs of one major cycle at which the truth's output takes the levels
    ``y_min + f·Δy`` on the way up and ``y_max − f·Δy`` on the way down (analytic branch inverses)."""
    t = TRUTH
    du = t.u_max - t.u_min
    up = t.u_min + du * fractions ** (1.0 / t.r1)
    down = t.u_max - du * fractions ** (1.0 / t.r2)
    return np.r_[up, down]


@pytest.mark.parametrize("levels, expected", [("paper", 1 / math.sqrt(3)), ("centred", 1 / math.sqrt(12))])
@pytest.mark.parametrize("n", [7, 20])
def test_held_out_rms_is_that_of_a_uniform_error(levels, expected, n):
    """Clean record, fitted on one major cycle, held out on a second one whose samples lie
    evenly in the output (midpoints between the fitted ones).  Within each gain step ``Δy`` the
    staircase error is then evenly spread: over ``[0, Δy)`` with the paper's levels (RMS
    ``Δy/√3``), over ``[−Δy/2, Δy/2)`` with centred ones (RMS ``Δy/√12``).  With ``M = 60``
    samples per step the discrete mean square differs from the continuous one by ``1/(12 M²)``
    of it (the midpoint rule), and the thresholds, linearly interpolated between fitted samples
    along a curved branch, move the switching points by far less than one sample; 1e-3
    relative covers both."""
    per_step = 60
    total = n * per_step
    fitted = uniform_in_output_cycle(np.arange(total + 1) / total)
    held = uniform_in_output_cycle((np.arange(total) + 0.5) / total)
    u = np.r_[fitted, held, TRUTH.u_min]
    y = TRUTH.apply(u)
    n_fit = fitted.size
    model = DiscretePreisach.from_loop(u[:n_fit], y[:n_fit], n, levels=levels)
    report = make_report(model, u, y, n_fit, 0, "from_loop")
    gain = (TRUTH.y_max - TRUTH.y_min) / n
    assert report.model_errors["held_out"]["rms"] == pytest.approx(expected * gain, rel=1e-3)
    error = (model.apply(u) - y)[n_fit:-1]  # the held-out cycle without the closing sample at u_min
    if levels == "paper":  # the staircase lies below the output on both branches, by up to one step
        assert error.mean() == pytest.approx(-0.5 * gain, rel=1e-3) and np.abs(error).max() <= gain * (1 + 1e-9)
    else:  # rounded to the nearest step: no mean offset, at most half a step
        assert abs(error.mean()) < 0.01 * gain and np.abs(error).max() <= 0.5 * gain * (1 + 1e-3)


def test_centred_levels_keep_the_range_and_halve_the_error_for_the_same_relays():
    u = np.r_[np.linspace(-500, 1500, 801), np.linspace(1500, -500, 801)[1:]]
    y = TRUTH.apply(u)
    paper = DiscretePreisach.from_loop(u, y, 10)
    centred, report = DiscretePreisach.from_loop(u, y, 10, levels="centred", report=True)
    assert report.settings["levels"] == "centred"
    # all off: y_min, all on: y_max, for both rules
    assert centred.apply([-500.0])[0] == pytest.approx(TRUTH.y_min, abs=1e-18)
    assert centred.apply([-500.0, 1500.0])[-1] == pytest.approx(TRUTH.y_max, rel=1e-12)
    e_paper = np.sqrt(np.mean((paper.apply(u) - y) ** 2))
    e_centred = np.sqrt(np.mean((centred.apply(u) - y) ** 2))
    assert e_centred / e_paper == pytest.approx(0.5, abs=0.05)  # √3/√12 = 1/2; coarse samples


def test_unknown_level_rule_is_refused():
    u = np.r_[np.linspace(-1, 1, 50), np.linspace(1, -1, 50)]
    with pytest.raises(ValueError, match=r"levels must be one of 'paper', 'centred', got 'middle'"):
        DiscretePreisach.from_loop(u, u**3, 5, levels="middle")
