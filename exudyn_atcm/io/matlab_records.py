"""Records from MATLAB files: plain arrays and the struct exports of real-time systems.

:func:`~exudyn_atcm.io.measurements.read_record` reads a ``.mat`` file (or any file that starts
with MATLAB's header) with :func:`scipy.io.loadmat` and makes a list of *channels* from it,
which take the place of a text file's columns: ``time``, ``input`` and ``output`` choose
channels by name or by their zero-based index in the list (defaults 0, 1, 2), and the rest
(units, rows with NaN dropped and counted, SI conversion, errors) is what text files get.

The channel list, in the file's order:

* a recorder's export, a struct with fields ``X`` and ``Y`` (dSPACE ControlDesk/TRACE style):
  the time vector(s) ``X(j).Data`` first (named by ``X(j).Name``, else ``"time"``), then every
  ``Y(k).Data`` named by ``Y(k).Name``; a ``Unit`` field gives the unit;
* Simulink's "structure with time" (a struct with ``time`` and ``signals``, as the Scope and
  To Workspace blocks save it): ``time``, then every ``signals(k).values`` named by its
  ``label`` (else ``blockName``);
* plain arrays: every numeric vector variable (named by the variable), every matrix cut into
  its columns (``data(:,1)``, ``data(:,2)``, ...; into rows ``data(1,:)`` ... when it is wider
  than tall), and the numeric fields of a plain struct (named by the field).  Scalars (a
  sample rate, a gain), text, logical and complex arrays are no channels.

Without ``variable`` the file's one export is used; several are refused (choose with
``variable``); a file without an export gives its numeric top-level variables, or, if it has
none, the fields of its one struct.  A name matches a channel's full name or, for names that
are paths (``"Model Root/Sensor/x"``), the last part, case-insensitively; a name that matches
several channels is refused with their indices.  The three channels chosen must have the same
length.  The notes of the record (``Record.processing``) say which channels were taken.

MATLAB v7.3 files are HDF5 files, which :func:`scipy.io.loadmat` cannot read: they are read
with ``h5py`` where it is installed (it is not a dependency of the package) and refused with
what to do otherwise.  MATLAB objects (``timeseries``, ``Simulink.SimulationData.Dataset``)
cannot be read from any version: save their data as arrays or a structure with time.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import shown
from .matlab_hdf5 import load_hdf5
from .record_columns import Columns

__all__ = ["Channel", "is_matlab_file", "matlab_channels", "matlab_columns"]

_MATLAB_HEADER = b"MATLAB"


@dataclass(frozen=True)
class Channel:
    """One channel of a MATLAB file: a name, its samples, the unit the file states and where it is."""

    name: str
    data: np.ndarray
    unit: str
    where: str


def is_matlab_file(path: Path) -> bool:
    """Whether ``path`` is to be read as a MATLAB file: a ``.mat`` suffix or MATLAB's header text."""
    if path.suffix.lower() == ".mat":
        return True
    with path.open("rb") as handle:
        return handle.read(len(_MATLAB_HEADER)) == _MATLAB_HEADER


def _load(path: Path) -> dict:
    """The file's variables as dicts (structs), lists (struct arrays, cells), arrays and strings."""
    import scipy.io  # noqa: PLC0415 - lazy: scipy.io is slow to import
    from scipy.io.matlab import matfile_version  # noqa: PLC0415 - lazy: scipy.io is slow to import
    try:
        major, _ = matfile_version(str(path))
    except Exception as exc:  # scipy raises its own MatReadError or ValueError for files it does not know
        raise ValueError(f"{path} is not a MATLAB file that can be read: {exc}") from None
    if major == 2:
        return load_hdf5(path)
    try:
        variables = scipy.io.loadmat(str(path), simplify_cells=True)
    except Exception as exc:  # a damaged file: scipy's message says what it found
        raise ValueError(f"{path}: the MATLAB file cannot be read ({type(exc).__name__}: {exc})") from None
    return {k: v for k, v in variables.items() if not k.startswith("__")}


def _text(value: Any) -> str:
    return value.strip() if isinstance(value, str) else ""


