"""Issue 9, sections 1 and 2: no silent wrong answers, long runs that behave.

Reference values are independent of the code: the voltage program's own definition (Eq. 11),
the step arithmetic (t_end / ceil(t_end / step)), the paper's loop (-500 ... 1500 V, 40 µm),
the MFC P1 rating (-500 ... +1500 V), and the uninterrupted run for the interrupted one.
"""

from __future__ import annotations

import io
import warnings

import numpy as np
import pytest

from exudyn_atcm.cells import CellKind
from exudyn_atcm.errors import AccuracyWarning
from exudyn_atcm.solve import run_checks
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.hysteresis import ContinuousPreisach, DiscretePreisach, PrandtlIshlinskii
from exudyn_atcm.model.materials import Layer
from exudyn_atcm.model.parameter_sets import paper_stroke_preisach, paper_strain_preisach
from exudyn_atcm.io.progress import ProgressBar, report_task, reporting
from exudyn_atcm.model.recording import recording_schedule
from exudyn_atcm.solve.run_checks import SimulationInterrupted, WallClock, snap_time, snap_times, time_grid
from exudyn_atcm.model.signals import Constant, PiecewiseLinear, Sine, Steps, Triangle
from exudyn_atcm.solve import simulate, solve_static

from _actuator_geometries import REF_A
from _cli_helpers import CASES


def _messages(record) -> list[str]:
    return [str(w.message) for w in record if issubclass(w.category, RuntimeWarning)]


def _fig12_case():
    from exudyn_atcm.casework import load_case

    return load_case(CASES / "paper_bending_actuator.py")


# ----------------------------------------------------------------------------- 1. step vs program
def test_fig12_step_1_is_refused_with_what_it_would_do():
    # issue 9: `--set step=1` ran 2 steps, sampled -500 V three times and printed a flat response
    with pytest.raises(ValueError) as info:
        _fig12_case().run({"step": 1.0})
    message = str(info.value)
    # the triangle of period 1 s has ramps of 0.5 s (Eq. 11); 4 steps per ramp need step <= 0.125 s
    assert "step = 1 s is too coarse" in message
    assert "a ramp of the triangle wave (half its period of 1 s), lasts 0.5 s, only 0.5 steps" in message
    assert "Use step <= 0.125 s" in message and "step <= 0.025 s" in message


def test_shortest_features_of_the_signals():
    assert Triangle(500.0, 1000.0, 1.0).shortest_feature()[0] == 0.5
    assert Sine(0.0, 100.0, 0.2).shortest_feature()[0] == pytest.approx(0.1)
    assert Constant(3.0).shortest_feature() is None
    assert Triangle(500.0, 0.0, 1.0).shortest_feature() is None  # no amplitude, no corners
    steps = Steps([0.0, 1.0, 1.25, 3.0], [0.0, 100.0, 200.0, 0.0])
    assert steps.shortest_feature()[0] == 0.25           # dwell 1.0 -> 1.25
    assert steps.shortest_feature(t_end=0.9) is None     # one switch before 0.9 s: no dwell
    # collinear points are not corners: 0 -> 1 s is one ramp, then a 0.1 s hold, then a ramp
    ramp = PiecewiseLinear([0.0, 0.5, 1.0, 1.1, 2.0], [0.0, 50.0, 100.0, 100.0, 0.0])
    assert ramp.shortest_feature()[0] == pytest.approx(0.1)
    assert ramp.shortest_feature(t_end=0.95)[0] == pytest.approx(1.0)


def test_coarse_but_allowed_step_warns_and_fine_step_is_silent():
    act = REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, 0.2), hysteresis=paper_strain_preisach()), cell="rigid")
    # ramp 0.1 s; step 0.01 s gives 10 steps per ramp: allowed (>= 4) but below 20
    with pytest.warns(AccuracyWarning) as record:
        simulate(act, 0.02, step=0.01 / 1.0)
    texts = _messages(record)
    assert any("only 10 steps: peaks can be missed by up to 5 %" in t for t in texts), texts
    # and the first mode, f1 = 35.97 Hz (period 0.0278 s), gets 2.78 steps: the second warning of this step
    assert len(texts) == 2 and any("with only 2.78 steps" in t for t in texts), texts
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        simulate(act, 0.002, step=1e-4)  # 1000 steps per ramp, f1 period 0.028 s / 1e-4 s: no warning


