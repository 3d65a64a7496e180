"""Byte-truncation sweep of both readers: a file cut at any byte never reads back silently wrong.

Every prefix of a small file is read with :func:`read_csv` and :func:`read_record`.  Each cut
must either raise a ``ValueError``, give a :class:`SuspectFileWarning`, or read back exactly
the first rows of the intact file (a cut at a row boundary of a file that states no row
count cannot be told from a shorter file).  The silent prefixes are counted and compared
with the row boundaries found independently in the bytes.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from exudyn_atcm.io import read_csv
from exudyn_atcm.io.file_checks import SuspectFileWarning
from exudyn_atcm.io.measurements import read_record
from exudyn_atcm.io.result import Result

#: Values chosen so that cutting them gives other valid numbers: -4e-06 -> -4e-0 (= -4),
#: 1.5e+05 -> 1.5e+0 (= 1.5), 0.000123 -> 0.0001, 1000 -> 10.
TIME = [0.0, 0.25, 0.5, 0.75]
VOLTAGE = [-500.0, 1000.0, 1500.0, 1000.0]
STROKE = [-4e-06, 1.5e-05, 0.000123, 2.5e-05]


def _result() -> Result:
    return Result({"time": TIME, "voltage": VOLTAGE, "stroke": STROKE}, {"time": "s", "voltage": "V", "stroke": "m"},
                  parameters={"period [s]": 1.0}, info={"exudyn_version": "1.13.6"})


def _outcome(read, path):
    """'error', 'warning' or ('read', value) for one cut file."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            value = read(path)
        except ValueError:
            return "error"
    if any(issubclass(w.category, SuspectFileWarning) for w in caught):
        return "warning"
    return ("read", value)


def _row_boundaries(data: bytes, header_end: int) -> dict[int, int]:
    """Cut positions just after a complete data row (or the header): position -> rows kept."""
    ends = [i + 1 for i, b in enumerate(data) if b == ord("\n") and i + 1 >= header_end]
    return {end: n for n, end in enumerate(ends)}


def _sweep(tmp_path, data: bytes, read, check_prefix):
    """Outcomes of every proper prefix of ``data``; asserts that silent reads are correct prefixes."""
    silent: dict[int, int] = {}
    counts = {"error": 0, "warning": 0}
    path = tmp_path / "cut.csv"
    for k in range(len(data)):
        path.write_bytes(data[:k])
        outcome = _outcome(read, path)
        if isinstance(outcome, str):
            counts[outcome] += 1
            continue
        rows = check_prefix(outcome[1])  # raises AssertionError if any value is wrong
        silent[k] = rows
    return silent, counts


def _csv_prefix(result: Result) -> int:
    assert result.names == ["time", "voltage", "stroke"]
    assert result.units == {"time": "s", "voltage": "V", "stroke": "m"}
    n = result.n_rows
    for name, values in (("time", TIME), ("voltage", VOLTAGE), ("stroke", STROKE)):
        np.testing.assert_array_equal(result[name], values[:n], err_msg=f"{name} after a cut")
    return n


def _record_prefix(record) -> int:
    n = record.n_samples
    np.testing.assert_array_equal(record.time, TIME[:n])
    np.testing.assert_array_equal(record.input, VOLTAGE[:n])
    np.testing.assert_array_equal(record.output, STROKE[:n])
    return n


def _written(tmp_path) -> bytes:
    path = tmp_path / "full.csv"
    _result().to_csv(path)
    return path.read_bytes()


def test_read_csv_refuses_every_cut_of_a_file_with_a_row_count(tmp_path):
    data = _written(tmp_path)
    assert b"# data_rows: 4\n" in data
    silent, counts = _sweep(tmp_path, data, read_csv, _csv_prefix)
    assert silent == {}, f"cuts read without complaint: {silent}"
    assert counts["error"] == len(data)
    assert _csv_prefix(read_csv(tmp_path / "full.csv")) == 4  # the intact file reads


def test_read_csv_hand_written_file_cuts_are_refused_warned_or_a_correct_prefix(tmp_path):
    data = b"".join(line for line in _written(tmp_path).splitlines(keepends=True) if not line.startswith(b"# data_rows"))
    header_end = data.index(b"time [s]")
    header_end = data.index(b"\n", header_end) + 1
    silent, counts = _sweep(tmp_path, data, read_csv, _csv_prefix)
    # silent reads are exactly the cuts at row boundaries (after the header and rows 1..3)
    assert silent == {end: n for end, n in _row_boundaries(data, header_end).items() if end < len(data)}
    assert sorted(silent.values()) == [0, 1, 2, 3]
    assert counts["warning"] > 0 and counts["error"] > 0
    assert counts["warning"] + counts["error"] + len(silent) == len(data)


def test_read_record_refuses_every_cut_of_a_file_with_a_row_count(tmp_path):
    data = _written(tmp_path)
    silent, counts = _sweep(tmp_path, data, read_record, _record_prefix)
    assert silent == {}, f"cuts read without complaint: {silent}"


@pytest.mark.parametrize("separator", [",", "\t", "  "])
def test_read_record_hand_written_file_cuts_are_refused_warned_or_a_correct_prefix(tmp_path, separator):
    lines = ["# bench test", separator.join(["time [s]", "voltage [V]", "stroke [m]"])]
    lines += [separator.join(repr(v) for v in row) for row in zip(TIME, VOLTAGE, STROKE)]
    data = ("\n".join(lines) + "\n").encode()
    header_end = data.index(b"\n", data.index(b"time [s]")) + 1
    silent, counts = _sweep(tmp_path, data, read_record, _record_prefix)
    # read_record needs 2 rows (min_samples): the boundaries after rows 2 and 3 read silently
    boundaries = _row_boundaries(data, header_end)
    assert silent == {end: n for end, n in boundaries.items() if n >= 2 and end < len(data)}
    assert counts["warning"] > 0


def test_the_sweep_file_has_cuts_that_would_read_as_other_numbers():
    """The sweep is meaningful: prefixes of its numbers parse as different numbers."""
    assert float("-4e-0") == -4.0 and float("0.0001") != 0.000123 and float("10") != 1000.0 and float("1.") == 1.0
