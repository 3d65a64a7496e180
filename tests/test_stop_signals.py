"""Stop signals and processes (issue 17): SIGTERM like Ctrl-C, no worker outlives its study."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from exudyn_atcm.io import read_csv
from exudyn_atcm.casework.termination import StopSignal, stop_signals_as_interrupt

from _cli_helpers import env

SYNTHETIC = Path(__file__).resolve().parent / "study_cases" / "synthetic_study.py"


def test_sigterm_inside_the_block_is_a_keyboard_interrupt_with_status_143():
    before = signal.getsignal(signal.SIGTERM)
    with pytest.raises(KeyboardInterrupt, match="SIGTERM"):
        with stop_signals_as_interrupt() as stop:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)  # pragma: no cover - the handler raises first
    assert stop.signum == signal.SIGTERM and stop.exit_status == 143 and stop.describe() == "terminated (SIGTERM)"
    assert signal.getsignal(signal.SIGTERM) is before  # restored
    assert StopSignal().exit_status == 130 and StopSignal().describe() == "interrupted (Ctrl-C)"


def test_an_ignored_signal_stays_ignored():
    previous = signal.signal(signal.SIGHUP, signal.SIG_IGN)  # as under nohup
    try:
        with stop_signals_as_interrupt() as stop:
            os.kill(os.getpid(), signal.SIGHUP)
            time.sleep(0.05)
        assert stop.signum is None
        assert signal.getsignal(signal.SIGHUP) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGHUP, previous)


SLOW_CASE = '''"""Rigid bender whose voltage program announces t >= 0.01 s in a file, then slows down."""
import time
from pathlib import Path

from exudyn_atcm.mechanism.actuator import BendingActuator
from exudyn_atcm.casework import Case, CaseOutput, Parameter
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.materials import Layer
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.solve.simulation import simulate

PARAMETERS = [Parameter("marker", "", "-", "file created once t >= 0.01 s ('' = none, full speed)")]


def run(p, ctx):
    triangle = Triangle(500.0, 1000.0, 0.1)

    def program(t):
        if p.marker and t >= 0.01:
            Path(p.marker).touch()
            time.sleep(0.002)
        return triangle(t)

    drive = PiezoDrive(program, hysteresis=paper_strain_preisach())
    act = BendingActuator(3, 29e-3, 28e-3, Layer(0.2e-3, 70e9, 1550.0), Layer(0.3e-3, 30.336e9, 5440.0),
                          drive, cell="rigid")
    return CaseOutput(simulate(act, 0.05, step=1e-4, progress=ctx.progress))


CASE = Case("slow_bender", __doc__, PARAMETERS, run)
'''


def test_sigterm_during_run_writes_the_partial_result_and_exits_143(tmp_path):
    case = tmp_path / "slow_bender.py"
    case.write_text(SLOW_CASE)
    marker = tmp_path / "started"
    proc = subprocess.Popen([sys.executable, "-m", "exudyn_atcm", "run", str(case), "--set", f"marker={marker}", "--out", "o",
                             "--no-plot"], cwd=tmp_path, env=env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120.0
        while not marker.exists() and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        assert proc.poll() is None, proc.communicate()
        proc.send_signal(signal.SIGTERM)  # what timeout, schedulers and docker stop send
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 143, err
    line = err.strip().splitlines()[-1]
    assert line.startswith("error: slow_bender: stopped by SIGTERM at t = ")
    assert "recorded instants up to there (marked partial) to o/slow_bender.csv" in line
    t_stop = float(line.split("at t = ")[1].split(" s;")[0])
    rows = int(line.split("wrote the ")[1].split(" recorded")[0])
    partial = read_csv(tmp_path / "o" / "slow_bender.csv")
    assert partial.info["partial"] is True and partial.n_rows == rows
    assert 0.01 <= t_stop < 0.05 and partial["time"][-1] == pytest.approx(t_stop, rel=1e-6)
    assert rows == round(t_stop / 1e-4) + 1  # one instant per step of 1e-4 s from t = 0
    # the partial rows are the full run's first rows (the same run, not stopped)
    full = subprocess.run([sys.executable, "-m", "exudyn_atcm", "run", str(case), "--out", "full", "--no-plot"],
                          cwd=tmp_path, env=env(), capture_output=True, text=True, timeout=300)
    assert full.returncode == 0, full.stderr
    complete = read_csv(tmp_path / "full" / "slow_bender.csv")
    for name in ("time", "actuator.voltage", "actuator.tip_y"):
        np.testing.assert_array_equal(partial[name], complete[name][:rows])


def _group(pgid: int) -> list[int]:
    out = subprocess.run(["ps", "-o", "pid=", "-g", str(pgid)], capture_output=True, text=True).stdout
    return [int(p) for p in out.split()]


def test_sigterm_stops_a_parallel_sweep_and_says_how_to_resume(tmp_path):
    log = tmp_path / "log"
    log.mkdir()
    args = ["sweep", str(SYNTHETIC), "--grid", "x=0:1:10", "--set", "delay=0.4", "--set", f"log_dir={log}",
            "--workers", "2", "--out", str(tmp_path / "out"), "--no-plot"]
    proc = subprocess.Popen([sys.executable, "-m", "exudyn_atcm", *args], env=env(), start_new_session=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    runs = tmp_path / "out" / "runs"
    try:
        deadline = time.monotonic() + 60.0
        while len(list(runs.glob("*/[0-9a-f]*.json"))) < 2 and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.02)
        assert proc.poll() is None, "the study finished before it could be stopped"
        proc.send_signal(signal.SIGTERM)  # to the study's process only, as `timeout` does
        _, err = proc.communicate(timeout=15)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 143, err
    lines = err.strip().splitlines()
    assert lines[-1] == "error: terminated (SIGTERM)"
    stored = len(list(runs.glob("*/[0-9a-f]*.json")))
    assert lines[-2] == (f"synthetic_study: sweep stopped with {stored} of 10 runs stored in {runs}; to resume (stored runs "
                         f"are not repeated): exudyn-atcm {' '.join(args)}")
    deadline = time.monotonic() + 10.0
    while _group(proc.pid) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert _group(proc.pid) == []  # the workers were stopped too
    done = subprocess.run([sys.executable, "-m", "exudyn_atcm", *args], env=env(), capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert f"10 runs ({10 - stored} executed, {stored} from the store, 0 failed)" in done.stdout


_PARENT = """
import sys
from exudyn_atcm.study import run_study
from exudyn_atcm.study.engines import ProcessEngine
engine = ProcessEngine(2, start_method=sys.argv[2])
run_study(sys.argv[1], {"x": [float(i) for i in range(40)]}, fixed={"delay": 2.0}, engine=engine)
"""


@pytest.mark.parametrize("start_method", ["fork", "forkserver"])
@pytest.mark.parametrize("kill_signal", [signal.SIGKILL, signal.SIGTERM])
def test_workers_end_when_the_study_process_is_killed(tmp_path, start_method, kill_signal):
    parent = subprocess.Popen([sys.executable, "-c", _PARENT, str(SYNTHETIC), start_method], env=env(),
                              start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60.0
        # the study's process, its 2 workers (and, for forkserver, the fork server)
        expected = 3 if start_method == "fork" else 4
        while len(_group(parent.pid)) < expected and time.monotonic() < deadline:
            time.sleep(0.05)
        before = _group(parent.pid)
        assert len(before) >= expected, before
        time.sleep(0.5)  # the workers are inside their first run (2 s each)
        os.kill(parent.pid, kill_signal)  # the study's process only, not its group
        parent.wait(timeout=30)
        deadline = time.monotonic() + 10.0
        while _group(parent.pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        left = _group(parent.pid)
    finally:
        for pid in _group(parent.pid):
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
    assert left == [], f"processes left after the study's process got {signal.Signals(kill_signal).name}: {left}"
