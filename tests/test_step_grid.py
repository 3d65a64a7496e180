"""A time integration stays on its step grid after Exudyn reduced a step (:mod:`exudyn_atcm.mbs.step_grid`).

Reference: the grid itself, ``k h`` for every ``k`` (each instant must be the end of an accepted
step), and the run without the keeper, whose grown steps end between the instants (measured:
half a step off), so that the test can fail.
"""

from __future__ import annotations

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.mbs import step_grid
from exudyn_atcm.mbs.step_grid import equal_part

from test_one_stepping import lone, paper_drive

H = 1e-4


def test_the_equal_part_is_a_halved_step_that_divides_the_distance_else_the_fewest_equal_parts():
    assert equal_part(H, 0.75 * H, H) == pytest.approx(0.5 * H, rel=1e-12)  # two halves
    assert equal_part(0.75 * H, 0.75 * H, H) == pytest.approx(0.25 * H, rel=1e-12)  # three quarters, on the halved grid
    assert equal_part(0.375 * H, 0.3 * H, H) == pytest.approx(0.125 * H, rel=1e-12)
    # 0.9 h is no whole number of halvings of h down to an eighth of the longest step: two equal parts
    assert equal_part(0.9 * H, 0.75 * H, H) == pytest.approx(0.45 * H, rel=1e-12)
    for distance, longest in ((0.9 * H, 0.75 * H), (0.37 * H, 0.05 * H), (H, 0.75 * H)):
        part = equal_part(distance, longest, H)
        assert part <= longest * (1 + 1e-9) and abs(distance / part - round(distance / part)) < 1e-9


def grid_misses(result) -> int:
    """How many instants ``k h`` of the run are no step's end (to 1e-6 of a step)."""
    t = np.asarray(result["time"], dtype=float)
    grid = np.arange(round(t[-1] / H) + 1) * H
    j = np.clip(np.searchsorted(t, grid), 1, len(t) - 1)
    miss = np.minimum(np.abs(t[j] - grid), np.abs(t[j - 1] - grid)) / H
    return int(np.sum(miss > 1e-6))


def capped_run():
    """A lone rod actuator whose Newton iterations are capped at 4: Exudyn reduces some steps (measured)."""
    return atcm.simulate(lone(paper_drive(), cell="rod"), 0.05, step=H,
                         settings={"timeIntegration.newton.maxIterations": 4})


def test_after_a_reduced_step_every_instant_of_the_grid_is_a_steps_end(monkeypatch):
    kept = capped_run()
    assert kept.info.get("steps_sent_to_the_grid", 0) > 0  # steps were reduced and grown back over instants
    assert grid_misses(kept) == 0
    # the same run without the keeper: Exudyn's grown steps end between the instants from the first reduction on
    monkeypatch.setattr(step_grid.GridKeeper, "watch", lambda self, t: None)
    loose = capped_run()
    assert "steps_sent_to_the_grid" not in loose.info
    assert grid_misses(loose) > 100
    # at the instants both hold the same run to its time discretisation (both converged Newton steps; the steps
    # differ where they were reduced): within 1e-3 of the tip's travel
    t_kept = np.asarray(kept["time"])
    on = np.abs(t_kept / H - np.round(t_kept / H)) < 1e-6
    tip = "b.tip_y"
    travel = float(np.ptp(kept[tip]))
    reference = atcm.simulate(lone(paper_drive(), cell="rod"), 0.05, step=H)
    np.testing.assert_allclose(np.asarray(kept[tip])[on], np.asarray(reference[tip]), rtol=0.0, atol=1e-3 * travel)


def test_a_run_without_a_reduced_step_never_installs_the_keeper():
    r = atcm.simulate(lone(paper_drive(), cell="rod"), 0.02, step=H)
    assert "steps_sent_to_the_grid" not in r.info and grid_misses(r) == 0 and r.n_rows == 201
