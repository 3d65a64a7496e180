"""Runs of several simulations (RunContext.plan): one announcement up front, one progress display across
them; the progress display during plots and GIF frames."""

from __future__ import annotations

import io
import sys
import warnings

import numpy as np
import pytest

from exudyn_atcm import BendingActuator, Layer, PiezoDrive, simulate
from exudyn_atcm.casework import Case, CaseOutput, PlannedRun, RunPlan
from exudyn_atcm.io.progress import ProgressBar, reporting
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.plots.gif import save_gif
from exudyn_atcm.plots.style import new_figure, save_figure
from exudyn_atcm.solve import mechanism_checks, run_checks, run_plan

from _cli_helpers import CASES

T_END, STEP = 0.01, 2e-4  # 50 steps per simulation
SECONDS_PER_STEP = 2.0  # the patched cost: 100 s per simulation, over the minute each


def _actuator() -> BendingActuator:
    return BendingActuator(n_cells=3, cell_length=29e-3, width=28e-3,
                           passive=Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0),
                           active=Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0),
                           drive=PiezoDrive(Triangle(500.0, 1000.0, 0.02)), cell="rigid", damping=0.02)


@pytest.fixture
def dear_steps(monkeypatch):
    """Every step predicted to cost SECONDS_PER_STEP [s] (in the plan and in each simulate)."""
    def estimate(cell, n_cells, n_steps, extra_per_step=0.0):
        return n_steps * SECONDS_PER_STEP
    monkeypatch.setattr(run_checks, "estimate_run_time", estimate)
    monkeypatch.setattr(run_plan, "estimate_run_time", estimate)
    # the drives' measured extra cost (tests/test_drive_cost.py) is timing, not what is tested here:
    # a noisy measurement would add its share to one simulation's words and not to another's
    monkeypatch.setattr(run_plan, "extra_drive_cost", lambda drives, step: 0.0)
    monkeypatch.setattr(mechanism_checks, "extra_drive_cost", lambda drives, step: 0.0)


def _case(events: list, planned: bool) -> Case:
    def run(p, ctx):
        act = _actuator()
        if planned:
            with ctx.plan([PlannedRun(act, T_END, STEP)] * 3) as plan:
                for k in range(3):
                    events.append(("start", k))
                    r = simulate(act, T_END, step=STEP, progress=plan.progress(k))
        else:
            for k in range(3):
                events.append(("start", k))
                r = simulate(act, T_END, step=STEP, progress=ctx.progress)
        return CaseOutput(r)

    return Case("three_runs", "Three simulations one after the other.", [], run)


def _capture(planned: bool, progress=None) -> list[tuple]:
    events: list[tuple] = []
    case = _case(events, planned)

    def show(message, category, filename, lineno, file=None, line=None):
        if "predicted to take" in str(message):
            events.append(("announced", str(message), filename))

    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = show
        case.run(progress=progress)
    return events


def test_a_planned_run_is_announced_once_before_its_first_simulation(dear_steps):
    events = _capture(planned=True)
    assert [e[0] for e in events] == ["announced", "start", "start", "start"]
    message, filename = events[0][1], events[0][2]
    # 3 x 50 steps x 2 s = 300 s, "5 min"; each simulation's cost named once, with the count
    assert message.startswith("this run is predicted to take about 5 min (3 simulations: 3 x 50 steps of "
                              "3 rigid cells at ~2e+06 µs per step, measured). ")
    assert filename == __file__  # the warning points at the case's run function (here, this file)
    # the same words as a single run's announcement after the parenthesis
    single = _capture(planned=False)
    # without a plan each simulation announces itself after it started; the same words three times
    # are shown once per case run (casework.run_warnings), so only the first one is seen
    assert [e[0] for e in single] == ["start", "announced", "start", "start"]
    assert single[1][1].startswith("this run is predicted to take about 100 s (50 steps of 3 rigid cells at "
                                   "~2e+06 µs per step, measured). ")
    assert message.split("). ", 1)[1] == single[1][1].split("). ", 1)[1]


