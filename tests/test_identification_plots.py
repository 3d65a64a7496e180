"""The identification plots show the held-out samples identify actually held out (interleaved cycles too).

On a growing-amplitude record ``identify`` holds out whole cycles in the middle of the record
(``ModelChoice.fit_mask``); before, the plots split at ``n_fit`` and so drew the fitted cycles
after the first held-out one as "held out".  The expected samples are the mask's own.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from exudyn_atcm.hysteresis import identify  # noqa: E402
from exudyn_atcm.hysteresis.identify_options import IdentifyOptions  # noqa: E402
from exudyn_atcm.plots.identification import fitted_samples, plot_fit, plot_fit_series, plot_model_choice  # noqa: E402

from test_fits_on_records import asymmetric_relays, growing_amplitude  # noqa: E402
from relays import relay_outputs  # noqa: E402


@pytest.fixture(scope="module")
def choice():
    u = growing_amplitude()
    alpha, beta, w = asymmetric_relays()
    y = relay_outputs(alpha, beta, w, 0.0, u)
    c = identify(u, y, families=("everett",), options=IdentifyOptions(n_levels=20))
    held = ~c.fit_mask
    # interleaved: some fitted samples come after the first held-out one (a split at n_fit cannot show it)
    assert held.any() and c.fit_mask[np.argmax(held):].any()
    return c


def test_the_model_choice_shows_exactly_the_held_out_samples(choice):
    fig = plot_model_choice(choice)
    measured = fig.axes[1].lines[0]
    np.testing.assert_array_equal(measured.get_xdata(), choice.input[~choice.fit_mask])


def test_the_fit_loops_split_by_the_mask(choice):
    report = choice.chosen.report
    assert np.array_equal(fitted_samples(report, choice.input.size), choice.fit_mask)
    fig = plot_fit(report, choice.input, choice.output)
    np.testing.assert_array_equal(fig.axes[0].lines[0].get_xdata(), choice.input[choice.fit_mask])
    np.testing.assert_array_equal(fig.axes[1].lines[0].get_xdata(), choice.input[~choice.fit_mask])


def test_the_series_shades_each_held_out_run(choice):
    fig = plot_fit_series(choice.chosen.report, choice.input, choice.output)
    held = ~choice.fit_mask
    starts = np.flatnonzero(np.diff(np.concatenate([[0], held.astype(int)])) == 1)
    spans = [p for p in fig.axes[0].patches]
    assert len(spans) == starts.size >= 2
    lefts = sorted(float(p.get_x()) if hasattr(p, "get_x") else float(np.min(np.asarray(p.get_xy())[:, 0]))
                   for p in spans)
    np.testing.assert_array_equal(lefts, starts.astype(float))  # x is the sample index without times
