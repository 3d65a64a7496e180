"""The command line: list, run, exit codes, one-line errors, progress bar."""

from __future__ import annotations

import io
import shutil
import sys
from pathlib import Path

import pytest

from exudyn_atcm.cli import main
from exudyn_atcm.io.progress import ProgressBar

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


# ----------------------------------------------------------------------------- issue 9
def test_cases_are_shipped_with_the_package(tmp_path):
    """`exudyn-atcm list` outside the checkout: the cases come with the installed package.

    setup.py's build step (the one a wheel and a non-editable `pip install .` use) copies the
    package; run the command line from that copy only, in an empty directory.
    """
    import subprocess

    from _cli_helpers import REPO, env

    pytest.importorskip("setuptools")
    lib = tmp_path / "lib"
    build = subprocess.run([sys.executable, "setup.py", "-q", "build_py", "--build-lib", str(lib)],
                           cwd=REPO, capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    assert (lib / "exudyn_atcm" / "example_cases" / "paper_bending_actuator.py").is_file()
    work = tmp_path / "elsewhere"
    work.mkdir()
    environment = env()
    environment["PYTHONPATH"] = str(lib)  # not the checkout
    proc = subprocess.run([sys.executable, "-m", "exudyn_atcm", "list"], cwd=work, env=environment,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    for name in ALL_CASES + ["paper_bending_actuator"]:
        assert f"{name}  ({lib / 'exudyn_atcm' / 'example_cases' / name}.py)" in proc.stdout


def test_list_with_no_cases_fails(monkeypatch, capsys):
    import exudyn_atcm.casework as cases

    monkeypatch.setattr(cases, "list_cases", lambda cases_dir=None: [])
    assert main(["list"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: no cases found (searched: ") and "--cases-dir" in err


def test_misspelt_case_and_parameter_get_the_closest_name(tmp_path):
    proc = cli(["run", "paper_bending_actuatr"], tmp_path)
    assert proc.returncode == 2
    assert "(did you mean 'paper_bending_actuator'?)" in _one_line_error(proc)
    proc = cli(["run", "paper_bending_actuator", "--set", "stpe=1e-3"], tmp_path)
    assert proc.returncode == 2
    assert "unknown parameter 'stpe' for case paper_bending_actuator (did you mean 'step'?)" in _one_line_error(proc)


def test_fig12_with_step_1_fails_with_advice(tmp_path):
    # issue 9: this printed a flat response with exit status 0
    proc = cli(["run", "paper_bending_actuator", "--set", "step=1", "--no-plot"], tmp_path)
    assert proc.returncode == 1
    line = _one_line_error(proc)
    assert "step = 1 s is too coarse" in line and "Use step <= 0.125 s" in line
    assert not (tmp_path / "out" / "paper_bending_actuator.csv").exists()


def test_output_directory_that_cannot_be_made_is_named(tmp_path):
    (tmp_path / "taken").write_text("a file, not a directory\n")
    proc = cli(["run", "paper_stroke_table", "--out", "taken"], tmp_path)
    assert proc.returncode == 1
    line = _one_line_error(proc)
    assert line == "error: cannot create the output directory 'taken': a file of that name exists"


INTERRUPTING_CASE = '''"""A case whose voltage program is interrupted (Ctrl-C) at t = 0.02 s."""
from exudyn_atcm.mechanism.actuator import BendingActuator
from exudyn_atcm.casework import Case, CaseOutput, Parameter
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.materials import Layer
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.solve import simulate

PARAMETERS = [Parameter("stop", 0.02, "s", "time of the Ctrl-C")]


def run(p, ctx):
    triangle = Triangle(500.0, 1000.0, 0.1)

    def program(t):
        if t > p.stop:
            raise KeyboardInterrupt
        return triangle(t)

    drive = PiezoDrive(program, hysteresis=paper_strain_preisach())
    act = BendingActuator(3, 29e-3, 28e-3, Layer(0.2e-3, 70e9, 1550.0), Layer(0.3e-3, 30.336e9, 5440.0),
                          drive, cell="rigid")
    return CaseOutput(simulate(act, 0.05, step=1e-4, progress=ctx.progress))


CASE = Case("interrupting", __doc__, PARAMETERS, run)

if __name__ == "__main__":
    raise SystemExit(CASE.main())
'''


def test_ctrl_c_in_a_run_writes_partial_results_and_exits_130(tmp_path):
    from exudyn_atcm.io import read_csv

    case = tmp_path / "interrupting.py"
    case.write_text(INTERRUPTING_CASE)
    proc = cli(["run", str(case), "--out", "o"], tmp_path)
    assert proc.returncode == 130
    line = _one_line_error(proc)
    # the first step after 0.02 s raised: the last accepted step is 0.02 s, 201 instants
    assert line == ("error: interrupting: interrupted at t = 0.02 s; wrote the 201 recorded instants up to "
                    "there (marked partial) to o/interrupting.csv; o holds this unfinished run, listed in "
                    "o/interrupting.partial.json")
    data = read_csv(tmp_path / "o" / "interrupting.csv")
    assert data.n_rows == 201 and data["time"][-1] == 0.02 and data.info["partial"] is True
    assert "solver" not in proc.stderr.lower() or "failed" not in proc.stderr