def test_a_plan_slower_than_predicted_says_so_once_with_the_remaining_time(dear_steps, monkeypatch):
    clock = {"now": 0.0}
    monkeypatch.setattr(run_plan, "perf_counter", lambda: clock["now"])
    events: list[tuple] = []

    def run(p, ctx):
        act = _actuator()
        with ctx.plan([PlannedRun(act, T_END, STEP)] * 3) as plan:  # 100 s predicted for each
            for k in range(3):
                clock["now"] = 300.0 * k  # each simulation takes 300 s: 3 times its prediction
                events.append(("start", k))
                r = simulate(act, T_END, step=STEP, progress=plan.progress(k))
        return CaseOutput(r)

    def show(message, category, filename, lineno, file=None, line=None):
        if "predicted" in str(message):
            events.append(("warned", str(message)))

    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = show
        Case("slow", "Three slow simulations.", [], run).run()
    assert [e[0] for e in events] == ["warned", "start", "start", "warned", "start"]  # once up front, once on pace
    assert events[0][1].startswith("this run is predicted to take about 5 min (3 simulations")
    assert events[3][1].startswith("the first 1 of 3 simulations took 5 min 00 s, 3 times their prediction of "
                                   "1 min 40 s (")
    assert "the remaining 2 are predicted to take about 10 min more" in events[3][1]  # 2 x 100 s x 3


def test_a_short_plan_stays_quiet_and_unknown_costs_are_said(monkeypatch):
    # the cells' estimate alone: the drives' measured extra (tests/test_drive_cost.py) is timing
    monkeypatch.setattr(run_plan, "extra_drive_cost", lambda drives, step: 0.0)
    quiet = RunPlan([PlannedRun(_actuator(), T_END, STEP)] * 3)  # measured cost: well under a minute
    # each simulation: its 50 steps and the build of its 3 cells (rigid: 1.6e-4 s per cell, measured)
    assert not quiet.announced and quiet.estimate == pytest.approx(
        3 * (50 * run_checks.estimate_run_time("rigid", 3, 1) + 3 * 1.6e-4))
    with pytest.warns(RuntimeWarning, match=r"about 2 min \(3 simulations: 2 x its own estimate; 50 steps of 3 "
                                            r"rigid cells at ~.* µs per step, measured\)") as record:
        plan = RunPlan([PlannedRun(t_end=1.0, step=0.1, seconds=60.0)] * 2 + [PlannedRun(_actuator(), T_END, STEP)])
    assert len(record) == 1 and plan.estimate == pytest.approx(120.0 + quiet.estimate / 3)


def test_the_progress_covers_the_whole_run_across_simulations(dear_steps):
    stages: list[tuple] = []
    calls: list[tuple] = []

    class Display:  # a display with stages, like the ProgressBar
        def __call__(self, t, t_end):
            calls.append((t, t_end))

        def stage(self, label, share, detail):
            stages.append((label, share, detail))

    _capture(planned=True, progress=Display())
    assert calls == []  # everything went through stage()
    labels = [s[0] for s in stages]
    assert labels[0] == "simulation 1/3" and labels[-1] == "simulation 3/3"
    assert labels == sorted(labels)  # 1/3 ... then 2/3 ... then 3/3, never back
    shares = np.array([s[1] for s in stages])
    assert np.all(np.diff(shares) >= -1e-15) and shares[-1] == pytest.approx(1.0)
    # equal costs: simulation k spans [k/3, (k+1)/3] of the whole
    for label, k in (("simulation 1/3", 0), ("simulation 2/3", 1), ("simulation 3/3", 2)):
        own = shares[[s[0] == label for s in stages]]
        assert own.min() >= k / 3 - 1e-12 and own.max() == pytest.approx((k + 1) / 3)
    assert stages[-1][2] == f"t = {T_END:.4g} / {T_END:.4g} s"

    plain: list[tuple] = []  # a plain progress(t, t_end): the whole run's share of the summed time
    _capture(planned=True, progress=lambda t, t_end: plain.append((t, t_end)))
    assert [c[1] for c in plain] == pytest.approx([3 * T_END] * len(plain))
    done = np.array([c[0] for c in plain])
    assert np.all(np.diff(done) >= -1e-15) and done[-1] == pytest.approx(3 * T_END)


