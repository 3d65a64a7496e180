"""Stale study results (issue 29, finding 4): the run key covers the files parameters name and the versions.

The truth of each check is the case's own arithmetic (``value = factor * x``, the factor read
from the file) or the linearity of a least-squares fit (a record whose output is doubled has a
best linear model whose held-out error is doubled), never what the store returned before.
"""

from __future__ import annotations

import csv
import hashlib
import json
from pathlib import Path

import exudyn
import numpy as np
import pytest

from exudyn_atcm.casework import load_case
from exudyn_atcm.study import run_study
from exudyn_atcm.study.options import RunOptions
from exudyn_atcm.study.store import RunStore
from exudyn_atcm.study.table import column

from _cli_helpers import CASES, cli

FILE_STUDY = Path(__file__).resolve().parent / "study_cases" / "file_study.py"


@pytest.fixture(scope="module")
def file_study():
    return load_case(FILE_STUDY)


def _logged(directory: Path) -> int:
    return len(list(directory.glob("*.run")))


def test_a_changed_file_named_by_a_parameter_reruns_and_the_table_says_it_was_stale(file_study, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    log = tmp_path / "log"
    log.mkdir()
    data = tmp_path / "factor.txt"
    data.write_text("2\n")
    study = dict(fixed={"log_dir": str(log)}, run=RunOptions(workers=1, out=tmp_path / "out"))
    first = run_study(file_study, {"x": [1.0, 3.0]}, **study)
    assert first.executed == 2 and first.stale == 0
    np.testing.assert_array_equal(column(first.table, "value"), [2.0, 6.0])  # 2 x
    assert column(first.table, "stale").tolist() == ["", ""]

    data.write_text("5\n")  # same size, same name: only the contents differ
    second = run_study(file_study, {"x": [1.0, 3.0]}, **study)
    assert second.executed == 2 and second.reused == 0 and second.stale == 2
    np.testing.assert_array_equal(column(second.table, "value"), [5.0, 15.0])  # 5 x, not the stored 2 x
    assert column(second.table, "stale").tolist() == [f"data file '{data}' changed"] * 2
    summary = json.loads((tmp_path / "out" / "file_study_sweep.json").read_text())
    assert summary["stale"] == {f"data file '{data}' changed": 2}
    assert _logged(log) == 4  # the case ran four times; the log directory's new files changed no key

    third = run_study(file_study, {"x": [1.0, 3.0]}, **study)
    assert third.executed == 0 and third.reused == 2 and third.stale == 0
    np.testing.assert_array_equal(column(third.table, "value"), [5.0, 15.0])

    data.write_text("2\n")  # back to the first contents: the first results are right again, and stored
    fourth = run_study(file_study, {"x": [1.0, 3.0]}, **study)
    assert fourth.executed == 0 and fourth.reused == 2
    np.testing.assert_array_equal(column(fourth.table, "value"), [2.0, 6.0])
    assert _logged(log) == 4


def test_a_file_that_appears_later_is_a_changed_input(file_study, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    study = dict(fixed={"data": "later.txt"}, run=RunOptions(workers=1, out=tmp_path / "out"))
    failed = run_study(file_study, {"x": [1.0, 2.0]}, **study)
    assert failed.failed == 2 and "FileNotFoundError" in column(failed.table, "error")[0]
    assert run_study(file_study, {"x": [1.0, 2.0]}, **study).executed == 0  # a failure is a result ...
    (tmp_path / "later.txt").write_text("3")
    again = run_study(file_study, {"x": [1.0, 2.0]}, **study)  # ... of a file that did not exist
    assert again.executed == 2 and again.failed == 0
    np.testing.assert_array_equal(column(again.table, "value"), [3.0, 6.0])
    assert column(again.table, "stale").tolist() == [f"data file '{tmp_path / 'later.txt'}' now exists"] * 2
    (tmp_path / "later.txt").unlink()
    gone = run_study(file_study, {"x": [1.0, 2.0]}, **study)  # the failed records are the right answer again
    assert gone.executed == 0 and gone.failed == 2


def test_relative_paths_are_read_from_the_current_directory(file_study, tmp_path, monkeypatch):
    """One store, the same relative name in three directories: the contents decide, not the name."""
    store = RunStore(tmp_path / "store")
    for name, factor in (("a", "2"), ("b", "3"), ("c", "2")):
        (tmp_path / name).mkdir()
        (tmp_path / name / "factor.txt").write_text(factor)
    results = {}
    for name in "abc":
        monkeypatch.chdir(tmp_path / name)
        results[name] = run_study(file_study, {"x": [1.0, 4.0]}, run=RunOptions(workers=1, store=store))
    np.testing.assert_array_equal(column(results["a"].table, "value"), [2.0, 8.0])
    np.testing.assert_array_equal(column(results["b"].table, "value"), [3.0, 12.0])
    assert results["b"].executed == 2 and results["b"].stale == 0  # another file: new runs, not stale ones
    assert results["c"].executed == 0  # c/factor.txt holds what a/factor.txt holds: a's runs are right
    np.testing.assert_array_equal(column(results["c"].table, "value"), [2.0, 8.0])


def test_a_new_exudyn_version_reruns_and_says_so(file_study, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "factor.txt").write_text("2")
    first = run_study(file_study, {"x": [1.0]}, run=RunOptions(workers=1, store=tmp_path / "store"))
    monkeypatch.setattr("exudyn_atcm.study.inputs.exudyn_version", lambda: "0.0.0-test")
    second = run_study(file_study, {"x": [1.0]}, run=RunOptions(workers=1, store=tmp_path / "store"))
    assert second.executed == 1 and column(second.table, "key")[0] != column(first.table, "key")[0]
    assert column(second.table, "stale").tolist() == [f"exudyn {exudyn.__version__} -> 0.0.0-test"]


def _key_before_issue_29(case_file: Path, name: str, values: dict, version: str) -> str:
    """The run key of exudyn_atcm 0.2.0 before issue 29, written out here: case, values, version only."""
    fingerprint = hashlib.sha256(name.encode() + b"\0" + case_file.read_text().encode()).hexdigest()
    plain = {k: repr(v) if isinstance(v, float) else v for k, v in sorted(values.items())}
    payload = json.dumps({"case": fingerprint, "values": plain, "version": version}, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(payload.encode()).hexdigest()


def test_a_record_stored_under_the_old_key_is_reported_stale(file_study, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "factor.txt").write_text("2")
    values = {"data": "factor.txt", "x": 1.0, "log_dir": "", "mode": "plain"}
    old = _key_before_issue_29(FILE_STUDY, "file_study", values, "0.2.0")
    store = RunStore(tmp_path / "store")
    store.save({"key": old, "status": "ok", "error": "", "scalars": {"value": 99.0}, "scalar_units": {"value": "-"},
                "steps": 1, "wall_time": 0.0, "values": values})
    result = run_study(file_study, {"x": [1.0]}, run=RunOptions(workers=1, store=store))
    assert result.executed == 1 and column(result.table, "value").tolist() == [2.0]
    assert column(result.table, "stale").tolist() == ["stored before the run key covered input files and Exudyn's version"]


def _doubled_record(source: Path, target: Path) -> None:
    """The record with its output column doubled (the numbers as written, times two)."""
    lines = source.read_text().splitlines()
    out = []
    for line in lines:
        if line[:1].isdigit() or line[:1] == "-":
            t, v, d = line.split(",")
            line = f"{t},{v},{2.0 * float(d)!r}"
        out.append(line)
    target.write_text("\n".join(out) + "\n")


def _table(path: Path) -> dict[str, list[str]]:
    rows = list(csv.reader(line for line in path.read_text().splitlines() if not line.startswith("#")))
    return {name: [r[i] for r in rows[1:]] for i, name in enumerate(rows[0])}


SMALL = ["--set", "n_plays=4", "--set", "n_relays_eq12=4", "--workers", "1", "--no-plot", "--out", "o"]


def test_issue_reproducer_on_the_command_line(tmp_path):
    """``sweep identify_and_predict --set record=rec.csv``, the record's output doubled, the same command.

    The best linear model's held-out RMS error is linear in the output (least squares), so it
    doubles exactly up to the rounding of the CSV (the doubled numbers are written with repr).
    """
    shipped = CASES / "data" / "preisach_record.csv"
    (tmp_path / "rec.csv").write_text(shipped.read_text())
    command = ["sweep", "identify_and_predict", "--set", "record=rec.csv", "--grid", "n_levels=6,8", *SMALL]
    first = cli(command, tmp_path)
    assert first.returncode == 0, first.stderr
    assert "2 runs (2 executed, 0 from the store, 0 failed)" in first.stdout
    before = _table(tmp_path / "o" / "identify_and_predict_sweep.csv")
    _doubled_record(shipped, tmp_path / "rec.csv")
    second = cli(command, tmp_path)
    assert second.returncode == 0, second.stderr
    assert "2 runs (2 executed, 0 from the store, 0 failed)" in second.stdout
    assert f"2 stale runs executed again" in second.stdout and f"record file '{tmp_path / 'rec.csv'}' changed" in second.stdout
    after = _table(tmp_path / "o" / "identify_and_predict_sweep.csv")
    ratio = np.array(after["held_out_rms_linear [m]"], float) / np.array(before["held_out_rms_linear [m]"], float)
    np.testing.assert_allclose(ratio, 2.0, rtol=1e-6)  # the shipped record has 7 significant digits
    assert after["stale [-]"] == [f"record file '{tmp_path / 'rec.csv'}' changed"] * 2
    third = cli(command, tmp_path)
    assert "2 runs (0 executed, 2 from the store, 0 failed)" in third.stdout and "stale" not in third.stdout


def test_issue_reproducer_in_python(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    case = load_case("identify_and_predict")
    shipped = CASES / "data" / "preisach_record.csv"
    (tmp_path / "rec.csv").write_text(shipped.read_text())
    study = dict(fixed={"record": "rec.csv", "n_plays": 4, "n_relays_eq12": 4}, run=RunOptions(workers=1, out=tmp_path / "o"))
    first = run_study(case, {"n_levels": [6, 8]}, **study)
    _doubled_record(shipped, tmp_path / "rec.csv")
    second = run_study(case, {"n_levels": [6, 8]}, **study)
    assert second.executed == 2 and second.stale == 2
    np.testing.assert_allclose(column(second.table, "held_out_rms_linear") / column(first.table, "held_out_rms_linear"),
                               2.0, rtol=1e-6)
