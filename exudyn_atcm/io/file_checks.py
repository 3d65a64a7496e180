"""Checks shared by the file readers (:func:`~exudyn_atcm.read_csv`, :func:`~exudyn_atcm.io.measurements.read_record`).

A file that reads without a syntax error can still give wrong numbers.  These checks look for
the ways that happens in practice and refuse (``ValueError``) or warn
(:class:`~exudyn_atcm.errors.SuspectFileWarning`, defined in :mod:`exudyn_atcm.errors` and
imported here) with what to change:

* a file cut inside its last line (an interrupted copy, download or write): the last line has
  no line end, and its last number may be a prefix of the real one (``-4e-06`` cut to
  ``-4e-0`` reads as -4);
* a ``[V]`` column whose values peak below :data:`~exudyn_atcm.physical_bounds.KV_SUSPECT_FRACTION` of the
  MFC's rating (3 V): most likely written in kV;
* times that go back (refused) or repeat (warned);
* header names with invisible characters (a byte-order mark inside the file, zero-width spaces):
  refused, since ``"\\ufefftime"`` and ``"time"`` look the same and differ.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence

import numpy as np

from .csv_format import invisible_characters
from ..errors import SuspectFileWarning
from ..physical_bounds import KV_SUSPECT_FRACTION, MFC_P1_RATED_RANGE

__all__ = ["SuspectFileWarning", "warn_unterminated_last_line", "check_volt_column", "check_times", "check_header_names"]


def warn_unterminated_last_line(name: str, line_number: int, line: str, *, stacklevel: int = 3) -> None:
    """Warn that the file ends inside line ``line_number`` (no line end): it may be cut off.

    Parameters
    ----------
    name : str
        The file.
    line_number : int
        1-based number of the last line.
    line : str
        Its text (quoted, shortened, in the message).
    stacklevel : int
        Passed to :func:`warnings.warn`.
    """
    text = line.strip()
    shown = text if len(text) <= 60 else "..." + text[-57:]
    warnings.warn(
        f"{name}: the last line ({line_number}: {shown!r}) has no line end, so the file may be truncated "
        "inside it (a cut number reads as a different value, e.g. -4e-06 cut to -4e-0 reads as -4); "
        "check the file is complete and end it with a newline",
        SuspectFileWarning,
        stacklevel=stacklevel,
    )


def check_volt_column(name: str, column: str, values: np.ndarray, *, stacklevel: int = 3) -> None:
    """Warn if a column in volts peaks (non-zero) below the kV-suspect level of the MFC P1's rating.

    The level is :data:`~exudyn_atcm.physical_bounds.KV_SUSPECT_FRACTION` times the largest rated
    magnitude (1500 V): 3 V, the level below which a voltage program is taken for kilovolts.
    """
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    if finite.size == 0:
        return
    peak = float(np.max(np.abs(finite)))
    rated = max(abs(MFC_P1_RATED_RANGE[0]), abs(MFC_P1_RATED_RANGE[1]))
    limit = KV_SUSPECT_FRACTION * rated
    if 0.0 < peak < limit:
        warnings.warn(
            f"{name}: column {column!r} is in V but peaks at |U| = {peak:.4g} V, below {limit:.3g} V "
            f"({100 * KV_SUSPECT_FRACTION:g} % of the MFC's largest rated voltage, {rated:g} V): if the values "
            "are kilovolts, write the unit as [kV] (read_record converts it) or multiply them by 1000",
            SuspectFileWarning,
            stacklevel=stacklevel,
        )


def check_times(name: str, column: str, times: np.ndarray, line_numbers: Sequence[int], *, stacklevel: int = 3) -> None:
    """Refuse times that go back; warn about times that repeat.

    Raises
    ------
    ValueError
        Naming the file, the line and both times, if a time is smaller than the one before.

    Warns
    -----
    SuspectFileWarning
        If a time equals the one before (count and the first line).
    """
    t = np.asarray(times, dtype=float)
    if t.size < 2:
        return
    step = np.diff(t)
    back = np.flatnonzero(step < 0.0)
    if back.size:
        i = int(back[0]) + 1
        raise ValueError(
            f"{name}, line {line_numbers[i]}: {column} goes back from {float(t[i - 1])!r} to {float(t[i])!r} "
            f"({back.size} such step{'s' if back.size > 1 else ''}); a time series must have increasing times "
            "(two files joined, or rows out of order?)"
        )
    same = np.flatnonzero(step == 0.0)
    if same.size:
        i = int(same[0]) + 1
        warnings.warn(
            f"{name}: {same.size} row{'s' if same.size > 1 else ''} repeat the time of the row before "
            f"(first at line {line_numbers[i]}, {column} = {float(t[i])!r}); derivatives and interpolation "
            "over these rows are undefined",
            SuspectFileWarning,
            stacklevel=stacklevel,
        )


def check_header_names(name: str, line_number: int, names: Sequence[str]) -> None:
    """Refuse header names holding invisible characters (a byte-order mark, zero-width spaces).

    Raises
    ------
    ValueError
        Naming the file, the line, the column and the characters.
    """
    for column, text in enumerate(names, start=1):
        found = invisible_characters(text)
        if found:
            bom = " (a byte-order mark: the file was joined from pieces, or saved with a BOM after other text)" \
                if "U+FEFF" in found else ""
            raise ValueError(
                f"{name}, line {line_number}: column {column} of the header, {text!r}, contains invisible "
                f"characters {found}{bom}; remove them so the name reads as written"
            )
