"""Measured input-output records (time, input, output) read from text or MATLAB files, split and preprocessed.

A *record* is what a designer measures on an actuator: the time [s], the input (usually the
voltage [V]) and the output (a displacement [m] or strain [-]) sampled together.
:func:`read_record` reads one from a CSV or whitespace-separated text file or a MATLAB file
(:mod:`exudyn_atcm.io.matlab_records`), with the units the file states or ``units=`` gives
(:mod:`exudyn_atcm.io.units`); :meth:`Record.split`
divides it by time into a part to fit a model on and a held-out part to check the prediction;
:func:`preprocess` removes an output offset and a linear drift, trims a settling start and
decimates, each step optional and written into :attr:`Record.processing`.

Nothing is dropped silently: rows holding a NaN (or an empty cell) in a selected column are
dropped and counted in a :class:`~exudyn_atcm.errors.SuspectFileWarning`; a cell that is not a number is an error naming
the line.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Union

import numpy as np

from .._checks import positive_int, shown
from .preprocessing import preprocess
from .record import Record
from .record_columns import Columns, build_record
from .file_checks import check_header_names, warn_unterminated_last_line
from .matlab_records import is_matlab_file, matlab_columns

__all__ = ["Record", "read_record", "preprocess"]  # preprocess: see exudyn_atcm.io.preprocessing

ColumnChoice = Union[str, int]
_UNIT = re.compile(r"^(.*?)\s*\[([^\]]*)\]\s*$")
_MISSING = {"", "nan", "NaN", "NAN", "na", "NA", "n/a", "N/A"}


# ------------------------------------------------------------------------------ reading

def _split_name(text: str) -> tuple[str, str]:
    match = _UNIT.match(text)
    if match:
        return match.group(1).strip(), match.group(2).strip()
    return text.strip(), ""


def _cells(line: str) -> list[str]:
    for sep in (",", ";", "\t"):
        if sep in line:
            return [c.strip() for c in line.split(sep)]
    return line.split()


def _stated_rows(body: str, previous: int | None) -> int | None:
    """The row count of a ``data_rows: N`` comment (as :meth:`Result.to_csv` writes it), else ``previous``."""
    match = re.fullmatch(r"\s*data_rows:\s*(\d+)\s*", body)
    return int(match.group(1)) if match else previous


#: A whitespace-separated header cell: a name, optionally followed by ``[unit]``.
_SPACED_CELL = re.compile(r"[^\s\[\]]+(?:\s*\[[^\]]*\])?")


def _header_cells(path: Path, line: int, text: str, cells: list[str], n_columns: int) -> list[str]:
    """The header's names, one per data column (``name [unit]`` kept together when blank-separated).

    A blank-separated header such as ``time [s]  voltage [V]  displacement [um]`` is split at
    runs of two or more blanks, or else into names each with its ``[unit]``, whichever gives
    as many names as the data has columns.

    Raises
    ------
    ValueError
        If the header has more names than the data has columns (the names cannot be matched
        to the columns), or names with invisible characters.
    """
    if not any(sep in text for sep in (",", ";", "\t")):
        options = [re.split(r"\s{2,}", text.strip()), _SPACED_CELL.findall(text), cells]
        cells = next((o for o in options if len(o) == n_columns), options[1] if "[" in text else cells)
    check_header_names(str(path), line, cells)
    named = list(cells)
    while named and named[-1] == "":
        named.pop()  # a trailing separator
    if len(named) > n_columns:
        raise ValueError(
            f"{path}, line {line}: the header has {len(named)} names {named!r} but the data rows have "
            f"{n_columns} columns; separate the header like the data (commas, semicolons, tabs, or blanks "
            "between 'name [unit]' cells)"
        )
    return cells


def _is_number(cell: str) -> bool:
    if cell in _MISSING:
        return True
    try:
        float(cell)
    except ValueError:
        return False
    return True


def _column(header: list[str] | None, choice: Any, default: int, parameter: str, path: Path, n_columns: int) -> int:
    if choice is None:
        index = default
    elif isinstance(choice, str):
        names = header or []
        full = [h.lower() for h in names]
        bare = [_split_name(h)[0].lower() for h in names]
        key = choice.strip().lower()
        matches = [i for i, h in enumerate(full) if h == key] or [i for i, b in enumerate(bare) if b == key]
        if len(matches) > 1:
            raise ValueError(
                f"{parameter} = {choice!r} names {len(matches)} columns of {path} (indices {matches}); "
                f"columns: {names!r}; choose one by its index or rename the duplicates"
            )
        if matches:
            index = matches[0]
        else:
            raise ValueError(f"{parameter} = {choice!r} is not a column of {path}; columns: {names!r}")
    elif isinstance(choice, (int, np.integer)) and not isinstance(choice, bool) and choice >= 0:
        index = int(choice)
    else:
        raise ValueError(f"{parameter} must be a column name or an index >= 0, got {shown(choice)}")
    if index >= n_columns:
        raise ValueError(f"{parameter} = {choice!r}: {path} has only {n_columns} column(s)")
    return index


def read_record(
    path: Union[str, Path],
    time: ColumnChoice | None = None,
    input: ColumnChoice | None = None,  # noqa: A002 - the record's input column
    output: ColumnChoice | None = None,
    *,
    units: Mapping[str, str] | None = None,
    comment: str = "#",
    min_samples: int = 2,
    si: bool = True,
    variable: str | None = None,
) -> Record:
    """Read a measured (time, input, output) record from a text or MATLAB file.

    A text file holds one sample per line, the cells separated by commas, semicolons, tabs or
    blanks.  Lines starting with ``comment`` are skipped, as are blank lines.  The first other
    line is a header if any of its cells is not a number; a header cell ``name [unit]`` gives
    the unit.  A blank leading column (lines starting with the separator, as some instruments
    write) is ignored.

    A MATLAB file (``.mat``, or any file starting with MATLAB's header) is read with
    :func:`scipy.io.loadmat`: plain arrays (vectors, or the columns of a matrix) or the struct
    exports of real-time systems, see :mod:`exudyn_atcm.io.matlab_records`.  Its channels take
    the place of the columns; everything else (units, NaN rows, SI) is the same.

    Parameters
    ----------
    path : str or Path
        The file.
    time, input, output : str or int, optional
        Column names (full header text such as ``"voltage [V]"`` or the name alone,
        case-insensitive) or zero-based indices counted after a dropped blank leading column;
        for a MATLAB file channel names or indices (see :mod:`~exudyn_atcm.io.matlab_records`).
        Defaults: columns 0, 1 and 2.
    units : mapping, optional
        Units of the columns, e.g. ``{"time": "ms", "input": "V", "output": "um"}``: for files
        that state none (a header-less file, a header without ``[unit]``, a MATLAB array), or to
        confirm the file's; a unit that differs from the one the file states is an error.  They
        are converted to SI like the file's (``si``).  Keys ``"time"``, ``"input"``,
        ``"output"``; the time unit must be a time.  Without it a column whose unit the file does
        not state has the unit ``""`` (unknown; the time is taken as seconds), and
        ``Record.processing`` says so: a record of unknown output unit is not taken for a strain
        anywhere (:func:`~exudyn_atcm.model.strain_conversion.record_to_strain` refuses it).
    comment : str, optional
        Comment prefix of text files (default ``#``).
    min_samples : int, optional
        Fewest valid rows accepted (default 2).
    si : bool, optional
        Convert columns whose unit is a decimal multiple of s, V or m (``ms``, ``µs``,
        ``mV``, ``kV``, ``cm``, ``mm``, ``µm``/``um``, ``nm``) or microstrain (``µε``) to SI
        (:data:`~exudyn_atcm.io.units.SI_SCALE`), as the rest of the package
        expects (``t_split`` in seconds, drives in volts, strains from metres); each
        conversion is listed in ``Record.processing`` (default True).  ``False`` keeps the
        file's numbers and units.
    variable : str, optional
        MATLAB files only: the variable holding the record (a matrix, a struct of vectors or
        a recorder's export); default: found (see :mod:`~exudyn_atcm.io.matlab_records`).

    Returns
    -------
    Record
        With ``units`` from the file and ``units`` (``"s"`` assumed for time when neither has one).

    Raises
    ------
    ValueError
        If the file is missing, a selected cell is not a number (the line is named), fewer than
        ``min_samples`` valid rows remain, the times are not strictly increasing, a unit given
        conflicts with the file's, or a MATLAB file cannot be read (v7.3 without h5py, no
        numeric data, channels of different lengths; the message says which).

    Warns
    -----
    SuspectFileWarning
        When rows holding NaN or empty cells in a selected column are dropped (with their count
        and the first line numbers or sample indices).
    """
    path = Path(path)
    min_samples = positive_int("min_samples", min_samples)
    if not path.is_file():
        raise ValueError(f"path must be an existing text file or MATLAB file, got {str(path)!r}")
    if is_matlab_file(path):
        columns = matlab_columns(path, time, input, output, variable=variable)
    else:
        if variable is not None:
            raise ValueError(f"variable applies to MATLAB files only, got variable = {variable!r} for the text file {path}")
        columns = _text_columns(path, time, input, output, comment)
    return build_record(columns, source=str(path), units=units, si=si, min_samples=min_samples)


def _text_columns(path: Path, time: Any, input: Any, output: Any, comment: str) -> Columns:  # noqa: A002
    """The three chosen columns of a text file (NaN for empty cells), with the header's names and units."""
    header: list[str] | None = None
    header_text = ""
    rows: list[tuple[int, list[str]]] = []
    stated_rows: int | None = None
    unterminated: tuple[int, str] | None = None  # (line, text) of a data or header line without a line end
    with path.open(encoding="utf-8-sig") as handle:
        for number, line in enumerate(handle, start=1):
            text = line.strip()
            if text.startswith(comment):
                stated_rows = _stated_rows(text[len(comment):], stated_rows)
            if not text or text.startswith(comment):
                continue
            if not line.endswith("\n"):
                unterminated = (number, line)
            cells = _cells(line.rstrip("\r\n"))
            if header is None and not rows and not all(_is_number(c) for c in cells if c):
                header, header_text, header_line = cells, line.rstrip("\r\n"), number
                continue
            rows.append((number, cells))
    if stated_rows is not None and len(rows) != stated_rows:
        raise ValueError(
            f"{path}: the file states {stated_rows} data rows (line 'data_rows') but holds {len(rows)}; "
            + ("it was cut off (an interrupted copy or write?)" if len(rows) < stated_rows
               else "rows were appended after it was written")
        )
    if unterminated is not None:
        if stated_rows is not None:
            raise ValueError(
                f"{path}, line {unterminated[0]}: the file ends inside this line (no line end); files with a "
                "'data_rows' line (written by Result.to_csv) end every line, so this one was cut off and its "
                "last number may be cut short"
            )
        warn_unterminated_last_line(str(path), unterminated[0], unterminated[1], stacklevel=4)
    if not rows:
        raise ValueError(f"{path}: no data rows")
    # a blank leading column: empty in the header (if any) and in every row
    if all(cells and cells[0] == "" for _, cells in rows) and (header is None or header[0] == ""):
        rows = [(n, cells[1:]) for n, cells in rows]
        header = header[1:] if header is not None else None
    n_columns = max(len(cells) for _, cells in rows)
    if header is not None:
        header = _header_cells(path, header_line, header_text, header, n_columns)
    indices = {
        "time": _column(header, time, 0, "time", path, n_columns),
        "input": _column(header, input, 1, "input", path, n_columns),
        "output": _column(header, output, 2, "output", path, n_columns),
    }
    data = np.empty((len(rows), 3))
    for r, (number, cells) in enumerate(rows):
        for c, key in enumerate(("time", "input", "output")):
            k = indices[key]
            cell = cells[k] if k < len(cells) else ""
            if cell in _MISSING:
                data[r, c] = math.nan
                continue
            try:
                data[r, c] = float(cell)
            except ValueError:
                raise ValueError(f"{path}: line {number}, column {k} ({key}) must be a number, got {shown(cell)}") from None
    names, file_units = {}, {}
    for key, k in indices.items():
        if header is not None and k < len(header):
            names[key], file_units[key] = _split_name(header[k])
        else:
            names[key], file_units[key] = key, ""
    hint = (f"check the columns chosen (time={indices['time']}, input={indices['input']}, output={indices['output']}), "
            "the separator and the decimal mark")
    return Columns(data, names, file_units, [n for n, _ in rows], "lines", "rows", hint)
