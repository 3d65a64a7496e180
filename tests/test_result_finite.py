"""A recorded state that is not finite is refused with the column and row that first show it.

Reference: a non-finite value put by the test into one coordinate of one row of the recorded states.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm import mbs as mb
from exudyn_atcm.errors import SolverError
from exudyn_atcm.mbs.recording import make_result

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)


def lever_model():
    arm = atcm.Link("arm", {"O": (0.0, 0.0), "P": (0.02, 0.0)}, mass=1e-4, inertia=1e-8)
    return mb.build(atcm.Mechanism("lever").add(arm).ground("arm.O", joint="pin", stiffness=0.05))


@pytest.mark.parametrize("bad", [math.nan, math.inf])
def test_a_non_finite_state_is_refused_naming_its_column_and_row(bad):
    model = lever_model()
    q = np.tile(np.asarray(model.coordinates(), dtype=float), (4, 1))
    forces = np.zeros((4, len(model.connector_names())))
    ok = make_result(model, np.arange(4.0), np.zeros((4, 0)), np.zeros((4, 0)), q, forces, {})
    assert np.all(np.isfinite(ok["arm.P_x"]))
    q[2, -1] = bad  # the arm's rotation in row 2
    with pytest.raises(SolverError, match=r"non-finite arm\.\w+ at row 2 \(t = 2 s\)"):
        make_result(model, np.arange(4.0), np.zeros((4, 0)), np.zeros((4, 0)), q, forces, {})
    # unchecked when asked (a partial result being written out)
    unchecked = make_result(model, np.arange(4.0), np.zeros((4, 0)), np.zeros((4, 0)), q, forces, {},
                            check_finite=False)
    assert not np.all(np.isfinite(unchecked["arm.angle"]))


def test_the_every_step_columns_refuse_a_non_finite_state_at_its_step():
    from exudyn_atcm.mbs.recording import RowLayout
    model = lever_model()
    layout = RowLayout(model)
    rows = np.zeros((5, layout.width))
    rows[:, 1:1 + layout.n_coordinates] = np.asarray(model.coordinates(), dtype=float)
    times = np.arange(5) * 1e-3
    columns = layout.every_step_columns(rows, times)
    assert np.all(np.isfinite(layout.every_step_result(columns, {})["arm.P_x"]))
    rows[3, layout.n_coordinates] = math.nan  # column 1 + 3 - 1: the arm's rotation (no drives), at step 3
    with pytest.raises(SolverError, match=r"non-finite arm\.\w+ at accepted step 3 \(t = 0\.003 s\)"):
        layout.every_step_result(layout.every_step_columns(rows, times), {})
