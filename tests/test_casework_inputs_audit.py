"""Inputs of cases refused or accepted as documented (user audit): empty list items, NumPy numbers,
a parameter set twice, a ``--cases-dir`` that does not exist."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.casework import CaseError, load_case
from exudyn_atcm.casework.parameters import Parameter
from exudyn_atcm.cli import main

from _cli_helpers import CASES


# ----------------------------------------------------------------------------- 1. empty list items
@pytest.mark.parametrize("text, where", [
    ("1,,2", "item 2 is empty (of 3)"),
    ("1,2,", "item 3 is empty (of 3)"),
    (",1", "item 1 is empty (of 2)"),
    ("1, ,2,,", "items 2, 4, 5 are empty (of 5)"),
])
def test_list_parameter_refuses_an_empty_item_naming_its_position(text, where):
    for default in ((0.0,), ()):  # also the list whose default is (): only an entirely empty text is empty
        parameter = Parameter("voltage_points", default, "V")
        with pytest.raises(ValueError) as info:
            parameter.parse(text)
        message = str(info.value)
        assert message.startswith("voltage_points must be comma-separated finite real numbers [V]")
        assert message.endswith(f"got {text!r}: {where}")
    assert Parameter("points", (), "V").parse("  ") == ()  # the documented exception stays
    assert Parameter("points", (), "V").parse(" 1 , 2 ") == (1.0, 2.0)


def test_run_with_an_empty_list_item_exits_2_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "b1"
    status = main(["run", "paper_discrete_preisach", "--set", "voltage_points=1,,2", "--no-plot", "--out", str(out)])
    err = capsys.readouterr().err
    assert status == 2
    assert len(err.strip().splitlines()) == 1
    assert "voltage_points must be comma-separated finite real numbers [V], got '1,,2': item 2 is empty (of 3)" in err
    assert not out.exists()


# ----------------------------------------------------------------------------- 2. NumPy numbers
def test_numpy_numbers_are_accepted_as_python_numbers():
    case = load_case(CASES / "paper_hysteresis_loop.py")
    params = case.resolve({"cycles": np.int64(3), "period": np.float32(0.5), "u_max": np.int32(1400)})
    assert params["cycles"] == 3 and type(params["cycles"]) is int
    assert params["period"] == 0.5 and type(params["period"]) is float
    assert params["u_max"] == 1400.0 and type(params["u_max"]) is float
    points = Parameter("v", (1.0,), "V").check(np.array([np.float32(0.25), np.int64(2)], dtype=object))
    assert points == (0.25, 2.0) and all(type(v) is float for v in points)


@pytest.mark.parametrize("name, value, message", [
    ("cycles", np.float64(2.0), "cycles must be an integer, got 2.0"),  # as 2.0: a float is not an int
    ("cycles", np.True_, "cycles must be an integer, got True"),  # as True: a bool is not a number
    ("period", np.False_, "period must be a finite real number [s], got False"),
    ("period", np.float64(np.inf), "period must be a finite real number [s], got inf"),
    ("cycles", np.int64(0), "cycles must be >= 1, got 0"),
])
def test_numpy_values_refused_like_python_ones_with_readable_messages(name, value, message):
    case = load_case(CASES / "paper_hysteresis_loop.py")
    with pytest.raises(CaseError) as info:
        case.resolve({name: value})
    assert f"case paper_hysteresis_loop: {message};" in str(info.value)
    assert "np." not in str(info.value)


def test_bools_are_not_numbers_in_a_list_either():
    parameter = Parameter("v", (1.0,), "V")
    for value in ((1.0, True), (np.float64(1.0), np.True_)):
        with pytest.raises(ValueError, match=r"^v must be comma-separated finite real numbers \[V\], got \(1\.0, True\)$"):
            parameter.check(value)


def test_numpy_bounds_and_defaults_are_shown_as_numbers():
    parameter = Parameter("y", np.float64(0.5), "m", maximum=np.int64(3))
    assert parameter.describe() == "y = 0.5 [m] (float, <= 3): "
    with pytest.raises(ValueError, match=r"^y must be <= 3 \[m\] \(every item\), got \(1\.0, 4\.0\)$"):
        parameter.check_range((np.float64(1.0), np.float64(4.0)))


# ----------------------------------------------------------------------------- 3. a parameter set twice
def test_parameter_set_twice_is_refused_naming_both_values(capsys, tmp_path):
    status = main(["run", "paper_stroke_table", "--set", "period=1", "--set", "cycles=2", "--set", "period=3",
                   "--no-plot", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert status == 2
    assert err.strip() == ("error: case paper_stroke_table: parameter 'period' is given twice (--set period=1 and "
                           "--set period=3); give each parameter once")
    assert not (tmp_path / "o").exists()
    case = load_case(CASES / "paper_stroke_table.py")
    with pytest.raises(CaseError, match="'cycles' is given twice"):
        case.resolve(["cycles=2", "cycles=2"])  # even the same value: one of them is a slip


# ----------------------------------------------------------------------------- 4. --cases-dir must exist
@pytest.mark.parametrize("argv", [["list", "--cases-dir", "{dir}"], ["--cases-dir", "{dir}", "list"],
                                  ["run", "my_table", "--cases-dir", "{dir}"],
                                  ["run", str(CASES / "paper_stroke_table.py"), "--cases-dir", "{dir}"]])
def test_cases_dir_that_does_not_exist_exits_2_naming_it(argv, tmp_path, capsys):
    folder = tmp_path / "case"
    status = main([a.replace("{dir}", str(folder)) for a in argv])
    err = capsys.readouterr().err
    assert status == 2
    assert err.strip() == (f"error: --cases-dir {folder}: does not exist (resolved: {folder.resolve()}); give an "
                           f"existing folder of case files")


def test_cases_dir_that_is_a_file_exits_2(tmp_path, capsys):
    path = tmp_path / "cases.txt"
    path.write_text("")
    assert main(["list", "--cases-dir", str(path)]) == 2
    assert f"--cases-dir {path}: is a file, not a folder" in capsys.readouterr().err
