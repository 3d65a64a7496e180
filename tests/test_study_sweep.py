"""Parameter studies: tables, engines, the run store, failures, sampling and grid specifications."""

from __future__ import annotations

import csv
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from exudyn_atcm.casework import load_case
from exudyn_atcm.cli import main
from exudyn_atcm.study import GridError, StudyTable, run_study, sample_points, sweep
from exudyn_atcm.study.options import RunOptions
from exudyn_atcm.study.table import column

from _cli_helpers import env

SYNTHETIC = Path(__file__).resolve().parent / "study_cases" / "synthetic_study.py"


@pytest.fixture(scope="module")
def synthetic():
    return load_case(SYNTHETIC)


def _runs_logged(directory: Path) -> int:
    return len(list(directory.glob("*.run")))


def _without_wall_time(table):
    return table.drop(columns=["wall_time [s]"])


def test_full_grid_table_has_closed_form_scalars_units_and_order(synthetic, tmp_path):
    grid = {"x": np.linspace(0.0, 1.0, 3), "n": [1, 5]}
    result = run_study(synthetic, grid, fixed={"a": 2.0}, run=RunOptions(workers=1, out=tmp_path))
    table = result.table
    # the last name varies fastest, like nested loops in the order given
    assert column(table, "x").tolist() == [0.0, 0.0, 0.5, 0.5, 1.0, 1.0]
    assert column(table, "n").tolist() == [1, 5, 1, 5, 1, 5]
    x, n = column(table, "x"), column(table, "n")
    np.testing.assert_array_equal(column(table, "y"), 2.0 * x**2 + n)  # y = a x^2 + n, a fixed at 2
    np.testing.assert_array_equal(column(table, "z"), np.sin(x) * n)
    assert list(table.columns[:3]) == ["run [-]", "x [m]", "n [-]"]
    assert {"y [m]", "z [-]", "status [-]", "error [-]", "wall_time [s]", "key [-]"} <= set(table.columns)
    assert (column(table, "status") == "ok").all() and result.varied == ["x", "n"]
    # the CSV: comment lines, then the header with units, then the same values
    lines = result.csv_path.read_text().splitlines()
    rows = list(csv.reader(line for line in lines if not line.startswith("#")))
    assert rows[0] == list(table.columns)
    assert [float(r[rows[0].index("y [m]")]) for r in rows[1:]] == column(table, "y").tolist()


def test_one_table_type_with_its_conversions(synthetic):
    table = sweep(synthetic, {"x": [1.0, 2.0]}, run=RunOptions(workers=1))
    assert type(table) is StudyTable
    assert len(table) == 2 and table.columns[:2] == ["run [-]", "x [m]"] and table.units["y [m]"] == "m"
    np.testing.assert_array_equal(table["y [m]"], np.array([1.0, 4.0]) + 2)  # y = a x^2 + n with the defaults a = 1, n = 2
    np.testing.assert_array_equal(table["y"], table["y [m]"])
    assert table[["x [m]", "y"]].columns == ["x [m]", "y [m]"]
    array = table.to_numpy()
    assert isinstance(array, np.ndarray) and array.dtype.names == tuple(table.columns)
    np.testing.assert_array_equal(array["y [m]"], table["y [m]"])
    assert not table.drop(columns=["wall_time [s]"]).equals(table) and table.equals(table[table.columns])
    with pytest.raises(ValueError, match=r"no column 'w' in the table; columns: run \[-\], x \[m\]"):
        table["w"]
    with pytest.warns(DeprecationWarning, match="use_pandas is deprecated"):
        legacy = sweep(synthetic, {"x": [1.0, 2.0]}, run=RunOptions(workers=1, use_pandas=False))
    assert isinstance(legacy, np.ndarray) and legacy.dtype.names[1] == "x [m]"


def test_to_pandas_keeps_values_and_units(synthetic):
    pd = pytest.importorskip("pandas")
    table = sweep(synthetic, {"x": [1.0, 2.0], "mode": ["plain", "other"]}, run=RunOptions(workers=1))
    frame = table.to_pandas()
    assert isinstance(frame, pd.DataFrame) and list(frame.columns) == table.columns
    assert frame.attrs["units"] == table.units
    for header in table.columns:
        assert frame[header].tolist() == table[header].tolist()