def test_step_against_first_eigenfrequency_warns():
    act = REF_A.actuator(PiezoDrive(Constant(500.0)), cell="rigid")
    f1 = act.first_frequency_estimate  # 35.97 Hz for the paper's actuator (beam theory)
    assert f1 == pytest.approx(35.97, abs=0.01)
    with pytest.warns(RuntimeWarning) as record:
        simulate(act, 0.02, step=0.01)
    text = " ".join(_messages(record))
    assert "f1 = 35.97 Hz" in text and "only 2.78 steps" in text and "step <= 0.00139 s" in text


# ----------------------------------------------------------------------------- 2. step used is recorded
def test_step_that_does_not_divide_the_run_is_recorded_and_warned():
    # issue 9: step = 0.3 with t_end = 2 ran 0.2857 s steps while the metadata said 0.3
    act = REF_A.actuator(PiezoDrive(Constant(500.0)), cell="rigid")
    with pytest.warns(RuntimeWarning) as record:
        r = simulate(act, 2.0, step=0.3)
    text = " ".join(_messages(record))
    assert "step = 0.3 s does not divide t_end = 2.0 s" in text and "7 steps of 0.285714 s" in text
    assert r.info["step [s]"] == 2.0 / 7.0 and r.info["step_requested [s]"] == 0.3
    assert r.info["accepted_steps"] == 7
    np.testing.assert_allclose(r["time"], np.arange(8) * 2.0 / 7.0, rtol=0, atol=1e-14)


def test_case_csv_states_the_step_used(tmp_path):
    # period 20 s: 0.3 s steps resolve the 10 s ramps; 20 / 0.3 = 66.7 -> 67 steps of 20/67 s
    from exudyn_atcm.io import read_csv

    with pytest.warns(AccuracyWarning) as record:
        _fig12_case().run({"step": 0.3, "period": 20.0, "cycles": 1}, out_dir=tmp_path, plot=False)
    texts = _messages(record)
    assert len(texts) == 2 and "step = 0.3 s does not divide t_end = 20.0 s" in texts[0], texts
    # the step is too coarse for the first mode (f1 = 35.97 Hz): quoted as given, with the step used
    assert texts[1].startswith("step = 0.3 s (used: 0.298507 s, so that it divides t_end = 20 s) resolves the "
                               "first bending mode"), texts
    data = read_csv(tmp_path / "paper_bending_actuator.csv")
    assert data.info["step [s]"] == 20.0 / 67.0
    assert data.info["step_requested [s]"] == 0.3
    assert np.diff(data["time"]) == pytest.approx(20.0 / 67.0, abs=1e-12)


def test_time_grid_and_snapping():
    grid = time_grid(2.0, 1e-4)
    assert (grid.n_steps, grid.step, grid.adjusted) == (20000, 1e-4, False)
    # accumulated round-off snaps to the grid point and prints short; off-grid times stay
    assert repr(snap_time(1.9998999999997962, 1e-4)) == "1.9999"
    assert snap_time(0.00015, 1e-4) == 0.00015


@pytest.mark.parametrize("step", [1e-4, 2e-3, 1.0 / 3.0, 0.15, 7.3e-4, 3e-6, 0.25])
def test_vectorised_snapping_equals_the_scalar_one(step):
    # the recorder snaps a whole record at once: the values must be snap_time's, element by
    # element, for solver times (accumulated sums), perturbed grid times and off-grid times
    rng = np.random.default_rng(7)
    k = np.arange(0, 30001)
    for times in (np.cumsum(np.full(k.size, step)) - step, k * step * (1 + rng.normal(0, 1e-13, k.size)),
                  rng.uniform(0.0, 5e4 * step, 3000), np.array([0.0, step, -step, 1e6 * step])):
        expected = np.array([snap_time(float(t), step) for t in times])
        np.testing.assert_array_equal(snap_times(times, step), expected)


