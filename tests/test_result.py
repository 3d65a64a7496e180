"""Issue 3, part 1: the Result object and its CSV export."""

from __future__ import annotations

import csv
import io
import os

import numpy as np
import pytest

import exudyn
from exudyn_atcm import __version__
from exudyn_atcm.io import read_csv
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.io.result import Result
from exudyn_atcm.solve import simulate

from _actuator_geometries import REF_A

HEADER = ("time [s],actuator.voltage [V],actuator.strain [-],actuator.stroke [m],actuator.base_x [m],"
          "actuator.base_y [m],actuator.tip_x [m],actuator.tip_y [m],actuator.base_angle [rad],actuator.tip_angle [rad]")


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
    assert r.names[:10] == ["time", "actuator.voltage", "actuator.strain", "actuator.stroke", "actuator.base_x",
                            "actuator.base_y", "actuator.tip_x", "actuator.tip_y", "actuator.base_angle",
                            "actuator.tip_angle"]
    assert r.names[10:] == ["actuator.cell_angle_1", "actuator.cell_angle_2", "actuator.cell_angle_3"]
    assert [r.unit(n) for n in r.names[:10]] == ["s", "V", "-", "m", "m", "m", "m", "m", "rad", "rad"]
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
    assert header.startswith(HEADER + ",actuator.cell_angle_1 [rad]")
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
    import errno

    import exudyn_atcm.io.atomic as atomic

    path = tmp_path / "out.csv"
    path.write_text("old content\n")
    r = small_result()

    def broken(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device", str(args[0]))

    monkeypatch.setattr(atomic.os, "replace", broken)
    with pytest.raises(OSError) as info:
        r.to_csv(path)
    # the user sees the file asked for and the reason, not the errno text or the temporary name
    message = str(info.value)
    assert "out.csv" in message and "the disk is full" in message
    assert ".tmp_" not in message and "Errno" not in message
    # the old file is untouched and no temporary file is left behind
    assert path.read_text() == "old content\n"
    assert sorted(os.listdir(tmp_path)) == ["out.csv"]
    monkeypatch.undo()
    r.to_csv(path)
    assert path.read_text().startswith("# exudyn_atcm")
    assert sorted(os.listdir(tmp_path)) == ["out.csv"]


def test_to_csv_creates_missing_directory(tmp_path):
    # issue 9: Result.to_csv("out/run.csv") failed after the simulation when out/ was missing
    target = tmp_path / "out" / "deeper" / "run.csv"
    small_result().to_csv(target)
    assert read_csv(target)["tip_y"].tolist() == small_result()["tip_y"].tolist()


@pytest.mark.skipif(os.geteuid() == 0 if hasattr(os, "geteuid") else True,
                    reason="root can write into read-only directories")
def test_to_csv_into_read_only_directory_says_what_and_why(tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        with pytest.raises(OSError) as info:
            small_result().to_csv(locked / "run.csv")
    finally:
        locked.chmod(0o700)
    message = str(info.value)
    assert "run.csv" in message and "permission denied" in message
    assert ".tmp_" not in message and "Errno" not in message


def test_write_error_messages_name_target_and_reason(tmp_path, monkeypatch):
    """Errno text and temporary names are replaced by the target and the reason (read-only file system)."""
    import errno
    import tempfile

    import exudyn_atcm.io.atomic as atomic

    def refuse(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system", str(tmp_path / ".tmp_abc123.csv"))

    monkeypatch.setattr(tempfile, "mkstemp", refuse)
    with pytest.raises(atomic.WriteError) as info:
        small_result().to_csv(tmp_path / "run.csv")
    message = str(info.value)
    assert message == f"cannot write {str(tmp_path / 'run.csv')!r} into {str(tmp_path)!r}: the file system is read-only"


def test_csv_floats_are_shortest_round_trip_text(tmp_path):
    # 19999 * 1e-4 is 1.9999000000000002 in floats; the file must show what the number carries
    r = Result({"time": [0.0, 1e-4, 1.9999, 2.0], "x": [0.1, -4e-06, 1 / 3, 1e-300]},
               {"time": "s", "x": "m"})
    r.to_csv(tmp_path / "r.csv")
    lines = (tmp_path / "r.csv").read_text().splitlines()
    data = lines[lines.index("time [s],x [m]") + 1:]
    assert data == ["0.0,0.1", "0.0001,-4e-06", "1.9999,0.3333333333333333", "2.0,1e-300"]
    back = read_csv(tmp_path / "r.csv")
    assert back["x"].tolist() == r["x"].tolist()
