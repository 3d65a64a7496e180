"""Result.to_csv writes only what read_csv reads back identically; anything else it refuses before writing."""

from __future__ import annotations

import math
import struct
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from exudyn_atcm.io import read_csv
from exudyn_atcm.io.result import Result
from exudyn_atcm.io.file_checks import SuspectFileWarning


def _identical(a, b) -> bool:
    """Same value and kind; floats bit for bit except that any NaN equals any NaN (independent of the package)."""
    if isinstance(a, float) and isinstance(b, float) and type(a) is type(b):
        return (math.isnan(a) and math.isnan(b)) or struct.pack("<d", a) == struct.pack("<d", b)
    if type(a) is not type(b):
        return False
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_identical(x, y) for x, y in zip(a, b))
    if isinstance(a, dict):
        return list(a) == list(b) and all(_identical(a[k], b[k]) for k in a)
    return a == b


def _same_series(original: Result, back: Result) -> None:
    assert back.names == original.names
    assert back.units == original.units
    for name in original:
        x, y = original[name], back[name]
        assert x.shape == y.shape
        assert np.array_equal(np.isnan(x), np.isnan(y))
        finite = ~np.isnan(x)
        assert np.array_equal(x[finite].view(np.int64), y[finite].view(np.int64)), name  # bit for bit, -0.0 too


def _plain_info(info: dict) -> dict:
    """Info as read back: an exudyn_version of None or 'unknown' means not known (no key)."""
    return {k: v for k, v in info.items() if not (k == "exudyn_version" and v in (None, "unknown"))}


def _check(result: Result, tmp_path_factory) -> bool:
    """Write; True if written (and read back identically), False if refused (and nothing written)."""
    path = tmp_path_factory.mktemp("rt") / "r.csv"
    try:
        result.to_csv(path)
    except ValueError:
        assert not path.exists()
        return False
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SuspectFileWarning)  # random [V] columns look like kV: beside the point here
        back = read_csv(path, allow_nonfinite=True)
    _same_series(result, back)
    assert _identical(back.parameters, result.parameters), (back.parameters, result.parameters)
    back_info = dict(back.info)
    expected = _plain_info(result.info)
    assert set(back_info) == set(expected)
    assert all(_identical(back_info[k], expected[k]) for k in expected), (back_info, expected)
    return True


_scalars = st.none() | st.booleans() | st.integers(-10**12, 10**12) | st.floats(allow_nan=True) | st.text(max_size=12)
_values = st.recursive(
    _scalars,
    lambda inner: st.lists(inner, max_size=3) | st.tuples(inner, inner)
    | st.dictionaries(st.text(max_size=4) | st.integers(-5, 5), inner, max_size=3),
    max_leaves=6,
)


@st.composite
def _any_result(draw):
    names = draw(st.lists(st.text(min_size=1, max_size=8), min_size=1, max_size=3, unique=True))
    n = draw(st.integers(0, 4))
    series = {name: draw(st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=n, max_size=n)) for name in names}
    units = {name: draw(st.text(max_size=6)) for name in names}
    parameters = draw(st.dictionaries(st.text(max_size=10), _values, max_size=4))
    info = draw(st.dictionaries(st.text(max_size=10), _values, max_size=3))
    if draw(st.booleans()):
        info["exudyn_version"] = draw(st.none() | st.text(max_size=8))
    try:
        return Result(series, units, parameters=parameters, info=info)
    except ValueError:
        assume(False)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(_any_result())
def test_anything_written_reads_back_identically_or_is_refused(tmp_path_factory, result):
    _check(result, tmp_path_factory)


_word = st.text(alphabet="abcdefghijklmnopqrstuvwxyz_0123456789.", min_size=1, max_size=8)
_unit = st.sampled_from(["s", "V", "m", "-", "rad", "N m^2", "kg/m^3", "", "µm"])
_ordinary = st.none() | st.booleans() | st.integers(-10**6, 10**6) | st.floats(allow_nan=False) | st.text(max_size=12) \
    | st.lists(st.floats(allow_nan=False, allow_infinity=False), max_size=3)


@st.composite
def _ordinary_result(draw):
    names = draw(st.lists(_word.filter(lambda w: w.strip(".") and w != "time"), min_size=1, max_size=3, unique=True))
    n = draw(st.integers(0, 5))
    series = {name: draw(st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=n, max_size=n)) for name in names}
    keys = st.builds(lambda w, u: f"{w} [{u}]" if u else w, _word.filter(lambda w: not w.startswith("info.") and w != "data_rows"), _unit)
    return Result(series, {name: draw(_unit) for name in names},
                  parameters=draw(st.dictionaries(keys, _ordinary, max_size=4)),
                  info={"exudyn_version": "1.13.6", **draw(st.dictionaries(_word, _ordinary, max_size=3))})


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(_ordinary_result())
def test_ordinary_results_are_always_written_and_read_back(tmp_path_factory, result):
    # names and units of letters, SI units, numbers, strings (including '1.0' and 'None'), lists: never refused
    assert _check(result, tmp_path_factory)