# ----------------------------------------------------------------------------- 3. voltage ranges
def test_voltage_beyond_operator_range_and_rating_warns_once_with_distance():
    drive = PiezoDrive(5000.0, hysteresis=paper_strain_preisach())
    act = REF_A.actuator(drive, cell="rigid")
    with pytest.warns(RuntimeWarning) as record:
        high = solve_static(act)
    text = " ".join(_messages(record))
    assert "reach 5000 V, 3500 V above the hysteresis operator's input range -500 ... 1500 V" in text
    assert "3500 V above the MFC's rated range -500 ... 1500 V" in text
    # the saturated answer (what the warning is about): the 1500 V strain, 40 µm / 29 mm
    assert high["actuator.strain"][0] == pytest.approx(40e-6 / 29e-3, rel=1e-12)


def test_dynamic_run_warns_once_per_run():
    drive = PiezoDrive(Triangle(1000.0, 1000.0, 0.02), hysteresis=paper_strain_preisach())  # 0 ... 2000 V
    act = REF_A.actuator(drive, cell="rigid")
    with pytest.warns(RuntimeWarning) as record:
        simulate(act, 0.02, step=1e-4)
    range_warnings = [m for m in _messages(record) if "rated range" in m]
    assert len(range_warnings) == 1
    assert "reach 2000 V, 500 V above" in range_warnings[0]


def test_linear_drive_beyond_rating_warns_and_rating_can_be_set():
    act = REF_A.actuator(PiezoDrive(-600.0), cell="rigid")
    with pytest.warns(RuntimeWarning, match=r"reach -600 V, 100 V below the MFC's rated range -500 \.\.\. 1500 V"):
        solve_static(act)
    act = REF_A.actuator(PiezoDrive(-600.0, rated_range=(-1000.0, 2000.0)), cell="rigid")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        solve_static(act)
    with pytest.raises(ValueError, match="rated_range must have U_min < U_max"):
        PiezoDrive(0.0, rated_range=(100.0, -100.0))


def test_operators_expose_their_input_range():
    assert paper_strain_preisach().input_range == (-500.0, 1500.0)
    relays = DiscretePreisach([100.0, 300.0], [-200.0, 50.0], [1.0, 1.0])
    assert relays.input_range == (-200.0, 300.0)  # below min beta all off, above max alpha all on
    assert PrandtlIshlinskii([0.0, 1.0], [1.0, 0.5], 0.0).input_range is None  # no saturation


# ----------------------------------------------------------------------------- 4. units
@pytest.mark.parametrize("kwargs, words", [
    ({"thickness": 0.2, "youngs_modulus": 70e9, "density": 1550.0}, "thickness = 0.2 m"),
    ({"thickness": 0.2e-3, "youngs_modulus": 70.0, "density": 1550.0}, "youngs_modulus = 70.0 Pa"),
    ({"thickness": 0.2e-3, "youngs_modulus": 70e9, "density": 1.55}, "density = 1.55 kg/m³"),
])
def test_implausible_layer_values_warn(kwargs, words):
    with pytest.warns(RuntimeWarning, match="outside the plausible range") as record:
        Layer(**kwargs)
    assert words in _messages(record)[0]


def test_paper_layers_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        Layer(0.2e-3, 70e9, 1550.0)
        Layer(0.3e-3, 30.336e9, 5440.0)


def test_stroke_operator_is_refused_by_the_drive():
    # issue 9: the stroke model used as strain gave a tip of 0.40 mm instead of 15 mm
    assert paper_stroke_preisach().output_quantity == "stroke"
    assert paper_strain_preisach().output_quantity == "strain"
    with pytest.raises(ValueError) as info:
        PiezoDrive(Triangle(500.0, 1000.0, 1.0), hysteresis=paper_stroke_preisach())
    message = str(info.value)
    assert "output is 'stroke'" in message and "paper_strain_preisach()" in message


def test_strain_in_percent_warns():
    # the paper's loop given in percent: 0.138 %, read as strain 0.138 -> 100x too large
    percent = ContinuousPreisach(-500.0, 1500.0, -0.0138, 0.138, 1.5, 2.0)
    with pytest.warns(RuntimeWarning, match="free strain of 0.138, more than 0.01"):
        PiezoDrive(0.0, hysteresis=percent)


