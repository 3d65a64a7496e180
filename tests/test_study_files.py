"""Study files (issue 17): errors worded like `run`'s, unusable store records, a second sweep on one table."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from exudyn_atcm.casework import load_case
from exudyn_atcm.study import run_study
from exudyn_atcm.study.options import RunOptions
from exudyn_atcm.study.lock import StudyLockedError, TableLock
from exudyn_atcm.study.store import RunStore, record_problem
from exudyn_atcm.study.table import column

from _cli_helpers import cli, env

SYNTHETIC = Path(__file__).resolve().parent / "study_cases" / "synthetic_study.py"


@pytest.fixture(scope="module")
def synthetic():
    return load_case(SYNTHETIC)


@pytest.mark.parametrize("command", [["sweep", str(SYNTHETIC), "--grid", "x=1,2", "--workers", "1"],
                                     ["optimize", str(SYNTHETIC), "--objective", "y", "--bound", "x=0:1", "--workers", "1",
                                      "--maxiter", "1", "--popsize", "1"]])
def test_output_directory_that_is_a_file_is_worded_like_run(tmp_path, command):
    (tmp_path / "afile").write_text("x\n")
    run = cli(["run", str(SYNTHETIC), "--out", "afile"], tmp_path)
    study = cli([*command, "--out", "afile", "--no-plot"], tmp_path)
    assert run.returncode == 1 and study.returncode == 1
    expected = "error: cannot create the output directory 'afile': a file of that name exists"
    assert run.stderr.strip().splitlines()[-1] == expected
    assert study.stderr.strip().splitlines()[-1] == expected
    assert "Errno" not in study.stderr


@pytest.mark.parametrize(
    "edit, words",
    [
        (lambda r: r.update(status=1), r"the field 'status' is 1 \(int\), expected str"),
        (lambda r: r.update(status="done"), r"the field 'status' is 'done', expected 'ok' or 'failed'"),
        (lambda r: r.update(scalars=[1.0]), r"the field 'scalars' is \[1.0\] \(list\), expected dict"),
        (lambda r: r["scalars"].update(y="4.0"), r"the scalar 'y' is '4.0' \(str\), expected a number"),
        (lambda r: r["scalars"].update(y=True), r"the scalar 'y' is True \(bool\), expected a number"),
        (lambda r: r.pop("error"), r"the field 'error' is missing"),
        (lambda r: r.update(steps="3"), r"the field 'steps' is '3' \(str\), expected int or NoneType"),
        (lambda r: r.update(key="0" * 64), r"its key is '0000"),
    ],
)
def test_a_store_record_of_wrong_types_names_the_file_and_is_run_again(synthetic, tmp_path, edit, words):
    out = tmp_path / "out"
    first = run_study(synthetic, {"x": [1.0, 2.0]}, run=RunOptions(workers=1, out=out))
    records = sorted((out / "runs").glob("*/*.json"))
    assert len(records) == 2
    damaged = next(p for p in records if json.loads(p.read_text())["values"]["x"] == 2.0)
    record = json.loads(damaged.read_text())
    edit(record)
    damaged.write_text(json.dumps(record))
    assert record_problem(record, damaged.stem) is not None
    with pytest.warns(RuntimeWarning, match=rf"run store record '{damaged}' cannot be used: {words}.*executed again"):
        again = run_study(synthetic, {"x": [1.0, 2.0]}, run=RunOptions(workers=1, out=out))
    assert again.executed == 1 and again.reused == 1
    np.testing.assert_array_equal(column(again.table, "y"), [3.0, 6.0])  # y = x^2 + 2
    np.testing.assert_array_equal(column(again.table, "y"), column(first.table, "y"))
    assert record_problem(json.loads(damaged.read_text()), damaged.stem) is None  # replaced by a good record


def test_a_store_record_that_is_not_json_is_run_again(synthetic, tmp_path):
    store = RunStore(tmp_path / "runs")
    run_study(synthetic, {"x": [1.0]}, run=RunOptions(workers=1, store=store))
    [path] = list((tmp_path / "runs").glob("*/*.json"))
    path.write_text('{"key": ')
    with pytest.warns(RuntimeWarning, match=rf"'{path}' cannot be used: not valid JSON"):
        again = run_study(synthetic, {"x": [1.0]}, run=RunOptions(workers=1, store=store))
    assert again.executed == 1


def test_a_good_record_passes_the_check(synthetic, tmp_path):
    run_study(synthetic, {"x": [1.0]}, run=RunOptions(workers=1, store=tmp_path / "runs"))
    [path] = list((tmp_path / "runs").glob("*/*.json"))
    assert record_problem(json.loads(path.read_text()), path.stem) is None


_HOLDER = """
import sys, time
from exudyn_atcm.study.lock import TableLock
with TableLock(sys.argv[1], "holder"):
    print("locked", flush=True)
    time.sleep(120)
"""


def test_a_second_sweep_on_the_same_table_is_refused_until_the_first_ends(synthetic, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    holder = subprocess.Popen([sys.executable, "-c", _HOLDER, str(out / "synthetic_study_sweep.csv")], env=env(),
                              stdout=subprocess.PIPE, text=True, start_new_session=True)
    try:
        assert holder.stdout.readline().strip() == "locked"
        with pytest.raises(StudyLockedError, match=rf"another study is writing '{out / 'synthetic_study_sweep.csv'}' now "
                                                   rf"\(pid {holder.pid} on .*: holder\); wait until it ends, or .*\(--out\)"):
            run_study(synthetic, {"x": [1.0]}, run=RunOptions(workers=1, out=out))
        assert not (out / "synthetic_study_sweep.csv").exists()
        # the command line: one line, exit status 1
        refused = cli(["sweep", str(SYNTHETIC), "--grid", "x=1,2", "--workers", "1", "--out", str(out), "--no-plot"], tmp_path)
        assert refused.returncode == 1 and "error: another study is writing" in refused.stderr
        # another case's table in the same directory is not blocked
        other = tmp_path / "other.py"
        other.write_text(SYNTHETIC.read_text().replace('Case("synthetic_study"', 'Case("other"'))
        assert run_study(load_case(other), {"x": [1.0]}, run=RunOptions(workers=1, out=out)).failed == 0
    finally:
        os.killpg(holder.pid, signal.SIGKILL)  # the lock ends with its process, even killed
        holder.wait(timeout=30)
        holder.stdout.close()
    result = run_study(synthetic, {"x": [1.0, 2.0]}, run=RunOptions(workers=1, out=out))
    assert result.csv_path.is_file() and result.failed == 0


def test_the_lock_is_released_for_the_next_study_in_the_same_process(tmp_path):
    table = tmp_path / "t.csv"
    with TableLock(table, "first"):
        with pytest.raises(StudyLockedError):
            with TableLock(table, "second"):
                pass  # pragma: no cover
    with TableLock(table, "third"):
        pass
    assert (tmp_path / ".t.lock").read_text() == ""  # no stale holder text
    start = time.perf_counter()
    with TableLock(table):
        pass
    assert time.perf_counter() - start < 5.0
