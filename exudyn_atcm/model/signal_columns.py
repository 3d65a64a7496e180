"""The columns of a voltage program's CSV file (:class:`~exudyn_atcm.model.signals.CsvSignal`): its rows, a
column chosen by name or index, and the factor of the unit in its header to SI."""

from __future__ import annotations

import csv
from pathlib import Path
from typing import Union

from .._checks import shown
from ..io.atomic import describe_os_error
from ..io.csv_format import COLUMN
from ..io.units import SI_SCALE, si_scale

__all__ = ["read_signal_table", "column_index", "header_scale"]


def read_signal_table(path: Path) -> tuple[list[str] | None, list[tuple[int, list[str]]]]:
    if not path.is_file():
        raise ValueError(f"path must be an existing CSV file, got {str(path)!r}")
    header: list[str] | None = None
    rows: list[tuple[int, list[str]]] = []
    try:
        handle = path.open(newline="")
    except OSError as exc:
        raise ValueError(f"path {str(path)!r} cannot be read: {describe_os_error(exc)}") from None
    with handle:
        for line_number, row in enumerate(csv.reader(handle), start=1):
            if not row or row[0].lstrip().startswith("#"):
                continue
            cells = [cell.strip() for cell in row]
            if header is None and not rows:
                try:
                    [float(cell) for cell in cells]
                except ValueError:
                    header = cells
                    continue
            rows.append((line_number, cells))
    return header, rows


def header_scale(header: list[str] | None, index: int, si: str, parameter: str, path: Path) -> float:
    """The factor to ``si`` (``"s"`` or ``"V"``) of the unit in column ``index``'s header cell (``name [unit]``);
    1 without a header or a unit.  A unit of another quantity or an unknown one is refused."""
    if header is None or index >= len(header):
        return 1.0
    found = COLUMN.match(header[index])  # ``name [unit]``, as the package's CSV files write a header cell
    if found is None or not found.group(2).strip():
        return 1.0
    unit = found.group(2).strip()
    scale = si_scale(unit)
    if scale is None or scale[1] != si:
        known = ", ".join(u for u, (_, base) in SI_SCALE.items() if base == si)
        raise ValueError(f"{parameter}: the column {header[index]!r} of {path} is in {unit!r}, which is not a "
                         f"{'time' if si == 's' else 'voltage'} unit this reader knows ({known})")
    return scale[0]


def column_index(
    header: list[str] | None, choice: Union[str, int, None], default_name: str, default_index: int,
    parameter: str, path: Path,
) -> int:
    if choice is None:
        if header is not None and default_name in header:
            return header.index(default_name)
        return default_index
    if isinstance(choice, str):
        if header is None or choice not in header:
            raise ValueError(f"{parameter} = {choice!r} is not a column of {path}; columns: {header!r}")
        return header.index(choice)
    if isinstance(choice, int) and choice >= 0:
        return choice
    raise ValueError(f"{parameter} must be a column name or an index >= 0, got {shown(choice)}")
