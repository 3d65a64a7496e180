"""Case output folders never mix two runs (issue 29, finding 5); an unfinished run leaves a marker.

A small case writes a CSV whose value is ``y = 3 x`` (so each file says which run wrote it),
one table, and ``n_plots`` "plots" (text files whose content is ``x``); it can stop while
plotting (``KeyboardInterrupt`` raised, ``SIGINT`` sent to itself, or a hang to be killed).
"""

from __future__ import annotations

import json
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from exudyn_atcm.casework import RunContext, load_case
from exudyn_atcm.casework.output_folder import OutputFolder
from exudyn_atcm.io import read_csv

from _cli_helpers import cli, env

CASE = '''"""Writes y = 3 x, a table, n_plots plot files holding x; can stop while plotting."""
import os
import signal
import time
from pathlib import Path

from exudyn_atcm.casework import Case, CaseOutput, Parameter
from exudyn_atcm.io.result import Result
from exudyn_atcm.solve.run_checks import SimulationInterrupted

PARAMETERS = [
    Parameter("x", 1.0, "-", "input"),
    Parameter("n_plots", 2, "-", "plot files", minimum=0),
    Parameter("stop", "none", "-", "how the plotting stops", choices=("none", "raise", "signal", "hang", "fail", "run", "signal_run")),
    Parameter("flag", "", "-", "file created once the first plot is written (for a test that kills the run)"),
    Parameter("note", "no", "-", "write a note through ctx.output_file during the run", choices=("no", "yes")),
    Parameter("interrupt_run", "no", "-", "stop the simulation half-way (a partial result)", choices=("no", "yes", "probe")),
]


def run(p, ctx):
    if p.stop == "run":
        raise ValueError("bad input found by the run")
    if p.stop == "signal_run":
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(30)
    if p.note == "yes" and ctx.out_dir is not None:
        ctx.output_file("output_case_note.txt").write_text(repr(p.x))
    result = Result({"time": [0.0, 1.0], "y": [0.0, 3.0 * p.x]}, {"time": "s", "y": "m"})
    if p.interrupt_run in ("yes", "probe"):
        info = {"partial": True}
        if p.interrupt_run == "probe":  # as simulate(accuracy=) marks its probe's partial run
            info["interrupted_in"] = "accuracy probe (a check at twice the chosen step), step 0.002 s"
        partial = Result({"time": [0.0], "y": [0.0]}, {"time": "s", "y": "m"}, info=info)
        raise SimulationInterrupted(0.5, partial)
    table = Result({"k": [1.0, 2.0], "x": [p.x, p.x]}, {"k": "-", "x": "-"})
    return CaseOutput(result, {"y": (3.0 * p.x, "m")}, tables={"table": table})


def plot(output, p, out_dir):
    files = []
    for k in range(p.n_plots):
        path = Path(out_dir) / f"output_case_plot{k}.png"
        path.write_text(repr(p.x))
        files.append(path)
        if k == 0 and p.flag:
            Path(p.flag).touch()
        if k == 0 and p.stop == "raise":
            raise KeyboardInterrupt
        if k == 0 and p.stop == "signal":
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(30)
        if k == 0 and p.stop == "hang":
            time.sleep(120)
        if k == 0 and p.stop == "fail":
            raise ValueError("no font")
    return files


CASE = Case("output_case", __doc__, PARAMETERS, run, plot)
'''

FULL = {"output_case.csv", "output_case_table.csv", "output_case.json", "output_case_plot0.png", "output_case_plot1.png"}


@pytest.fixture()
def case_file(tmp_path):
    path = tmp_path / "output_case.py"
    path.write_text(CASE)
    return path


def _files(folder: Path) -> set[str]:
    return {p.name for p in folder.iterdir()}


def _y(folder: Path) -> float:
    return float(read_csv(folder / "output_case.csv")["y"][-1])


def _complete_first_run(case, folder: Path) -> None:
    case.run({"x": 1.0, "n_plots": 3}, out_dir=folder)
    (folder / "my_notes.txt").write_text("the user's own file")
    assert _files(folder) == FULL | {"output_case_plot2.png", "my_notes.txt"}


