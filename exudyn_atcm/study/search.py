"""The scipy stages of :func:`~exudyn_atcm.study.optimize`: differential evolution, its polish, local methods.

Each stage minimises a :class:`~exudyn_atcm.study.problem.Problem` (normalised design vectors
to penalised objective values) with :mod:`scipy.optimize` and returns scipy's result with
``x`` in normalised coordinates.  Whole populations and simplices are handed to the problem at
once (:meth:`~exudyn_atcm.study.problem.Problem.prefetch`), so their runs go to the engine in
parallel.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .problem import Problem

__all__ = ["differential_evolution", "polish", "local_search", "simplex", "small_simplex", "absolute_fatol"]


def local_search(problem: Problem, method: str, start: np.ndarray, xatol: float, fatol: float, maxiter: int):
    """Nelder-Mead (from a simplex of 10 % of each range) or L-BFGS-B (finite differences) from ``start``."""
    from scipy import optimize as so  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    n = start.size
    if method == "nelder-mead":
        first = simplex(start)
        return so.minimize(problem, start, method="Nelder-Mead", bounds=[(0.0, 1.0)] * n,
                           options={"xatol": xatol, "fatol": absolute_fatol(problem, first, fatol),
                                    "maxiter": maxiter * n * 20, "initial_simplex": first})
    return so.minimize(problem, start, method="L-BFGS-B", bounds=[(0.0, 1.0)] * n,
                       options={"maxiter": maxiter * n, "eps": 1e-6})


def simplex(start: np.ndarray, fraction: float = 0.1) -> np.ndarray:
    """Nelder-Mead simplex: ``fraction`` of each (unit) range from the start, pointing inwards.

    The default 10 % starts a search; :func:`small_simplex` (2 %) polishes a found point.
    """
    n = start.size
    vertices = np.tile(start, (n + 1, 1))
    for i in range(n):
        vertices[i + 1, i] += fraction if start[i] <= 1.0 - fraction else -fraction
    return vertices


def differential_evolution(problem: Problem, kinds: Sequence[str], seed, maxiter: int, popsize: int, tol: float,
                           scipy_constraints: bool):
    """scipy's differential evolution over the design, each population run at once by the engine.

    Float variables run on ``[0, 1]``, integers on their own range (``integrality``).
    Penalty constraints: scipy's ``workers=`` map with deferred updating.  scipy
    constraints: ``vectorized=True``, so that the objective and every
    :class:`~scipy.optimize.NonlinearConstraint` receive the whole population at once.
    """
    from scipy import optimize as so  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
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


def absolute_fatol(problem: Problem, vertices: np.ndarray, fatol: float, free=None, base=None) -> float:
    """``fatol`` times the objective's scale on the initial simplex (run in parallel first).

    scipy's Nelder-Mead takes an absolute function tolerance; the objective's units are the
    case's, so the scale is the largest finite ``|objective|`` on the initial simplex (1 when
    none is finite or all are 0).
    """
    us = []
    for v in vertices:
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


def polish(problem: Problem, best_u: np.ndarray, kinds: Sequence[str], xatol: float, fatol: float, maxiter: int):
    """Nelder-Mead on the float variables from ``best_u`` (integers fixed)."""
    from scipy import optimize as so  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    free = np.array([k == "float" for k in kinds])

    def func(v):
        u = best_u.copy()
        u[free] = v
        return problem(u)

    start = best_u[free]
    first = small_simplex(start)
    result = so.minimize(func, start, method="Nelder-Mead", bounds=[(0.0, 1.0)] * int(free.sum()),
                         options={"xatol": xatol, "fatol": absolute_fatol(problem, first, fatol, free, best_u),
                                  "maxiter": maxiter * int(free.sum()) * 20, "initial_simplex": first})
    u = best_u.copy()
    u[free] = result.x
    result.x = u
    return result


def small_simplex(start: np.ndarray) -> np.ndarray:
    """A simplex of 2 % of each range around the start (a polish, not a new search)."""
    return simplex(start, 0.02)
