"""The table of a study: one row per run, columns ``name [unit]``, as DataFrame or structured array.

Columns, in this order: ``run [-]`` (the run's position in the study), every declared
parameter of the case (declaration order), every key scalar that any run returned (in the
order of first appearance along the runs), then ``status [-]`` (``ok`` or ``failed``),
``error [-]`` (one line, empty if ok), ``wall_time [s]`` and ``key [-]`` (the run's store
key).  A failed run has NaN for its scalars.  Rows are in the study's order, whatever
order the runs finished in.
"""

from __future__ import annotations

import csv
import io
import math
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..io.atomic import write_text
from ..casework import Case

__all__ = ["Column", "table_columns", "to_table", "write_table_csv", "column", "unit_of"]


class Column:
    """One column: ``name``, ``unit``, ``kind`` (``float``, ``int``, ``bool``, ``str``) and values."""

    def __init__(self, name: str, unit: str, kind: str, values: list[Any]) -> None:
        self.name = name
        self.unit = unit
        self.kind = kind
        self.values = values

    @property
    def header(self) -> str:
        """``name [unit]``."""
        return f"{self.name} [{self.unit}]"


def _param_cell(value: Any) -> Any:
    return ",".join(repr(float(v)) for v in value) if isinstance(value, (tuple, list)) else value


def table_columns(case: Case, records: Sequence[Mapping[str, Any]]) -> list[Column]:
    """The columns of the table of ``records`` (sorted by their ``index``)."""
    rows = sorted(records, key=lambda r: r["index"])
    columns = [Column("run", "-", "int", [int(r["index"]) for r in rows])]
    for parameter in case.parameters:
        kind = "str" if parameter.kind == "floats" else parameter.kind
        values = [_param_cell(r["values"].get(parameter.name, parameter.default)) for r in rows]
        columns.append(Column(parameter.name, parameter.unit, kind, values))
    names: dict[str, str] = {}
    for r in rows:
        for name in r.get("scalars", {}):
            if name not in names:
                names[name] = r.get("scalar_units", {}).get(name, "-")
    taken = {c.name for c in columns}
    for name, unit in names.items():
        label = name if name not in taken else f"{name}_result"
        columns.append(Column(label, unit, "float", [float(r.get("scalars", {}).get(name, math.nan)) for r in rows]))
    columns.append(Column("status", "-", "str", [str(r["status"]) for r in rows]))
    columns.append(Column("error", "-", "str", [str(r.get("error", "")) for r in rows]))
    columns.append(Column("wall_time", "s", "float", [float(r.get("wall_time", math.nan)) for r in rows]))
    columns.append(Column("key", "-", "str", [str(r["key"]) for r in rows]))
    return columns


def to_table(columns: Sequence[Column], *, use_pandas: bool | None = None):
    """A pandas DataFrame (if pandas is installed, or ``use_pandas``) or a numpy structured array.

    Column names are ``name [unit]`` in both; the DataFrame's ``attrs["units"]`` maps them
    to the units.
    """
    if use_pandas is None or use_pandas:
        try:
            import pandas as pd
        except ImportError:
            if use_pandas:
                raise
        else:
            data = {c.header: np.asarray(c.values, dtype=_dtype(c)) if c.kind != "str" else list(c.values) for c in columns}
            frame = pd.DataFrame(data, columns=[c.header for c in columns])
            frame.attrs["units"] = {c.header: c.unit for c in columns}
            return frame
    n = len(columns[0].values) if columns else 0
    dtype = [(c.header, _dtype(c)) for c in columns]
    array = np.zeros(n, dtype=dtype)
    for c in columns:
        array[c.header] = c.values
    return array


def _dtype(c: Column) -> Any:
    if c.kind == "float":
        return np.float64
    if c.kind == "int":
        return np.int64
    if c.kind == "bool":
        return np.bool_
    return f"U{max([1] + [len(str(v)) for v in c.values])}"


def _cell(kind: str, value: Any) -> str:
    if kind == "float":
        return repr(float(value))
    if kind == "bool":
        return "true" if value else "false"
    return str(value)


def write_table_csv(path: str | os.PathLike, columns: Sequence[Column], comments: Mapping[str, Any] | None = None) -> Path:
    """Write the table as CSV (``# key: value`` comment lines, then the ``name [unit]`` header), atomically."""
    buffer = io.StringIO()
    for key, value in (comments or {}).items():
        buffer.write(f"# {key}: {value}\n")
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([c.header for c in columns])
    n = len(columns[0].values) if columns else 0
    for i in range(n):
        writer.writerow([_cell(c.kind, c.values[i]) for c in columns])
    return write_text(path, buffer.getvalue())


def column(table: Any, name: str) -> np.ndarray:
    """Values of the column whose name (without unit) or header is ``name``, from a DataFrame or structured array."""
    header = _header(table, name)
    return np.asarray(table[header])


def unit_of(table: Any, name: str) -> str:
    """Unit of column ``name``."""
    header = _header(table, name)
    return header[header.rindex("[") + 1 : -1]


def _header(table: Any, name: str) -> str:
    headers = list(table.columns) if hasattr(table, "columns") else list(table.dtype.names)
    if name in headers:
        return name
    for header in headers:
        if header.rsplit(" [", 1)[0] == name:
            return header
    raise ValueError(f"no column {name!r} in the table; columns: {', '.join(headers)}")
