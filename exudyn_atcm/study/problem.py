"""The optimisation problem behind :func:`~exudyn_atcm.study.optimize`: design vectors to runs.

:class:`Problem` maps normalised design vectors ``u`` in ``[0, 1]^n`` to parameter points,
runs them through a study engine (whole populations at once, remembering every record),
and turns each record into the objective, the constraint violation and the penalised value
the scipy optimiser minimises.  Every evaluation is kept in order for the history table.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from ..casework import Case
from .sweep import run_study
from .table import Column

__all__ = ["Problem", "Objective", "check_objective", "check_constraints", "history_columns"]

#: A key scalar's name, or ``objective(scalars, values) -> float``.
Objective = str | Callable[[Mapping[str, float], Mapping[str, Any]], float]


class Problem:
    """Maps normalised design vectors to runs, objective values and constraint violations."""

    def __init__(self, case, names, lows, highs, kinds, fixed, objective, maximize, constraints, penalty,
                 engine, store):
        self.case, self.names, self.kinds = case, names, kinds
        self.lows, self.highs = np.asarray(lows, float), np.asarray(highs, float)
        self.fixed, self.objective, self.maximize = fixed, objective, maximize
        self.constraints, self.penalty = constraints, penalty
        self.engine, self.store = engine, store
        self.records: dict[tuple, dict[str, Any]] = {}
        self.history: list[tuple[dict[str, Any], dict[str, Any]]] = []
        self.executed = 0
        self.error: Exception | None = None
        #: ``monitor(known, executed)`` after every batch of runs (e.g. a :class:`~exudyn_atcm.study.budget.RunBudget`)
        self.monitor: Callable[[int, int], None] | None = None

    # -- coordinates ----------------------------------------------------------------------
    def point(self, u: np.ndarray) -> dict[str, Any]:
        x = self.lows + np.clip(np.asarray(u, float), 0.0, 1.0) * (self.highs - self.lows)
        return {n: int(round(v)) if k == "int" else float(v) for n, v, k in zip(self.names, x, self.kinds)}

    def _key(self, point: Mapping[str, Any]) -> tuple:
        return tuple(point[n] for n in self.names)

    # -- runs ------------------------------------------------------------------------------
    def prefetch(self, us: Sequence[np.ndarray]) -> None:
        """Run (in parallel) every point of ``us`` not yet known."""
        points = []
        for u in us:
            p = self.point(u)
            if self._key(p) not in self.records and p not in points:
                points.append(p)
        if not points:
            return
        result = run_study(self.case, points=points, fixed=self.fixed, store=self.store, engine=self.engine)
        self.executed += result.executed
        for p, record in zip(points, result.records):
            self.records[self._key(p)] = record
        if self.monitor is not None:
            self.monitor(len(self.records), self.executed)

    def record(self, u: np.ndarray) -> dict[str, Any]:
        p = self.point(u)
        if self._key(p) not in self.records:
            self.prefetch([u])
        return self.records[self._key(p)]

    # -- objective and constraints -----------------------------------------------------------
    def raw_objective(self, record: Mapping[str, Any]) -> float:
        if record["status"] != "ok":
            return math.nan
        scalars = record["scalars"]
        if callable(self.objective):
            return float(self.objective(scalars, record["values"]))
        if self.objective not in scalars:
            raise ValueError(f"objective {self.objective!r} is not a key scalar of case {self.case.name}; "
                             f"its key scalars: {', '.join(scalars) or '(none)'}")
        return float(scalars[self.objective])

    def violation(self, record: Mapping[str, Any]) -> float:
        """Sum of relative constraint violations (0 if feasible; inf if the run failed)."""
        if record["status"] != "ok":
            return math.inf
        total = 0.0
        for name, (low, high) in self.constraints.items():
            if name not in record["scalars"]:
                raise ValueError(f"constraints: {name!r} is not a key scalar of case {self.case.name}; "
                                 f"its key scalars: {', '.join(record['scalars']) or '(none)'}")
            value = record["scalars"][name]
            if not math.isfinite(value):
                return math.inf
            if low is not None and value < low:
                total += (low - value) / max(abs(low), 1e-300)
            if high is not None and value > high:
                total += (value - high) / max(abs(high), 1e-300)
        return total

    def __call__(self, u: np.ndarray) -> float:
        """The penalised objective to minimise (inf for a failed run)."""
        record = self.record(u)
        f = self.raw_objective(record)
        v = self.violation(record)
        sign = -1.0 if self.maximize else 1.0
        if not (math.isfinite(f) and math.isfinite(v)):
            value = math.inf
        else:
            value = sign * f + self.penalty * v * max(abs(f), 1e-300)
        self.history.append((self.point(u), {"objective": f, "violation": v, "penalised": value, "record": record}))
        return value

    def mapper(self, func: Callable, iterable) -> list[float]:
        """scipy's ``workers=`` map: run the whole population at once, then evaluate."""
        us = list(iterable)
        try:
            self.prefetch(us)
            return [func(u) for u in us]
        except Exception as exc:
            self.error = exc  # scipy replaces errors inside the map by a RuntimeError of its own
            raise


def check_objective(case: Case, objective: Objective) -> Objective:
    if callable(objective):
        return objective
    if not isinstance(objective, str) or not objective:
        raise ValueError(f"objective must be the name of a key scalar of {case.name} or a callable(scalars, values), got {objective!r}")
    return objective


def check_constraints(constraints: Mapping[str, tuple[float | None, float | None]] | None) -> dict[str, tuple[float | None, float | None]]:
    checked = {}
    for name, pair in (constraints or {}).items():
        try:
            low, high = pair
        except (TypeError, ValueError):
            raise ValueError(f"constraints[{name!r}] must be (low, high) with None for an open side, got {pair!r}") from None
        for side in (low, high):
            if side is not None and not (isinstance(side, (int, float)) and math.isfinite(side)):
                raise ValueError(f"constraints[{name!r}] must be finite numbers or None, got {pair!r}")
        if low is None and high is None:
            raise ValueError(f"constraints[{name!r}]: give a lower or an upper limit, got {pair!r}")
        checked[name] = (None if low is None else float(low), None if high is None else float(high))
    return checked


def history_columns(case: Case, problem: Problem, names: Sequence[str]) -> list[Column]:
    units = {p.name: p.unit for p in case.parameters}
    rows = problem.history
    columns = [Column("evaluation", "-", "int", list(range(len(rows))))]
    for name, kind in zip(names, problem.kinds):
        columns.append(Column(name, units[name], kind, [p[name] for p, _ in rows]))
    obj_name = problem.objective if isinstance(problem.objective, str) else "objective"
    obj_unit = "-"
    for _, info in rows:
        if isinstance(problem.objective, str) and info["record"].get("scalar_units"):
            obj_unit = info["record"]["scalar_units"].get(problem.objective, "-")
            break
    columns.append(Column(obj_name, obj_unit, "float", [h["objective"] for _, h in rows]))
    columns.append(Column("violation", "-", "float", [h["violation"] for _, h in rows]))
    columns.append(Column("penalised", "-", "float", [h["penalised"] for _, h in rows]))
    columns.append(Column("status", "-", "str", [h["record"]["status"] for _, h in rows]))
    columns.append(Column("key", "-", "str", [h["record"]["key"] for _, h in rows]))
    return columns
