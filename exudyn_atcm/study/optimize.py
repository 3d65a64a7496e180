"""Design optimisation of a case with scipy.optimize, its runs executed by the study engines.

Every evaluation is one run of the case, executed by the same engines as a study (this
process, a process pool, Dask) and stored in the same run store, so an interrupted
optimisation started again replays the stored runs instantly and goes on; a sweep and an
optimisation of the same case share runs.  Differential evolution evaluates each
generation's population in parallel (scipy's ``workers=`` map with deferred updating); the
local methods (Nelder-Mead, L-BFGS-B with finite differences) run one point at a time.

The design variables are optimised in normalised coordinates ``u = (x - low)/(high - low)``
in ``[0, 1]``, so that thicknesses of 1e-4 m and moduli of 1e10 Pa are equally easy for
every method.  Integer parameters are handled by differential evolution's
``integrality``; the local methods keep them fixed.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..io.atomic import make_directory, write_json
from ..casework import Case, CaseOutput, load_case
from .budget import RunBudget, max_runs
from .design import GridError, case_parameter, check_point
from .engines import make_engine
from .problem import Objective, Problem, check_constraints, check_objective, history_columns
from .store import RunStore
from .table import to_table, write_table_csv

__all__ = ["optimize", "OptimizationResult", "METHODS"]

#: Methods of :func:`optimize`.
METHODS = ("differential_evolution", "nelder-mead", "l-bfgs-b")


@dataclass
class OptimizationResult:
    """The outcome of :func:`optimize`.

    Attributes
    ----------
    design : dict
        The best values of the design variables.
    values : dict
        All parameter values of the best run.
    objective : float
        The objective at the best design (as defined, i.e. not negated for ``maximize``).
    scalars : dict
        The key scalars of the best run.
    feasible : bool
        Whether the best design satisfies every constraint.
    output : CaseOutput or None
        The full run of the best design (files in ``out/best`` with ``out``).
    history : StudyTable
        Every evaluation in order: the design variables, objective, constraint violation,
        status.
    evaluations : int
        Number of evaluations requested by the optimiser (stored ones included).
    executed : int
        Runs actually executed (the rest came from the store or were repeats).
    message : str
        The optimiser's message.
    scipy_result : scipy.optimize.OptimizeResult
        The raw result (in normalised coordinates), of the last stage.
    """

    design: dict[str, Any]
    values: dict[str, Any]
    objective: float
    scalars: dict[str, float]
    feasible: bool
    output: CaseOutput | None
    history: Any
    evaluations: int
    executed: int
    message: str
    scipy_result: Any = None
    files: list[Path] = field(default_factory=list)


def optimize(
    case: Case | str | os.PathLike,
    objective: Objective,
    bounds: Mapping[str, tuple[float, float]],
    *,
    method: str = "differential_evolution",
    maximize: bool = False,
    constraints: Mapping[str, tuple[float | None, float | None]] | None = None,
    penalty: float = 10.0,
    constraint_handling: str = "penalty",
    fixed: Mapping[str, Any] | None = None,
    x0: Mapping[str, float] | None = None,
    seed: int | None = 0,
    maxiter: int = 100,
    popsize: int = 15,
    tol: float = 1e-3,
    xatol: float = 1e-4,
    fatol: float = 1e-4,
    polish: bool = True,
    workers: int | None = None,
    client: Any = None,
    scheduler: str | None = None,
    out: str | os.PathLike | None = None,
    store: str | os.PathLike | RunStore | None = None,
    rerun_best: bool = True,
    plot: bool = False,
) -> OptimizationResult:
    """Find the parameters of a case that minimise (or maximise) one of its key scalars.

    Parameters
    ----------
    case : Case or str or os.PathLike
        The case (loaded, or its name or file).
    objective : str or callable
        Name of a key scalar, or ``objective(scalars, values) -> float`` computed from a
        run's key scalars and parameter values (in the calling process).
    bounds : mapping of str to (low, high)
        The design variables and their ranges (float or int parameters; ints only with
        differential evolution).
    method : {"differential_evolution", "nelder-mead", "l-bfgs-b"}
        Global search (:func:`scipy.optimize.differential_evolution`, population evaluated
        in parallel) or a local method (:func:`scipy.optimize.minimize`; L-BFGS-B with
        finite-difference gradients).
    maximize : bool
        Maximise the objective instead of minimising it.
    constraints : mapping of str to (low, high), optional
        Limits on key scalars, ``None`` for an open side, e.g. ``{"f1": (50.0, None)}``.
        Applied as a penalty: ``f + penalty * v * |f|`` with ``v`` the sum of relative
        violations (``(low - value)/|low|``); a failed run counts as ``inf``.
    penalty : float
        Weight of the relative violation (default 10: a 10 % violation costs as much as
        the whole objective).
    constraint_handling : {"penalty", "scipy"}
        ``"scipy"`` (differential evolution only): the constraints become
        :class:`scipy.optimize.NonlinearConstraint` objects, handled by scipy's feasibility
        rules (Lampinen 2002: feasible beats infeasible, lower violation beats higher),
        with the population still evaluated at once (``vectorized=True``).
    fixed : mapping, optional
        Values of other parameters for every run.
    x0 : mapping, optional
        Start of a local method (default: the middle of the bounds).
    seed : int or None
        Seed of differential evolution (default 0: reproducible, and resumable from the store).
    maxiter, popsize, tol : int, int, float
        Differential evolution: generations, population size factor, relative tolerance.
        Local methods: ``maxiter`` is multiplied by the number of variables.
    xatol, fatol : float
        Nelder-Mead stopping tolerances (local method and polish): it stops when every vertex
        of the simplex lies within ``xatol`` of the best one in normalised coordinates
        (default 1e-4 of each range) *and* their objective values differ by at most
        ``fatol`` times the objective's scale, the largest finite ``|objective|`` on the
        initial simplex (default 1e-4, relative).  ``fatol=0`` means "values equal", which
        in practice runs to the iteration cap.
    polish : bool
        After differential evolution, refine the best design with Nelder-Mead on the float
        variables (integers fixed).
    workers, client, scheduler :
        The engine, as for :func:`~exudyn_atcm.study.sweep`.
    out : str or os.PathLike, optional
        Directory for ``<case>_optimize_history.csv``, ``<case>_optimize.json``, the run store
        ``runs/`` (unless ``store``) and the best design's full run in ``best/``.
    store : str or os.PathLike or RunStore, optional
        Run store (see :func:`~exudyn_atcm.study.sweep`).
    rerun_best : bool
        Run the best design again in this process to return its full :class:`CaseOutput`.
    plot : bool
        Write the best run's plots (with ``out``).

    Returns
    -------
    OptimizationResult

    Raises
    ------
    GridError
        For an unknown parameter, a non-numeric design variable or empty bounds.
    ValueError
        For an unknown method, integers with a local method, bad constraints or objective.
    """
    from scipy import optimize as so

    case = case if isinstance(case, Case) else load_case(case)
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    objective = check_objective(case, objective)
    checked_constraints = check_constraints(constraints)
    if not isinstance(bounds, Mapping) or not bounds:
        raise GridError("bounds must map at least one design variable to (low, high)")
    names, lows, highs, kinds = [], [], [], []
    for name, pair in bounds.items():
        parameter = case_parameter(case, name, "bounds")
        if parameter.kind not in ("float", "int"):
            raise GridError(f"bounds: {name!r} is a {parameter.kind} parameter; design variables must be float or int")
        try:
            low, high = (float(v) for v in pair)
        except (TypeError, ValueError):
            raise GridError(f"bounds: {name!r} must be (low, high), got {pair!r}") from None
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise GridError(f"bounds: {name!r} must be finite with low < high, got ({low!r}, {high!r})")
        try:  # the optimiser may try either end: both must be values the case accepts
            parameter.check_range(low, high)
        except ValueError as exc:
            raise GridError(f"bounds: {exc} (the case's declared range)") from None
        names.append(name)
        lows.append(low)
        highs.append(high)
        kinds.append(parameter.kind)
    for label, tol_value, high in (("xatol", xatol, 1.0), ("fatol", fatol, math.inf)):
        if not (isinstance(tol_value, (int, float)) and not isinstance(tol_value, bool) and 0.0 <= tol_value < high):
            raise ValueError(f"{label} must be a number in [0, {high:g}) (relative Nelder-Mead tolerance), got {tol_value!r}")
    if constraint_handling not in ("penalty", "scipy"):
        raise ValueError(f"constraint_handling must be 'penalty' or 'scipy', got {constraint_handling!r}")
    if constraint_handling == "scipy" and method != "differential_evolution":
        raise ValueError(f"constraint_handling='scipy' needs method='differential_evolution', got {method!r} (use penalties)")
    if method != "differential_evolution" and "int" in kinds:
        raise ValueError(f"method {method!r} is continuous: integer design variables {[n for n, k in zip(names, kinds) if k == 'int']} need method='differential_evolution' (or fix them)")
    fixed_values = check_point(case, fixed or {})
    overlap = sorted(set(fixed_values) & set(names))
    if overlap:
        raise GridError(f"parameters {overlap} are both fixed and design variables")
    out_dir = make_directory(out) if out is not None else None
    run_store = store if isinstance(store, RunStore) else RunStore(store) if store is not None else (
        RunStore(out_dir / "runs") if out_dir is not None else None)

    engine = make_engine(workers, client, scheduler)
    problem = Problem(case, names, lows, highs, kinds, fixed_values, objective, maximize, checked_constraints,
                       float(penalty) if constraint_handling == "penalty" else 0.0, engine, run_store)
    n = len(names)
    problem.monitor = RunBudget(max_runs(method, n, maxiter, popsize),
                                f"{method} over {n} variable{'s' if n > 1 else ''} of case {case.name}",
                                announce=method == "differential_evolution")
    try:
        if method == "differential_evolution":
            result = _differential_evolution(so, problem, kinds, seed, maxiter, popsize, tol, constraint_handling == "scipy")
            best_u = np.asarray(result.x, float)
            if polish and any(k == "float" for k in kinds):
                problem.penalty = float(penalty)  # Nelder-Mead knows constraints only as penalties
                result = _polish(so, problem, best_u, kinds, xatol, fatol, maxiter)
                best_u = np.asarray(result.x, float)
        else:
            start = np.array([
                (float(x0[nm]) - lo) / (hi - lo) if x0 and nm in x0 else 0.5
                for nm, lo, hi in zip(names, lows, highs)
            ])
            if method == "nelder-mead":
                simplex = _simplex(start)
                result = so.minimize(problem, start, method="Nelder-Mead", bounds=[(0.0, 1.0)] * n,
                                     options={"xatol": xatol, "fatol": _absolute_fatol(problem, simplex, fatol),
                                              "maxiter": maxiter * n * 20, "initial_simplex": simplex})
            else:
                result = so.minimize(problem, start, method="L-BFGS-B", bounds=[(0.0, 1.0)] * n,
                                     options={"maxiter": maxiter * n, "eps": 1e-6})
            best_u = np.asarray(result.x, float)
    except RuntimeError:
        engine.abort()
        if problem.error is not None:
            raise problem.error from None
        raise
    except BaseException:
        engine.abort()
        raise
    finally:
        engine.close()

    # the best evaluated design: feasible ones first, then the least infeasible
    candidates = [(h["violation"] > 0.0, h["violation"] if h["violation"] > 0.0 else 0.0, h["penalised"], i)
                  for i, (_, h) in enumerate(problem.history) if math.isfinite(h["penalised"]) and math.isfinite(h["violation"])]
    if candidates:
        best_index = min(candidates)[3]
        best_point, info = problem.history[best_index]
    else:
        best_point, info = problem.point(best_u), {"record": problem.record(best_u), "objective": math.nan, "violation": math.inf}
    record = info["record"]
    history = history_columns(case, problem, names)
    files: list[Path] = []
    output = None
    if rerun_best and record["status"] == "ok":
        output = case.run(record["values"], out_dir=(out_dir / "best") if out_dir is not None else None, plot=plot)
        files.extend(output.files)
    opt = OptimizationResult(
        design=dict(best_point),
        values=dict(record["values"]),
        objective=float(info["objective"]),
        scalars=dict(record.get("scalars", {})),
        feasible=bool(info["violation"] == 0.0),
        output=output,
        history=to_table(history),
        evaluations=len(problem.history),
        executed=problem.executed,
        message=str(getattr(result, "message", "")),
        scipy_result=result,
    )
    if out_dir is not None:
        files.append(write_table_csv(out_dir / f"{case.name}_optimize_history.csv", history,
                                     {"case": case.name, "method": method, "maximize": maximize}))
        files.append(write_json(out_dir / f"{case.name}_optimize.json", {
            "case": case.name, "method": method, "maximize": maximize,
            "objective": objective if isinstance(objective, str) else getattr(objective, "__name__", repr(objective)),
            "bounds": {n: [lo, hi] for n, lo, hi in zip(names, lows, highs)},
            "constraints": {k: list(v) for k, v in checked_constraints.items()},
            "fixed": {k: list(v) if isinstance(v, tuple) else v for k, v in fixed_values.items()},
            "design": opt.design, "objective value": opt.objective, "feasible": opt.feasible,
            "scalars": opt.scalars, "evaluations": opt.evaluations, "executed": opt.executed, "message": opt.message,
        }))
    opt.files = files
    return opt


def _simplex(start: np.ndarray, fraction: float = 0.1) -> np.ndarray:
    """Nelder-Mead simplex: ``fraction`` of each (unit) range from the start, pointing inwards.

    The default 10 % starts a search; :func:`_small_simplex` (2 %) polishes a found point.
    """
    n = start.size
    simplex = np.tile(start, (n + 1, 1))
    for i in range(n):
        simplex[i + 1, i] += fraction if start[i] <= 1.0 - fraction else -fraction
    return simplex


def _differential_evolution(so, problem: Problem, kinds, seed, maxiter, popsize, tol, scipy_constraints: bool):
    """scipy's differential evolution over the design, each population run at once by the engine.

    Float variables run on ``[0, 1]``, integers on their own range (``integrality``).
    Penalty constraints: scipy's ``workers=`` map with deferred updating.  scipy
    constraints: ``vectorized=True``, so that the objective and every
    :class:`~scipy.optimize.NonlinearConstraint` receive the whole population at once.
    """
    lows, highs = problem.lows.copy(), problem.highs.copy()
    de_bounds = [(0.0, 1.0) if k == "float" else (lo, hi) for k, lo, hi in zip(kinds, lows, highs)]
    integrality = [k == "int" for k in kinds] if "int" in kinds else None

    def to_u(x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, float)
        return np.array([xi if k == "float" else (xi - lo) / (hi - lo) for xi, k, lo, hi in zip(x, kinds, lows, highs)])

    def guarded(evaluate):
        try:
            return evaluate()
        except Exception as exc:
            problem.error = exc  # scipy replaces errors inside its map by a RuntimeError of its own
            raise

    def func(x):
        return problem(to_u(x))

    def mapper(f, iterable):
        xs = list(iterable)

        def evaluate():
            problem.prefetch([to_u(x) for x in xs])
            return [f(x) for x in xs]
        return guarded(evaluate)

    options = dict(seed=seed, maxiter=maxiter, popsize=popsize, tol=tol, polish=False, updating="deferred",
                   integrality=integrality, init="latinhypercube")
    if not scipy_constraints:
        result = so.differential_evolution(func, de_bounds, workers=mapper, **options)
    else:
        def members(X):
            us = [to_u(x) for x in np.atleast_2d(np.asarray(X, float).T)]
            guarded(lambda: problem.prefetch(us))
            return us

        def vector_func(X):
            return np.array([problem(u) for u in members(X)])

        def constraint(name, low):
            def values(X):
                out = []
                for u in members(X):
                    record = problem.record(u)
                    value = record["scalars"].get(name, math.nan) if record["status"] == "ok" else math.nan
                    out.append(value if math.isfinite(value) else (-math.inf if low is not None else math.inf))
                return np.array(out)[None, :]  # (M = 1, S)
            return values

        nonlinear = [so.NonlinearConstraint(constraint(name, low), -np.inf if low is None else low,
                                            np.inf if high is None else high)
                     for name, (low, high) in problem.constraints.items()]
        result = so.differential_evolution(vector_func, de_bounds, vectorized=True, constraints=nonlinear, **options)
    result.x = to_u(result.x)
    return result


def _absolute_fatol(problem: Problem, simplex: np.ndarray, fatol: float, free=None, base=None) -> float:
    """``fatol`` times the objective's scale on the initial simplex (run in parallel first).

    scipy's Nelder-Mead takes an absolute function tolerance; the objective's units are the
    case's, so the scale is the largest finite ``|objective|`` on the initial simplex (1 when
    none is finite or all are 0).
    """
    us = []
    for v in simplex:
        if free is None:
            us.append(np.asarray(v, float))
        else:
            u = base.copy()
            u[free] = v
            us.append(u)
    problem.prefetch(us)
    values = [abs(problem.raw_objective(problem.record(u))) for u in us]
    finite = [v for v in values if math.isfinite(v) and v > 0.0]
    return float(fatol) * (max(finite) if finite else 1.0)


def _polish(so, problem: Problem, best_u: np.ndarray, kinds, xatol, fatol, maxiter):
    """Nelder-Mead on the float variables from ``best_u`` (integers fixed)."""
    free = np.array([k == "float" for k in kinds])

    def func(v):
        u = best_u.copy()
        u[free] = v
        return problem(u)

    start = best_u[free]
    simplex = _small_simplex(start)
    result = so.minimize(func, start, method="Nelder-Mead", bounds=[(0.0, 1.0)] * int(free.sum()),
                         options={"xatol": xatol, "fatol": _absolute_fatol(problem, simplex, fatol, free, best_u),
                                  "maxiter": maxiter * int(free.sum()) * 20, "initial_simplex": simplex})
    u = best_u.copy()
    u[free] = result.x
    result.x = u
    return result


def _small_simplex(start: np.ndarray) -> np.ndarray:
    """A simplex of 2 % of each range around the start (a polish, not a new search)."""
    return _simplex(start, 0.02)