WITHOUT_PANDAS = """
import sys
sys.modules["pandas"] = None  # an import of pandas now raises ImportError, as if it were not installed
import numpy as np
from exudyn_atcm.casework import load_case
from exudyn_atcm.study import StudyTable, column, run_study, sweep
case = load_case(sys.argv[1])
table = sweep(case, {"x": [0.0, 0.5, 1.0], "n": [1, 5]}, fixed={"a": 2.0}, workers=1)
assert type(table) is StudyTable, type(table)
x, n = column(table, "x"), column(table, "n")
assert np.array_equal(column(table, "y"), 2.0 * x**2 + n)
assert list(table.columns[:3]) == ["run [-]", "x [m]", "n [-]"]
assert table.drop(columns=["wall_time [s]"]).equals(
    run_study(case, {"x": [0.0, 0.5, 1.0], "n": [1, 5]}, fixed={"a": 2.0}, workers=1).table.drop(columns=["wall_time [s]"]))
try:
    table.to_pandas()
except ImportError as exc:
    print("ImportError:", exc)
"""


def test_same_type_without_pandas(tmp_path):
    """With pandas blocked in a fresh interpreter, sweep and run_study return the same StudyTable and
    everything but to_pandas works (the two tests that needed pandas before run this way here)."""
    proc = subprocess.run([sys.executable, "-c", WITHOUT_PANDAS, str(SYNTHETIC)], capture_output=True, text=True,
                          timeout=300, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert proc.stdout.strip() == ("ImportError: StudyTable.to_pandas needs pandas, which is not installed "
                                   "(pip install pandas); table[name] and table.to_numpy() work without it")


def test_same_table_with_one_two_workers_and_dask(synthetic, tmp_path):
    """Row order and every value (wall times aside) do not depend on the engine."""
    grid = {"x": [0.5, -1.0, 2.0, 1.5, 3.0], "mode": ["plain", "other"]}
    fixed = {"fail_below": 0.0, "delay": 0.01}  # x = -1 fails; short runs finish out of order
    one = sweep(synthetic, grid, fixed=fixed, run=RunOptions(workers=1))
    two = sweep(synthetic, grid, fixed=fixed, run=RunOptions(workers=2))
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            dask = sweep(synthetic, grid, fixed=fixed, run=RunOptions(client=client))
        by_address = sweep(synthetic, grid, fixed=fixed, run=RunOptions(scheduler=cluster.scheduler_address))  # as --scheduler
    assert _without_wall_time(one).equals(_without_wall_time(two))
    assert _without_wall_time(one).equals(_without_wall_time(dask))
    assert _without_wall_time(one).equals(_without_wall_time(by_address))
    assert column(one, "status").tolist().count("failed") == 2


def test_real_case_same_with_one_and_two_workers():
    """paper_stroke_table: the linear law's stroke d33 U_max L / t_IDE = 40.02 µm (Eqs. 2-3) in every row."""
    case = load_case("paper_stroke_table")
    grid = {"period": [1.0, 2.0], "points_per_period": [10, 20]}
    one = sweep(case, grid, run=RunOptions(workers=1))
    two = sweep(case, grid, run=RunOptions(workers=2))
    assert _without_wall_time(one).equals(_without_wall_time(two))
    np.testing.assert_allclose(column(one, "stroke_linear_law"), 460e-12 * 1500.0 / 0.5e-3 * 29e-3, rtol=1e-12)
    # the table's points: the interpolation error does not depend on the period (rate-independent operator)
    err = column(one, "table_max_interpolation_error")
    np.testing.assert_allclose(err[:2], err[2:], rtol=1e-9)


def test_failing_run_is_recorded_and_the_study_goes_on(synthetic, tmp_path):
    log = tmp_path / "log"
    log.mkdir()
    result = run_study(synthetic, {"x": [1.0, -2.0, 3.0]}, fixed={"fail_below": 0.0, "log_dir": str(log)}, run=RunOptions(workers=1, out=tmp_path / "out"))
    status = column(result.table, "status").tolist()
    assert status == ["ok", "failed", "ok"]
    error = column(result.table, "error")[1]
    assert error == "ValueError: x = -2.0 is below fail_below = 0.0"
    assert math.isnan(column(result.table, "y")[1]) and column(result.table, "y")[2] == 11.0
    assert result.failed == 1 and _runs_logged(log) == 2
    # a failure is a result: stored, not repeated ...
    again = run_study(synthetic, {"x": [1.0, -2.0, 3.0]}, fixed={"fail_below": 0.0, "log_dir": str(log)}, run=RunOptions(workers=1, out=tmp_path / "out"))
    assert again.executed == 0 and again.reused == 3
    # ... unless asked for
    retried = run_study(synthetic, {"x": [1.0, -2.0, 3.0]}, fixed={"fail_below": 0.0, "log_dir": str(log)}, run=RunOptions(workers=1, out=tmp_path / "out", retry_failed=True))
    assert retried.executed == 1


def test_killed_study_resumes_without_recomputing(tmp_path):
    """Kill a running study (SIGKILL), start it again: only the runs not stored are executed."""
    log = tmp_path / "log"
    log.mkdir()
    out = tmp_path / "out"
    n_points = 12
    script = (
        "from exudyn_atcm.study import sweep\n"
        f"sweep({str(SYNTHETIC)!r}, {{'x': [float(i) for i in range({n_points})]}}, "
        f"fixed={{'delay': 0.15, 'log_dir': {str(log)!r}}}, workers=1, out={str(out)!r})\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", script], env=env(), start_new_session=True)
    try:
        deadline = time.monotonic() + 60.0
        while len(list((out / "runs").glob("*/[0-9a-f]*.json"))) < 3 and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.02)
        assert proc.poll() is None, "the study finished before it could be killed"
        os.killpg(proc.pid, signal.SIGKILL)
    finally:
        proc.wait(timeout=30)
    stored = len(list((out / "runs").glob("*/[0-9a-f]*.json")))  # not a .tmp_ file a kill may leave behind
    assert 3 <= stored < n_points
    assert not list(out.glob("*.csv"))  # the table is written only at the end
    before = _runs_logged(log)
    assert before >= stored  # a run may have finished but not yet been stored when killed
    resumed = run_study(SYNTHETIC, {"x": [float(i) for i in range(n_points)]}, fixed={"delay": 0.15, "log_dir": str(log)}, run=RunOptions(workers=2, out=out))
    assert resumed.reused == stored and resumed.executed == n_points - stored
    assert _runs_logged(log) - before == n_points - stored  # counted by the case itself
    assert (column(resumed.table, "status") == "ok").all()
    np.testing.assert_array_equal(column(resumed.table, "y"), np.arange(n_points, dtype=float) ** 2 + 2)


