"""Issue 3, part 1: the Result object and its CSV export."""

from __future__ import annotations

import csv
import io
import os

import numpy as np
import pytest

import exudyn
from exudyn_atcm._version import __version__
from exudyn_atcm.drive import PiezoDrive
from exudyn_atcm.result import Result
from exudyn_atcm.simulation import simulate

from _actuator_geometries import REF_A

HEADER = "time [s],voltage [V],strain [-],stroke [m],tip_x [m],tip_y [m],tip_angle [rad]"


def small_result() -> Result:
    t = np.linspace(0.0, 0.1, 5)
    return Result(
        {"time": t, "tip_y": 1e-3 * t, "tip_angle": 0.1 * t},
        {"time": "s", "tip_y": "m", "tip_angle": "rad"},
        parameters={"n_cells": 3, "cell_length [m]": 0.029},
        info={"exudyn_version": "9.9.9"},
    )


def test_series_are_arrays_with_units():
    r = small_result()
    assert isinstance(r["tip_y"], np.ndarray)
    np.testing.assert_array_equal(r["tip_y"], 1e-3 * np.linspace(0.0, 0.1, 5))
    assert r.unit("tip_y") == "m" and r.unit("time") == "s"
    assert r.names == ["time", "tip_y", "tip_angle"]
    assert r.n_rows == 5
    with pytest.raises(KeyError, match="tip_z"):
        r["tip_z"]
    with pytest.raises(KeyError, match="tip_z"):
        r.unit("tip_z")
    with pytest.raises(ValueError):
        r["tip_y"][0] = 1.0  # read-only views: results cannot be altered by accident


def test_constructor_rejects_inconsistent_series():
    with pytest.raises(ValueError, match="units"):
        Result({"a": [1.0]}, {})
    with pytest.raises(ValueError, match="b"):
        Result({"a": [1.0, 2.0], "b": [1.0]}, {"a": "-", "b": "-"})
    with pytest.raises(ValueError, match=","):
        Result({"a,b": [1.0]}, {"a,b": "-"})


def test_simulation_result_has_standard_columns_and_csv_roundtrip(tmp_path):
    act = REF_A.actuator(PiezoDrive(lambda t: 1000.0 * t), cell="rigid")
    r = simulate(act, 0.01, step=1e-3)
    assert r.names[:7] == ["time", "voltage", "strain", "stroke", "tip_x", "tip_y", "tip_angle"]
    assert r.names[7:] == ["cell_angle_1", "cell_angle_2", "cell_angle_3"]
    assert [r.unit(n) for n in r.names[:7]] == ["s", "V", "-", "m", "m", "m", "rad"]
    path = tmp_path / "run.csv"
    r.to_csv(path)
    text = path.read_text()
    lines = text.splitlines()
    comments = [ln for ln in lines if ln.startswith("#")]
    assert lines[: len(comments)] == comments  # all comments first
    assert f"# exudyn_atcm {__version__}" in comments
    assert f"# exudyn {exudyn.__version__}" in comments
    assert any(ln.startswith("# n_cells: 3") for ln in comments)
    assert any(ln.startswith("# cell: rigid") for ln in comments)
    header = lines[len(comments)]
    assert header.startswith(HEADER + ",cell_angle_1 [rad]")
    # numpy: comment lines are skipped, then the header row
    data = np.loadtxt(path, delimiter=",", comments="#", skiprows=len(comments) + 1)
    assert data.shape == (r.n_rows, len(r))
    for j, name in enumerate(r.names):
        np.testing.assert_array_equal(data[:, j], r[name])  # 17 digits: exact round trip
    back = Result.from_csv(path)
    assert back.names == r.names and back.units == r.units
    for name in r.names:
        np.testing.assert_array_equal(back[name], r[name])
    assert back.info["exudyn_version"] == exudyn.__version__
    # what pandas.read_csv(comment="#") does: drop comment lines, first remaining row is the header
    body = "\n".join(ln for ln in lines if not ln.startswith("#"))
    rows = list(csv.reader(io.StringIO(body)))
    assert rows[0] == header.split(",")
    assert len(rows) == r.n_rows + 1


def test_pandas_reads_the_csv(tmp_path):
    pd = pytest.importorskip("pandas")
    r = small_result()
    r.to_csv(tmp_path / "r.csv")
    df = pd.read_csv(tmp_path / "r.csv", comment="#")
    assert list(df.columns) == ["time [s]", "tip_y [m]", "tip_angle [rad]"]
    np.testing.assert_array_equal(df["tip_y [m]"].to_numpy(), r["tip_y"])


def test_to_csv_is_atomic(tmp_path, monkeypatch):
    path = tmp_path / "out.csv"
    path.write_text("old content\n")
    r = small_result()

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(np, "savetxt", broken)
    with pytest.raises(OSError, match="disk full"):
        r.to_csv(path)
    # the old file is untouched and no temporary file is left behind
    assert path.read_text() == "old content\n"
    assert sorted(os.listdir(tmp_path)) == ["out.csv"]
    monkeypatch.undo()
    r.to_csv(path)
    assert path.read_text().startswith("# exudyn_atcm")
    assert sorted(os.listdir(tmp_path)) == ["out.csv"]


def test_to_csv_rejects_missing_directory(tmp_path):
    with pytest.raises(ValueError, match="directory"):
        small_result().to_csv(tmp_path / "missing" / "r.csv")
