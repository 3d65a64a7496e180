"""Declared parameters of a case: :class:`Parameter` (name, default, unit, help, choices, bounds)
and the typed values of one run, :class:`Parameters`; :class:`CaseError` for a case that cannot be found,
loaded or configured.
"""

from __future__ import annotations

import math
import numbers
import sys
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..cells import cell_kind_names
from ..suggestions import close_names

__all__ = ["Parameter", "Parameters", "CaseError", "CellChoices", "closest", "json_value"]

_TYPES = ("float", "int", "bool", "str", "floats")
#: bound fields of a :class:`Parameter` and their comparison
_BOUNDS = {"minimum": ">=", "exclusive_minimum": ">", "maximum": "<=", "exclusive_maximum": "<"}
_TRUE = {"true", "yes", "on", "1"}
_FALSE = {"false", "no", "off", "0"}


class CaseError(ValueError):
    """A case could not be found, loaded or configured (message is one line)."""


def closest(name: str, candidates: Sequence[str]) -> str:
    """`` (did you mean 'x'?)`` for the candidate closest to a misspelt ``name``, else ``""``."""
    match = close_names(name, candidates, cutoff=0.6, ignore_case=True)
    return f" (did you mean {match[0]!r}?)" if match else ""


def _is_bool(value: Any) -> bool:
    """A Python or a NumPy bool (refused where a number is expected); NumPy is not imported for this."""
    if isinstance(value, bool):
        return True
    np = sys.modules.get("numpy")
    return np is not None and isinstance(value, np.bool_)


def _is_integer(value: Any) -> bool:
    """A Python or a NumPy integer, not a bool (a whole float is not an integer)."""
    return isinstance(value, numbers.Integral) and not _is_bool(value)


def _is_real(value: Any) -> bool:
    """A Python or a NumPy int or float, not a bool."""
    return isinstance(value, numbers.Real) and not _is_bool(value)


def _shown(value: Any) -> str:
    """``value`` for a message: the repr, with NumPy scalars as their Python values (``2``, not ``np.int64(2)``)."""
    if isinstance(value, (tuple, list)):
        items = ", ".join(_shown(v) for v in value)
        return f"({items},)" if isinstance(value, tuple) and len(value) == 1 else (
            f"({items})" if isinstance(value, tuple) else f"[{items}]")
    item = getattr(value, "item", None)
    if type(value).__module__ == "numpy" and callable(item) and getattr(value, "ndim", None) == 0:
        value = item()
    return repr(value)


# ----------------------------------------------------------------------------- parameters
def _infer_type(default: Any) -> str:
    if isinstance(default, bool):
        return "bool"
    if isinstance(default, int):
        return "int"
    if isinstance(default, float):
        return "float"
    if isinstance(default, str):
        return "str"
    if isinstance(default, (tuple, list)) and all(
        isinstance(v, (int, float)) and not isinstance(v, bool) for v in default
    ):
        return "floats"
    raise ValueError(
        f"default must be a float, int, bool, str or tuple of floats, got {default!r} "
        f"of type {type(default).__name__}"
    )