def test_duplicate_points_run_once(synthetic, tmp_path):
    log = tmp_path / "log"
    log.mkdir()
    result = run_study(synthetic, points=[{"x": 1.0}, {"x": 2.0}, {"x": 1.0}], fixed={"log_dir": str(log)}, run=RunOptions(workers=1))
    assert result.executed == 2 and _runs_logged(log) == 2
    assert column(result.table, "y").tolist() == [3.0, 6.0, 3.0]


def test_latin_hypercube_samples_fill_every_stratum(synthetic):
    n = 16
    points = sample_points(synthetic, {"x": (2.0, 4.0), "n": (1, 4)}, n, method="lhs", seed=3)
    x = np.array([p["x"] for p in points])
    assert ((x >= 2.0) & (x < 4.0)).all()
    # Latin hypercube (McKay et al. 1979): exactly one point in each of the n equal strata
    assert sorted(np.floor((x - 2.0) / 2.0 * n).astype(int).tolist()) == list(range(n))
    ints = [p["n"] for p in points]
    assert set(ints) == {1, 2, 3, 4} and all(isinstance(v, int) for v in ints)
    assert sample_points(synthetic, {"x": (2.0, 4.0)}, 5, seed=3) == sample_points(synthetic, {"x": (2.0, 4.0)}, 5, seed=3)
    random = sample_points(synthetic, {"x": (0.0, 1.0)}, 5, method="random", seed=1)
    assert len(random) == 5 and all(0.0 <= p["x"] < 1.0 for p in random)


