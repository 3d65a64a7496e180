"""The points of a study: full grids, random or Latin-hypercube samples, explicit lists.

Every function here returns a list of ``{name: value}`` dictionaries with values already
checked against the case's declared :class:`~exudyn_atcm.casework.parameters.Parameter` (type, choices),
in a fixed order: a full grid varies its *last* named parameter fastest (like nested
``for`` loops written in the order given), samples come in the order the generator draws
them.  The order is the study's run order and the row order of its table, whatever engine
runs it.

Grid specifications on the command line (:func:`parse_grid_spec`)::

    name=start:stop:n    n evenly spaced values from start to stop (both included)
    name=start:stop      integers: every integer from start to stop; with --samples: a range
    name=a,b,c           an explicit list (any type; ';' separates lists of a floats parameter)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from .._checks import shown
from ..suggestions import close_names
from ..casework import Case, CaseError, Parameter

__all__ = [
    "GridError",
    "full_grid",
    "sample_points",
    "explicit_points",
    "parse_grid_spec",
    "check_point",
    "SAMPLING_METHODS",
]

#: Sampling methods of :func:`sample_points`.
SAMPLING_METHODS = ("lhs", "random")


class GridError(CaseError):
    """A grid, sample or point specification is invalid (one-line message)."""


def _declared(case: Case) -> dict[str, Parameter]:
    return {p.name: p for p in case.parameters}


def case_parameter(case: Case, name: str, what: str = "grid") -> Parameter:
    declared = _declared(case)
    if name in declared:
        return declared[name]
    close = close_names(name, declared, cutoff=0.5)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    names = ", ".join(declared) or "(none)"
    raise GridError(f"{what}: unknown parameter {name!r} for case {case.name}{hint} (parameters: {names})")


def _check_value(parameter: Parameter, value: Any, case: Case) -> Any:
    if isinstance(value, np.generic):
        value = value.item()
    if parameter.kind == "int" and isinstance(value, float) and value.is_integer():
        value = int(value)
    try:
        if isinstance(value, str) and parameter.kind != "str":
            return parameter.parse(value)
        return parameter.check(value)
    except ValueError as exc:
        raise GridError(f"case {case.name}: {exc}") from None


def check_point(case: Case, point: Mapping[str, Any]) -> dict[str, Any]:
    """Check one point ``{name: value}`` against the case's parameters; the typed values.

    Raises
    ------
    GridError
        For an unknown name (with the closest declared name) or a value of the wrong type.
    """
    if not isinstance(point, Mapping):
        raise GridError(f"a point must be a mapping of parameter names to values, got {shown(point)}")
    return {name: _check_value(case_parameter(case, name, "point"), value, case) for name, value in point.items()}


def full_grid(case: Case, grid: Mapping[str, Iterable[Any]]) -> list[dict[str, Any]]:
    """Every combination of the values in ``grid`` (the last name varies fastest).

    Parameters
    ----------
    case : Case
        The case whose declared parameters the names refer to.
    grid : mapping of str to iterable
        Values of each varied parameter, e.g. ``{"n_cells": [2, 4], "period": np.linspace(1, 2, 3)}``.

    Raises
    ------
    GridError
        For an unknown parameter, an empty list of values, or a value of the wrong type.
    """
    if not isinstance(grid, Mapping):
        raise GridError(f"grid must be a mapping of parameter names to lists of values, got {type(grid).__name__}")
    names: list[str] = []
    axes: list[list[Any]] = []
    for name, values in grid.items():
        parameter = case_parameter(case, name)
        if isinstance(values, (str, bytes)) or not isinstance(values, Iterable):
            raise GridError(f"grid: values of {name!r} must be a list or array of values, got {shown(values)}")
        checked = [_check_value(parameter, v, case) for v in (np.asarray(values).tolist() if isinstance(values, np.ndarray) else values)]
        if not checked:
            raise GridError(f"grid: {name!r} has no values (empty range)")
        names.append(name)
        axes.append(checked)
    return [dict(zip(names, combo)) for combo in itertools.product(*axes)]


def sample_points(
    case: Case,
    bounds: Mapping[str, tuple[float, float]],
    n: int,
    *,
    method: str = "lhs",
    seed: int | None = 0,
) -> list[dict[str, Any]]:
    """``n`` points drawn within ``bounds``: Latin hypercube (default) or uniform random.

    Parameters
    ----------
    case : Case
        The case.
    bounds : mapping of str to (low, high)
        Range of each sampled parameter (``float`` or ``int`` parameters; integers are
        drawn from ``low ... high`` inclusive, each integer with equal probability).
    n : int
        Number of points, >= 1.
    method : {"lhs", "random"}
        ``"lhs"``: :class:`scipy.stats.qmc.LatinHypercube`; ``"random"``: independent uniform.
    seed : int or None
        Seed of the generator (default 0: a study is reproducible).

    Raises
    ------
    GridError
        For an unknown or non-numeric parameter, ``low > high``, non-finite bounds, ``n < 1``
        or an unknown method.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise GridError(f"samples: n must be an integer >= 1, got {shown(n)}")
    if method not in SAMPLING_METHODS:
        raise GridError(f"samples: method must be one of {', '.join(SAMPLING_METHODS)}, got {shown(method)}")
    if not bounds:
        raise GridError("samples: bounds must name at least one parameter")
    names = list(bounds)
    params = [case_parameter(case, name, "samples") for name in names]
    lows, highs = [], []
    for parameter in params:
        if parameter.kind not in ("float", "int"):
            raise GridError(f"samples: {parameter.name!r} is a {parameter.kind} parameter; only float and int parameters can be sampled in a range")
        try:
            low, high = (float(v) for v in bounds[parameter.name])
        except (TypeError, ValueError):
            raise GridError(f"samples: bounds of {parameter.name!r} must be (low, high), got {bounds[parameter.name]!r}") from None
        if not (math.isfinite(low) and math.isfinite(high)) or low > high:
            raise GridError(f"samples: bounds of {parameter.name!r} must be finite with low <= high, got ({low!r}, {high!r}) (empty range)")
        try:  # every sample lies in [low, high]: both ends must be values the case accepts
            parameter.check_range(low, high)
        except ValueError as exc:
            raise GridError(f"samples: {exc} (the case's declared range)") from None
        if parameter.kind == "int":
            if not (low.is_integer() and high.is_integer()):
                raise GridError(f"samples: bounds of the int parameter {parameter.name!r} must be integers, got ({low!r}, {high!r})")
            high += 1.0  # integers low ... high inclusive: floor of U(low, high + 1)
        lows.append(low)
        highs.append(high)
    if method == "lhs":
        from scipy.stats import qmc

        unit = qmc.LatinHypercube(d=len(names), seed=seed).random(int(n))
    else:
        unit = np.random.default_rng(seed).random((int(n), len(names)))
    scaled = np.asarray(lows) + unit * (np.asarray(highs) - np.asarray(lows))
    points = []
    for row in scaled:
        point = {}
        for parameter, value, high in zip(params, row, highs):
            if parameter.kind == "int":
                point[parameter.name] = int(min(math.floor(value), high - 1.0))
            else:
                point[parameter.name] = float(value)
        points.append(point)
    return points


