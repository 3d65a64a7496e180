"""Units of a record's columns: which the readers know, how they convert to SI, how given units merge with the file's.

A record's columns (``"time"``, ``"input"``, ``"output"``) carry a unit string: from the file
(a header cell ``name [unit]``, the ``Unit`` field of a recorder's export) or given by the
user (``read_record(..., units={"output": "um"})``).  :data:`SI_SCALE` lists the units the
readers convert to SI (``si=True``): decimal multiples of s, V and m, and strain given in
microstrain.  An empty unit means *unknown*: nothing in the package takes an unknown output
unit for a strain silently (see :func:`exudyn_atcm.model.strain_conversion.model_to_strain`
and :class:`~exudyn_atcm.model.drive.PiezoDrive`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any
from .._checks import shown

__all__ = ["ROLES", "SI_SCALE", "si_scale", "same_unit", "is_length", "is_time", "merge_units"]

#: The three columns of a record.
ROLES = ("time", "input", "output")

#: Units the readers convert to SI: unit -> (factor to the SI unit, SI unit).  The SI units
#: themselves are listed with factor 1 (they are known, nothing is converted).
SI_SCALE: dict[str, tuple[float, str]] = {
    "s": (1.0, "s"), "ms": (1e-3, "s"), "µs": (1e-6, "s"), "μs": (1e-6, "s"), "us": (1e-6, "s"),
    "V": (1.0, "V"), "mV": (1e-3, "V"), "kV": (1e3, "V"),
    "m": (1.0, "m"), "cm": (1e-2, "m"), "mm": (1e-3, "m"), "µm": (1e-6, "m"), "μm": (1e-6, "m"), "um": (1e-6, "m"),
    "nm": (1e-9, "m"),
    "-": (1.0, "-"), "µε": (1e-6, "-"), "με": (1e-6, "-"), "microstrain": (1e-6, "-"),
}


def si_scale(unit: str) -> tuple[float, str] | None:
    """``(factor, SI unit)`` of a known unit (``"um"`` -> ``(1e-6, "m")``), ``None`` for an unknown or empty one."""
    return SI_SCALE.get(unit.strip()) if isinstance(unit, str) else None


def same_unit(a: str, b: str) -> bool:
    """Whether two unit strings mean the same unit (``"um"``, ``"µm"`` and ``"μm"`` do)."""
    a, b = a.strip(), b.strip()
    if a == b:
        return True
    sa, sb = si_scale(a), si_scale(b)
    return sa is not None and sa == sb


def is_length(unit: str) -> bool:
    """Whether ``unit`` is a length the readers know (m and its decimal multiples)."""
    scale = si_scale(unit)
    return scale is not None and scale[1] == "m"


def is_time(unit: str) -> bool:
    """Whether ``unit`` is a time the readers know (s and its decimal multiples)."""
    scale = si_scale(unit)
    return scale is not None and scale[1] == "s"


def _given_units(units: Any) -> dict[str, str]:
    """Check the ``units`` argument of a reader: a mapping of roles to non-empty unit strings."""
    if units is None:
        return {}
    if not isinstance(units, Mapping):
        raise ValueError(f"units must be a mapping such as {{'output': 'um'}}, got {shown(units)}")
    given = {}
    for role, unit in units.items():
        if role not in ROLES:
            raise ValueError(f"units: {role!r} is not a column of a record; the keys are {', '.join(ROLES)}")
        if not isinstance(unit, str) or not unit.strip() or any(c in unit for c in "[]"):
            raise ValueError(f"units[{role!r}] must be a non-empty unit string such as 'um' (no brackets), got {shown(unit)}")
        given[role] = unit.strip()
    time_unit = given.get("time")
    if time_unit is not None and not is_time(time_unit):
        known = ", ".join(u for u, (_, base) in SI_SCALE.items() if base == "s")
        raise ValueError(f"units['time'] must be a unit of time ({known}), got {shown(time_unit)}")
    return given


def merge_units(file_units: Mapping[str, str], units: Any, labels: Mapping[str, str], source: str) -> tuple[dict, list]:
    """The columns' units from the file's and the ones given, with a note for each unit given.

    Parameters
    ----------
    file_units : mapping
        The unit the file states for each role (``""``: none).
    units : mapping or None
        The ``units`` argument: role -> unit, for columns the file gives no unit or to confirm
        the file's.
    labels : mapping
        How each role's column is called in messages (``"'disp [mm]'"``).
    source : str
        The file, for messages.

    Returns
    -------
    (dict, list of str)
        The unit of every role (time defaults to ``"s"`` when neither says) and notes for
        ``Record.processing``.

    Raises
    ------
    ValueError
        If ``units`` is not a mapping of roles to unit strings, the time unit is not a time,
        or a unit given differs from the one the file states (both are named).
    """
    given = _given_units(units)
    merged, notes = {}, []
    for role in ROLES:
        stated = (file_units.get(role) or "").strip()
        unit = given.get(role)
        if unit is None:
            merged[role] = stated
        elif not stated:
            merged[role] = unit
            notes.append(f"{role} unit {unit!r} given (units=); the file states none")
        elif same_unit(unit, stated):
            merged[role] = stated
        else:
            raise ValueError(
                f"{source}: units[{role!r}] = {unit!r} conflicts with the unit the file states for the {role} "
                f"column {labels.get(role, role)} ({stated!r}); give the file's unit (or leave the key out), or "
                "correct the file"
            )
    if not merged["time"]:
        merged["time"] = "s"
        notes.append("time unit not stated, taken as s")
    for role in ("input", "output"):
        if not merged[role]:
            notes.append(f"{role} unit unknown (the file states none; give it with units={{{role!r}: ...}})")
    return merged, notes
