"""The table of a study: one row per run, columns ``name [unit]``, as a :class:`StudyTable`.

:class:`StudyTable` is the package's own table type, returned whatever is installed (the same
object with and without pandas): ``table["y [m]"]`` or ``table["y"]`` is a numpy array,
``table.to_pandas()`` a DataFrame (pandas is optional and needed only there), ``table.to_numpy()``
a numpy structured array.

Columns, in this order: ``run [-]`` (the run's position in the study), every declared
parameter of the case (declaration order), every key scalar that any run returned (in the
order of first appearance along the runs), then ``status [-]`` (``ok`` or ``failed``),
``error [-]`` (one line, empty if ok), ``stale [-]`` (empty, or why the store's result of the
same case and values was not reused: the input that changed), ``wall_time [s]`` and ``key [-]`` (the run's store
key).  A failed run has NaN for its scalars.  Rows are in the study's order, whatever
order the runs finished in.
"""

from __future__ import annotations

import csv
import io
import math
import os
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import shown
from ..io.atomic import write_text
from ..casework import Case
from ..errors import AtcmDeprecationWarning

__all__ = ["Column", "StudyTable", "table_columns", "to_table", "write_table_csv", "column", "unit_of"]


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
    columns.append(Column("stale", "-", "str", [str(r.get("stale", "")) for r in rows]))
    columns.append(Column("wall_time", "s", "float", [float(r.get("wall_time", math.nan)) for r in rows]))
    columns.append(Column("key", "-", "str", [str(r["key"]) for r in rows]))
    return columns


class StudyTable:
    """The table of a study or an optimisation history: rows of runs, columns ``name [unit]``.

    The same type whatever is installed.  Read a column as a numpy array with ``table["y [m]"]``
    or ``table["y"]`` (name without unit), several as a smaller table with
    ``table[["x [m]", "y [m]"]]``; ``table.columns`` lists the headers in order,
    ``table.units`` maps them to their units, ``len(table)`` is the number of rows.

    Parameters
    ----------
    columns : sequence of Column
        The columns, all of the same length.
    """

    def __init__(self, columns: Sequence[Column]) -> None:
        lengths = {len(c.values) for c in columns}
        if len(lengths) > 1:
            raise ValueError(f"columns must have the same length, got lengths {sorted(lengths)}")
        self._columns = list(columns)
        self._arrays = {c.header: np.asarray(c.values, dtype=_dtype(c)) for c in columns}
        for array in self._arrays.values():
            array.flags.writeable = False
        self._rows = lengths.pop() if lengths else 0

    @property
    def columns(self) -> list[str]:
        """The column headers ``name [unit]``, in order."""
        return [c.header for c in self._columns]

    @property
    def units(self) -> dict[str, str]:
        """``{header: unit}``."""
        return {c.header: c.unit for c in self._columns}

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, columns)``."""
        return (self._rows, len(self._columns))

    def __len__(self) -> int:
        return self._rows

    def __iter__(self):
        return iter(self.columns)

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and any(name in (c.header, c.name) for c in self._columns)

    def __getitem__(self, key: str | Sequence[str]) -> Any:
        if isinstance(key, str):
            return self._arrays[_header(self, key)]
        if isinstance(key, Sequence) and all(isinstance(k, str) for k in key):
            wanted = [_header(self, k) for k in key]
            by_header = {c.header: c for c in self._columns}
            return StudyTable([by_header[h] for h in wanted])
        raise ValueError(f"key must be a column name or a list of column names, got {shown(key)}")

    def drop(self, columns: str | Sequence[str]) -> StudyTable:
        """The table without ``columns`` (names or headers)."""
        names = [columns] if isinstance(columns, str) else list(columns)
        dropped = {_header(self, n) for n in names}
        return StudyTable([c for c in self._columns if c.header not in dropped])

    def equals(self, other: object) -> bool:
        """Same headers and the same values (NaN equal to NaN), like ``DataFrame.equals``."""
        if not isinstance(other, StudyTable) or other.columns != self.columns or len(other) != len(self):
            return False
        for header, mine in self._arrays.items():
            theirs = other._arrays[header]
            if mine.dtype.kind == "f" or theirs.dtype.kind == "f":
                if not np.array_equal(mine, theirs, equal_nan=True):
                    return False
            elif not np.array_equal(mine, theirs):
                return False
        return True

    def to_numpy(self) -> np.ndarray:
        """A numpy structured array with the headers as field names."""
        array = np.zeros(self._rows, dtype=[(c.header, _dtype(c)) for c in self._columns])
        for header, values in self._arrays.items():
            array[header] = values
        return array

    def to_pandas(self):
        """A :class:`pandas.DataFrame` with the same columns; ``attrs["units"]`` maps headers to units.

        Raises
        ------
        ImportError
            If pandas is not installed (it is optional: ``pip install pandas``).
        """
        try:
            import pandas as pd  # noqa: PLC0415 - optional dependency, needed only here
        except ImportError:
            raise ImportError("StudyTable.to_pandas needs pandas, which is not installed (pip install pandas); "
                              "table[name] and table.to_numpy() work without it") from None
        data = {c.header: self._arrays[c.header] if c.kind != "str" else list(c.values) for c in self._columns}
        frame = pd.DataFrame(data, columns=self.columns)
        frame.attrs["units"] = self.units
        return frame

    def __repr__(self) -> str:
        return f"StudyTable({self._rows} rows: {', '.join(self.columns)})"

    def __str__(self) -> str:
        """The table as aligned text (at most 20 rows shown)."""
        shown = range(min(self._rows, 20))
        cells = [[_text_cell(self._arrays[h][i]) for h in self.columns] for i in shown]
        widths = [max([len(h)] + [len(r[j]) for r in cells]) for j, h in enumerate(self.columns)]
        lines = ["  ".join(h.rjust(w) for h, w in zip(self.columns, widths))]
        lines += ["  ".join(v.rjust(w) for v, w in zip(row, widths)) for row in cells]
        if self._rows > len(shown):
            lines.append(f"... ({self._rows} rows)")
        return "\n".join(lines)


def _text_cell(value: Any) -> str:
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.6g}"
    return str(value)


def to_table(columns: Sequence[Column], *, use_pandas: bool | None = None) -> Any:
    """The :class:`StudyTable` of ``columns``.

    ``use_pandas`` is deprecated (the table no longer depends on what is installed): ``True``
    returns ``StudyTable.to_pandas()``, ``False`` ``StudyTable.to_numpy()``, each with a
    :class:`DeprecationWarning`.
    """
    table = StudyTable(columns)
    if use_pandas is None:
        return table
    warnings.warn("use_pandas is deprecated: studies return a StudyTable whatever is installed; "
                  "use table.to_pandas() or table.to_numpy()", AtcmDeprecationWarning, stacklevel=3)
    return table.to_pandas() if use_pandas else table.to_numpy()


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
    """Values of the column whose name (without unit) or header is ``name``, from a :class:`StudyTable`
    (or a DataFrame or structured array of one)."""
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