def test_samples_crossed_with_a_grid(synthetic):
    result = run_study(synthetic, {"mode": ["plain", "other"]}, samples=3, bounds={"x": (0.0, 1.0)}, run=RunOptions(workers=1))
    assert column(result.table, "mode").tolist() == ["plain"] * 3 + ["other"] * 3
    assert column(result.table, "x")[:3].tolist() == column(result.table, "x")[3:].tolist()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"grid": {"xx": [1.0]}}, "unknown parameter 'xx' for case synthetic_study; did you mean 'x'?"),
        ({"grid": {"x": []}}, "'x' has no values (empty range)"),
        ({"grid": {"n": [1.5]}}, "n must be an integer, got 1.5"),
        ({"grid": {"x": ["abc"]}}, "x must be a finite real number [m], got 'abc'"),
        ({"samples": 0, "bounds": {"x": (0, 1)}}, "n must be an integer >= 1, got 0"),
        ({"samples": 2, "bounds": {"x": (1, 0)}}, "low <= high"),
        ({"samples": 2, "bounds": {"mode": (1, 0)}}, "'mode' is a str parameter"),
        ({"grid": {"delay": [0.0, -1.0]}}, "delay must be >= 0 [s], got -1.0"),
        ({"samples": 2, "bounds": {"delay": (-1.0, 1.0)}}, "samples: delay must be >= 0 [s], got -1.0 (the case's declared range)"),
        ({}, "nothing to vary"),
    ],
)
def test_bad_study_specifications_are_one_line_errors(synthetic, kwargs, message):
    with pytest.raises(GridError) as info:
        sweep(synthetic, run=RunOptions(workers=1), **kwargs)
    text = str(info.value)
    assert message in text and "\n" not in text


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("xx=1:2:3", "error: --grid: unknown parameter 'xx' for case synthetic_study; did you mean 'x'? "
                     "(parameters: x, n, a, mode, fail_below, delay, crash_at, log_dir)"),
        ("x=1:2:0", "error: --grid x: N must be an integer >= 1, got 0"),
        ("n=5:2", "error: --grid n: empty range '5:2' (START > STOP)"),
        ("x=", "error: --grid x: no values given (empty range) in 'x='"),
        ("x=a,b", "error: --grid x: x must be a finite real number [m], got 'a'"),
        ("n=1:2:3", "error: --grid n: n is an integer parameter but '1:2:3' gives non-integer values [1.0, 1.5, 2.0]"),
        ("x=1:2", "error: --grid x: a float range needs the number of values, START:STOP:N, got '1:2'"),
        ("x", "error: --grid expects NAME=START:STOP:N or NAME=A,B,C, got 'x'"),
        ("delay=-1:1:3", "error: case synthetic_study: delay must be >= 0 [s], got -1.0"),
    ],
)
def test_bad_grid_specs_on_the_command_line(spec, message, tmp_path, capsys):
    status = main(["sweep", str(SYNTHETIC), "--grid", spec, "--out", str(tmp_path), "--workers", "1"])
    err = capsys.readouterr().err
    assert status == 2
    assert err.strip() == message


def test_cli_sweep_writes_table_plots_and_resumes(tmp_path, capsys):
    args = ["sweep", str(SYNTHETIC), "--grid", "x=0:1:3", "--grid", "n=1:2", "--set", "a=3",
            "--workers", "2", "--out", str(tmp_path)]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "synthetic_study: 6 runs (6 executed, 0 from the store, 0 failed)" in out
    rows = [r for r in csv.reader(l for l in (tmp_path / "synthetic_study_sweep.csv").read_text().splitlines() if not l.startswith("#"))]
    header = rows[0]
    y = [float(r[header.index("y [m]")]) for r in rows[1:]]
    assert y == [3.0 * x**2 + n for x in (0.0, 0.5, 1.0) for n in (1, 2)]
    assert (tmp_path / "synthetic_study_sweep_y_map.png").is_file()
    assert (tmp_path / "synthetic_study_sweep_y_vs_x.png").is_file()
    assert main(args + ["--no-plot"]) == 0
    assert "(0 executed, 6 from the store, 0 failed)" in capsys.readouterr().out


def test_cli_sweep_with_a_failing_run_exits_1(tmp_path, capsys):
    status = main(["sweep", str(SYNTHETIC), "--grid", "x=-1,1", "--set", "fail_below=0", "--workers", "1",
                   "--out", str(tmp_path), "--no-plot"])
    out = capsys.readouterr().out
    assert status == 1
    assert "run 0 failed: ValueError: x = -1.0 is below fail_below = 0.0" in out


def test_cli_latin_hypercube_study(tmp_path, capsys):
    status = main(["sweep", str(SYNTHETIC), "--grid", "x=0:2", "--grid", "n=1:3", "--samples", "6",
                   "--workers", "1", "--out", str(tmp_path)])
    assert status == 0
    assert "6 runs (6 executed" in capsys.readouterr().out
    lines = [l for l in (tmp_path / "synthetic_study_sweep.csv").read_text().splitlines() if not l.startswith("#")]
    rows = list(csv.reader(lines))
    x = np.array([float(r[rows[0].index("x [m]")]) for r in rows[1:]])
    n = np.array([int(r[rows[0].index("n [-]")]) for r in rows[1:]])
    assert sorted(np.floor(x / 2.0 * 6).astype(int).tolist()) == list(range(6))  # one point per stratum
    np.testing.assert_array_equal([float(r[rows[0].index("y [m]")]) for r in rows[1:]], x**2 + n)
    assert (tmp_path / "synthetic_study_sweep_y_map.png").is_file()  # scattered points, coloured


