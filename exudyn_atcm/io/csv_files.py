"""The package's time-series CSV format: its header and the reader behind :func:`exudyn_atcm.read_csv`.

The format is the one :meth:`Result.to_csv` writes::

    # exudyn_atcm 0.1.0
    # exudyn 1.13.6
    # period [s]: 1.0              <- parameters, "# key: value"
    # info.steps: 801              <- run information, "# info.key: value"
    # data_rows: 801               <- number of data rows (checked when present)
    time [s],voltage [V],stroke [m]
    0,-500,-4e-06
    ...

:func:`read_csv` round-trips it: series names, units and values exactly (each number is
written as the shortest text that reads back to the same float), parameters and info where
their text parses as a Python literal (numbers, booleans, ``None``, lists, dicts), otherwise
as strings.  A malformed file is refused with a ``ValueError`` that names the file, the line
and what is wrong: among others a file with fewer or more rows than its ``data_rows`` line
states (cut off or appended to), a file that ends inside its last line when it has a
``data_rows`` line (cut inside a number: ``-4e-06`` cut to ``-4e-0`` would read as -4), a
``time`` column that goes back, header names with invisible characters, and non-finite numbers
(``nan``, ``inf``, ``1e400``) unless ``allow_nonfinite=True``.  A
:class:`~exudyn_atcm.errors.SuspectFileWarning` is given for a file without ``data_rows``
whose last line has no line end (possibly cut off), repeated times, and a ``[V]`` column that
peaks below 3 V (kilovolts?).  A byte-order mark at the start of the file is not part of the
text (``utf-8-sig``).  The rules the writer and the reader share are in
:mod:`exudyn_atcm.io.csv_format`.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .atomic import describe_os_error
from .csv_format import COLUMN, parse_value, split_comment
from .file_checks import check_header_names, check_times, check_volt_column, warn_unterminated_last_line

__all__ = ["read_table", "read_csv_header", "CsvHeader", "CsvTable"]

@dataclass
class CsvHeader:
    """The metadata of a result CSV file.

    Attributes
    ----------
    names, units : list of str
        Series names and units from the header row.
    package_version, exudyn_version : str or None
        Versions from the first two comment lines (``None`` if absent or ``unknown``).
    parameters, info : dict
        ``# key: value`` and ``# info.key: value`` lines, values parsed where possible.
    header_line : int
        1-based line number of the header row.
    data_rows : int or None
        Number of data rows stated by the ``# data_rows: N`` line (``None`` if absent).
    """

    names: list[str] = field(default_factory=list)
    units: list[str] = field(default_factory=list)
    package_version: str | None = None
    exudyn_version: str | None = None
    parameters: dict[str, Any] = field(default_factory=dict)
    info: dict[str, Any] = field(default_factory=dict)
    header_line: int = 0
    data_rows: int | None = None


def _read_lines(path: str | os.PathLike) -> tuple[str, list[str]]:
    name = os.fspath(path)
    if name == "":
        raise ValueError("path must name a CSV file, got '' (an empty path)")
    try:
        with open(name, encoding="utf-8-sig", newline=None) as handle:  # -sig: a leading BOM is not text
            return name, handle.read().split("\n")
    except FileNotFoundError:
        raise ValueError(f"{name}: no such file") from None
    except IsADirectoryError:
        raise ValueError(f"{name}: is a directory, not a CSV file") from None
    except OSError as exc:
        raise ValueError(f"{name}: cannot be read: {describe_os_error(exc)}") from None
    except UnicodeDecodeError as exc:
        raise ValueError(f"{name}: not a UTF-8 text file ({exc.reason} at byte {exc.start})") from None


def _parse_header(name: str, lines: list[str]) -> tuple[CsvHeader, int]:
    header = CsvHeader()
    comment_index = 0
    for index, line in enumerate(lines):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith("#"):
            body = stripped[1:].strip()
            comment_index += 1
            if comment_index == 1 and body.startswith("exudyn_atcm "):
                header.package_version = body.split(None, 1)[1].strip()
                continue
            if comment_index <= 2 and body.startswith("exudyn "):
                version = body.split(None, 1)[1].strip()
                header.exudyn_version = None if version == "unknown" else version
                continue
            parsed = split_comment(body)
            if parsed is None:
                continue  # free comment
            key, value = parsed
            if key == "data_rows":
                try:
                    header.data_rows = int(value.strip())
                except ValueError:
                    raise ValueError(
                        f"{name}, line {index + 1}: data_rows must be a whole number of rows, got {value.strip()!r}"
                    ) from None
                if header.data_rows < 0:
                    raise ValueError(f"{name}, line {index + 1}: data_rows must be >= 0, got {header.data_rows}")
                continue
            if key.startswith("info."):
                header.info[key[5:]] = parse_value(value)
            else:
                header.parameters[key] = parse_value(value)
            continue
        # the header row
        cells = line.split(",")
        for column, cell in enumerate(cells, start=1):
            match = COLUMN.match(cell)
            if match is None:
                if _looks_numeric(cell):
                    raise ValueError(
                        f"{name}, line {index + 1}: expected the header row 'name [unit],...' "
                        f"before the data, got a data row {line.strip()[:60]!r}"
                    )
                raise ValueError(
                    f"{name}, line {index + 1}: column {column} of the header is {cell.strip()!r}; "
                    "each column must be written 'name [unit]' (unit '-' if unit-free)"
                )
            header.names.append(match.group(1).strip())
            header.units.append(match.group(2).strip())
        check_header_names(name, index + 1, header.names)
        duplicates = sorted({n for n in header.names if header.names.count(n) > 1})
        if duplicates:
            raise ValueError(f"{name}, line {index + 1}: duplicate column names {duplicates}")
        header.header_line = index + 1
        return header, index
    raise ValueError(f"{name}: no header row 'name [unit],...' found (the file is empty or only comments)")


def _looks_numeric(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def read_csv_header(path: str | os.PathLike) -> CsvHeader:
    """Metadata of a result CSV file (versions, parameters, info, names and units).

    Raises
    ------
    ValueError
        If the file is missing or its header row is malformed.
    """
    name, lines = _read_lines(path)
    header, _ = _parse_header(name, lines)
    return header


@dataclass(frozen=True)
class CsvTable:
    """The content of a result CSV file: series by name, their units, parameters and info."""

    series: dict[str, np.ndarray]
    units: dict[str, str]
    parameters: dict[str, Any]
    info: dict[str, Any]


def read_table(path: str | os.PathLike, *, allow_nonfinite: bool = False) -> CsvTable:
    """Read a result CSV file into a :class:`CsvTable`; :func:`exudyn_atcm.read_csv` makes it a Result.

    Same arguments and errors as :func:`exudyn_atcm.read_csv`.
    """
    name, lines = _read_lines(path)
    header, header_index = _parse_header(name, lines)
    n_columns = len(header.names)
    rows: list[list[float]] = []
    row_lines: list[int] = []
    for index in range(header_index + 1, len(lines)):
        line = lines[index]
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        cells = stripped.split(",")
        if len(cells) != n_columns:
            raise ValueError(
                f"{name}, line {index + 1}: {len(cells)} cells, but the header has {n_columns} columns"
            )
        row = []
        for column, cell in enumerate(cells):
            try:
                value = float(cell)
            except ValueError:
                raise ValueError(
                    f"{name}, line {index + 1}: column {column + 1} ({header.names[column]}) is "
                    f"{cell.strip()!r}, not a number"
                ) from None
            if math.isnan(value) and cell.strip().lower() not in ("nan", "+nan", "-nan"):
                raise ValueError(f"{name}, line {index + 1}: column {column + 1} is {cell.strip()!r}, not a number")
            if not allow_nonfinite and not math.isfinite(value):
                raise ValueError(
                    f"{name}, line {index + 1}: column {column + 1} ({header.names[column]}) is "
                    f"{cell.strip()!r}, not a finite number"
                    + (" (too large for a float)" if cell.strip().lower().lstrip("+-") not in ("nan", "inf", "infinity") else "")
                    + "; pass allow_nonfinite=True to read non-finite values"
                )
            row.append(value)
        rows.append(row)
        row_lines.append(index + 1)
    _check_last_line(name, lines, header, header_index, row_lines)
    if header.data_rows is not None and len(rows) != header.data_rows:
        raise ValueError(
            f"{name}: the file states {header.data_rows} data rows (line 'data_rows') but holds {len(rows)}; "
            + ("it was cut off (an interrupted copy or write?)" if len(rows) < header.data_rows
               else "rows were appended after it was written")
        )
    matrix = np.array(rows, dtype=float).reshape(len(rows), n_columns)
    _check_columns(name, header, matrix, row_lines)
    info = dict(header.info)
    if header.exudyn_version is not None:
        info = {"exudyn_version": header.exudyn_version, **info}
    return CsvTable(
        {n: matrix[:, i] for i, n in enumerate(header.names)},
        dict(zip(header.names, header.units)),
        dict(header.parameters),
        info,
    )


def _check_last_line(name: str, lines: list[str], header: CsvHeader, header_index: int, row_lines: list[int]) -> None:
    """A file ending inside its header or a data row (no line end) may be cut off inside a number.

    Refused for a file with a ``data_rows`` line (:meth:`Result.to_csv` ends every line, so
    the file was cut), warned otherwise (a hand-written file may just lack the last newline).
    """
    last = len(lines) - 1
    if not lines[last].strip() or lines[last].strip().startswith("#"):
        return
    if last != header_index and (not row_lines or row_lines[-1] != last + 1):  # pragma: no cover - every other line is a row
        return
    if header.data_rows is not None:
        raise ValueError(
            f"{name}, line {last + 1}: the file ends inside this line (no line end); files written by to_csv "
            "end every line, so this one was cut off (an interrupted copy or write?) and its last number "
            "may be cut short"
        )
    warn_unterminated_last_line(name, last + 1, lines[last], stacklevel=5)


def _check_columns(name: str, header: CsvHeader, matrix: np.ndarray, row_lines: list[int]) -> None:
    """Times that go back (refused) or repeat (warned); ``[V]`` columns that look like kilovolts (warned)."""
    for i, (column, unit) in enumerate(zip(header.names, header.units)):
        if column == "time":
            check_times(name, f"time [{unit}]", matrix[:, i], row_lines, stacklevel=5)
        if unit == "V":
            check_volt_column(name, f"{column} [V]", matrix[:, i], stacklevel=5)