@dataclass(frozen=True)
class Parameter:
    """One declared parameter of a case.

    Parameters
    ----------
    name : str
        Identifier used in ``--set NAME=VALUE`` and as ``p.name`` in the run function.
    default : float, int, bool, str or tuple of float
        Default value; its Python type fixes the parameter's type (``1.0`` is a float,
        ``1`` an int, a tuple of numbers is a comma-separated list of floats).  A list
        parameter whose default is the empty tuple ``()`` also accepts an empty value
        (``--set NAME=`` or ``()``), which then means the same as its default (the help
        text says what, e.g. "empty: from the reference design"); any other list parameter
        needs at least one number.
    unit : str
        SI unit of the value (``"-"`` if unit-free).
    help : str
        One-line description.
    choices : tuple or callable, optional
        Allowed values (for ``str`` parameters, typically), or a function of no arguments returning
        them when they are used (a registry that may grow after the case is loaded, e.g.
        :class:`CellChoices`).
    minimum, exclusive_minimum, maximum, exclusive_maximum : float, optional
        Bounds of a number (``float``, ``int``; for a list of floats, of every item), in the
        parameter's unit, as in JSON Schema: ``value >= minimum``, ``value > exclusive_minimum``,
        ``value <= maximum``, ``value < exclusive_maximum``.  A value outside is refused when
        ``--set``, a sweep's grid or samples, or an optimisation's bounds are read, before
        anything runs; ``exudyn-atcm list`` shows them.  Example: ``Parameter("step", 1e-4, "s", "time step", exclusive_minimum=0.0)``.
    """

    name: str
    default: Any
    unit: str = "-"
    help: str = ""
    choices: tuple | Callable[[], tuple] | None = None
    minimum: float | None = None
    exclusive_minimum: float | None = None
    maximum: float | None = None
    exclusive_maximum: float | None = None
    kind: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise ValueError(f"name must be a Python identifier, got {self.name!r}")
        object.__setattr__(self, "kind", _infer_type(self.default))
        if self.kind == "floats":
            object.__setattr__(self, "default", tuple(float(v) for v in self.default))
        elif self.kind == "float":
            object.__setattr__(self, "default", float(self.default))  # a NumPy float is a float: shown as 0.5
        if self.choices is not None:
            if not callable(self.choices):
                object.__setattr__(self, "choices", tuple(self.choices))
            if self.default not in self.allowed():
                raise ValueError(f"default of {self.name!r} must be one of {self.allowed()}, got {_shown(self.default)}")
        bounds = {key: getattr(self, key) for key in _BOUNDS}
        given = {key: value for key, value in bounds.items() if value is not None}
        if given and self.kind not in ("float", "int", "floats"):
            raise ValueError(f"{', '.join(given)} of {self.name!r}: bounds need a number parameter (float, int or "
                             f"a list of floats), it is a {self.kind} parameter")
        for key, value in given.items():
            if not _is_real(value) or math.isnan(value):
                raise ValueError(f"{key} of {self.name!r} must be a number, got {_shown(value)}")
            object.__setattr__(self, key, int(value) if _is_integer(value) else float(value))
        if given and not self._in_bounds(self.default):
            raise ValueError(f"default of {self.name!r} must be {self._bounds_text()}, got {_shown(self.default)}")

    def allowed(self) -> tuple | None:
        """The allowed values, read now (``None``: any value of the type)."""
        if self.choices is None:
            return None
        return tuple(self.choices()) if callable(self.choices) else self.choices

    def describe(self) -> str:
        """``name = default [unit] (type): help``."""
        default = ",".join(repr(v) for v in self.default) if self.kind == "floats" else repr(self.default)
        choices = f", one of {'/'.join(map(str, self.allowed()))}" if self.choices else ""
        bounds = f", {self._bounds_text()}" if self._bounds_text() else ""
        return f"{self.name} = {default} [{self.unit}] ({self.kind}{choices}{bounds}): {self.help}"

    def parse(self, text: str) -> Any:
        """Convert the text of ``--set NAME=TEXT`` to the parameter's type.

        Numbers are read as by Python's ``float`` and ``int`` (``1e-3``, ``inf`` is then refused as not
        finite; digit-group underscores such as ``1_000`` are accepted, as in Python source).  A list
        (``floats``) is comma-separated; an empty item (``1,,2``, ``1,2,``) is refused, and only a list
        parameter whose default is ``()`` accepts an entirely empty text (meaning its default).

        Raises
        ------
        ValueError
            If the text is not a value of the parameter's type (or not one of the choices).
        """
        raw = text.strip()
        if self.kind == "floats" and raw != "":
            items = [v.strip() for v in raw.split(",")]
            empty = [str(i) for i, v in enumerate(items, start=1) if v == ""]
            if empty:
                where = f"item {empty[0]} is" if len(empty) == 1 else f"items {', '.join(empty)} are"
                raise ValueError(f"{self.name} must be {self._kind_text()}, got {text!r}: {where} empty "
                                 f"(of {len(items)})")
        try:
            if self.kind == "float":
                value: Any = float(raw)
            elif self.kind == "int":
                value = int(raw)
            elif self.kind == "bool":
                low = raw.lower()
                if low not in _TRUE | _FALSE:
                    raise ValueError
                value = low in _TRUE
            elif self.kind == "floats":
                value = () if raw == "" and self._empty_allowed() else tuple(float(v) for v in raw.split(","))
            else:
                value = text
        except ValueError:
            raise ValueError(f"{self.name} must be {self._kind_text()}, got {text!r}") from None
        return self.check(value)

    def check(self, value: Any) -> Any:
        """Check a Python value for this parameter and return it (ints accepted for floats).

        NumPy numbers are accepted as the Python ones (``np.int64(2)`` for an int, ``np.float64(0.5)`` or an
        integer for a float) and returned as Python ``int`` or ``float``; bools (Python or NumPy) are not
        numbers, and a float is not an int even if whole (``2.0`` and ``np.float64(2.0)`` are refused for an
        int parameter).
        """
        ok = True
        if self.kind == "float":
            ok = _is_real(value) and math.isfinite(value)
            value = float(value) if ok else value
        elif self.kind == "int":
            ok = _is_integer(value)
            value = int(value) if ok else value
        elif self.kind == "bool":
            ok = isinstance(value, bool)
        elif self.kind == "str":
            ok = isinstance(value, str)
        elif self.kind == "floats":
            try:
                items = tuple(value)
                ok = all(_is_real(v) and math.isfinite(v) for v in items) and (len(items) > 0 or self._empty_allowed())
                value = tuple(float(v) for v in items) if ok else value
            except TypeError:
                ok = False
        if not ok:
            raise ValueError(f"{self.name} must be {self._kind_text()}, got {_shown(value)}")
        if self.choices is not None and value not in self.allowed():
            raise ValueError(f"{self.name} must be one of {', '.join(map(str, self.allowed()))}, got {_shown(value)}")
        self.check_range(value)
        return value

    def check_range(self, *values: Any) -> None:
        """Raise ``ValueError`` for the first of ``values`` (numbers; a tuple: any of its items) outside the
        declared bounds; a range ``(low, high)`` of a sweep or an optimisation passes both ends."""
        for value in values:
            if not self._in_bounds(value):
                unit = "" if self.unit == "-" else f" [{self.unit}]"
                items = " (every item)" if isinstance(value, tuple) else ""
                raise ValueError(f"{self.name} must be {self._bounds_text()}{unit}{items}, got {_shown(value)}")

    def _in_bounds(self, value: Any) -> bool:
        values = value if isinstance(value, tuple) else (value,)
        return all((self.minimum is None or v >= self.minimum)
                   and (self.exclusive_minimum is None or v > self.exclusive_minimum)
                   and (self.maximum is None or v <= self.maximum)
                   and (self.exclusive_maximum is None or v < self.exclusive_maximum) for v in values)

    def _bounds_text(self) -> str:
        """``"> 0"``, ``">= 1 and <= 10"``; empty without bounds."""
        parts = [f"{sign} {getattr(self, key):g}" for key, sign in _BOUNDS.items() if getattr(self, key) is not None]
        return " and ".join(parts)

    def _empty_allowed(self) -> bool:
        return self.kind == "floats" and len(self.default) == 0

    def _kind_text(self) -> str:
        if self._empty_allowed():
            return f"comma-separated finite real numbers [{self.unit}], or empty"
        return {
            "float": f"a finite real number [{self.unit}]",
            "int": "an integer",
            "bool": "true or false",
            "str": "a string",
            "floats": f"comma-separated finite real numbers [{self.unit}]",
        }[self.kind]