def test_ctrl_c_while_plotting_leaves_one_run_and_the_marker(case_file, tmp_path):
    case = load_case(case_file)
    folder = tmp_path / "out"
    _complete_first_run(case, folder)
    with pytest.raises(KeyboardInterrupt):
        case.run({"x": 2.0, "stop": "raise"}, out_dir=folder)
    # the second run's CSV, table and JSON, the marker, the user's file; no plot of either run
    assert _files(folder) == {"output_case.csv", "output_case_table.csv", "output_case.json", "output_case.partial.json",
                              "my_notes.txt"}
    assert _y(folder) == 6.0  # 3 x of the second run
    assert read_csv(folder / "output_case_table.csv")["x"].tolist() == [2.0, 2.0]
    record = json.loads((folder / "output_case.json").read_text())
    assert record["parameters"]["x"]["value"] == 2.0 and record["complete"] is False
    marker = json.loads((folder / "output_case.partial.json").read_text())
    assert marker["partial"] is True and marker["state"] == "interrupted while drawing the plots"
    assert set(marker["files"]) == {"output_case.csv", "output_case_table.csv", "output_case.json"}
    assert (folder / "my_notes.txt").read_text() == "the user's own file"
    # the next complete run: its own files, no marker
    case.run({"x": 4.0, "n_plots": 1}, out_dir=folder)
    assert _files(folder) == {"output_case.csv", "output_case_table.csv", "output_case.json", "output_case_plot0.png",
                              "my_notes.txt"}
    assert _y(folder) == 12.0 and (folder / "output_case_plot0.png").read_text() == "4.0"
    assert json.loads((folder / "output_case.json").read_text())["complete"] is True


def test_sigint_while_plotting_on_the_command_line(case_file, tmp_path):
    case = load_case(case_file)
    folder = tmp_path / "o"
    _complete_first_run(case, folder)
    stopped = cli(["run", str(case_file), "--set", "x=5", "--set", "stop=signal", "--out", "o"], tmp_path)
    assert stopped.returncode == 130, stopped.stderr
    assert stopped.stderr.strip().splitlines()[-1] == (
        "error: output_case: interrupted (Ctrl-C) before the simulation started or after it ended; the files written "
        "are one unfinished run, listed in o/output_case.partial.json")
    assert _files(folder) == {"output_case.csv", "output_case_table.csv", "output_case.json", "output_case.partial.json",
                              "my_notes.txt"}
    assert _y(folder) == 15.0


def test_an_interrupted_simulation_on_the_command_line_names_the_marker(case_file, tmp_path):
    """The partial CSV is said, and that the folder holds an unfinished run, with the marker that lists it."""
    case = load_case(case_file)
    _complete_first_run(case, tmp_path / "o")
    stopped = cli(["run", str(case_file), "--set", "x=2", "--set", "interrupt_run=yes", "--out", "o"], tmp_path)
    assert stopped.returncode == 130, stopped.stderr
    assert stopped.stderr.strip().splitlines()[-1] == (
        "error: output_case: interrupted at t = 0.5 s; wrote the 1 recorded instants up to there (marked partial) to "
        "o/output_case.csv; o holds this unfinished run, listed in o/output_case.partial.json")
    marker = json.loads((tmp_path / "o" / "output_case.partial.json").read_text())
    assert marker["state"] == "interrupted at t = 0.5 s" and set(marker["files"]) == {"output_case.csv", "output_case.json"}
    assert _files(tmp_path / "o") == {"output_case.csv", "output_case.json", "output_case.partial.json", "my_notes.txt"}


def test_ctrl_c_before_the_first_file_leaves_the_previous_run_and_says_so(case_file, tmp_path):
    """Stopped inside the run, before anything is written: no marker, the previous run's files untouched."""
    case = load_case(case_file)
    folder = tmp_path / "o"
    _complete_first_run(case, folder)
    stopped = cli(["run", str(case_file), "--set", "x=9", "--set", "stop=signal_run", "--out", "o"], tmp_path)
    assert stopped.returncode == 130, stopped.stderr
    assert stopped.stderr.strip().splitlines()[-1] == (
        "error: output_case: interrupted (Ctrl-C) before the simulation started or after it ended; o holds no unfinished "
        "run (no output_case.partial.json)")
    assert _files(folder) == FULL | {"output_case_plot2.png", "my_notes.txt"}
    assert _y(folder) == 3.0 and json.loads((folder / "output_case.json").read_text())["complete"] is True


def test_a_failing_plot_is_said_in_the_marker(case_file, tmp_path):
    case = load_case(case_file)
    folder = tmp_path / "out"
    _complete_first_run(case, folder)
    with pytest.raises(ValueError, match="no font"):
        case.run({"x": 2.0, "stop": "fail"}, out_dir=folder)
    marker = json.loads((folder / "output_case.partial.json").read_text())
    assert marker["state"] == "failed while drawing the plots: ValueError: no font"
    assert not {"output_case_plot0.png", "output_case_plot1.png", "output_case_plot2.png"} & _files(folder)


