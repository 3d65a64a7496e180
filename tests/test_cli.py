"""The command line: list, run, exit codes, one-line errors, progress bar."""

from __future__ import annotations

import io
import shutil
import sys
from pathlib import Path

import pytest

from exudyn_atcm.cli import main
from exudyn_atcm.progress import ProgressBar

from _cli_helpers import CASES, cli

ALL_CASES = ["paper_discrete_preisach", "paper_hysteresis_loop", "paper_stroke_table", "stiffness_comparison"]


def _one_line_error(proc) -> str:
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("error: ")
    assert "Traceback" not in proc.stderr
    return lines[0]


def test_list_shows_cases_descriptions_and_parameters(tmp_path):
    proc = cli(["list"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    for name in ALL_CASES:
        assert name in proc.stdout
    assert "Figs. 6 and 8" in proc.stdout
    assert "x_m1 = 1.2e-05 [m] (float)" in proc.stdout


def test_run_success_prints_scalars_and_writes_files(tmp_path):
    proc = cli(["run", "paper_stroke_table", "--out", "o"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "stroke_max = 4e-05 [m]" in proc.stdout
    names = {p.name for p in (tmp_path / "o").iterdir()}
    assert {"paper_stroke_table.csv", "paper_stroke_table.json"} <= names
    assert any(n.endswith(".png") for n in names)
    assert "\r[" not in proc.stdout  # no progress bar when stdout is not a terminal


def test_unknown_case_is_one_line_and_exit_2(tmp_path):
    proc = cli(["run", "no_such_case"], tmp_path)
    assert proc.returncode == 2
    line = _one_line_error(proc)
    assert "no case named 'no_such_case'" in line and "paper_stroke_table" in line


def test_unknown_parameter_lists_valid_ones(tmp_path):
    proc = cli(["run", "paper_stroke_table", "--set", "speed=3"], tmp_path)
    assert proc.returncode == 2
    line = _one_line_error(proc)
    for name in ("period", "cycles", "points_per_period", "exponents", "fine_factor"):
        assert name in line


def test_wrong_type_is_refused(tmp_path):
    proc = cli(["run", "paper_stroke_table", "--set", "cycles=two"], tmp_path)
    assert proc.returncode == 2
    assert "cycles must be an integer" in _one_line_error(proc)


def test_failing_run_exit_1_and_debug_shows_traceback(tmp_path):
    proc = cli(["run", "paper_stroke_table", "--set", "points_per_period=3", "--out", "o"], tmp_path)
    assert proc.returncode == 1
    assert "points_per_period must be an even integer" in _one_line_error(proc)
    proc = cli(["run", "paper_stroke_table", "--set", "points_per_period=3", "--out", "o", "--debug"], tmp_path)
    assert proc.returncode == 1
    assert "Traceback" in proc.stderr


def test_usage_errors(tmp_path):
    proc = cli(["--bogus"], tmp_path)
    assert proc.returncode == 2
    _one_line_error(proc)
    proc = cli(["bench", "--update-references"], tmp_path)
    assert proc.returncode == 2
    assert "--reason" in _one_line_error(proc)
    assert main([]) == 2


def test_case_script_and_cli_share_options(tmp_path):
    from _cli_helpers import run

    proc = run([str(CASES / "paper_stroke_table.py"), "--set", "nope=1"], tmp_path)
    assert proc.returncode == 2
    assert "unknown parameter 'nope'" in _one_line_error(proc)
    proc = run([str(CASES / "paper_stroke_table.py"), "--help"], tmp_path)
    assert proc.returncode == 0 and "--set NAME=VALUE" in proc.stdout and "points_per_period" in proc.stdout


def test_main_in_process(tmp_path, capsys):
    assert main(["run", "paper_hysteresis_loop", "--out", str(tmp_path), "--no-plot", "--set", "cycles=1"]) == 0
    assert "r1 = 1.459432" in capsys.readouterr().out


def _console_script():
    beside = Path(sys.executable).parent / "exudyn-atcm"
    return str(beside) if beside.is_file() else shutil.which("exudyn-atcm")


@pytest.mark.skipif(_console_script() is None, reason="console script not installed (pip install -e .)")
def test_console_script(tmp_path):
    import subprocess

    from _cli_helpers import env

    proc = subprocess.run([_console_script(), "list"], cwd=tmp_path, capture_output=True, text=True, env=env())
    assert proc.returncode == 0 and "paper_stroke_table" in proc.stdout


def test_progress_bar_draws_only_when_enabled():
    stream = io.StringIO()
    bar = ProgressBar(stream, delay=0.0, force=True)
    bar(0.5, 2.0)
    bar.close()
    text = stream.getvalue()
    assert "25%" in text and "t = 0.5 / 2 s" in text and text.endswith("\n")
    quiet = io.StringIO()  # not a terminal
    bar = ProgressBar(quiet, delay=0.0)
    bar(1.0, 2.0)
    bar.close()
    assert quiet.getvalue() == ""