# ----------------------------------------------------------------------------- 9. Ctrl-C
def _interrupt_after(t_stop):
    def progress(t, t_end):
        if t >= t_stop:
            raise KeyboardInterrupt
    return progress


def test_interrupt_from_progress_keeps_the_steps_computed():
    act = REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, 0.1), hysteresis=paper_strain_preisach()), cell="rigid")
    full = simulate(act, 0.05, step=1e-4)
    with pytest.raises(SimulationInterrupted) as info:
        simulate(act, 0.05, step=1e-4, progress=_interrupt_after(0.02))
    exc = info.value
    assert isinstance(exc, KeyboardInterrupt)
    # progress is called about every 1 % of t_end (0.5 ms): the first call at or after 0.02 s
    assert 0.02 <= exc.time < 0.0206
    assert str(exc) == f"interrupted at t = {exc.time:.6g} s"
    partial = exc.result
    assert partial.info["partial"] is True and partial.info["interrupted_at [s]"] == exc.time
    n = partial.n_rows
    assert partial["time"][-1] == exc.time and n == round(exc.time / 1e-4) + 1
    # what was computed is the uninterrupted run's beginning
    for name in ("time", "actuator.voltage", "actuator.strain", "actuator.tip_y", "actuator.tip_angle"):
        np.testing.assert_array_equal(partial[name], full[name][:n])


def test_interrupt_from_the_voltage_program():
    triangle = Triangle(500.0, 1000.0, 0.1)

    def program(t):
        if t > 0.0305:
            raise KeyboardInterrupt
        return triangle(t)

    act = REF_A.actuator(PiezoDrive(program, hysteresis=paper_strain_preisach()), cell="rigid")
    with pytest.raises(SimulationInterrupted, match=r"interrupted at t = 0\.0305 s") as info:
        simulate(act, 0.05, step=1e-4)
    assert info.value.result["time"][-1] == 0.0305


def test_interrupted_case_writes_partial_files(tmp_path):
    from exudyn_atcm.io import read_csv

    with pytest.raises(SimulationInterrupted):
        _fig12_case().run({"period": 0.1, "cycles": 1}, out_dir=tmp_path, progress=_interrupt_after(0.03))
    data = read_csv(tmp_path / "paper_bending_actuator.csv")
    t_stop = data["time"][-1]
    assert data.info["partial"] is True and 0.03 <= t_stop < 0.0312  # progress every 1 % of 0.1 s
    import json

    record = json.loads((tmp_path / "paper_bending_actuator.json").read_text())
    assert record["notes"]["partial"] is True and record["notes"]["interrupted_at [s]"] == t_stop


def test_interrupt_guard_stops_without_raising_through_the_solver():
    guard = run_checks.InterruptGuard()

    def hook(t):
        raise KeyboardInterrupt

    wrapped = guard.wrap(hook)
    assert wrapped(0.5) is False and guard.interrupted and guard.at == 0.5


# ----------------------------------------------------------------------------- 10. progress
def test_progress_bar_shows_eta_and_tasks(monkeypatch):
    clock = iter([100.0, 110.0, 111.0, 112.0])
    monkeypatch.setattr("exudyn_atcm.io.progress.time.perf_counter", lambda: next(clock))
    stream = io.StringIO()
    bar = ProgressBar(stream, delay=0.0, force=True)  # starts at 100 s
    bar(0.5, 2.0)  # 10 s elapsed for a quarter: 30 s to go
    assert "25% t = 0.5 / 2 s  10 s elapsed, ETA 30 s" in stream.getvalue()
    with reporting(bar):
        report_task("GIF frames", 15, 60)  # task starts at 111 s
        report_task("GIF frames", 60, 60)
    assert "GIF frames 60/60" in stream.getvalue()


