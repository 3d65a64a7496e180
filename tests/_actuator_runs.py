"""Runs and checks shared by the actuator tests of every cell (rigid, six-bar, beam, ancf, ritz).

Each check asserts against an independent reference: the hysteresis operator applied offline
to the recorded voltages, the static solve of the same actuator, or the other stroke path.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.errors import AccuracyWarning
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.solve import run_actuator, simulate, solve_static

from _actuator_geometries import REF_A


def fast_triangle_actuator(cell, hysteresis):
    # the paper's actuator, a 20 Hz triangle over the paper's full range: fast enough to need Newton work
    return REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, 0.05), hysteresis=hysteresis), cell=cell)


def coarse_step_expected():
    """The fast triangle (ramps of 0.025 s) at step 2e-3 s has 12.5 steps per ramp, fewer than the
    20 recommended: coarse on purpose (Newton must reject steps), so its warning is expected."""
    return pytest.warns(AccuracyWarning, match=r"lasting 0\.025 s, with only 12\.5 steps")


class WrappedOperator:
    """A hysteresis operator that hands everything to ``inner``; subclasses change evaluate/commit."""

    def __init__(self, inner):
        self.inner = inner

    def evaluate(self, u):
        return self.inner.evaluate(u)

    def commit(self, u):
        return self.inner.commit(u)

    def reset(self):
        self.inner.reset()

    def apply(self, u_series):
        return self.inner.apply(u_series)

    def checkpoint(self):
        return self.inner.checkpoint()

    def restore(self, snapshot):
        self.inner.restore(snapshot)


class LeakyOperator(WrappedOperator):
    """A deliberately wrong integration of the operator: commits on every trial evaluation."""

    def evaluate(self, u):
        return self.inner.commit(u)


def check_in_step_hysteresis_equals_offline_replay(cell, settings):
    """Run the fast triangle with step-rejecting ``settings``; check the strain against the offline replay.

    Asserts that steps were rejected, that the strain equals the operator applied offline to the
    recorded voltages (to 1e-15) and that the run covered the whole loop (so the comparison is not
    trivial).  Returns the run for further checks.
    """
    H = paper_strain_preisach()
    with coarse_step_expected():
        r = simulate(fast_triangle_actuator(cell, H), 0.1, step=2e-3, settings=settings)
    assert r.info["rejected_steps"] > 0
    np.testing.assert_allclose(r["actuator.strain"], H.apply(r["actuator.voltage"]), rtol=0, atol=1e-15)
    assert np.ptp(r["actuator.strain"]) > 0.9 * (1.3793e-3 + 1.3793e-4)
    return r


def check_run_starts_in_static_equilibrium(cell, n_cells, force=(0.0, -0.2)):
    """Constant 1500 V and a tip force (default (0, -0.2) N): a 40-step run stays at the static solve.

    Asserts 41 rows and tip x, y within 1e-8 m and tip angle within 1e-7 rad of the static
    solution at every row.  Returns ``(run, static)``.
    """
    act = REF_A.actuator(PiezoDrive(1500.0), n_cells=n_cells, cell=cell)
    r = simulate(act, 40 * 1e-4, step=1e-4, tip_force=force)
    s = solve_static(act, tip_force=force)
    assert r.n_rows == 41
    for name, atol in (("actuator.tip_x", 1e-8), ("actuator.tip_y", 1e-8), ("actuator.tip_angle", 1e-7)):
        np.testing.assert_allclose(r[name], s[name][0], rtol=0, atol=atol)
    return r, s


def check_end_torque_equals_prestep_path(cell, rel_atol):
    """The default ``"prestep"`` stroke path against ``"offsets"`` over 0.05 s of the fast triangle.

    Asserts 501 rows in both runs and tip x, y, angle and cell angles 1 and 3 equal to
    ``rel_atol`` times the largest absolute value of each column.
    """
    H1, H2 = paper_strain_preisach(), paper_strain_preisach()
    a = run_actuator(fast_triangle_actuator(cell, H1), 0.05, 1e-4, (0.0, 0.0), None, stroke_path="prestep")
    b = run_actuator(fast_triangle_actuator(cell, H2), 0.05, 1e-4, (0.0, 0.0), None, stroke_path="offsets")
    assert a.n_rows == b.n_rows == 501
    for name in ("actuator.tip_x", "actuator.tip_y", "actuator.tip_angle", "actuator.cell_angle_1", "actuator.cell_angle_3"):
        np.testing.assert_allclose(a[name], b[name], rtol=0, atol=rel_atol * np.max(np.abs(b[name])))