def _series():
    return {"time": [0.0, 1.0], "x": [1e-6, 2e-6]}


@pytest.mark.parametrize(
    "units, parameters, info, words",
    [
        ({"time": "s", "x": "m,m"}, {}, {}, r"series 'x' with unit 'm,m' .* contains one of , \[ \]"),
        ({"time": "s", "x": "m]"}, {}, {}, r"series 'x' with unit 'm\]' .* contains one of , \[ \]"),
        ({"time": "s", "x": "m\n"}, {}, {}, r"series 'x' .* line break"),
        ({"time": "s", "x": "\ufeffm"}, {}, {}, r"invisible characters \['U\+FEFF'\]"),
        ({"time": "s", "x": " m"}, {}, {}, r"begins or ends with blanks"),
        ({"time": "s", "x": "m"}, {"data_rows": 3}, {}, r"parameter 'data_rows' cannot be written to CSV: .* reserved"),
        ({"time": "s", "x": "m"}, {"info.steps": 3}, {}, r"parameter 'info.steps' .* reserved"),
        ({"time": "s", "x": "m"}, {"a: b": 1}, {}, r"parameter 'a: b' .* contains ': '"),
        ({"time": "s", "x": "m"}, {"a\nb": 1}, {}, r"line break"),
        ({"time": "s", "x": "m"}, {"": 1}, {}, r"parameter '' .* it is empty"),
        ({"time": "s", "x": "m"}, {1: 1}, {}, r"parameter names must be strings"),
        ({"time": "s", "x": "m"}, {"f": object()}, {}, r"parameter 'f' = <object .* cannot be written to CSV so that read_csv reads it back"),
        ({"time": "s", "x": "m"}, {"v": [float("nan")]}, {}, r"parameter 'v' = \[nan\]"),
        ({"time": "s", "x": "m"}, {}, {"solver": {1, 2}}, r"info 'solver' = \{1, 2\}"),
        ({"time": "s", "x": "m"}, {}, {"exudyn_version": "1.13\n"}, r"exudyn_version'\] must be a one-line version string"),
    ],
)
def test_what_read_csv_cannot_read_back_is_refused_before_writing(tmp_path, units, parameters, info, words):
    result = Result(_series(), units, parameters=parameters, info=info)
    path = tmp_path / "r.csv"
    with pytest.raises(ValueError, match=words):
        result.to_csv(path)
    assert not path.exists()


def test_strings_that_look_like_other_values_are_quoted_and_read_back_as_strings(tmp_path):
    parameters = {"voltage": "1000.0", "hysteresis": "None", "flag": "True", "note": "two\nlines", "list": "[1, 2]",
                  "plain": "my case", "empty": "", "number": 1.0, "none": None, "arr": np.array([1.5, 2.0]), "i": np.int64(3)}
    path = tmp_path / "r.csv"
    Result(_series(), {"time": "s", "x": "m"}, parameters=parameters).to_csv(path)
    text = path.read_text()
    assert "# voltage: '1000.0'\n" in text and "# hysteresis: 'None'\n" in text and "# note: 'two\\nlines'\n" in text
    assert "# plain: my case\n" in text and "# number: 1.0\n" in text  # ordinary text stays unquoted
    back = read_csv(path).parameters
    assert back["voltage"] == "1000.0" and back["hysteresis"] == "None" and back["flag"] == "True"
    assert back["note"] == "two\nlines" and back["list"] == "[1, 2]" and back["plain"] == "my case" and back["empty"] == ""
    assert back["number"] == 1.0 and back["none"] is None
    assert back["arr"] == [1.5, 2.0] and back["i"] == 3 and type(back["i"]) is int  # numpy as Python numbers and lists


def test_a_time_series_that_goes_back_is_refused_and_one_that_repeats_is_written(tmp_path):
    with pytest.raises(ValueError, match=r"series 'time' goes back from 1.0 to 0.5 at row 2; read_csv refuses"):
        Result({"time": [0.0, 1.0, 0.5]}, {"time": "s"}).to_csv(tmp_path / "back.csv")
    assert not (tmp_path / "back.csv").exists()
    Result({"time": [0.0, 1.0, 1.0]}, {"time": "s"}).to_csv(tmp_path / "repeat.csv")
    with pytest.warns(SuspectFileWarning, match="repeat the time"):
        assert read_csv(tmp_path / "repeat.csv")["time"].tolist() == [0.0, 1.0, 1.0]


def test_a_result_without_series_is_refused(tmp_path):
    with pytest.raises(ValueError, match="without series cannot be written"):
        Result({}, {}).to_csv(tmp_path / "e.csv")
