"""read_record on MATLAB files: plain arrays and real-time systems' struct exports (issue 28, part 7).

The files are written here with scipy.io.savemat (struct arrays as numpy structured arrays of
objects, as MATLAB's loaders give them back); the record read must be the arrays written,
converted to SI where a unit says so, with the text reader's rules for NaN rows and errors.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.io

from exudyn_atcm.errors import SuspectFileWarning
from exudyn_atcm.io import matlab_hdf5
from exudyn_atcm.io.measurements import read_record

N = 50
T = np.linspace(0.0, 0.049, N)  # [s]
U = 750.0 * (1.0 - np.cos(2 * math.pi * 20.0 * T))  # [V]
Y_UM = 40.0 * (U / 1500.0) ** 1.4  # [um]


def save(tmp_path, variables, name="rec.mat", **kwargs):
    path = tmp_path / name
    scipy.io.savemat(str(path), variables, **kwargs)
    return path


def struct_array(fields, rows):
    """A 1 x k MATLAB struct array: a structured numpy array of objects."""
    array = np.zeros((1, len(rows)), dtype=[(f, object) for f in fields])
    for k, row in enumerate(rows):
        array[0, k] = tuple(row)
    return array


def dspace_export():
    """A ControlDesk-style export: X = time, Y(k) = channels with names (model paths) and units."""
    x = struct_array(("Name", "Type", "Data", "Unit"), [("Time", "Time", T, "s")])
    y = struct_array(("Name", "Type", "Raster", "Data", "Unit", "XIndex"), [
        ("Model Root/amplifier/U_out", "Value", "Task 1", U, "V", 1.0),
        ("Model Root/laser/x", "Value", "Task 1", Y_UM, "um", 1.0),
        ("Model Root/laser/x_raw", "Value", "Task 1", np.round(Y_UM * 100).astype(np.int16), "", 1.0),
    ])
    export = np.zeros((1, 1), dtype=[("X", object), ("Y", object), ("Description", object)])
    export[0, 0] = (x, y, "hysteresis run 3")
    return export


def assert_record(rec, y_factor=1e-6):
    np.testing.assert_allclose(rec.time, T, rtol=1e-15)
    np.testing.assert_allclose(rec.input, U, rtol=1e-15)
    np.testing.assert_allclose(rec.output, Y_UM * y_factor, rtol=1e-15)


def test_a_matrix_of_columns_with_units_given(tmp_path):
    path = save(tmp_path, {"data": np.column_stack([T, U, Y_UM])})
    rec = read_record(path, units={"input": "V", "output": "um"})
    assert_record(rec)
    assert rec.units == {"time": "s", "input": "V", "output": "m"}
    assert rec.names == {"time": "data(:,1)", "input": "data(:,2)", "output": "data(:,3)"}
    assert rec.processing[0] == ("MATLAB file, the numeric variables: time = channel 0 'data(:,1)' (data(:,1)), "
                                 "input = channel 1 'data(:,2)' (data(:,2)), output = channel 2 'data(:,3)' (data(:,3))")
    assert "output converted from um to m (x 1e-06)" in rec.processing
    # a matrix of rows (3 x N) reads the same, its rows the channels; by name or index
    rows = save(tmp_path, {"data": np.vstack([T, U, Y_UM])}, name="rows.mat")
    rec = read_record(rows, time="data(1,:)", input=1, output="DATA(3,:)", units={"output": "um"})
    assert_record(rec)


def test_named_vectors_by_name_or_index_and_a_version_4_file(tmp_path):
    variables = {"fs": 1000.0, "t": T, "U": U, "x": Y_UM.reshape(-1, 1), "comment": "run 3"}
    path = save(tmp_path, variables)
    rec = read_record(path, time="t", input="u", output="x", units={"output": "um"})  # names case-insensitive
    assert_record(rec)
    assert rec.units["input"] == "" and rec.names == {"time": "t", "input": "U", "output": "x"}
    assert_record(read_record(path, time=0, input=1, output=2, units={"output": "um"}))  # fs (a scalar) is no channel
    v4 = save(tmp_path, {"t": T, "U": U, "x": Y_UM}, name="v4.mat", format="4")
    assert_record(read_record(v4, units={"output": "um"}))


def test_the_fields_of_a_plain_struct(tmp_path):
    path = save(tmp_path, {"meas": {"t": T, "u": U, "y": Y_UM, "note": "bench"}})
    rec = read_record(path, time="t", input="u", output="y", units={"output": "um"})
    assert_record(rec)
    assert rec.processing[0].startswith("MATLAB file, the struct 'meas': time = channel 0 't' (meas.t)")


def test_a_dspace_style_export_with_units_and_path_names(tmp_path):
    path = save(tmp_path, {"run3": dspace_export(), "other": np.eye(3)})
    rec = read_record(path, input="U_out", output="Model Root/laser/x")  # the last part of a path, or the path
    assert_record(rec)
    assert rec.units == {"time": "s", "input": "V", "output": "m"}  # the export's Unit fields, converted to SI
    assert rec.names["output"] == "Model Root/laser/x"
    assert rec.processing[0] == ("MATLAB file, the X/Y export 'run3': time = channel 0 'Time' (run3.X(1).Data), "
                                 "input = channel 1 'Model Root/amplifier/U_out' (run3.Y(1).Data), "
                                 "output = channel 2 'Model Root/laser/x' (run3.Y(2).Data)")
    # default channels 0, 1, 2: time, Y(1), Y(2)
    assert_record(read_record(path))
    # an integer channel of unknown unit, given one: converted like the header's units
    raw = read_record(path, output=3, units={"output": "nm"})
    np.testing.assert_allclose(raw.output, np.round(Y_UM * 100) * 1e-9, rtol=1e-15)
    with pytest.raises(ValueError, match=r"units\['output'\] = 'mm' conflicts with the unit the file states for the "
                                         r"output column 'Model Root/laser/x \[um\]' \('um'\)"):
        read_record(path, output="x", units={"output": "mm"})


def test_simulink_structure_with_time(tmp_path):
    signals = struct_array(("values", "dimensions", "label", "blockName"), [
        (np.column_stack([U, 2 * U]), 2.0, "voltage", "model/Scope"),
        (Y_UM, 1.0, "", "model/Laser"),
    ])
    scope = np.zeros((1, 1), dtype=[("time", object), ("signals", object), ("blockName", object)])
    scope[0, 0] = (T, signals, "model/Scope")
    path = save(tmp_path, {"ScopeData": scope})
    rec = read_record(path, input="voltage(:,1)", output="model/Laser", units={"output": "um"})
    assert_record(rec)
    assert rec.names == {"time": "time", "input": "voltage(:,1)", "output": "model/Laser"}
    doubled = read_record(path, input=2, output=3, units={"output": "um"})
    np.testing.assert_allclose(doubled.input, 2 * U, rtol=1e-15)


def test_nan_samples_are_dropped_and_counted_like_text_rows(tmp_path):
    y = Y_UM.copy()
    y[[3, 7]] = np.nan
    u = U.copy()
    u[20] = np.inf
    path = save(tmp_path, {"t": T, "u": u, "y": y})
    with pytest.warns(SuspectFileWarning, match=r"dropped 3 of 50 samples with NaN, infinite or empty cells .* "
                                                r"\(first at sample indices \[3, 7, 20\]\)"):
        rec = read_record(path, units={"output": "um"})
    keep = np.ones(N, bool)
    keep[[3, 7, 20]] = False
    np.testing.assert_allclose(rec.output, Y_UM[keep] * 1e-6, rtol=1e-15)
    assert "dropped 3 samples with non-finite values" in rec.processing


def test_channels_that_are_not_there_or_not_alike_are_refused(tmp_path):
    path = save(tmp_path, {"run3": dspace_export()})
    with pytest.raises(ValueError, match=r"output = 'y' is not a channel of .*; channels: 0: 'Time', "
                                         r"1: 'Model Root/amplifier/U_out', 2: 'Model Root/laser/x', 3: 'Model Root/laser/x_raw'"):
        read_record(path, output="y")
    with pytest.raises(ValueError, match=r"input = 7: .* has only 4 channel\(s\)"):
        read_record(path, input=7)
    with pytest.raises(ValueError, match=r"output must be a channel name or an index >= 0, got -1"):
        read_record(path, output=-1)
    two = save(tmp_path, {"a": dspace_export(), "b": dspace_export()}, name="two.mat")
    with pytest.raises(ValueError, match=r"holds 2 recorder exports \(a, b\); choose one with variable="):
        read_record(two)
    assert_record(read_record(two, variable="b"))
    with pytest.raises(ValueError, match=r"variable = 'c' is not a variable of .*; its variables: a \(X/Y export\), "
                                         r"b \(X/Y export\)"):
        read_record(two, variable="c")
    with pytest.raises(ValueError, match=r"the channels chosen have different lengths: time 't' 50, input 'short' 3"):
        read_record(save(tmp_path, {"t": T, "short": U[:3], "y": Y_UM}, name="short.mat"))
    with pytest.raises(ValueError, match=r"no numeric channel found in the file; its variables: note \(str\)"):
        read_record(save(tmp_path, {"note": "nothing here"}, name="text.mat"))
    with pytest.raises(ValueError, match=r"time must be strictly increasing, got time\[1\] = 0.0 s after 1.0 s"):
        read_record(save(tmp_path, {"t": np.array([1.0, 0.0, 2.0]), "u": U[:3], "y": Y_UM[:3]}, name="back.mat"))
    with pytest.raises(ValueError, match=r"3 valid samples, at least min_samples = 10 are needed"):
        read_record(save(tmp_path, {"t": T[:3], "u": U[:3], "y": Y_UM[:3]}, name="few.mat"), min_samples=10)


def test_a_name_matching_two_channels_is_refused(tmp_path):
    x = struct_array(("Name", "Data"), [("Time", T)])
    y = struct_array(("Name", "Data"), [("Plant/a/x", U), ("Plant/b/x", Y_UM)])
    export = np.zeros((1, 1), dtype=[("X", object), ("Y", object)])
    export[0, 0] = (x, y)
    path = save(tmp_path, {"e": export})
    with pytest.raises(ValueError, match=r"output = 'x' names 2 channels of .* \(indices \[1, 2\]\); choose one by its "
                                         r"index or full name"):
        read_record(path, output="x")
    assert_record(read_record(path, input="plant/a/x", output="Plant/b/x", units={"output": "um"}))


def test_files_that_are_not_matlab_files_or_v7_3_without_h5py(tmp_path, monkeypatch):
    fake = tmp_path / "fake.mat"
    fake.write_text("t,u,y\n0,1,2\n")
    with pytest.raises(ValueError, match=r"fake.mat is not a MATLAB file that can be read"):
        read_record(fake)
    # the v7.3 header (HDF5 behind a 512-byte user block): version 0x0200 at byte 124
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Jan  1 00:00:00 2024 HDF5 schema 1.00 .".ljust(116)
    v73 = tmp_path / "big.mat"
    v73.write_bytes(header + b"\x00" * 8 + b"\x00\x02" + b"IM" + b"\x00" * 384)
    monkeypatch.setattr(matlab_hdf5, "h5py", None)
    with pytest.raises(ValueError, match=r"big.mat is a MATLAB v7.3 file \(HDF5\), which scipy.io cannot read; save it "
                                         r"in MATLAB as save\(file, ..., '-v7'\), or install h5py"):
        read_record(v73)
    # a MATLAB file without the suffix is known by its header; a text file refuses variable=
    plain = save(tmp_path, {"t": T, "u": U, "y": Y_UM}, name="rec.bin")
    assert_record(read_record(plain, units={"output": "um"}))
    text = tmp_path / "rec.csv"
    text.write_text("0,1,2\n1,2,3\n")
    with pytest.raises(ValueError, match=r"variable applies to MATLAB files only, got variable = 'x'"):
        read_record(text, variable="x")


# ------------------------------------------------------------------ MATLAB v7.3 (HDF5) with h5py
def write_v73(path, build):
    """A file in MATLAB's v7.3 layout: HDF5 behind a 512-byte user block with MATLAB's header.

    Arrays are stored transposed (MATLAB is column-major), text as UTF-16 code units with
    ``MATLAB_class = "char"``, a struct as a group, a struct array as a group of reference
    datasets into ``#refs#``.
    """
    h5py = pytest.importorskip("h5py")
    with h5py.File(str(path), "w", userblock_size=512) as f:
        build(f, h5py)
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Jan  1 00:00:00 2024 HDF5 schema 1.00 .".ljust(116)
    with open(path, "r+b") as handle:
        handle.write(header + b"\x00" * 8 + b"\x00\x02" + b"IM")
    return path


def numeric(group, name, values):
    data = group.create_dataset(name, data=np.atleast_2d(values))  # a 1 x n row in MATLAB: n x 1 here
    data.attrs["MATLAB_class"] = np.bytes_("double")
    return data


def text(group, name, value):
    data = group.create_dataset(name, data=np.array([[ord(c)] for c in value], dtype=np.uint16))
    data.attrs["MATLAB_class"] = np.bytes_("char")
    return data


def test_v7_3_plain_arrays_with_h5py(tmp_path):
    def build(f, h5py):
        numeric(f, "data", np.column_stack([T, U, Y_UM]).T)  # MATLAB N x 3, stored 3 x N
        text(f, "note", "bench 3")

    rec = read_record(write_v73(tmp_path / "big.mat", build), units={"output": "um"})
    assert_record(rec)
    assert rec.names["output"] == "data(:,3)"


def test_v7_3_dspace_export_with_h5py(tmp_path):
    def build(f, h5py):
        refs = f.create_group("#refs#")
        count = iter(range(1000))

        def ref(make):
            name = f"r{next(count)}"
            make(refs, name)
            return refs[name].ref

        run = f.create_group("run3")
        run.attrs["MATLAB_class"] = np.bytes_("struct")
        x = run.create_group("X")
        x.attrs["MATLAB_class"] = np.bytes_("struct")
        numeric(x, "Data", T[:, None])
        text(x, "Name", "Time")
        y = run.create_group("Y")  # a 1 x 2 struct array: each field a 2 x 1 dataset of references
        y.attrs["MATLAB_class"] = np.bytes_("struct")
        for field, values in (("Name", ["Model Root/amp/U", "Model Root/laser/x"]), ("Unit", ["V", "um"]),
                              ("Data", [U, Y_UM])):
            make = text if field != "Data" else numeric
            y.create_dataset(field, data=np.array([[ref(lambda g, n, v=v: make(g, n, v if field != "Data" else v[:, None]))]
                                                   for v in values], dtype=h5py.ref_dtype))

    rec = read_record(write_v73(tmp_path / "run.mat", build))
    assert_record(rec)
    assert rec.units == {"time": "s", "input": "V", "output": "m"}
    assert rec.names == {"time": "Time", "input": "Model Root/amp/U", "output": "Model Root/laser/x"}
