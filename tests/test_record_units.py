"""Units for a record's columns: given to read_record for files that state none, checked against the ones they state."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.errors import SuspectFileWarning
from exudyn_atcm.io.measurements import read_record
from exudyn_atcm.io.units import is_length, merge_units, same_unit, si_scale

# a record in SI: 0.5 ms steps, volts, a displacement of tens of micrometres
T_SI = np.array([0.0, 5e-4, 1e-3, 1.5e-3])
U_SI = np.array([0.0, 400.0, 800.0, 1200.0])
Y_SI = np.array([0.0, 4.5e-6, 11e-6, 19.25e-6])


def write(tmp_path, text, name="rec.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def file_in(t_factor, u_factor, y_factor, header=""):
    rows = "".join(f"{float(t / t_factor)!r},{float(u / u_factor)!r},{float(y / y_factor)!r}\n" for t, u, y in zip(T_SI, U_SI, Y_SI))
    return header + rows


def test_headerless_columns_take_the_units_given_and_are_converted_to_si(tmp_path):
    path = write(tmp_path, file_in(1e-3, 1.0, 1e-6))  # ms, V, um; no header
    rec = read_record(path, units={"time": "ms", "input": "V", "output": "um"})
    np.testing.assert_allclose(rec.time, T_SI, rtol=1e-12)
    np.testing.assert_allclose(rec.input, U_SI, rtol=1e-12)
    np.testing.assert_allclose(rec.output, Y_SI, rtol=1e-12)
    assert rec.units == {"time": "s", "input": "V", "output": "m"}
    assert "output unit 'um' given (units=); the file states none" in rec.processing
    assert "output converted from um to m (x 1e-06)" in rec.processing
    assert "time converted from ms to s (x 0.001)" in rec.processing
    # si=False keeps the file's numbers with the units given
    raw = read_record(path, units={"time": "ms", "input": "V", "output": "um"}, si=False)
    np.testing.assert_allclose(raw.output, Y_SI / 1e-6, rtol=1e-12)
    assert raw.units == {"time": "ms", "input": "V", "output": "um"}


def test_a_header_without_units_takes_them_from_the_argument(tmp_path):
    path = write(tmp_path, file_in(1.0, 1e3, 1e-3, header="t,u,y\n"))  # s, kV, mm
    rec = read_record(path, units={"input": "kV", "output": "mm"})
    np.testing.assert_allclose(rec.input, U_SI, rtol=1e-12)
    np.testing.assert_allclose(rec.output, Y_SI, rtol=1e-12)
    assert rec.units == {"time": "s", "input": "V", "output": "m"}
    assert "time unit not stated, taken as s" in rec.processing


def test_units_given_confirm_the_header_or_are_refused_when_they_differ(tmp_path):
    path = write(tmp_path, file_in(1.0, 1.0, 1e-6, header="time [s],voltage [V],disp [um]\n"))
    plain = read_record(path)
    confirmed = read_record(path, units={"output": "µm", "time": "s"})  # µm and um are one unit
    np.testing.assert_array_equal(confirmed.output, plain.output)
    assert confirmed.processing == plain.processing
    with pytest.raises(ValueError, match=r"units\['output'\] = 'mm' conflicts with the unit the file states for the "
                                         r"output column 'disp \[um\]' \('um'\)"):
        read_record(path, units={"output": "mm"})


def test_without_units_the_output_unit_is_unknown_and_said(tmp_path):
    rec = read_record(write(tmp_path, file_in(1.0, 1.0, 1.0)))
    assert rec.units == {"time": "s", "input": "", "output": ""}
    assert any(n.startswith("output unit unknown") for n in rec.processing)
    assert any(n.startswith("input unit unknown") for n in rec.processing)


@pytest.mark.parametrize("units, pattern", [
    ("um", r"units must be a mapping such as \{'output': 'um'\}, got 'um'"),
    ({"displacement": "um"}, r"units: 'displacement' is not a column of a record; the keys are time, input, output"),
    ({"time": "V"}, r"units\['time'\] must be a unit of time \(s, ms, .*\), got 'V'"),
    ({"output": ""}, r"units\['output'\] must be a non-empty unit string"),
    ({"output": "[um]"}, r"units\['output'\] must be a non-empty unit string such as 'um' \(no brackets\), got '\[um\]'"),
])
def test_bad_units_arguments_are_refused(tmp_path, units, pattern):
    with pytest.raises(ValueError, match=pattern):
        read_record(write(tmp_path, file_in(1.0, 1.0, 1.0)), units=units)


def test_volts_given_for_a_column_in_kilovolts_warn_like_a_header(tmp_path):
    path = write(tmp_path, "0,-0.5,0\n1,1.5,1e-5\n")
    with pytest.warns(SuspectFileWarning, match=r"'input \[V\]' is in V but peaks at \|U\| = 1.5 V"):
        read_record(path, units={"input": "V", "output": "m"})


def test_unit_table():
    assert si_scale("cm") == (1e-2, "m") and si_scale("µε") == (1e-6, "-") and si_scale("furlong") is None
    assert same_unit("um", "μm") and same_unit("µm", "um") and not same_unit("um", "mm") and not same_unit("", "m")
    assert is_length("nm") and not is_length("-") and not is_length("")
    merged, notes = merge_units({"time": "", "input": "V", "output": ""}, {"output": "µε"}, {}, "f")
    assert merged == {"time": "s", "input": "V", "output": "µε"} and len(notes) == 2