def test_progress_is_reported_by_wall_time_when_simulated_time_crawls(monkeypatch):
    calls = []
    clock = iter(np.arange(0.0, 100.0, 1.0))  # one second of wall time per step
    monkeypatch.setattr("exudyn_atcm.solve.interrupts.time.perf_counter", lambda: float(next(clock)))
    tick = WallClock(lambda t, t_end: calls.append(t), t_end=1e9)
    for k in range(1, 6):
        tick(k * 1e-4)  # far below 1 % of t_end
    assert calls == pytest.approx([1e-4, 2e-4, 3e-4, 4e-4, 5e-4])


def test_plots_and_gif_report_progress(tmp_path):
    from exudyn_atcm.plots.result import animate_actuator, plot_result

    act = REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, 0.01), hysteresis=paper_strain_preisach()), cell="rigid")
    r = simulate(act, 0.01, step=1e-4)
    seen = []

    class Recorder:
        def __call__(self, t, t_end):
            pass

        def task(self, label, done, total):
            seen.append((label, done, total))

    with reporting(Recorder()):
        plot_result(r, tmp_path)
        animate_actuator(r, tmp_path / "a.gif", frames=4)
    assert ("plots", 3, 3) in seen and ("GIF frames", 4, 4) in seen


# ----------------------------------------------------------------------------- 11. recording
def test_record_every_thins_without_changing_the_solution():
    act = REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, 0.02), hysteresis=paper_strain_preisach()), cell="rigid")
    full = simulate(act, 0.0105, step=1e-4)  # 105 steps
    by_steps = simulate(act, 0.0105, step=1e-4, record_every=10)
    by_time = simulate(act, 0.0105, step=1e-4, record_every=1e-3)
    keep = list(range(0, 106, 10)) + [105]  # every 10th step and the last one
    for thin in (by_steps, by_time):
        assert thin.info["accepted_steps"] == 105
        for name in ("time", "actuator.voltage", "actuator.strain", "actuator.tip_y"):
            np.testing.assert_array_equal(thin[name], full[name][keep])
    assert [repr(float(t)) for t in by_time["time"][:3]] == ["0.0", "0.001", "0.002"]
    assert by_steps.info["recorded"] == "every 10 steps" and by_time.info["recorded"] == "every 0.001 s"


def test_record_every_is_checked():
    # 0 and 0.0 are not here: they mean every step, as on the command line (tests/test_runtime_noise.py)
    for bad in (-1, -0.5, float("nan"), float("inf"), "10", "0", True, False):
        with pytest.raises(ValueError, match="record_every"):
            recording_schedule(bad, 1e-4)


def test_recorded_times_are_on_the_grid_and_short():
    act = REF_A.actuator(PiezoDrive(Constant(0.0)), cell="rigid")
    r = simulate(act, 0.2, step=1e-4)
    t = r["time"]
    np.testing.assert_array_equal(t, [float(f"{k * 1e-4:.15g}") for k in range(2001)])
    assert max(len(repr(float(v))) for v in t) <= 6  # e.g. 0.1999, never 0.19989999999999


# ----------------------------------------------------------------------------- 12. long runs
def test_long_run_estimate_and_warning(monkeypatch):
    # 40 six-bar cells for 20 s at 1e-4 s: 2e5 steps x (140 + 61*40 + 0.55*1600) µs = 692 s
    assert run_checks.estimate_run_time("six-bar", 40, 200_000) == pytest.approx(200_000 * 3460e-6)

    class Unmeasured(CellKind):
        name = "unmeasured"

    assert run_checks.estimate_run_time(Unmeasured(), 4, 10) is None  # no measured cost
    with pytest.raises(ValueError, match="cell must be one of"):
        run_checks.estimate_run_time("no-such-cell", 4, 10)
    with pytest.warns(RuntimeWarning, match=r"predicted to take about 12 min \(200000 steps of 40 six-bar cells"):
        run_checks.warn_if_long("six-bar", 40, 200_000)
    # through simulate, with a tiny limit (the warning comes before the run)
    monkeypatch.setattr(run_checks, "LONG_RUN_SECONDS", 1e-6)
    act = REF_A.actuator(PiezoDrive(Constant(0.0)), cell="rigid")
    with pytest.warns(RuntimeWarning, match="predicted to take about 0 s"):
        simulate(act, 0.001, step=1e-4)


