"""What a case file declares about itself besides its parameters: its smoke settings, its
regression benchmarks and its line in the case tables (issue 30, part 4).

A case is one file.  Everything kept about it elsewhere is generated from, or checked against,
what it declares in ``CASE = Case(...)``:

``smoke``
    The cheap ``--set`` values a smoke test runs the case with (a mapping of parameter names to
    values; ``{}`` or ``None``: the defaults are cheap).  The package's smoke test runs every case
    it finds with these settings and fails on any package warning.
``benchmarks``
    The case's entries of the regression suite, each one entry in the ``suite.json`` schema
    (:mod:`exudyn_atcm.casework.regression`) without the ``"case"`` key, which is the case's name:
    an ``"id"``, fixed ``"parameters"``, the ``"channels"`` and ``"scalars"`` compared with their
    tolerances (analytic values with their ``"source"``), ``"quick"``, ``"base"``, ``"enabled"``
    and ``"note"``.  The suite runs the benchmarks of every case in its case folders.
``summary`` and ``table_order``
    The case's row in the case tables of the README and the docs (``exudyn-atcm list --table md``
    prints them, :mod:`exudyn_atcm.casework.case_table`): what it shows and its reference, and its
    position (cases with the same summary share a row).  Without a summary the row is the case's
    one-line description; without an order the row comes after the ordered ones, by name.

Every declaration is checked when the case file is loaded (a misspelt parameter, a value of the
wrong type, a benchmark without tolerance, a duplicate id): a ``ValueError`` naming the case.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

__all__ = ["BENCHMARK_KEYS", "SCALAR_KEYS", "check_benchmark", "declared_benchmarks", "declared_smoke",
           "declared_order"]

#: Keys of one benchmark entry (``suite.json`` or a case's ``benchmarks``).
BENCHMARK_KEYS = frozenset({"id", "case", "parameters", "quick", "channels", "scalars", "enabled", "note", "base"})
#: Keys of one scalar metric of a benchmark.
SCALAR_KEYS = frozenset({"name", "scalar", "analytic", "source", "abs", "rel"})


def check_benchmark(bench: Mapping[str, Any], where: str) -> None:
    """Check one benchmark entry; ``where`` starts the error message (file and position).

    Raises
    ------
    ValueError
        For unknown keys, an ``id`` or ``case`` that is not a string, a channel tolerance or a
        scalar without a tolerance that is a number >= 0, or an analytic value without its source.
    """
    if not isinstance(bench, Mapping):
        raise ValueError(f"{where}: a benchmark must be a mapping (a suite.json entry), got {bench!r}")
    unknown = set(bench) - BENCHMARK_KEYS
    if unknown:
        raise ValueError(f"{where}: unknown keys {sorted(unknown)}; allowed: {sorted(BENCHMARK_KEYS)}")
    for key in ("id", "case"):
        if not isinstance(bench.get(key), str) or not bench[key]:
            raise ValueError(f"{where}: {key!r} must be a non-empty string, got {bench.get(key)!r}")
    for channel, tol in bench.get("channels", {}).items():
        for key in ("rms", "max"):
            value = tol.get(key) if isinstance(tol, Mapping) else None
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not value >= 0:
                raise ValueError(f"{where}: channels[{channel!r}][{key!r}] must be a number >= 0, got {value!r}")
    for j, metric in enumerate(bench.get("scalars", [])):
        unknown = set(metric) - SCALAR_KEYS
        if unknown:
            raise ValueError(f"{where}: scalars[{j}]: unknown keys {sorted(unknown)}; allowed: {sorted(SCALAR_KEYS)}")
        if not isinstance(metric.get("scalar"), str):
            raise ValueError(f"{where}: scalars[{j}]: 'scalar' must name a key scalar of the case")
        if "abs" not in metric and "rel" not in metric:
            raise ValueError(f"{where}: scalars[{j}] ({metric['scalar']}): give a tolerance 'abs' and/or 'rel'")
        for key in ("abs", "rel"):
            value = metric.get(key, 0.0)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not value >= 0:
                raise ValueError(f"{where}: scalars[{j}] ({metric['scalar']}): {key!r} must be a number >= 0, got {value!r}")
        if "analytic" in metric and "source" not in metric:
            raise ValueError(f"{where}: scalars[{j}] ({metric['scalar']}): an analytic value needs its 'source'")


def declared_benchmarks(name: str, benchmarks: Sequence[Mapping[str, Any]] | None,
                        resolve: Callable[[Mapping[str, Any]], Any]) -> tuple[dict[str, Any], ...]:
    """The checked benchmark entries of case ``name``, each with ``"case": name``.

    ``resolve`` checks a benchmark's ``parameters`` against the case's declared parameters
    (:meth:`Case.resolve <exudyn_atcm.casework.case.Case.resolve>`).  The entries are copied, so a
    case file cannot change them afterwards.

    Raises
    ------
    ValueError
        For an entry that :func:`check_benchmark` refuses, a ``"case"`` other than ``name``, a
        duplicate id or a fixed parameter the case does not declare or of the wrong type.
    """
    if benchmarks is None:
        return ()
    if isinstance(benchmarks, Mapping) or not isinstance(benchmarks, Sequence):
        raise ValueError(f"case {name}: benchmarks must be a list of suite entries, got {type(benchmarks).__name__}")
    entries: list[dict[str, Any]] = []
    for i, bench in enumerate(benchmarks):
        where = f"case {name}: benchmarks[{i}]"
        if isinstance(bench, Mapping) and bench.get("case", name) != name:
            raise ValueError(f"{where}: 'case' is the declaring case {name!r}, got {bench['case']!r} (leave it out)")
        entry = {"id": None, "case": name, **copy.deepcopy(dict(bench))} if isinstance(bench, Mapping) else bench
        check_benchmark(entry, where)
        if entry["id"] in [e["id"] for e in entries]:
            raise ValueError(f"{where}: duplicate id {entry['id']!r}")
        parameters = entry.get("parameters", {})
        if not isinstance(parameters, Mapping):
            raise ValueError(f"{where}: 'parameters' must be a mapping of parameter names to values, got {parameters!r}")
        try:
            resolve(parameters)
        except ValueError as exc:
            raise ValueError(f"{where} ({entry['id']}): parameters: {_own(name, exc)}") from None
        entries.append(entry)
    return tuple(entries)


def declared_smoke(name: str, smoke: Mapping[str, Any] | None,
                   resolve: Callable[[Mapping[str, Any]], Any]) -> dict[str, Any]:
    """The checked smoke settings of case ``name`` (``{}``: its defaults).

    Raises
    ------
    ValueError
        For settings that are not a mapping, or a name or value the case refuses.
    """
    if smoke is None:
        return {}
    if not isinstance(smoke, Mapping):
        raise ValueError(f"case {name}: smoke must be a mapping of parameter names to cheap values, got {smoke!r}")
    try:
        resolve(smoke)
    except ValueError as exc:
        raise ValueError(f"case {name}: smoke: {_own(name, exc)}") from None
    return dict(smoke)


def declared_order(name: str, table_order: float | None) -> float:
    """The case's position in the case tables (``inf``: after the ordered cases).

    Raises
    ------
    ValueError
        For an order that is not a real number.
    """
    if table_order is None:
        return math.inf
    if isinstance(table_order, bool) or not isinstance(table_order, (int, float)) or math.isnan(table_order):
        raise ValueError(f"case {name}: table_order must be a number (the row's position), got {table_order!r}")
    return float(table_order)


def _own(name: str, exc: ValueError) -> str:
    """The message of a refusal by the case itself, without its leading ``case NAME:``."""
    return str(exc).removeprefix(f"case {name}: ")