def test_a_run_killed_while_plotting_is_marked_and_cleaned_by_the_next(case_file, tmp_path):
    case = load_case(case_file)
    folder = tmp_path / "o"
    _complete_first_run(case, folder)
    flag = tmp_path / "plotting"
    proc = subprocess.Popen([sys.executable, "-m", "exudyn_atcm", "run", str(case_file), "--set", "x=7", "--set", "stop=hang",
                             "--set", f"flag={flag}", "--out", "o"], cwd=tmp_path, env=env(), stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120.0
        while not flag.exists() and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        assert proc.poll() is None
        proc.kill()  # SIGKILL: no handler runs
    finally:
        proc.wait(timeout=30)
    visible = {n for n in _files(folder) if not n.startswith(".")}
    assert visible == {"output_case.csv", "output_case_table.csv", "output_case.json", "output_case.partial.json",
                       "my_notes.txt"}
    assert _y(folder) == 21.0
    assert json.loads((folder / "output_case.partial.json").read_text())["state"] == "writing"
    case.run({"x": 1.0, "n_plots": 0}, out_dir=folder)
    assert _files(folder) == {"output_case.csv", "output_case_table.csv", "output_case.json", "my_notes.txt"}


def test_a_partial_simulation_replaces_the_previous_run_and_is_marked(case_file, tmp_path):
    case = load_case(case_file)
    folder = tmp_path / "out"
    _complete_first_run(case, folder)
    with pytest.raises(KeyboardInterrupt) as info:
        case.run({"x": 2.0, "interrupt_run": "yes"}, out_dir=folder)
    assert [p.name for p in info.value.files] == ["output_case.csv", "output_case.json"]
    assert _files(folder) == {"output_case.csv", "output_case.json", "output_case.partial.json", "my_notes.txt"}
    assert read_csv(folder / "output_case.csv").info["partial"] is True
    assert json.loads((folder / "output_case.partial.json").read_text())["state"] == "interrupted at t = 0.5 s"
    assert json.loads((folder / "output_case.json").read_text())["notes"]["partial"] is True


def test_files_the_run_writes_itself_are_its_outputs(case_file, tmp_path):
    case = load_case(case_file)
    folder = tmp_path / "out"
    first = case.run({"x": 1.0, "note": "yes", "n_plots": 0}, out_dir=folder)
    assert (folder / "output_case_note.txt").read_text() == "1.0"
    assert "output_case_note.txt" in json.loads((folder / "output_case.json").read_text())["files"]
    assert folder / "output_case_note.txt" in first.files and first.files[0].name == "output_case.csv"
    case.run({"x": 2.0, "n_plots": 0}, out_dir=folder)  # writes no note: the first run's note goes
    assert _files(folder) == {"output_case.csv", "output_case_table.csv", "output_case.json"}
    ctx = RunContext("c", folder, folder=OutputFolder(folder, "c"))
    for name in ("../x", "sub/x", "", ".."):
        with pytest.raises(ValueError, match=rf"output_file: name must be a plain file name without directories, got '{re.escape(name)}'"):
            ctx.output_file(name)
    with pytest.raises(ValueError, match="this run of c writes no files"):
        RunContext("c").output_file("x.txt")


def test_a_run_that_fails_before_writing_keeps_the_previous_run(case_file, tmp_path):
    case = load_case(case_file)
    folder = tmp_path / "out"
    _complete_first_run(case, folder)
    with pytest.raises(ValueError, match="bad input found by the run"):
        case.run({"x": 1.0, "stop": "run"}, out_dir=folder)  # fails before anything is written
    assert _files(folder) == FULL | {"output_case_plot2.png", "my_notes.txt"}


def test_a_hand_edited_file_list_never_removes_files_outside_the_folder(case_file, tmp_path):
    case = load_case(case_file)
    folder = tmp_path / "out"
    case.run({"x": 1.0, "n_plots": 0}, out_dir=folder)
    outside = tmp_path / "precious.txt"
    outside.write_text("keep")
    (folder / "sub").mkdir()
    record = json.loads((folder / "output_case.json").read_text())
    record["files"] += ["../precious.txt", str(outside), "sub", ".."]
    (folder / "output_case.json").write_text(json.dumps(record))
    case.run({"x": 2.0, "n_plots": 0}, out_dir=folder)
    assert outside.read_text() == "keep" and (folder / "sub").is_dir()


def test_a_run_stopped_in_the_accuracy_probe_says_so_in_the_message_and_the_notes(case_file, tmp_path):
    # the probe's partial run (twice the chosen step) is written as the case's partial result: the error line and the
    # JSON notes say which run of simulate(accuracy=)'s choice it is
    stopped = cli(["run", str(case_file), "--set", "interrupt_run=probe", "--out", "o"], tmp_path)
    assert stopped.returncode == 130, stopped.stderr
    line = stopped.stderr.strip().splitlines()[-1]
    assert line.startswith("error: output_case: interrupted at t = 0.5 s in the accuracy probe (a check at twice the "
                           "chosen step), step 0.002 s; wrote the 1 recorded instants"), line
    notes = json.loads((tmp_path / "o" / "output_case.json").read_text())["notes"]
    assert notes["interrupted_in"].startswith("accuracy probe") and notes["partial"] is True
