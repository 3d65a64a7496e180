"""Creep and a rate lag evaluated in the solver step (issue 16, part 4): a lone rigid-cell actuator
with ``WithDynamics`` as its drive's operator, against the closed-form step response, against itself
at two step sizes, against the offline replay despite rejected steps, and against the offline
``CreepHysteresis``."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.hysteresis import PrandtlIshlinskii
from exudyn_atcm.hysteresis.creep import Creep, CreepHysteresis
from exudyn_atcm.hysteresis.dynamics import RateLag, WithDynamics
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import PiecewiseLinear, Triangle
from exudyn_atcm.model.strain_sources import TableStrain
from exudyn_atcm.solve import simulate, solve_static, static_sweep

from _actuator_geometries import REF_A
from test_mechanism_solve import bender, cantilever, four_bar

CREEP = Creep([0.01, 0.1], [0.05, 0.08])
pytestmark = pytest.mark.filterwarnings("ignore:step = .* resolves the shortest feature:RuntimeWarning")
REJECTING = {"timeIntegration.newton.maxIterations": 2, "timeIntegration.newton.useModifiedNewton": False}


def run(operator, voltage, t_end, step, settings=None):
    return simulate(REF_A.actuator(PiezoDrive(voltage, hysteresis=operator), cell="rigid"), t_end, step=step,
                    settings=settings)


def shared(a, b):
    """Rows of runs ``a`` and ``b`` at the instants both recorded (to 1e-12 s)."""
    ia = np.round(a["time"] * 1e9).astype(np.int64)
    ib = np.round(b["time"] * 1e9).astype(np.int64)
    common, ka, kb = np.intersect1d(ia, ib, return_indices=True)
    return ka, kb, common.size


def test_step_response_in_simulate_is_the_closed_form_sum_of_lags():
    # constant 1500 V from t = 0: the operator jumps from its reset output h0 (negative saturation)
    # to h1 and the lags, at rest at h0, creep: y = h1 + sum c_k (h1 + (h0 - h1) exp(-t / tau_k))
    H = paper_strain_preisach()
    h0, h1 = H.y_min, float(paper_strain_preisach().apply([1500.0])[-1])
    r = run(WithDynamics(H, CREEP), 1500.0, 0.3, 1e-3)
    t = r["time"]
    closed = h1 + np.sum(CREEP.c * (h1 + (h0 - h1) * np.exp(-t[:, None] / CREEP.tau)), axis=1)
    assert r.n_rows == 301
    np.testing.assert_allclose(r["actuator.strain"], closed, rtol=1e-9, atol=0)  # measured 2.2e-16 relative
    # the creep is really there: 12.7 % of the jump at 0.3 s (so the comparison is not trivial)
    assert (r["actuator.strain"][-1] - r["actuator.strain"][0]) / (h1 - h0) == pytest.approx(
        np.sum(CREEP.c * (1 - np.exp(-0.3 / CREEP.tau))), rel=1e-9)


@pytest.mark.parametrize("lag", [None, RateLag(0.005)])
def test_held_input_gives_the_same_strain_at_step_1e_3_and_1e_4(lag):
    # exact update for an input held between commits: the shared instants agree to rounding
    ra = run(WithDynamics(paper_strain_preisach(), CREEP, lag), 1500.0, 0.2, 1e-3)
    rb = run(WithDynamics(paper_strain_preisach(), CREEP, lag), 1500.0, 0.2, 1e-4)
    ka, kb, n = shared(ra, rb)
    assert n == 201
    np.testing.assert_allclose(ra["actuator.strain"][ka], rb["actuator.strain"][kb], rtol=1e-12, atol=0)


def test_ramps_through_a_linear_operator_give_the_same_strain_at_both_steps():
    # h linear in time between commits (ramps with corners on both grids, a linear operator):
    # the first-order-hold update is exact, so the step size does not matter
    linear = PrandtlIshlinskii([], [], 1e-6).with_output_quantity("strain")
    program = PiecewiseLinear([0.0, 0.05, 0.1, 0.2], [0.0, 1000.0, 1000.0, -200.0])
    ra = run(WithDynamics(linear, CREEP, RateLag(0.005)), program, 0.25, 1e-3)
    rb = run(WithDynamics(PrandtlIshlinskii([], [], 1e-6), CREEP, RateLag(0.005)), program, 0.25, 1e-4)
    ka, kb, n = shared(ra, rb)
    assert n == 251
    scale = np.max(np.abs(ra["actuator.strain"]))
    np.testing.assert_allclose(ra["actuator.strain"][ka], rb["actuator.strain"][kb], rtol=0, atol=1e-12 * scale)


def test_nonlinear_operator_output_is_second_order_in_the_step():
    # not exact: along a triangle the Preisach output is curved in time (steepest just after a
    # reversal), and the update takes it linear between commits.  Measured: largest difference
    # between step 1e-3 and 1e-4 at the shared instants 2.5e-4 of the strain range with the 5 ms
    # lag (1.3e-5 with the creep alone), a 20 Hz triangle whose corners lie on both grids
    runs = [run(WithDynamics(paper_strain_preisach(), CREEP, RateLag(0.005)), Triangle(500.0, 1000.0, 0.05), 0.1, s)
            for s in (1e-3, 1e-4)]
    ka, kb, _ = shared(*runs)
    diff = np.max(np.abs(runs[0]["actuator.strain"][ka] - runs[1]["actuator.strain"][kb])) / np.ptp(runs[1]["actuator.strain"])
    assert 1e-12 < diff < 1e-3


def test_in_step_equals_offline_replay_despite_rejected_steps():
    # trials at rejected step lengths change nothing: the accepted strain history is the offline
    # replay of the accepted (time, voltage) pairs
    op = WithDynamics(paper_strain_preisach(), CREEP, RateLag(0.005))
    r = run(op, Triangle(500.0, 1000.0, 0.05), 0.1, 2e-3, REJECTING)
    assert r.info["rejected_steps"] > 0
    assert np.diff(r["time"]).min() < 2e-3 * 0.75
    replay = WithDynamics(paper_strain_preisach(), CREEP, RateLag(0.005)).apply(r["actuator.voltage"], r["time"])
    np.testing.assert_allclose(r["actuator.strain"], replay, rtol=0, atol=1e-15)
    assert np.ptp(r["actuator.strain"]) > 0.5 * (1.3793e-3 + 1.3793e-4)


def test_in_step_creep_equals_the_offline_creep_hysteresis():
    # the program starts at -500 V, where the Preisach operator's reset state already is, so the
    # offline model (lags at rest at h[0]) and the in-step one (at rest at the reset output) agree
    r = run(WithDynamics(paper_strain_preisach(), CREEP), Triangle(500.0, 1000.0, 0.05), 0.1, 2e-3, REJECTING)
    assert r.info["rejected_steps"] > 0
    offline = CreepHysteresis(paper_strain_preisach(), CREEP).apply(r["actuator.voltage"], r["time"])
    np.testing.assert_allclose(r["actuator.strain"], offline, rtol=0, atol=1e-15)


class LeakyTimed(WithDynamics):
    """Deliberately wrong: commits on every trial (negative control)."""

    def evaluate(self, u, t=None):
        return self.commit(u, t)


def test_committing_inside_trials_would_be_caught():
    op = LeakyTimed(paper_strain_preisach(), CREEP, RateLag(0.005))
    with pytest.raises(ValueError, match="must not precede the committed time"):
        # a rejected step retried with a shorter step goes back before the leaked commit; the one solve
        # path re-raises an error of the step's own functions as it is (earlier the actuator path wrapped
        # it into a SolverError)
        run(op, Triangle(500.0, 1000.0, 0.05), 0.1, 2e-3, REJECTING)


def test_table_strain_and_static_strain_of_a_timed_operator():
    op = WithDynamics(paper_strain_preisach(), CREEP)
    drive = PiezoDrive(Triangle(500.0, 1000.0, 0.05), hysteresis=op)
    table = TableStrain.from_drive(drive, 0.1, 1e-3)
    np.testing.assert_allclose(table.strains, op.apply(table.voltages, table.times), rtol=0, atol=0)
    # held for ever: the operator's static output times the long-term gain 1.13
    assert drive.static_strain(1500.0) == pytest.approx(1.13 * float(paper_strain_preisach().apply([1500.0])[-1]),
                                                        rel=1e-14)


@pytest.mark.filterwarnings("ignore:step = .* resolves the first bending mode:RuntimeWarning")
def test_in_step_creep_and_lag_in_a_closed_four_bar_despite_rejected_steps():
    # the mechanism path uses the same strain source: the crank's strain is the offline replay
    op = WithDynamics(paper_strain_preisach(), CREEP, RateLag(0.005))
    m = four_bar(PiezoDrive(Triangle(500.0, 1000.0, 0.05), hysteresis=op))
    # one Newton iteration: the lag smooths the strain so much that two would not reject (27 rejected)
    r = simulate(m, 0.06, step=2e-3, settings={**REJECTING, "timeIntegration.newton.maxIterations": 1})
    assert r.info["rejected_steps"] > 0
    replay = WithDynamics(paper_strain_preisach(), CREEP, RateLag(0.005)).apply(r["crank.voltage"], r["time"])
    np.testing.assert_allclose(r["crank.strain"], replay, rtol=0, atol=1e-15)


def test_static_solve_and_sweep_take_the_fully_crept_strain():
    h1 = float(paper_strain_preisach().apply([1500.0])[-1])
    act = REF_A.actuator(PiezoDrive(1500.0, hysteresis=WithDynamics(paper_strain_preisach(), CREEP)), cell="rigid")
    # the same strain from a linear drive (d33 U / t_IDE = 1.13 h1) gives the same equilibrium
    linear = REF_A.actuator(PiezoDrive(1500.0, d33=1.13 * h1 * 0.5e-3 / 1500.0, electrode_spacing=0.5e-3), cell="rigid")
    crept, same = solve_static(act), solve_static(linear)
    assert crept["actuator.strain"][0] == pytest.approx(1.13 * h1, rel=1e-14)
    for name in ("actuator.tip_x", "actuator.tip_y", "actuator.tip_angle"):
        assert crept[name][0] == pytest.approx(same[name][0], rel=1e-12)
    # a sweep holds each point for ever: 1.13 times the rate-independent operator's path (memory kept
    # between points: 500 V falling lies on the falling branch)
    path = [0.0, 500.0, 1500.0, 500.0]
    b = bender(drive=PiezoDrive(0.0, hysteresis=WithDynamics(paper_strain_preisach(), CREEP)))
    swept = static_sweep(cantilever(b), path)
    np.testing.assert_allclose(swept[f"{b.name}.strain"], 1.13 * paper_strain_preisach().apply(path), rtol=1e-14, atol=0)