@dataclass(frozen=True)
class CellChoices:
    """The names of the registered cell kinds a case accepts, read when used (so that a kind registered with
    :func:`exudyn_atcm.register_cell_kind` after the case was loaded is accepted by name).

    Parameters
    ----------
    joins_anywhere : bool
        Only kinds whose bender ends can be joined to other parts (no cantilever-only kinds).
    carries_tip_load : bool
        Only kinds that carry tip loads.
    first : tuple of str
        Names listed first (the case's usual choice), the others in registration order.
    """

    joins_anywhere: bool = False
    carries_tip_load: bool = False
    first: tuple[str, ...] = ()

    def __call__(self) -> tuple[str, ...]:
        names = cell_kind_names(lambda kind: (not self.joins_anywhere or all(
            kind.end_refusal(end, "joined") is None for end in ("base", "tip")))
            and (not self.carries_tip_load or kind.carries_tip_load))
        return tuple([n for n in self.first if n in names] + [n for n in names if n not in self.first])


class Parameters(Mapping):
    """The resolved, typed parameter values of one run: ``p.name`` or ``p["name"]``."""

    def __init__(self, declared: Sequence[Parameter], values: Mapping[str, Any]) -> None:
        self._declared = {d.name: d for d in declared}
        self._values = dict(values)

    def __getitem__(self, name: str) -> Any:
        return self._values[name]

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self._values[name]
        except KeyError:
            raise AttributeError(f"no parameter {name!r}; declared: {', '.join(self._values)}") from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def unit(self, name: str) -> str:
        """Unit of parameter ``name``."""
        return self._declared[name].unit

    def with_units(self) -> dict[str, Any]:
        """``{"name [unit]": value}``, as written into CSV metadata."""
        return {f"{n} [{self._declared[n].unit}]": json_value(v) for n, v in self._values.items()}

    def __repr__(self) -> str:
        return "Parameters(" + ", ".join(f"{k}={v!r}" for k, v in self._values.items()) + ")"


def json_value(value: Any) -> Any:
    """A parameter value as written to JSON and CSV metadata: tuples (``floats`` parameters) as lists."""
    return list(value) if isinstance(value, tuple) else value