def test_run_progress_bar_counts_runs():
    import io

    from exudyn_atcm.study.command import RunProgressBar

    stream = io.StringIO()
    bar = RunProgressBar(stream, force=True, width=10)
    bar(0, 4, 0)
    bar(2, 4, 1)
    bar(4, 4, 1)
    bar.close()
    text = stream.getvalue()
    assert "[#####.....] 2/4 runs, 1 failed" in text and "[##########] 4/4 runs, 1 failed" in text
    assert text.endswith("\n")
    silent = io.StringIO()
    RunProgressBar(silent)(1, 2, 0)  # not a terminal: nothing drawn
    assert silent.getvalue() == ""


def test_ctrl_c_stops_a_parallel_study_at_once_and_it_resumes(tmp_path):
    """SIGINT to the whole process group (Ctrl-C in a terminal) with 2 workers: exit 130 within
    seconds, no worker left behind, finished runs kept; the same command then runs only the rest."""
    log = tmp_path / "log"
    log.mkdir()
    args = [sys.executable, "-m", "exudyn_atcm", "sweep", str(SYNTHETIC), "--grid", "x=0:1:10", "--set", "delay=0.4",
            "--set", f"log_dir={log}", "--workers", "2", "--out", str(tmp_path / "out"), "--no-plot"]
    proc = subprocess.Popen(args, env=env(), start_new_session=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60.0
        runs = tmp_path / "out" / "runs"
        while len(list(runs.glob("*/[0-9a-f]*.json"))) < 2 and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.02)
        assert proc.poll() is None, "the study finished before it could be interrupted"
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=15)  # runs in flight are abandoned, not waited for
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 130 and err.strip().endswith("error: interrupted")
    left = subprocess.run(["ps", "-o", "pid=", "-g", str(proc.pid)], capture_output=True, text=True).stdout.split()
    assert left == []  # the workers were stopped too
    stored = len(list((tmp_path / "out" / "runs").glob("*/[0-9a-f]*.json")))
    assert 2 <= stored < 10
    before = _runs_logged(log)
    done = subprocess.run(args, env=env(), capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert f"10 runs ({10 - stored} executed, {stored} from the store, 0 failed)" in done.stdout
    assert _runs_logged(log) - before == 10 - stored


def test_a_crashing_worker_does_not_stop_the_study(synthetic, tmp_path):
    """A run that kills its worker process: found by running the lost runs alone, recorded failed
    and stored; every other run finishes, and nothing is repeated on a second start."""
    grid = {"x": [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]}
    log = tmp_path / "log"
    log.mkdir()
    fixed = {"crash_at": 2.0, "log_dir": str(log)}
    result = run_study(synthetic, grid, fixed=fixed, run=RunOptions(workers=2, out=tmp_path / "out"))
    assert column(result.table, "status").tolist() == ["ok", "ok", "failed", "ok", "ok", "ok"]
    assert column(result.table, "error")[2].startswith("the worker process died during this run (run alone")
    x = np.array(grid["x"])
    np.testing.assert_array_equal(column(result.table, "y")[x != 2.0], x[x != 2.0] ** 2 + 2)
    assert _runs_logged(log) >= 5  # runs lost with the crashed pool ran again
    again = run_study(synthetic, grid, fixed=fixed, run=RunOptions(workers=2, out=tmp_path / "out"))
    assert again.executed == 0 and again.reused == 6


def test_grid_spec_of_a_list_parameter_and_the_csv_read_by_pandas(synthetic, tmp_path):
    from exudyn_atcm.study import parse_grid_spec

    case = load_case("tip_tracking")
    assert parse_grid_spec(case, "frequencies=0.25,0.75;0.5,1") == ("frequencies", [(0.25, 0.75), (0.5, 1.0)])
    pd = pytest.importorskip("pandas")
    result = run_study(synthetic, {"x": [0.5, 1.5], "mode": ["plain", "other"]}, run=RunOptions(workers=1, out=tmp_path))
    back = pd.read_csv(result.csv_path, comment="#")
    assert list(back.columns) == list(result.table.columns)
    np.testing.assert_array_equal(back["y [m]"].to_numpy(), column(result.table, "y"))
    assert back["mode [-]"].tolist() == ["plain", "other", "plain", "other"]
