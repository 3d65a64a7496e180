"""Reading, splitting and preprocessing measured records (exudyn_atcm.io.measurements)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from exudyn_atcm.io.file_checks import SuspectFileWarning
from exudyn_atcm.io.measurements import Record, preprocess, read_record


def write(tmp_path, text, name="rec.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_header_units_comments_and_column_names(tmp_path):
    path = write(tmp_path, "# instrument X\n# more\ntime [s],voltage [V],disp [um],temp [C]\n"
                           "0.0,1.0,10.0,20\n0.1,2.0,11.0,20\n0.2,3.0,12.5,21\n")
    rec = read_record(path, time="time", input="voltage [V]", output="disp", si=False)
    np.testing.assert_array_equal(rec.time, [0.0, 0.1, 0.2])
    np.testing.assert_array_equal(rec.input, [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(rec.output, [10.0, 11.0, 12.5])
    assert rec.units == {"time": "s", "input": "V", "output": "um"}
    assert rec.label("output") == "disp [um]"
    # default: a decimal multiple of s, V or m becomes SI, and the record says so
    rec = read_record(path, time="time", input="voltage [V]", output="disp")
    np.testing.assert_allclose(rec.output, [10e-6, 11e-6, 12.5e-6], rtol=1e-15)
    assert rec.units == {"time": "s", "input": "V", "output": "m"}
    assert rec.processing == ("output converted from um to m (x 1e-06)",)


def test_millisecond_millivolt_micrometre_record_is_read_in_si(tmp_path):
    """ms, mV and µm columns (an oscilloscope export): seconds, volts and metres, so t_split in s works."""
    path = write(tmp_path, "time [ms],voltage [mV],displacement [µm]\n0,0,0\n500,150000,2.5\n1000,-50000,-1\n")
    rec = read_record(path)
    np.testing.assert_allclose(rec.time, [0.0, 0.5, 1.0], rtol=1e-15)
    np.testing.assert_allclose(rec.input, [0.0, 150.0, -50.0], rtol=1e-15)
    np.testing.assert_allclose(rec.output, [0.0, 2.5e-6, -1e-6], rtol=1e-15)
    assert rec.units == {"time": "s", "input": "V", "output": "m"}
    assert len(rec.processing) == 3
    fit, held_out = rec.split(0.75)  # seconds: samples at 0 and 0.5 s fit, 1 s held out
    assert fit.n_samples == 2 and held_out.n_samples == 1
    with pytest.raises(ValueError, match="si must be True or False"):
        read_record(path, si="yes")


def test_blank_leading_column_and_indices_without_header(tmp_path):
    path = write(tmp_path, ",0,5,7\n,1,6,9\n,2,7,8\n")
    rec = read_record(path, time=0, input=2, output=1)
    np.testing.assert_array_equal(rec.input, [7, 9, 8])
    np.testing.assert_array_equal(rec.output, [5, 6, 7])
    assert rec.units["time"] == "s" and rec.units["input"] == ""


def test_whitespace_separated_with_blank_header_column(tmp_path):
    path = write(tmp_path, "\ttime [s]\tU [V]\tx [m]\n\t0\t100\t2\n\t1\t200\t3\n")
    rec = read_record(path)
    assert rec.units == {"time": "s", "input": "V", "output": "m"}
    np.testing.assert_array_equal(rec.output, [2, 3])


def test_nan_rows_are_dropped_and_counted(tmp_path):
    path = write(tmp_path, "t,u,y\n0,1,2\n1,nan,3\n2,3,\n3,4,5\n")
    with pytest.warns(RuntimeWarning, match=r"dropped 2 of 4 rows .* lines \[3, 4\]"):
        rec = read_record(path)
    np.testing.assert_array_equal(rec.time, [0, 3])
    assert "dropped 2 rows" in rec.processing[0]


@pytest.mark.parametrize(
    "text, kwargs, pattern",
    [
        ("t,u,y\n0,1,x\n1,2,3\n", {}, r"line 2, column 2 \(output\) must be a number, got 'x'"),
        ("t,u,y\n0,1,2\n", {}, r"1 valid rows, at least min_samples = 2"),
        ("t,u,y\n0,1,2\n1,2,3\n", {"output": "z"}, r"output = 'z' is not a column"),
        ("t,u,y\n0,1,2\n1,2,3\n", {"input": 5}, r"input = 5: .* has only 3 column"),
        ("t,u,y\n1,1,2\n0,2,3\n", {}, r"time must be strictly increasing, got time\[1\] = 0.0"),
    ],
)
def test_bad_files(tmp_path, text, kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        read_record(write(tmp_path, text), **kwargs)


def test_missing_file(tmp_path):
    with pytest.raises(ValueError, match="must be an existing text file"):
        read_record(tmp_path / "none.csv")


def test_split_by_time():
    rec = Record(np.arange(10.0), np.arange(10.0), np.arange(10.0) ** 2)
    first, second = rec.split(4.0)
    np.testing.assert_array_equal(first.time, [0, 1, 2, 3])
    np.testing.assert_array_equal(second.output, [16, 25, 36, 49, 64, 81])
    assert rec.split_index(4.5) == 5
    with pytest.raises(ValueError, match=r"t_split must lie in \(0.0, 9.0\]"):
        rec.split(0.0)


def test_preprocess_removes_known_drift_offset_and_reports():
    # a triangle input with period 2 s; a rate-independent response (u**2) plus a known
    # offset 3 and drift 0.5 per second: drift and offset must come back out exactly
    t = np.linspace(0.0, 8.0, 801)
    u = 1.0 - np.abs((t % 2.0) - 1.0)  # minima (u = 0) at t = 0, 2, 4, 6, 8
    clean = u**2
    rec = Record(t, u, clean + 3.0 + 0.5 * t, units={"time": "s", "input": "V", "output": "m"})
    out = preprocess(rec, drift=True, offset_samples=1)
    np.testing.assert_allclose(out.output, clean, atol=1e-12)
    assert any("drift of 0.5 m/s" in n for n in out.processing)
    assert any("offset of 3 m" in n for n in out.processing)


def test_preprocess_trim_and_decimate():
    t = np.arange(10.0)
    rec = Record(t, t, 2 * t)
    out = preprocess(rec, trim_start=2.0, decimate=3)
    # samples 2..9 remain (8), blocks of 3: means of (2,3,4), (5,6,7); 2 samples dropped
    np.testing.assert_array_equal(out.time, [3.0, 6.0])
    np.testing.assert_array_equal(out.output, [6.0, 12.0])
    assert "dropped the last 2 samples" in out.processing[-1]
    with pytest.raises(ValueError, match="decimate must be an integer >= 1"):
        preprocess(rec, decimate=0)
    with pytest.raises(ValueError, match="trim_start must be >= 0"):
        preprocess(rec, trim_start=-1)


# ---------------------------------------------------------------- issue 17: files that read but mislead
def test_blank_separated_header_with_units_gives_three_names(tmp_path):
    # the header splits at blanks into six words; the data has three columns
    path = write(tmp_path, "time [s]  voltage [V]  displacement [um]\n0.0 0 0.0\n0.5 500 10.0\n1.0 1000 22.5\n")
    rec = read_record(path)
    assert rec.names == {"time": "time", "input": "voltage", "output": "displacement"}
    np.testing.assert_array_equal(rec.input, [0.0, 500.0, 1000.0])
    np.testing.assert_allclose(rec.output, [0.0, 10e-6, 22.5e-6], rtol=1e-15)  # um -> m
    assert rec.units == {"time": "s", "input": "V", "output": "m"}
    # single blanks, and names holding a blank separated by two
    rec = read_record(write(tmp_path, "time [s] voltage [V] displacement [um]\n0 0 0\n1 500 10\n"), output="displacement")
    assert rec.units["output"] == "m" and rec.output[1] == pytest.approx(10e-6, rel=1e-15)
    rec = read_record(write(tmp_path, "time [s]  drive voltage [V]  tip displacement [um]\n0 0 0\n1 500 10\n"),
                      input="drive voltage")
    assert rec.names["input"] == "drive voltage" and rec.units["output"] == "m"


def test_header_with_more_names_than_columns_is_refused(tmp_path):
    with pytest.raises(ValueError, match=r"line 1: the header has 4 names .* the data rows have 3 columns"):
        read_record(write(tmp_path, "t,u,y,z\n0,1,2\n1,2,3\n"))


def test_a_name_that_matches_two_columns_is_refused(tmp_path):
    path = write(tmp_path, "time [s],voltage [V],voltage [kV],x [m]\n0,100,0.1,1\n1,200,0.2,2\n")
    with pytest.raises(ValueError, match=r"input = 'voltage' names 2 columns .* \(indices \[1, 2\]\)"):
        read_record(path, input="voltage", output="x")
    rec = read_record(path, input="voltage [kV]", output="x")  # the full header text is unique
    np.testing.assert_allclose(rec.input, [100.0, 200.0], rtol=1e-15)


def test_byte_order_marks(tmp_path):
    path = tmp_path / "bom.csv"
    path.write_bytes("\ufefftime [s],U [V],x [m]\n0,100,1\n1,200,2\n".encode())
    assert read_record(path).names["time"] == "time"  # a leading BOM is not text
    path.write_bytes("# exported\n\ufefftime [s],U [V],x [m]\n0,100,1\n1,200,2\n".encode())
    with pytest.raises(ValueError, match=r"line 2: column 1 of the header, .* \['U\+FEFF'\] \(a byte-order mark"):
        read_record(path)


def test_record_that_lost_most_rows_says_so(tmp_path):
    path = write(tmp_path, "t,u,y\n0,1,2\n1,nan,3\n2,,4\n3,4,\n4,5,6\n")  # 3 of 5 rows lost
    with pytest.warns(SuspectFileWarning, match=r"dropped 3 of 5 rows .* most of the record \(60 %\): check the columns"):
        rec = read_record(path)
    assert rec.n_samples == 2


def test_volt_input_that_looks_like_kilovolts_warns(tmp_path):
    with pytest.warns(SuspectFileWarning, match=r"'voltage \[V\]' is in V but peaks at \|U\| = 1.5 V, below 3 V"):
        read_record(write(tmp_path, "time [s],voltage [V],x [m]\n0,-0.5,0\n1,1.5,1e-5\n"))
    # written as kV: converted, no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", SuspectFileWarning)
        rec = read_record(write(tmp_path, "time [s],voltage [kV],x [m]\n0,-0.5,0\n1,1.5,1e-5\n"))
    np.testing.assert_allclose(rec.input, [-500.0, 1500.0], rtol=1e-15)


def test_record_checks_a_stated_row_count(tmp_path):
    path = write(tmp_path, "# data_rows: 3\nt,u,y\n0,100,2\n1,200,3\n")
    with pytest.raises(ValueError, match=r"states 3 data rows .* holds 2; it was cut off"):
        read_record(path)
