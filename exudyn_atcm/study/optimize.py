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
import time
from collections.abc import Mapping
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import hide_keywords, option_values, options_from_keywords, shown
from ..io.atomic import make_directory, write_json
from ..casework import Case, CaseOutput, load_case
from ..casework.output_folder import OutputFolder
from . import search
from .budget import RunBudget, evaluation_bounds, max_runs
from .design import GridError, case_parameter, check_point
from .engines import make_engine
from .held_cores import CoreClock, one_worker_for
from .lock import TableLock
from .options import METHODS, OptimizeOptions, RunOptions
from .problem import Objective, Problem, check_constraints, check_objective, history_columns
from .stops import ObjectiveNotFiniteError, SearchStopped
from .store import RunStore
from .table import to_table, write_table_csv

__all__ = ["optimize", "OptimizationResult", "METHODS"]


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
        The optimiser's message, or why the search stopped (the evaluation budget).
    scipy_result : scipy.optimize.OptimizeResult or None
        The raw result (in normalised coordinates) of the last stage that finished (``None``
        if the budget stopped the first).
    files : list of pathlib.Path
        The files written (with ``out``).
    max_evaluations : int
        The cap on evaluations that was in force: ``max_evaluations`` if given, else the
        methods' own bound (:func:`~exudyn_atcm.study.budget.evaluation_bounds`).
    search_time : float
        Wall time [s] of the search, its runs included (not the re-run of the best design).
    cores : int
        The most workers that ran the evaluations (1 in the calling process; a pool's or a Dask
        cluster's workers).
    stages : list of (int, float)
        The workers held and the wall time [s] of each stage of the search: a differential
        evolution's polish runs one design at a time on a pool of one forked worker
        (:func:`~exudyn_atcm.study.held_cores.one_worker_for`).
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
    max_evaluations: int = 0
    search_time: float = 0.0
    cores: int = 1
    stages: list[tuple[int, float]] = field(default_factory=list)

    @property
    def core_seconds(self) -> float:
        """Wall time times the workers held [s], summed over the :attr:`stages` (``search_time * cores`` without them)."""
        if self.stages:
            return float(sum(workers * seconds for workers, seconds in self.stages))
        return self.search_time * max(1, self.cores)

    @property
    def evaluation_rate(self) -> float:
        """Runs executed per second per core held [1/s] (``executed / core_seconds``; runs taken from the store
        are not counted; ``nan`` when none was executed)."""
        if self.executed <= 0 or not self.core_seconds > 0.0:
            return math.nan
        return self.executed / self.core_seconds

    def describe_rate(self) -> str:
        """:attr:`evaluation_rate` as a sentence for a report (per minute per core, with what it counts)."""
        if math.isnan(self.evaluation_rate):
            return f"no run executed (all {self.evaluations} evaluations from the store or repeats)"
        held = {workers for workers, _ in self.stages} or {self.cores}
        if len(held) == 1:
            on = f"on {self.cores} worker{'s' if self.cores > 1 else ''}"
        else:
            on = "on " + ", then ".join(f"{w} worker{'s' if w > 1 else ''} for {t:.3g} s" for w, t in self.stages)
        return (f"{60.0 * self.evaluation_rate:.0f} evaluations per minute per core ({self.executed} runs executed in "
                f"{self.search_time:.3g} s {on}; runs from the store not counted)")


@hide_keywords
def optimize(
    case: Case | str | os.PathLike,
    objective: Objective,
    bounds: Mapping[str, tuple[float, float]],
    *,
    method: str = "differential_evolution",
    maximize: bool = False,
    constraints: Mapping[str, tuple[float | None, float | None]] | None = None,
    fixed: Mapping[str, Any] | None = None,
    x0: Mapping[str, float] | None = None,
    options: OptimizeOptions | None = None,
    run: RunOptions | None = None,
    **legacy: Any,
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
    fixed : mapping, optional
        Values of other parameters for every run.
    x0 : mapping, optional
        Start of a local method (default: the middle of the bounds).
    options : OptimizeOptions, optional
        The settings of the search (:class:`~exudyn_atcm.study.options.OptimizeOptions`), each
        described below.
    run : RunOptions, optional
        Where the runs execute and are stored (:class:`~exudyn_atcm.study.options.RunOptions`:
        ``workers``, ``client``, ``scheduler``, ``out``, ``store``; described below).  The flat
        keywords of the earlier signature (``optimize(..., maxiter=20, out="opt")``) still work for
        one release, with an :class:`~exudyn_atcm.AtcmDeprecationWarning`.

    Other Parameters
    ----------------
    penalty : float
        Weight of the relative violation (default 10: a 10 % violation costs as much as
        the whole objective).
    constraint_handling : {"penalty", "scipy"}
        ``"scipy"`` (differential evolution only): the constraints become
        :class:`scipy.optimize.NonlinearConstraint` objects, handled by scipy's feasibility
        rules (Lampinen 2002: feasible beats infeasible, lower violation beats higher),
        with the population still evaluated at once (``vectorized=True``).
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
    max_evaluations : int, optional
        The most evaluations of the objective, polish included (each is at most one run of
        the case; a design met again is not run again, a stored run is replayed): the search
        stops exactly there and returns the best design found (``message`` says so).  No run
        is started beyond it.  Default: the methods' own bound
        (:func:`~exudyn_atcm.study.budget.evaluation_bounds`), also enforced.
    workers, client, scheduler :
        The engine, as for :func:`~exudyn_atcm.study.sweep`.
    out : str or os.PathLike, optional
        Directory for ``<case>_optimize_history.csv``, ``<case>_optimize.json``, the run store
        ``runs/`` (unless ``store``) and the best design's full run in ``best/``.  Locked for
        the case while the optimisation runs (``.<case>_optimize_history.lock``, as
        :func:`~exudyn_atcm.study.sweep` locks its table): a second optimisation of the case
        into the same directory is refused.
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
        For an unknown method, integers with a local method, bad constraints or objective,
        ``max_evaluations`` not an integer >= 1.
    ObjectiveNotFiniteError
        If the objective (or a constraint's scalar) is not finite (NaN, inf, failed runs) at any
        design of the first batch (differential evolution's initial population, the
        Nelder-Mead simplex, L-BFGS-B's start and gradient): the message names the objective
        and designs with what they gave.  The history is written first (with ``out``).
    exudyn_atcm.study.lock.StudyLockedError
        If another optimisation of the case is writing ``out`` now.
    """
    options, run = options_from_keywords("optimize", legacy, options=(OptimizeOptions, options), run=(RunOptions, run))
    (seed, maxiter, popsize, tol, xatol, fatol, polish, max_evaluations, penalty, constraint_handling, rerun_best,
     plot) = option_values(options)
    workers, client, scheduler, out, store = option_values(run)[:5]
    if option_values(run)[5:] != option_values(RunOptions())[5:]:
        raise ValueError("optimize: run.retry_failed, run.progress and run.use_pandas apply to sweeps only; got "
                         f"{run!r}")
    case = case if isinstance(case, Case) else load_case(case)
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {shown(method)}")
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
            raise GridError(f"bounds: {name!r} must be (low, high), got {shown(pair)}") from None
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
            raise ValueError(f"{label} must be a number in [0, {high:g}) (relative Nelder-Mead tolerance), got {shown(tol_value)}")
    if constraint_handling not in ("penalty", "scipy"):
        raise ValueError(f"constraint_handling must be 'penalty' or 'scipy', got {shown(constraint_handling)}")
    if constraint_handling == "scipy" and method != "differential_evolution":
        raise ValueError(f"constraint_handling='scipy' needs method='differential_evolution', got {shown(method)} (use penalties)")
    if method != "differential_evolution" and "int" in kinds:
        raise ValueError(f"method {method!r} is continuous: integer design variables {[n for n, k in zip(names, kinds) if k == 'int']} need method='differential_evolution' (or fix them)")
    fixed_values = check_point(case, fixed or {})
    overlap = sorted(set(fixed_values) & set(names))
    if overlap:
        raise GridError(f"parameters {overlap} are both fixed and design variables")
    whole = isinstance(max_evaluations, (int, np.integer)) and not isinstance(max_evaluations, bool)
    if max_evaluations is not None and not (whole and max_evaluations >= 1):
        raise ValueError(f"max_evaluations must be an integer >= 1 (the most objective evaluations), got {shown(max_evaluations)}")
    n = len(names)
    cap = sum(evaluation_bounds(method, n, kinds.count("float"), maxiter, popsize, polish))
    cap = min(cap, int(max_evaluations)) if max_evaluations is not None else cap
    out_dir = make_directory(out) if out is not None else None
    with ExitStack() as stack:
        if out_dir is not None:  # two optimisations of one case never write one folder at once
            stack.enter_context(TableLock(out_dir / f"{case.name}_optimize_history.csv", f"optimize of {case.name}"))
        run_store = store if isinstance(store, RunStore) else RunStore(store) if store is not None else (
            RunStore(out_dir / "runs") if out_dir is not None else None)
        members = max(popsize * n, 5)  # scipy's population (at least 5)
        first = {"differential_evolution": (members, "the initial population of differential evolution"),
                 "nelder-mead": (n + 1, "the initial simplex of Nelder-Mead"),
                 "l-bfgs-b": (n + 1, "the start and finite-difference gradient of L-BFGS-B")}[method]
        engine = make_engine(workers, client, scheduler)
        problem = Problem(case, names, lows, highs, kinds, fixed_values, objective, maximize, checked_constraints,
                          float(penalty) if constraint_handling == "penalty" else 0.0, engine, run_store,
                          max_evaluations=cap, first_batch=first[0], first_label=first[1])
        if max_evaluations is None or cap < max_evaluations:
            problem.budget_what = f"the bound of the methods' iteration limits ({cap})"
        problem.monitor = RunBudget(min(max_runs(method, n, maxiter, popsize), cap),
                                    f"{method} over {n} variable{'s' if n > 1 else ''} of case {case.name}",
                                    announce=method == "differential_evolution")
        start = np.array([(float(x0[nm]) - lo) / (hi - lo) if x0 and nm in x0 else 0.5
                          for nm, lo, hi in zip(names, lows, highs)])
        searched = time.perf_counter()
        clock = CoreClock(engine)
        result, stopped = _search(problem, method, start, kinds, seed, maxiter, popsize, tol, xatol, fatol, polish,
                                  penalty, constraint_handling == "scipy", clock)
        searched = time.perf_counter() - searched
        problem.add_unvisited()
        history = history_columns(case, problem, names)
        summary = {"case": case.name, "method": method, "maximize": maximize,
                   "objective": objective if isinstance(objective, str) else getattr(objective, "__name__", repr(objective)),
                   "bounds": {n: [lo, hi] for n, lo, hi in zip(names, lows, highs)},
                   "constraints": {k: list(v) for k, v in checked_constraints.items()},
                   "fixed": {k: list(v) if isinstance(v, tuple) else v for k, v in fixed_values.items()},
                   "max_evaluations": cap}
        error = stopped if isinstance(stopped, ObjectiveNotFiniteError) else None
        if error is None and not problem.finite_seen:  # the search ended before its first batch was complete
            error = problem.not_finite_error("any design evaluated before the search stopped")
        if error is not None:
            if out_dir is not None:
                _clear_best(out_dir, case.name)
                written = _write_summary(out_dir, case.name, history, {
                    **summary, "design": None, "objective value": None, "feasible": False, "evaluations": len(problem.history),
                    "executed": problem.executed, "message": str(error)})
                error.args = (f"{error} (every evaluation is in {written[0]})",)
            raise error
        opt = _best(case, problem, history, result, stopped, cap, rerun_best, out_dir, plot)
        opt.search_time, opt.stages = searched, clock.stages
        opt.cores = max(workers for workers, _ in clock.stages)
        if out_dir is not None:
            opt.files += _write_summary(out_dir, case.name, history, {
                **summary, "design": opt.design, "objective value": opt.objective, "feasible": opt.feasible,
                "scalars": opt.scalars, "evaluations": opt.evaluations, "executed": opt.executed, "message": opt.message})
        return opt


def _search(problem: Problem, method: str, start: np.ndarray, kinds: list[str], seed, maxiter: int, popsize: int, tol: float,
            xatol: float, fatol: float, polish: bool, penalty: float, scipy_constraints: bool, clock: CoreClock):
    """Run the scipy stages; ``(result of the last finished stage or None, the stop or None)``.

    A differential evolution's polish runs on one worker (:func:`~exudyn_atcm.study.held_cores.one_worker_for`);
    ``clock`` times the stages (stopped when the engine is closed).

    A spent evaluation budget (:class:`SearchStopped`) and an objective never finite on the
    first batch (:class:`ObjectiveNotFiniteError`) end the search and are returned; any other
    error stops the engine's workers and propagates (as itself, not scipy's wrapper).
    """
    result = None
    try:
        if method == "differential_evolution":
            result = search.differential_evolution(problem, kinds, seed, maxiter, popsize, tol, scipy_constraints)
            if polish and "float" in kinds:
                problem.penalty = float(penalty)  # Nelder-Mead knows constraints only as penalties
                problem.engine = one_worker_for(problem.engine)  # one design at a time
                clock.switch(problem.engine)
                result = search.polish(problem, np.asarray(result.x, float), kinds, xatol, fatol, maxiter)
        else:
            result = search.local_search(problem, method, start, xatol, fatol, maxiter)
    except (SearchStopped, ObjectiveNotFiniteError) as exc:
        return result, exc
    except BaseException as exc:
        problem.engine.abort()
        if isinstance(exc, RuntimeError) and problem.error is not None:  # scipy's wrapper of an error in its map
            if isinstance(problem.error, (SearchStopped, ObjectiveNotFiniteError)):
                return result, problem.error
            raise problem.error from None
        raise
    finally:
        problem.engine.close()
        clock.stop()
    return result, None


def _best(case: Case, problem: Problem, history, result, stopped, cap: int, rerun_best: bool, out_dir: Path | None,
          plot: bool) -> OptimizationResult:
    """The best evaluated design (feasible ones first, then the least infeasible), run again if asked."""
    candidates = [(h["violation"] > 0.0, h["violation"] if h["violation"] > 0.0 else 0.0, h["penalised"], i)
                  for i, (_, h) in enumerate(problem.history) if math.isfinite(h["penalised"]) and math.isfinite(h["violation"])]
    best_point, info = problem.history[min(candidates)[3]]
    record = info["record"]
    output = None
    if rerun_best and record["status"] == "ok":
        output = case.run(record["values"], out_dir=(out_dir / "best") if out_dir is not None else None, plot=plot)
    elif out_dir is not None:
        _clear_best(out_dir, case.name)
    if stopped is not None:
        message = str(stopped)
    else:
        message = str(getattr(result, "message", ""))
    return OptimizationResult(
        design=dict(best_point),
        values=dict(record["values"]),
        objective=float(info["objective"]),
        scalars=dict(record.get("scalars", {})),
        feasible=bool(info["violation"] == 0.0),
        output=output,
        history=to_table(history),
        evaluations=len(problem.history),
        executed=problem.executed,
        message=message,
        scipy_result=result,
        files=list(output.files) if output is not None else [],
        max_evaluations=cap,
    )


def _clear_best(out_dir: Path, case_name: str) -> None:
    """Remove a previous optimisation's best run of the case from ``out/best`` (this one writes none there)."""
    if (out_dir / "best").is_dir():
        folder = OutputFolder(out_dir / "best", case_name)
        folder.begin()
        folder.finish()


def _write_summary(out_dir: Path, case_name: str, history, summary: dict[str, Any]) -> list[Path]:
    """``<case>_optimize_history.csv`` and ``<case>_optimize.json``."""
    return [write_table_csv(out_dir / f"{case_name}_optimize_history.csv", history,
                            {"case": case_name, "method": summary["method"], "maximize": summary["maximize"]}),
            write_json(out_dir / f"{case_name}_optimize.json", summary)]