def test_the_bar_draws_the_stage_with_the_whole_run_s_time(monkeypatch):
    clock = iter([100.0, 120.0])
    monkeypatch.setattr("exudyn_atcm.io.progress.time.perf_counter", lambda: next(clock))
    stream = io.StringIO()
    bar = ProgressBar(stream, delay=0.0, force=True, width=10)  # starts at 100 s
    bar.stage("simulation 2/4", 0.5, "t = 1 / 2 s")  # 20 s for half: 20 s to go
    assert stream.getvalue() == "\r[#####.....]  50% simulation 2/4: t = 1 / 2 s  20 s elapsed, ETA 20 s"


def test_bad_plans_are_refused():
    with pytest.raises(ValueError, match=r"PlannedRun.t_end must be a positive time \[s\], got -1.0"):
        PlannedRun(_actuator(), -1.0, 0.1)
    with pytest.raises(ValueError, match="needs the system simulated .* or its own estimate"):
        PlannedRun(t_end=1.0, step=0.1)
    with pytest.raises(ValueError, match="runs must be a non-empty sequence of PlannedRun"):
        RunPlan([])
    plan = RunPlan([PlannedRun(_actuator(), T_END, STEP)])
    with pytest.raises(ValueError, match=r"k must be the index of a planned simulation, 0 ... 0, got 1"):
        plan.progress(1)


def test_tip_tracking_announces_its_four_simulations_once(monkeypatch):
    monkeypatch.setattr(run_plan, "LONG_RUN_SECONDS", 0.0)  # announce any plan
    monkeypatch.setattr(run_checks, "LONG_RUN_SECONDS", 0.0)  # and any single simulation outside one
    sys.path.insert(0, str(CASES))
    try:
        import tip_tracking
    finally:
        sys.path.remove(str(CASES))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        tip_tracking.CASE.run({"duration": 0.05, "settle": 0.0})
    announced = [str(w.message) for w in record if str(w.message).startswith("this run is predicted to take")]
    assert len(announced) == 1
    assert "(4 simulations: 4 x 250 steps of 3 rigid cells at ~" in announced[0]


# ----------------------------------------------------------------------------- plots and GIF frames
class _Tasks:
    def __init__(self):
        self.seen: list[tuple] = []

    def __call__(self, t, t_end):
        pass

    def task(self, label, done, total):
        self.seen.append((label, done, total))


def test_gif_frames_are_reported_in_order_up_to_the_total(tmp_path):
    fig, (ax,) = new_figure()
    (line,) = ax.plot([], [])
    display, own = _Tasks(), []
    with reporting(display):
        save_gif(fig, lambda k: line.set_data([0, k], [0, k]), 7, tmp_path / "a.gif", fps=10,
                 progress=lambda done, total: own.append((done, total)))
    assert display.seen == [("GIF frames", k, 7) for k in range(8)]  # 0/7 before the first frame ... 7/7
    assert own == [(k, 7) for k in range(1, 8)]


def test_figures_written_are_counted_on_the_display(tmp_path):
    display = _Tasks()
    with reporting(display):
        for name in ("a.png", "b.png", "c.png"):
            fig, _ = new_figure()
            save_figure(fig, tmp_path / name)
    assert display.seen == [("figures written", 1, None), ("figures written", 2, None), ("figures written", 3, None)]
    stream = io.StringIO()
    bar = ProgressBar(stream, delay=0.0, force=True)
    bar.task("figures written", 3, None)
    assert "figures written: 3  0 s elapsed" in stream.getvalue()
