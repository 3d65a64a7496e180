"""Simulation results: named, unit-tagged series, CSV export.

:class:`Result` knows nothing about Exudyn; it holds numpy arrays, their units and the
parameters of the run.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np

from .._checks import shown
from ..errors import AccuracyWarning, AtcmDeprecationWarning
from ..suggestions import close_names
from .atomic import write_atomic
from .._version import __version__
from .csv_files import read_table
from .csv_format import comment_line, header_cell, invisible_characters


class Result(Mapping):
    """Named time series of one simulation, each with its unit.

    Parameters
    ----------
    series : mapping of str to array_like
        Series in output order, each 1-D and of the same length (one value per recorded
        instant).  Names must not contain commas or brackets.
    units : mapping of str to str
        Unit of every series (SI; ``"-"`` for unit-free quantities).
    parameters : mapping, optional
        Parameters of the run (names may carry units in brackets); written to CSV headers.
    info : mapping, optional
        Run statistics and versions (e.g. ``exudyn_version``, ``rejected_steps``).
    every_step : Result, optional
        The light columns at every accepted solver step, for a run whose record is thinned
        (see :attr:`every_step`); default: this result itself.
    old_names : mapping of str to str, optional
        Deprecated names of series, each to the series it now is (a lone actuator's result:
        ``{"tip_y": "actuator.tip_y", ...}``).  An old name can still be read (``result["tip_y"]``,
        :meth:`unit`, ``in``) for one release, with an :class:`~exudyn_atcm.AtcmDeprecationWarning`
        naming the new name; old names are not iterated, counted or written to files.

    Examples
    --------
    >>> r = Result({"time": [0.0, 0.1], "b.tip_y": [0.0, 1e-3]}, {"time": "s", "b.tip_y": "m"})
    >>> r["b.tip_y"]
    array([0.   , 0.001])
    >>> r.unit("b.tip_y")
    'm'

    Notes
    -----
    The series of :func:`exudyn_atcm.simulate` for a lone :class:`~exudyn_atcm.BendingActuator` are
    those of its one-bender mechanism (bender ``actuator``): ``time`` [s], ``actuator.voltage`` [V],
    ``actuator.strain`` [-] (free strain of the active layer), ``actuator.stroke`` [m] (motor stroke
    of one cell), ``actuator.base_x``, ``actuator.base_y``, ``actuator.tip_x``, ``actuator.tip_y``
    [m], ``actuator.base_angle``, ``actuator.tip_angle`` [rad] (the tip: the passive-layer point of
    the last interface), then ``actuator.cell_angle_1`` ... ``actuator.cell_angle_N`` [rad]
    (rotation of each cell's passive layer).  Static solves and sweeps have ``point`` [-] in place
    of ``time``.
    """

    def __init__(
        self,
        series: Mapping[str, Any],
        units: Mapping[str, str],
        parameters: Mapping[str, Any] | None = None,
        info: Mapping[str, Any] | None = None,
        every_step: "Result | None" = None,
        old_names: Mapping[str, str] | None = None,
    ) -> None:
        data: dict[str, np.ndarray] = {}
        length = None
        for name, values in series.items():
            if not isinstance(name, str) or not name or any(c in name for c in ",[]\n#"):
                raise ValueError(f"series names must be non-empty strings without ',', '[', ']', '#', got {shown(name)}")
            array = np.asarray(values, dtype=float)
            if array.ndim != 1:
                raise ValueError(f"series {name!r} must be 1-D, got shape {array.shape}")
            if length is None:
                length = array.size
            elif array.size != length:
                raise ValueError(f"series {name!r} has {array.size} values, the others {length}")
            array.setflags(write=False)
            data[name] = array
        missing = [n for n in data if n not in units]
        if missing:
            raise ValueError(f"units missing for series {missing}")
        self._series = data
        self._units = {n: str(units[n]) for n in data}
        self.parameters: dict[str, Any] = dict(parameters or {})
        self.info: dict[str, Any] = dict(info or {})
        if every_step is not None and not isinstance(every_step, Result):
            raise ValueError(f"every_step must be a Result or None, got {type(every_step).__name__}")
        self._every_step = every_step
        old = dict(old_names or {})
        wrong = {o: n for o, n in old.items() if n not in data or o in data}
        if wrong:
            raise ValueError(f"old_names must map names that are not series to series of this result, got {shown(wrong)} "
                             f"(series: {', '.join(data)})")
        self._old_names = old

    @property
    def every_step(self) -> "Result":
        """The light columns at every accepted solver step (this result when every step is recorded).

        A run recorded with ``record_every`` keeps only some instants in its columns (and files);
        the solver's every accepted step is still kept for the columns scalars are computed from
        (every column but the cell angles).  Extremes, crossings and
        last-cycle figures computed from ``result.every_step`` are the same for any recording
        interval.  Not written to files: a result read from a file recorded at an interval
        (``info["recorded"]`` other than ``"every step"``) has only its recorded rows, and asking for
        its ``every_step`` gives them with an :class:`~exudyn_atcm.AccuracyWarning`.
        """
        if self._every_step is not None:
            return self._every_step
        recorded = self.info.get("recorded")
        if isinstance(recorded, str) and recorded != "every step":
            warnings.warn(f"every_step: this result holds only its recorded rows ({recorded}; files do not hold every "
                          "step): extremes and crossings computed from them can miss what happened between the rows. "
                          "Run the simulation again (or with record_every=None) for every step",
                          AccuracyWarning, stacklevel=2)
        return self

    # Mapping interface ---------------------------------------------------------------
    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._series[name]
        except (KeyError, TypeError):
            pass
        new = self._renamed(name)
        if new is not None:
            return self._series[new]
        raise self._missing(name) from None

    def __contains__(self, name: object) -> bool:
        try:
            if name in self._series:
                return True
        except TypeError:
            return False
        return self._renamed(name) is not None

    @property
    def old_names(self) -> dict[str, str]:
        """Deprecated series names readable for one release, each to its new name (see the constructor)."""
        return dict(self._old_names)

    def _renamed(self, name: Any, stacklevel: int = 3) -> str | None:
        """The new name of the deprecated series name ``name`` (warning), or None for no such name."""
        try:
            new = self._old_names.get(name)
        except TypeError:
            return None
        if new is not None:
            warnings.warn(f"series {name!r} is now named {new!r}, as in a mechanism's result; the old name "
                          "goes away in the next release", AtcmDeprecationWarning, stacklevel=stacklevel)
        return new

    def _missing(self, name: Any) -> KeyError:
        """KeyError for an unknown series, with the closest name (a unit or component prefix is a common slip)."""
        text = str(name)
        bare = text.split(" [", 1)[0].strip()
        if bare != text and bare in self._series:  # "b.tip_y [m]" as in a CSV header
            return KeyError(f"no series {name!r} (series names carry no unit: use {bare!r}, and "
                            f"result.unit({bare!r}) for its unit); available: {', '.join(self._series)}")
        guesses = [n for n in self._series if n.endswith("." + bare)]  # "tip_y" -> "b.tip_y"
        guesses += [n for n in close_names(bare, self._series, n=2, cutoff=0.75) if n not in guesses]
        hint = f" (did you mean {' or '.join(repr(g) for g in guesses[:3])}?)" if guesses else ""
        return KeyError(f"no series {name!r}{hint}; available: {', '.join(self._series)}")

    def __iter__(self) -> Iterator[str]:
        return iter(self._series)

    def __len__(self) -> int:
        return len(self._series)

    @property
    def names(self) -> list[str]:
        """Series names in output order."""
        return list(self._series)

    @property
    def n_rows(self) -> int:
        """Number of recorded instants."""
        first = next(iter(self._series.values()), None)
        return 0 if first is None else int(first.size)

    def unit(self, name: str) -> str:
        """Unit of series ``name`` (SI; ``"-"`` if unit-free)."""
        if name in self._units:
            return self._units[name]
        new = self._renamed(name)
        if new is not None:
            return self._units[new]
        raise self._missing(name)

    @property
    def units(self) -> dict[str, str]:
        """Units of all series."""
        return dict(self._units)

    def column_header(self) -> str:
        """The CSV header row, ``name [unit],...``.

        Raises
        ------
        ValueError
            If a name or unit cannot be read back (see :func:`exudyn_atcm.io.csv_format.header_cell`),
            or there are no series.
        """
        if not self._series:
            raise ValueError("a Result without series cannot be written to CSV (the file would have no header row)")
        return ",".join(header_cell(n, self._units[n]) for n in self._series)

    def header_comment_lines(self) -> list[str]:
        """The ``#`` comment lines written before the header row.

        Raises
        ------
        ValueError
            If a parameter or info entry cannot be read back as itself (see
            :func:`exudyn_atcm.io.csv_format.comment_line`).
        """
        lines = [f"# exudyn_atcm {__version__}"]
        exu_version = self.info.get("exudyn_version")
        lines.append(f"# exudyn {_version_text(exu_version)}")
        lines.extend(comment_line(key, value) for key, value in self.parameters.items())
        lines.extend(comment_line(key, value, prefix="info.", what="info")
                     for key, value in self.info.items() if key != "exudyn_version")
        return lines

    def to_csv(self, path: str | os.PathLike) -> None:
        """Write all series to a CSV file, atomically.

        The file starts with ``#`` comment lines (package and Exudyn versions, parameters,
        run information, and ``# data_rows: N``, the number of data rows, which
        :func:`~exudyn_atcm.read_csv` checks), then the header row
        ``time [s],voltage [V],...``, then one row per recorded instant.  Each number is
        written as the shortest text that reads back to the same float (``1.9999``, not
        ``1.9998999999999999``).  The file is written to a temporary file in the target
        directory and renamed over ``path``, so readers never see a partial file.

        Read it back with :meth:`from_csv`, ``pandas.read_csv(path, comment="#")``, or
        ``numpy.loadtxt(path, delimiter=",", skiprows=k)`` with ``k`` the number of ``#`` lines
        plus one (numpy's ``skiprows`` counts comment lines too; ``len(header_comment_lines()) + 2``
        with the ``data_rows`` line).

        Whatever this method writes, :func:`~exudyn_atcm.read_csv` reads back identically
        (names, units, every value bit for bit, parameters and info; numpy numbers and arrays as
        Python numbers and lists; non-finite values with ``allow_nonfinite=True``), or it
        refuses to write: see :mod:`exudyn_atcm.io.csv_format` for the rules.

        Parameters
        ----------
        path : str or os.PathLike
            Target file; missing parent directories are created.

        Raises
        ------
        ValueError
            Before anything is written, naming the series or key: a name or unit holding ``,``,
            ``[``, ``]``, a line break or an invisible character; a parameter named
            ``data_rows`` or ``info.*``; a parameter or info value that would not read back as
            itself (an arbitrary object); a ``time`` series that goes back.
        exudyn_atcm.errors.WriteError
            (an ``OSError``) if the file cannot be written, naming the file and the reason (an empty
            path, a name too long for the file system, a directory, no permission, a full disk).
        """
        comments = self.header_comment_lines()  # validates before the file is touched
        header = self.column_header()
        if "time" in self._series and self._series["time"].size >= 2:
            back = np.flatnonzero(np.diff(self._series["time"]) < 0.0)
            if back.size:  # read_csv refuses a time series that goes back
                i = int(back[0]) + 1
                raise ValueError(f"series 'time' goes back from {float(self._series['time'][i - 1])!r} to "
                                 f"{float(self._series['time'][i])!r} at row {i}; read_csv refuses such a file "
                                 "(rename the series if it is not a time)")
        columns = [self._series[n].tolist() for n in self._series]

        def write(handle) -> None:
            for line in comments:
                handle.write(line + "\n")
            handle.write(f"# data_rows: {self.n_rows}\n")
            handle.write(header + "\n")
            if columns:
                fmt = float.__repr__
                handle.writelines(",".join(map(fmt, row)) + "\n" for row in zip(*columns))

        write_atomic(path, write, make_dirs=True)

    @classmethod
    def from_csv(cls, path: str | os.PathLike) -> "Result":
        """Read a file written by :meth:`to_csv`; the same as :func:`exudyn_atcm.read_csv`."""
        return read_csv(path)

    def to_pandas(self):
        """The series as a ``pandas.DataFrame`` with ``name [unit]`` columns (needs pandas)."""
        import pandas as pd  # optional dependency

        return pd.DataFrame({f"{n} [{self._units[n]}]": self._series[n] for n in self._series})

    def plot(self, out_dir: str | os.PathLike, prefix: str = "") -> list[str]:
        """Write the standard PNG plots of this result (a lone actuator's or a mechanism's) to ``out_dir``.

        Returns the paths written; see :func:`exudyn_atcm.plots.result.plot_result`.
        """
        from ..plots.result import plot_result

        return plot_result(self, out_dir, prefix=prefix)

    def __repr__(self) -> str:
        return f"Result({self.n_rows} rows: {', '.join(self.names[:8])}{', ...' if len(self) > 8 else ''})"


def _version_text(version: Any) -> str:
    """The Exudyn version as written on the second line (``unknown`` for ``None``; read back as absent).

    Raises
    ------
    ValueError
        If the version is not a one-line string without surrounding blanks (it would not read back).
    """
    if version is None:
        return "unknown"
    text = version if isinstance(version, str) else None
    if (text is None or not text.strip() or text != text.strip() or "\n" in text or "\r" in text
            or invisible_characters(text)):
        raise ValueError(f"info['exudyn_version'] must be a one-line version string (or None), got {shown(version)}")
    return text


def read_csv(path: str | os.PathLike, *, allow_nonfinite: bool = False) -> Result:
    """Read a CSV file written by :meth:`Result.to_csv` (or by hand in the same format).

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    allow_nonfinite : bool, optional
        Accept ``nan``, ``inf`` and numbers too large for a float (``1e400``); by default
        they are refused (a simulation result never holds them, so they mean a damaged or
        hand-edited file).

    Returns
    -------
    Result
        Series with their units; ``parameters`` from the ``# key: value`` lines, ``info``
        from the ``# info.key: value`` lines plus ``exudyn_version`` when the file names one.
        Version and parameter lines are parsed as Python literals where possible.

    Raises
    ------
    ValueError
        Naming the file, the line and the fault: missing file, no header row, a header
        column without ``[unit]``, duplicate names, a row with the wrong number of cells,
        a cell that is not a number, a non-finite number (unless ``allow_nonfinite``), or a
        number of data rows different from the file's ``# data_rows: N`` line (a file cut
        off at a row boundary), a file with a ``data_rows`` line that ends inside its last
        line (cut inside a number), a ``time`` column that goes back, or header names with
        invisible characters (a byte-order mark inside the file).

    Warns
    -----
    exudyn_atcm.errors.SuspectFileWarning
        A file without ``data_rows`` whose last line has no line end (possibly cut inside its
        last number), repeated times, or a ``[V]`` column peaking below 3 V (kilovolts?).

    Examples
    --------
    >>> import tempfile, os
    >>> r = Result({"time": [0.0, 0.5], "stroke": [0.0, 4e-5]}, {"time": "s", "stroke": "m"})
    >>> path = os.path.join(tempfile.mkdtemp(), "r.csv")
    >>> r.to_csv(path)
    >>> read_csv(path).unit("stroke")
    'm'
    """
    table = read_table(path, allow_nonfinite=allow_nonfinite)
    return Result(table.series, table.units, parameters=table.parameters, info=table.info)