def explicit_points(case: Case, points: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """An explicit list of points, each ``{name: value}``, checked (order kept)."""
    if isinstance(points, Mapping) or not isinstance(points, Sequence) or not points:
        raise GridError("points must be a non-empty list of {name: value} mappings")
    return [check_point(case, point) for point in points]


def parse_grid_spec(case: Case, text: str, *, ranges: bool = False, option: str = "--grid") -> tuple[str, list[Any] | tuple[float, float]]:
    """Parse one ``--grid`` specification.

    Parameters
    ----------
    case : Case
        The case.
    text : str
        ``name=start:stop:n``, ``name=start:stop`` or ``name=a,b,c`` (see the module docs).
    ranges : bool
        With ``--samples``: ``start:stop`` of a float or int parameter is a range to sample
        from and is returned as ``(start, stop)``.
    option : str
        The command-line option named in the messages (``"--grid"`` or ``"--bound"``).

    Returns
    -------
    (str, list or (float, float))
        The parameter name and its values, or its range when ``ranges`` and a range is given.

    Raises
    ------
    GridError
        One line: malformed text, unknown parameter (with the closest name), wrong type,
        ``n < 1``, an empty range or list.
    """
    name, sep, spec = text.partition("=")
    name = name.strip()
    if not sep or not name:
        raise GridError(f"{option} expects NAME=START:STOP:N or NAME=A,B,C, got {shown(text)}")
    parameter = case_parameter(case, name, option)
    spec = spec.strip()
    if not spec:
        raise GridError(f"{option} {name}: no values given (empty range) in {text!r}")
    if ":" in spec and parameter.kind in ("float", "int"):
        parts = [s.strip() for s in spec.split(":")]
        if len(parts) not in (2, 3) or any(not s for s in parts):
            raise GridError(f"{option} {name}: a range is START:STOP:N (or START:STOP), got {shown(spec)}")
        try:
            start, stop = float(parts[0]), float(parts[1])
        except ValueError:
            raise GridError(f"{option} {name}: START and STOP must be numbers, got {parts[0]!r} and {parts[1]!r}") from None
        if not (math.isfinite(start) and math.isfinite(stop)):
            raise GridError(f"{option} {name}: START and STOP must be finite, got {shown(spec)}")
        if len(parts) == 2:
            if ranges:
                if start > stop:
                    raise GridError(f"{option} {name}: empty range {spec!r} (START > STOP)")
                if parameter.kind == "int" and not (start.is_integer() and stop.is_integer()):
                    raise GridError(f"{option} {name}: {name} is an integer parameter, got the range {spec!r}")
                return name, (start, stop)
            if parameter.kind != "int":
                raise GridError(f"{option} {name}: a float range needs the number of values, START:STOP:N, got {shown(spec)}")
            if not (start.is_integer() and stop.is_integer()):
                raise GridError(f"{option} {name}: {name} is an integer parameter, got the range {spec!r}")
            if start > stop:
                raise GridError(f"{option} {name}: empty range {spec!r} (START > STOP)")
            return name, list(range(int(start), int(stop) + 1))
        try:
            count = int(parts[2])
        except ValueError:
            raise GridError(f"{option} {name}: N must be an integer >= 1, got {parts[2]!r}") from None
        if count < 1:
            raise GridError(f"{option} {name}: N must be an integer >= 1, got {count}")
        if count == 1 and start != stop:
            raise GridError(f"{option} {name}: N = 1 needs START == STOP, got {shown(spec)}")
        values = np.linspace(start, stop, count)
        if parameter.kind == "int":
            if not np.allclose(values, np.round(values), rtol=0.0, atol=1e-9):
                raise GridError(f"{option} {name}: {name} is an integer parameter but {spec!r} gives non-integer values {values.tolist()}")
            return name, [int(round(v)) for v in values]
        return name, [float(v) for v in values]
    separator = ";" if parameter.kind == "floats" else ","
    items = [s.strip() for s in spec.split(separator)]
    if any(not s for s in items):
        raise GridError(f"{option} {name}: empty item in the list {spec!r}")
    try:
        return name, [parameter.parse(s) for s in items]
    except ValueError as exc:
        raise GridError(f"{option} {name}: {exc}") from None