def test_fig12_case_output_is_thinned_and_matches_every_step_run(tmp_path):
    # issue 9: the Fig. 12 case wrote 4.2 MB for 2 s (20001 rows of 17-digit numbers)
    # at a fixed step of 1e-4 s (10 steps per recorded ms; the default step is chosen for `accuracy`)
    out = _fig12_case().run({"cycles": 1, "step": 1e-4}, out_dir=tmp_path, plot=False)
    path = tmp_path / "paper_bending_actuator.csv"
    assert out.result.n_rows == 1001 and out.steps == 10000
    assert path.stat().st_size < 220_000  # 1001 rows of 10 shortest-repr numbers, < 220 bytes a row
    every = _fig12_case().run({"cycles": 1, "record_every": 0.0, "step": 1e-4})
    assert every.result.n_rows == 10001
    np.testing.assert_array_equal(out.result["actuator.tip_y"], every.result["actuator.tip_y"][::10])


@pytest.mark.filterwarnings("ignore:record_every = .* keeps only:RuntimeWarning")  # thinned on purpose
def test_asynchronous_ctrl_c_during_the_solver_stops_cleanly():
    """A real Ctrl-C arrives while Exudyn's C++ solver runs: ``_thread.interrupt_main`` raises
    ``KeyboardInterrupt`` in the main thread at its next Python code, i.e. inside a solver hook
    (before the fix: a solver failure "at t = -92507 s" with advice about step sizes)."""
    import _thread
    import threading

    act = REF_A.actuator(PiezoDrive(Triangle(500.0, 1000.0, 0.1), hysteresis=paper_strain_preisach()), cell="rigid")
    timer = threading.Timer(1.0, _thread.interrupt_main)  # the run takes several seconds
    timer.start()
    try:
        with pytest.raises(SimulationInterrupted) as info:
            simulate(act, 20.0, step=1e-4, record_every=100)
    finally:
        timer.cancel()
    exc = info.value
    assert 0.0 < exc.time < 20.0
    assert str(exc) == f"interrupted at t = {exc.time:.6g} s"
    partial = exc.result
    assert partial.info["partial"] is True and partial["time"][-1] == exc.time
    assert np.all(np.diff(partial["time"]) > 0)


def test_interrupt_that_surfaces_as_system_error_is_still_an_interrupt():
    """A Ctrl-C landing while a C function returns inside a hook is reported by CPython as
    ``SystemError: ... returned a result with an exception set`` caused by the
    ``KeyboardInterrupt`` (seen in the asynchronous test above, about 1 run in 3)."""

    def hook(t):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as exc:
            raise SystemError("<function Signal.__call__> returned a result with an exception set") from exc

    guard = run_checks.InterruptGuard()
    assert guard.wrap(hook)(0.25) is False
    assert guard.interrupted and guard.at == 0.25

    def broken(t):
        raise SystemError("a genuine fault")

    with pytest.raises(SystemError, match="genuine fault"):
        run_checks.InterruptGuard().wrap(broken)(0.0)


# ----------------------------------------------------------------------------- the steps the warning suggests
@pytest.mark.parametrize("t_end, step", [(1.0, 3e-4), (1.0, 3.0001e-4), (2.0, 1.3e-4), (0.37, 1.0001e-4), (5.0, 7e-5),
                                         (1.0, 0.7), (0.1, 0.03)])
def test_the_steps_the_warning_suggests_divide_the_run(t_end, step):
    """Following the advice silences the warning: the suggestions were the quotients to 6 digits (0.00029994 for
    1 s / 3334), which divide nothing, so ``--set step=0.00029994`` warned again."""
    import re
    with pytest.warns(AccuracyWarning) as record:
        time_grid(t_end, step)
    finer, coarser = (float(v) for v in re.search(r"e\.g\. (\S+) or (\S+) s\)", str(record[0].message)).groups())
    assert finer < step < coarser
    for suggested in (finer, coarser):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            grid = time_grid(t_end, suggested)
        assert grid.step == suggested and grid.n_steps * suggested == pytest.approx(t_end, rel=1e-12)