def _as_list(value: Any) -> list:
    if isinstance(value, dict):
        return [value]
    if isinstance(value, np.ndarray) and value.dtype == object:
        return list(value.ravel())
    return list(value) if isinstance(value, (list, tuple)) else []


def _numeric(value: Any) -> np.ndarray | None:
    """``value`` as a numeric array, or ``None`` when it is not real numbers (text, logical, complex, objects)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        value = np.asarray(value, dtype=float)
    if not isinstance(value, np.ndarray) or value.dtype == bool or not np.issubdtype(value.dtype, np.number):
        return None
    if np.issubdtype(value.dtype, np.complexfloating):
        return None
    return value


def _array_channels(name: str, value: Any, unit: str, where: str) -> list[Channel]:
    """A vector as one channel, a matrix as its columns (its rows if wider than tall); a scalar is none."""
    array = _numeric(value)
    if array is None or array.size <= 1:
        return []
    if array.ndim <= 1 or sum(d > 1 for d in array.shape) <= 1:
        return [Channel(name, array.astype(float).ravel(), unit, where)]
    if array.ndim > 2:
        return []
    if array.shape[0] >= array.shape[1]:
        return [Channel(f"{name}(:,{j + 1})", array[:, j].astype(float), unit, f"{where}(:,{j + 1})")
                for j in range(array.shape[1])]
    return [Channel(f"{name}({j + 1},:)", array[j, :].astype(float), unit, f"{where}({j + 1},:)")
            for j in range(array.shape[0])]


def _export_kind(value: Any) -> str | None:
    if isinstance(value, dict):
        if "X" in value and "Y" in value:
            return "X/Y"
        if "time" in value and "signals" in value:
            return "structure with time"
    return None


def _export_channels(name: str, value: dict) -> list[Channel]:
    channels: list[Channel] = []
    if _export_kind(value) == "X/Y":
        xs, ys = _as_list(value["X"]), _as_list(value["Y"])
        for j, x in enumerate(xs):
            if isinstance(x, dict):
                label = _text(x.get("Name")) or ("time" if len(xs) == 1 else f"X({j + 1})")
                channels += _array_channels(label, x.get("Data"), _text(x.get("Unit")), f"{name}.X({j + 1}).Data")
        for k, y in enumerate(ys):
            if isinstance(y, dict):
                label = _text(y.get("Name")) or f"Y({k + 1})"
                channels += _array_channels(label, y.get("Data"), _text(y.get("Unit")), f"{name}.Y({k + 1}).Data")
        return channels
    channels += _array_channels("time", value["time"], "", f"{name}.time")
    for k, signal in enumerate(_as_list(value["signals"])):
        if isinstance(signal, dict):
            label = _text(signal.get("label")) or _text(signal.get("blockName")) or f"signals({k + 1})"
            channels += _array_channels(label, signal.get("values"), "", f"{name}.signals({k + 1}).values")
    return channels


def _variable_channels(name: str, value: Any) -> list[Channel]:
    if _export_kind(value):
        return _export_channels(name, value)
    if isinstance(value, dict):
        channels = []
        for field, item in value.items():
            channels += _array_channels(field, item, "", f"{name}.{field}")
        return channels
    return _array_channels(name, value, "", name)


def matlab_channels(path: Path, variable: str | None = None) -> tuple[list[Channel], str]:
    """The channels of a MATLAB file (see the module) and a description of where they come from.

    Raises
    ------
    ValueError
        If the file cannot be read, ``variable`` is not one of its variables, the file holds
        several exports and no ``variable`` chooses one, or no numeric channel is found.
    """
    variables = _load(path)
    listing = ", ".join(f"{k} ({_describe(v)})" for k, v in variables.items()) or "none"
    if variable is not None:
        if not isinstance(variable, str) or variable not in variables:
            raise ValueError(f"variable = {variable!r} is not a variable of {path}; its variables: {listing}")
        channels, origin = _variable_channels(variable, variables[variable]), f"variable {variable!r}"
    else:
        exports = [k for k, v in variables.items() if _export_kind(v)]
        structs = [k for k, v in variables.items() if isinstance(v, dict)]
        plain = [k for k, v in variables.items() if not isinstance(v, dict)]
        if len(exports) > 1:
            raise ValueError(f"{path} holds {len(exports)} recorder exports ({', '.join(exports)}); choose one with "
                             "variable=")
        if exports:
            channels, origin = _variable_channels(exports[0], variables[exports[0]]), \
                f"the {_export_kind(variables[exports[0]])} export {exports[0]!r}"
        else:
            channels = [c for k in plain for c in _variable_channels(k, variables[k])]
            origin = "the numeric variables"
            if not channels and len(structs) == 1:
                channels, origin = _variable_channels(structs[0], variables[structs[0]]), f"the struct {structs[0]!r}"
    if not channels:
        raise ValueError(
            f"{path}: no numeric channel found in {origin if variable is not None else 'the file'}; its variables: "
            f"{listing}. MATLAB objects (timeseries, Simulink Dataset) cannot be read: save their data as arrays or "
            "as a structure with time"
        )
    return channels, origin


def _describe(value: Any) -> str:
    kind = _export_kind(value)
    if kind:
        return f"{kind} export"
    if isinstance(value, dict):
        return "struct"
    if isinstance(value, np.ndarray):
        return f"{value.dtype} array {'x'.join(map(str, value.shape)) or 'scalar'}"
    return type(value).__name__


def _last_part(name: str) -> str:
    return name.replace("\\", "/").rsplit("/", 1)[-1].strip()


def _choose(channels: list[Channel], choice: Any, default: int, parameter: str, path: Path) -> int:
    def listing() -> str:
        shown = ", ".join(f"{i}: {c.name!r}" for i, c in enumerate(channels[:30]))
        return shown + (f", ... ({len(channels)} in all)" if len(channels) > 30 else "")

    if choice is None:
        index = default
    elif isinstance(choice, str):
        key = choice.strip().lower()
        matches = [i for i, c in enumerate(channels) if c.name.lower() == key] or \
                  [i for i, c in enumerate(channels) if _last_part(c.name).lower() == key]
        if len(matches) > 1:
            raise ValueError(f"{parameter} = {choice!r} names {len(matches)} channels of {path} (indices {matches}); "
                             f"choose one by its index or full name; channels: {listing()}")
        if not matches:
            raise ValueError(f"{parameter} = {choice!r} is not a channel of {path}; channels: {listing()}")
        index = matches[0]
    elif isinstance(choice, (int, np.integer)) and not isinstance(choice, bool) and choice >= 0:
        index = int(choice)
    else:
        raise ValueError(f"{parameter} must be a channel name or an index >= 0, got {shown(choice)}")
    if index >= len(channels):
        raise ValueError(f"{parameter} = {choice!r}: {path} has only {len(channels)} channel(s): {listing()}")
    return index


def matlab_columns(path: Path, time: Any, input: Any, output: Any, *,  # noqa: A002 - the record's input
                   variable: str | None = None) -> Columns:
    """The time, input and output channels of a MATLAB file as the columns of a record.

    Raises
    ------
    ValueError
        As :func:`matlab_channels`, for a channel that is not in the file (the channels are
        listed) or names several, and for chosen channels of different lengths.
    """
    channels, origin = matlab_channels(path, variable)
    chosen = {role: _choose(channels, choice, default, role, path)
              for role, choice, default in (("time", time, 0), ("input", input, 1), ("output", output, 2))}
    picked = {role: channels[i] for role, i in chosen.items()}
    lengths = {role: c.data.size for role, c in picked.items()}
    if len(set(lengths.values())) > 1:
        raise ValueError(
            f"{path}: the channels chosen have different lengths: "
            + ", ".join(f"{role} {picked[role].name!r} {lengths[role]}" for role in picked)
            + "; choose channels recorded together (with one time base)"
        )
    data = np.column_stack([picked[role].data for role in ("time", "input", "output")])
    note = f"MATLAB file, {origin}: " + ", ".join(
        f"{role} = channel {chosen[role]} {picked[role].name!r} ({picked[role].where})" for role in picked)
    hint = ("check the channels chosen (" + ", ".join(f"{role}={chosen[role]}" for role in chosen) + ")")
    return Columns(data, {role: c.name for role, c in picked.items()}, {role: c.unit for role, c in picked.items()},
                   list(range(data.shape[0])), "sample indices", "samples", hint, [note])
