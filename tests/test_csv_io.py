"""exudyn_atcm.read_csv: round trip of Result.to_csv, header format, malformed files."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from exudyn_atcm.io import read_csv, read_csv_header
from exudyn_atcm.io.file_checks import SuspectFileWarning
from exudyn_atcm.io.result import Result


def _result() -> Result:
    t = np.linspace(0.0, 1.0, 11)
    return Result(
        {"time": t, "voltage": 500.0 + 1000.0 * np.sin(t), "stroke": 4e-5 * t**1.5 - 4e-6 / 3.0},
        {"time": "s", "voltage": "V", "stroke": "m"},
        parameters={"period [s]": 1.0, "cycles [-]": 2, "rounded [-]": True, "case": "my case", "points [V]": [-500.0, 1500.0]},
        info={"exudyn_version": "1.13.6", "steps": 11, "solver": "static"},
    )


def test_round_trip_is_exact(tmp_path):
    original = _result()
    path = tmp_path / "r.csv"
    original.to_csv(path)
    back = read_csv(path)
    assert back.names == original.names
    assert back.units == original.units
    for name in original:
        np.testing.assert_array_equal(back[name], original[name])  # shortest round-trip text: exact
    assert back.parameters == original.parameters
    assert back.info == original.info
    # and a second round is identical text
    path2 = tmp_path / "r2.csv"
    back.to_csv(path2)
    assert path2.read_text() == path.read_text()


def test_header_row_and_comment_lines(tmp_path):
    path = tmp_path / "r.csv"
    _result().to_csv(path)
    lines = path.read_text().splitlines()
    first_data = next(i for i, line in enumerate(lines) if not line.startswith("#"))
    assert lines[first_data] == "time [s],voltage [V],stroke [m]"
    assert lines[0].startswith("# exudyn_atcm ")
    assert lines[1] == "# exudyn 1.13.6"
    header = read_csv_header(path)
    assert header.names == ["time", "voltage", "stroke"]
    assert header.units == ["s", "V", "m"]
    assert header.exudyn_version == "1.13.6"
    assert header.header_line == first_data + 1
    # readable by numpy (skiprows counts the comment lines too)
    data = np.loadtxt(path, delimiter=",", skiprows=first_data + 1)
    assert data.shape == (11, 3)


def test_empty_series_round_trip(tmp_path):
    r = Result({"time": [], "x": []}, {"time": "s", "x": "m"})
    path = tmp_path / "e.csv"
    r.to_csv(path)
    back = read_csv(path)
    assert back.names == ["time", "x"] and back.n_rows == 0


def _write(tmp_path, text: str):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    "text, line, words",
    [
        ("# only a comment\n", None, "no header row"),
        ("", None, "no header row"),
        ("# c\n0.0,1.0\n1.0,2.0\n", 2, "header row"),
        ("time [s],stroke\n0,1\n", 1, "column 2"),
        ("time [s],stroke [m]\n0,1\n1,2,3\n", 3, "3 cells"),
        ("time [s],stroke [m]\n0,1\n1\n", 3, "1 cells"),
        ("time [s],stroke [m]\n0,1\n1,abc\n", 3, "not a number"),
        ("time [s],time [s]\n0,1\n", 1, "duplicate"),
    ],
)
def test_malformed_files_are_refused_with_file_and_line(tmp_path, text, line, words):
    path = _write(tmp_path, text)
    with pytest.raises(ValueError) as info:
        read_csv(path)
    message = str(info.value)
    assert str(path) in message
    assert words in message
    if line is not None:
        assert f"line {line}:" in message


def test_missing_file(tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        read_csv(tmp_path / "nope.csv")


def test_hand_written_file_without_metadata(tmp_path):
    path = _write(tmp_path, "time [s], tip_y [m]\n0, 0\n0.5, 1e-3\n")
    r = read_csv(path)
    assert r.unit("tip_y") == "m"
    np.testing.assert_array_equal(r["tip_y"], [0.0, 1e-3])
    assert r.parameters == {} and r.info == {}


def test_file_cut_at_a_row_boundary_is_refused(tmp_path):
    # issue 9: a file cut after a complete row used to read as a shorter, valid result
    path = tmp_path / "r.csv"
    _result().to_csv(path)
    lines = path.read_text().splitlines(keepends=True)
    assert "# data_rows: 11\n" in lines
    cut = tmp_path / "cut.csv"
    cut.write_text("".join(lines[:-3]))  # 8 of 11 rows, ends with a complete line
    with pytest.raises(ValueError) as info:
        read_csv(cut)
    message = str(info.value)
    assert str(cut) in message and "states 11 data rows" in message and "holds 8" in message
    assert "cut off" in message
    appended = tmp_path / "appended.csv"
    appended.write_text("".join(lines) + lines[-1])
    with pytest.raises(ValueError, match="states 11 data rows .* holds 12"):
        read_csv(appended)
    assert read_csv(path).n_rows == 11  # the intact file reads


@pytest.mark.parametrize("cell, extra", [("nan", ""), ("inf", ""), ("-inf", ""), ("1e400", "too large for a float")])
def test_non_finite_numbers_are_refused_unless_asked(tmp_path, cell, extra):
    path = _write(tmp_path, f"time [s],stroke [m]\n0,1\n0.5,{cell}\n")
    with pytest.raises(ValueError) as info:
        read_csv(path)
    message = str(info.value)
    assert str(path) in message and "line 3:" in message and "(stroke)" in message
    assert "not a finite number" in message and "allow_nonfinite=True" in message and extra in message
    value = read_csv(path, allow_nonfinite=True)["stroke"][1]
    assert not np.isfinite(value)
    assert (np.isnan(value) if cell == "nan" else value == float(cell))


def test_unreadable_path_is_named_without_errno(tmp_path):
    with pytest.raises(ValueError) as info:
        read_csv(tmp_path)
    assert str(info.value) == f"{tmp_path}: is a directory, not a CSV file"


# ---------------------------------------------------------------- issue 17: files that read but mislead


def test_leading_byte_order_mark_is_not_part_of_the_first_name(tmp_path):
    path = tmp_path / "excel.csv"
    path.write_bytes("\ufefftime [s],stroke [m]\n0,1e-6\n0.5,2e-6\n".encode())
    r = read_csv(path)
    assert r.names == ["time", "stroke"]  # not "\ufefftime"
    np.testing.assert_array_equal(r["time"], [0.0, 0.5])


@pytest.mark.parametrize("name", ["\ufefftime", "ti\u200bme", "stroke\ufeff"])
def test_invisible_characters_in_a_name_are_refused(tmp_path, name):
    # a BOM after other text (two files joined), a zero-width space: the name looks right and is not
    path = _write(tmp_path, f"# joined\n{name} [s],x [m]\n0,1\n1,2\n")
    with pytest.raises(ValueError, match=r"line 2: column 1 of the header, .* contains invisible characters \['U\+"):
        read_csv(path)


def test_times_that_go_back_are_refused_and_repeats_warned(tmp_path):
    path = _write(tmp_path, "time [s],x [m]\n0,1\n0.5,2\n0.25,3\n1,4\n")
    with pytest.raises(ValueError, match=r"line 4: time \[s\] goes back from 0.5 to 0.25 \(1 such step\)"):
        read_csv(path)
    path = _write(tmp_path, "time [s],x [m]\n0,1\n0.5,2\n0.5,3\n1,4\n1,5\n")
    with pytest.warns(SuspectFileWarning, match=r"2 rows repeat the time of the row before \(first at line 4, time \[s\] = 0.5\)"):
        r = read_csv(path)
    assert r.n_rows == 5  # warned, not dropped


@pytest.mark.parametrize("peak, warns", [(1.5, True), (2.999, True), (-0.5, True), (3.0, False), (1500.0, False), (0.0, False)])
def test_a_volt_column_that_looks_like_kilovolts_warns(tmp_path, peak, warns):
    # 3 V = KV_SUSPECT_FRACTION (0.2 %) of the MFC P1's 1500 V: the drive's own kV threshold
    path = _write(tmp_path, f"time [s],voltage [V]\n0,0\n1,{peak!r}\n")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        read_csv(path)
    messages = [str(w.message) for w in caught if issubclass(w.category, SuspectFileWarning)]
    assert bool(messages) == warns
    if warns:
        assert "'voltage [V]' is in V but peaks at" in messages[0] and "kilovolts" in messages[0]


def test_hand_written_file_without_final_newline_warns(tmp_path):
    path = _write(tmp_path, "time [s],x [m]\n0,1\n0.5,2.5")
    with pytest.warns(SuspectFileWarning, match=r"last line \(3: '0.5,2.5'\) has no line end, so the file may be truncated"):
        r = read_csv(path)
    np.testing.assert_array_equal(r["x"], [1.0, 2.5])


def test_written_file_ending_inside_its_last_line_is_refused(tmp_path):
    path = tmp_path / "r.csv"
    _result().to_csv(path)
    cut = tmp_path / "cut.csv"
    cut.write_bytes(path.read_bytes()[:-1])  # only the final newline gone: the row count still matches
    last = len(path.read_text().splitlines())  # the last line's number
    with pytest.raises(ValueError, match=rf"line {last}: the file ends inside this line .* cut off"):
        read_csv(cut)
