"""From three columns read out of a file to a :class:`Record`: the rules every reader shares.

Text files (:func:`~exudyn_atcm.io.measurements.read_record`) and MATLAB files
(:mod:`exudyn_atcm.io.matlab_records`) both end here, so both drop the same rows with the
same warning, refuse the same short records, merge the units given with the file's the same
way and convert to SI alike.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._checks import shown
from ..errors import SuspectFileWarning
from .file_checks import check_volt_column
from .record import Record
from .units import ROLES, merge_units, si_scale

__all__ = ["Columns", "build_record"]


@dataclass
class Columns:
    """The time, input and output columns a reader found in a file, before any row is dropped.

    Attributes
    ----------
    data : numpy.ndarray
        Shape ``(n, 3)``: time, input, output; NaN where a cell was empty or missing.
    names, file_units : dict
        Each role's column name and the unit the file states (``""``: none).
    positions : sequence of int
        Where each row is in the file (line numbers, sample indices), for messages.
    position_word, row_word : str
        ``"lines"``/``"rows"`` for text files, ``"samples"``/``"samples"`` for arrays.
    choice_hint : str
        What to check when most rows are dropped (the columns chosen ...).
    notes : list of str
        Notes placed first in ``Record.processing`` (which channels were chosen ...).
    """

    data: np.ndarray
    names: dict
    file_units: dict
    positions: Sequence[int]
    position_word: str
    row_word: str
    choice_hint: str
    notes: list = field(default_factory=list)


def build_record(columns: Columns, *, source: str, units: Any, si: bool, min_samples: int) -> Record:
    """The record of ``columns``, rows with non-finite values dropped, units merged and converted to SI.

    Parameters
    ----------
    columns : Columns
        What the reader found.
    source : str
        The file (messages and ``Record.source``).
    units : mapping or None
        Units given by the user (:func:`~exudyn_atcm.io.units.merge_units`).
    si : bool
        Convert known decimal multiples to SI.
    min_samples : int
        Fewest valid rows accepted.

    Raises
    ------
    ValueError
        Fewer than ``min_samples`` valid rows, ``si`` not a bool, units that conflict.

    Warns
    -----
    SuspectFileWarning
        When rows are dropped (count and first positions), or a ``[V]`` column peaks below 3 V.
    """
    if not isinstance(si, bool):
        raise ValueError(f"si must be True or False, got {shown(si)}")
    data, names, file_units = columns.data, columns.names, columns.file_units
    positions, position_word, row_word = columns.positions, columns.position_word, columns.row_word
    processing = list(columns.notes)
    bad = ~np.all(np.isfinite(data), axis=1)
    n = data.shape[0]
    if bad.any():
        first = [positions[i] for i in np.flatnonzero(bad)[:5]]
        message = (
            f"{source}: dropped {int(bad.sum())} of {n} {row_word} with NaN, infinite or empty cells in the "
            f"time/input/output columns (first at {position_word} {first})"
        )
        if 2 * int(bad.sum()) > n:
            message += f"; that is most of the record ({100.0 * bad.sum() / n:.0f} %): {columns.choice_hint}"
        warnings.warn(message, SuspectFileWarning, stacklevel=3)
        processing.append(f"dropped {int(bad.sum())} {row_word} with non-finite values")
        data = data[~bad]
    if data.shape[0] < min_samples:
        raise ValueError(f"{source}: {data.shape[0]} valid {row_word}, at least min_samples = {min_samples} are needed")
    labels = {role: repr(f"{names[role]} [{file_units[role]}]" if file_units.get(role) else names[role]) for role in ROLES}
    merged, unit_notes = merge_units(file_units, units, labels, source)
    processing += unit_notes
    data = np.array(data, dtype=float)
    for c, role in enumerate(ROLES):
        if merged[role] == "V":
            check_volt_column(source, f"{names[role]} [V]", data[:, c], stacklevel=4)
    if si:
        for c, role in enumerate(ROLES):
            scale = si_scale(merged[role])
            if scale is not None and (scale[0] != 1.0 or scale[1] != merged[role]):
                factor, base = scale
                data[:, c] *= factor
                processing.append(f"{role} converted from {merged[role]} to {base} (x {factor:g})")
                merged[role] = base
    return Record(data[:, 0], data[:, 1], data[:, 2], units=merged, names=dict(names),
                  processing=tuple(processing), source=source)
