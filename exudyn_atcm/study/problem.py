"""The optimisation problem behind :func:`~exudyn_atcm.study.optimize`: design vectors to runs.

:class:`Problem` maps normalised design vectors ``u`` in ``[0, 1]^n`` to parameter points,
runs them through a study engine (whole populations at once, remembering every record),
and turns each record into the objective, the constraint violation and the penalised value
the scipy optimiser minimises.  Every evaluation is kept in order for the history table.

Two stops end a search early, whatever the scipy method does: the evaluation budget
(``max_evaluations``: the call that would exceed it raises :class:`SearchStopped`, and no run
is started beyond it), and an objective that is not finite at any design of the first batch
(differential evolution's initial population, Nelder-Mead's simplex, L-BFGS-B's start and
gradient), which raises :class:`ObjectiveNotFiniteError` naming designs and what they gave:
scipy would otherwise search a landscape of ``inf`` until its iteration limits.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from .._checks import shown
from ..casework import Case
from .stops import ObjectiveNotFiniteError, SearchStopped
from .sweep import run_study
from .options import RunOptions
from .table import Column

# Problem is the optimiser's internal (built by optimize, 15 parameters), not public API
__all__ = ["Objective", "check_objective", "check_constraints",
           "history_columns", "objective_label"]

#: A key scalar's name, or ``objective(scalars, values) -> float``.
Objective = str | Callable[[Mapping[str, float], Mapping[str, Any]], float]


def objective_label(objective: Objective) -> str:
    """``'work'`` for a key scalar, ``the objective function name()`` for a callable."""
    if isinstance(objective, str):
        return repr(objective)
    return f"the objective function {getattr(objective, '__name__', type(objective).__name__)}()"


class Problem:
    """Maps normalised design vectors to runs, objective values and constraint violations.

    ``max_evaluations`` caps the calls of the objective (and so the runs); ``first_batch``
    evaluations (``first_label`` says what they are) must give at least one finite value.
    """

    def __init__(self, case, names, lows, highs, kinds, fixed, objective, maximize, constraints, penalty,
                 engine, store, max_evaluations: int | None = None, first_batch: int = 1, first_label: str = "first"):
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
        self.max_evaluations, self.first_batch, self.first_label = max_evaluations, max(int(first_batch), 1), first_label
        #: what ``max_evaluations`` is, for the message of a search it stops
        self.budget_what = f"max_evaluations = {max_evaluations}"
        #: designs handed to :meth:`prefetch` so far (repeats included): the first batch is complete at ``first_batch``
        self.asked = 0
        #: whether a design with a finite objective and finite constraint values has been seen
        self.finite_seen = False

    # -- coordinates ----------------------------------------------------------------------
    def point(self, u: np.ndarray) -> dict[str, Any]:
        x = self.lows + np.clip(np.asarray(u, float), 0.0, 1.0) * (self.highs - self.lows)
        return {n: int(round(v)) if k == "int" else float(v) for n, v, k in zip(self.names, x, self.kinds)}

    def _key(self, point: Mapping[str, Any]) -> tuple:
        return tuple(point[n] for n in self.names)

    # -- runs ------------------------------------------------------------------------------
    def prefetch(self, us: Sequence[np.ndarray]) -> None:
        """Run (in parallel) every point of ``us`` not yet known, within the evaluation budget.

        With ``max_evaluations``, only the points of the evaluations the budget still allows
        are run (the first ones of ``us``), and never more runs than it allows.
        """
        us = list(us)
        if self.max_evaluations is not None:
            us = us[:max(self.max_evaluations - len(self.history), 0)]
        self.asked += len(us)
        points = []
        for u in us:
            p = self.point(u)
            if self._key(p) not in self.records and p not in points:
                points.append(p)
        if self.max_evaluations is not None:
            points = points[:max(self.max_evaluations - len(self.records), 0)]
        if not points:
            self._check_finite()
            return
        result = run_study(self.case, points=points, fixed=self.fixed, engine=self.engine, run=RunOptions(store=self.store))
        self.executed += result.executed
        for p, record in zip(points, result.records):
            self.records[self._key(p)] = record
        if self.monitor is not None:
            self.monitor(len(self.records), self.executed)
        self._check_finite()

    def record(self, u: np.ndarray) -> dict[str, Any]:
        p = self.point(u)
        if self._key(p) not in self.records:
            self.prefetch([u])
        if self._key(p) not in self.records:
            raise SearchStopped(self.budget_message())
        return self.records[self._key(p)]

    def budget_message(self) -> str:
        return f"stopped after {len(self.history)} evaluations: {self.budget_what} reached"

    def _check_finite(self) -> None:
        """Raise :class:`ObjectiveNotFiniteError` once the first batch is run and none of it was usable."""
        if self.finite_seen:
            return
        if any(self.usable(record) for record in self.records.values()):
            self.finite_seen = True
        elif self.records and max(len(self.records), self.asked) >= self.first_batch:
            raise self.not_finite_error(f"any design of {self.first_label}")

    def usable(self, record: Mapping[str, Any]) -> bool:
        """Whether a run gave a finite objective and finite constraint values."""
        return math.isfinite(self.raw_objective(record)) and math.isfinite(self.violation(record))

    def not_finite_error(self, where: str, shown: int = 3) -> ObjectiveNotFiniteError:
        """The error for a search whose designs so far gave no finite value (``where``: which designs)."""
        units = {p.name: p.unit for p in self.case.parameters}
        designs, objective_bad = [], True
        for record in self.records.values():
            design = {n: record["values"][n] for n in self.names}
            if record["status"] != "ok":
                what = f"the run failed ({' '.join(str(record.get('error', '')).split())})"
            else:
                f = self.raw_objective(record)
                name = self.objective if isinstance(self.objective, str) else "the objective"
                if math.isfinite(f):
                    objective_bad = False
                    bad = [n for n in self.constraints if not math.isfinite(record["scalars"].get(n, math.nan))]
                    what = f"{name} = {f:.6g} but " + ", ".join(f"{n} = {record['scalars'].get(n, math.nan)!r}" for n in bad)
                else:
                    what = f"{name} = {f!r}"
            designs.append((design, what))
        label = objective_label(self.objective)
        if objective_bad:
            subject = f"the objective {label} of case {self.case.name} was not"
        else:
            subject = (f"the objective {label} and the constraints ({', '.join(repr(n) for n in self.constraints)}) "
                       f"of case {self.case.name} were never all")
        examples = "; ".join(", ".join(f"{n} = {v:.6g} {units[n]}" for n, v in d.items()) + f" gave {what}"
                             for d, what in designs[:shown])
        more = f" (and {len(designs) - shown} more)" if len(designs) > shown else ""
        failed = all(r["status"] != "ok" for r in self.records.values())
        computed = "the objective" if objective_bad else ", ".join(repr(n) for n in self.constraints)
        hint = ("every run failed: see the errors" if failed else
                f"check that case {self.case.name} computes {computed} for these designs, or narrow the bounds to where it does")
        return ObjectiveNotFiniteError(
            f"{subject} finite (NaN or inf) at {where} ({len(designs)} designs), so "
            f"no design can be compared with another and the search stops: {examples}{more}; {hint}", designs)

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

    def evaluate(self, record: Mapping[str, Any]) -> dict[str, Any]:
        """The objective, violation and penalised value of a run (the history's entry)."""
        f = self.raw_objective(record)
        v = self.violation(record)
        sign = -1.0 if self.maximize else 1.0
        if not (math.isfinite(f) and math.isfinite(v)):
            value = math.inf
        else:
            value = sign * f + self.penalty * v * max(abs(f), 1e-300)
        return {"objective": f, "violation": v, "penalised": value, "record": record}

    def __call__(self, u: np.ndarray) -> float:
        """The penalised objective to minimise (inf for a failed run)."""
        if self.max_evaluations is not None and len(self.history) >= self.max_evaluations:
            raise SearchStopped(self.budget_message())
        info = self.evaluate(self.record(u))
        self.history.append((self.point(u), info))
        return info["penalised"]

    def add_unvisited(self) -> None:
        """Append to the history the runs made but not yet evaluated (a search stopped between the two)."""
        seen = {self._key(p) for p, _ in self.history}
        for key, record in self.records.items():
            if key not in seen:
                self.history.append((dict(zip(self.names, key)), self.evaluate(record)))


def check_objective(case: Case, objective: Objective) -> Objective:
    if callable(objective):
        return objective
    if not isinstance(objective, str) or not objective:
        raise ValueError(f"objective must be the name of a key scalar of {case.name} or a callable(scalars, values), got {shown(objective)}")
    return objective


def check_constraints(constraints: Mapping[str, tuple[float | None, float | None]] | None) -> dict[str, tuple[float | None, float | None]]:
    checked = {}
    for name, pair in (constraints or {}).items():
        try:
            low, high = pair
        except (TypeError, ValueError):
            raise ValueError(f"constraints[{name!r}] must be (low, high) with None for an open side, got {shown(pair)}") from None
        for side in (low, high):
            if side is not None and not (isinstance(side, (int, float)) and math.isfinite(side)):
                raise ValueError(f"constraints[{name!r}] must be finite numbers or None, got {shown(pair)}")
        if low is None and high is None:
            raise ValueError(f"constraints[{name!r}]: give a lower or an upper limit, got {shown(pair)}")
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
