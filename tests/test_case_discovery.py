"""Case discovery (issue 17, part 5): the current directory's cases/ only when asked; a name in two files is said."""

from __future__ import annotations

import pytest

from exudyn_atcm.casework import case_files, find_case

from _cli_helpers import CASES, cli

#: A case file that leaves a marker when it is executed (imported).
_MARKING = '''"""A case found in someone else's archive."""
from pathlib import Path
Path(__file__).with_suffix(".ran").write_text("executed\\n")
from exudyn_atcm.casework import Case, CaseOutput, Parameter
from exudyn_atcm.io.result import Result

def run(p, ctx):
    return CaseOutput(Result({"time": [0.0]}, {"time": "s"}))

CASE = Case("{name}", __doc__, [Parameter("x", 1.0, "-", "x")], run)
'''


def _archive(tmp_path):
    """A directory like an unpacked archive: cases/ with a new case and one shadowing a built-in name."""
    cases = tmp_path / "cases"
    cases.mkdir()
    (cases / "their_case.py").write_text(_MARKING.replace("{name}", "their_case"))
    (cases / "paper_stroke_table.py").write_text(_MARKING.replace("{name}", "paper_stroke_table"))
    return cases


def test_list_run_and_sweep_do_not_execute_the_current_directorys_cases(tmp_path):
    cases = _archive(tmp_path)
    listed = cli(["list"], tmp_path)
    assert listed.returncode == 0, listed.stderr
    assert "their_case" not in listed.stdout and f"paper_stroke_table  ({CASES / 'paper_stroke_table.py'})" in listed.stdout
    run = cli(["run", "paper_stroke_table", "--out", "o", "--no-plot"], tmp_path)
    assert run.returncode == 0, run.stderr
    assert "stroke_max = 4e-05 [m]" in run.stdout  # the built-in case ran (the paper's 40 µm), not the local file
    sweep = cli(["sweep", "paper_stroke_table", "--grid", "period=1,2", "--workers", "1", "--out", "s", "--no-plot"], tmp_path)
    assert sweep.returncode == 0, sweep.stderr
    assert "(1 worker)" in sweep.stdout  # it said "(1 workers)"
    missing = cli(["run", "their_case"], tmp_path)
    assert missing.returncode == 2
    assert missing.stderr.strip().endswith(
        "cases/their_case.py exists here, but the current directory is searched only when asked: "
        "give --cases-dir cases or the path cases/their_case.py")
    assert not list(cases.glob("*.ran"))  # none of the archive's files was executed


def test_asked_for_the_local_directory_and_a_name_found_twice_is_said(tmp_path):
    cases = _archive(tmp_path)
    listed = cli(["list", "--cases-dir", "cases"], tmp_path)
    assert listed.returncode == 0, listed.stderr
    assert f"their_case  ({cases.resolve() / 'their_case.py'})" in listed.stdout
    assert f"paper_stroke_table  ({cases.resolve() / 'paper_stroke_table.py'})" in listed.stdout
    assert f"    also {CASES / 'paper_stroke_table.py'} (not used: the first file of a name wins)" in listed.stdout
    run = cli(["run", "paper_stroke_table", "--cases-dir", "cases", "--out", "o", "--no-plot"], tmp_path)
    assert run.returncode == 0, run.stderr
    warning = [line for line in run.stderr.splitlines() if line.startswith("warning: case 'paper_stroke_table'")]
    assert warning == [f"warning: case 'paper_stroke_table' is found in 2 different files: using {cases.resolve() / 'paper_stroke_table.py'} "
                       f"(the first in the search order --cases-dir, $EXUDYN_ATCM_CASES, the package's cases); "
                       f"not using {CASES / 'paper_stroke_table.py'}"]
    assert (cases / "paper_stroke_table.ran").is_file()  # asked for: executed
    by_path = cli(["run", "cases/their_case.py", "--out", "p", "--no-plot"], tmp_path)  # a path is asking too
    assert by_path.returncode == 0, by_path.stderr


def test_case_files_lists_distinct_files_in_search_order(tmp_path):
    cases = _archive(tmp_path)
    assert case_files("paper_stroke_table") == [CASES / "paper_stroke_table.py"]
    assert case_files("paper_stroke_table", cases) == [cases.resolve() / "paper_stroke_table.py", CASES / "paper_stroke_table.py"]
    same = tmp_path / "copy"
    same.mkdir()
    (same / "paper_stroke_table.py").write_bytes((CASES / "paper_stroke_table.py").read_bytes())
    assert case_files("paper_stroke_table", same) == [same.resolve() / "paper_stroke_table.py"]  # identical copies count once
    with pytest.warns(RuntimeWarning, match="found in 2 different files"):
        assert find_case("paper_stroke_table", cases) == cases.resolve() / "paper_stroke_table.py"
