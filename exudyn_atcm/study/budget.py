"""An optimisation's run budget: one warning up front when it may take long, progress by runs.

An optimiser's number of runs is not known in advance, only its bound (the iteration limits
of the method).  :class:`RunBudget` times the runs after the first batch (from a differential
evolution's first generation on; at least :data:`MIN_MEASURED_RUNS` runs) and, when the bound times that pace exceeds a minute, warns once with the
estimate (an upper bound: the search stops earlier when it converges).  After
every batch it reports ``optimisation runs done/bound`` to the active progress display
(:func:`exudyn_atcm.io.progress.report_task`), so a case that optimises shows its progress.
"""

from __future__ import annotations

import math
import warnings
from time import perf_counter

from ..errors import RunCostWarning
from ..io.progress import format_duration, report_task
from ..solve.run_checks import LONG_RUN_SECONDS

__all__ = ["RunBudget", "max_runs", "evaluation_bounds", "describe_evaluations", "MIN_MEASURED_RUNS", "LINE_SEARCH_STEPS"]

#: Runs timed before the pace is trusted.  They are counted after the first batch, which also
#: pays for loading the case and starting the workers (a first batch of one run, as scipy's
#: constraint handling makes, gave a pace 10 times too slow).
MIN_MEASURED_RUNS = 5

#: Steps of one L-BFGS-B line search at most (scipy's ``maxls``, left at its default 20).  A line
#: search that fails is restarted once in the same iteration, with the memory cleared
#: (L-BFGS-B's ``RESTART_FROM_LNSRCH``), so an iteration takes at most twice this.
LINE_SEARCH_STEPS = 20


def max_runs(method: str, n_variables: int, maxiter: int, popsize: int) -> int:
    """The evaluations an optimisation makes at most before its polish (the methods' iteration limits).

    Differential evolution: ``(maxiter + 1) * max(popsize * n, 5)`` (initial population and
    ``maxiter`` generations; scipy keeps at least 5 members); its Nelder-Mead polish is not
    counted (it usually takes tens of runs, its cap is far looser: :func:`evaluation_bounds`).
    Nelder-Mead: at most ``20 * maxiter * n`` iterations of ``n + 2`` evaluations, plus the
    simplex; L-BFGS-B ``maxiter * n`` iterations, each at most two line searches of
    :data:`LINE_SEARCH_STEPS` steps of ``n + 1`` evaluations (finite-difference gradients), plus
    the start.  Each evaluation is at most one run of the case.
    """
    n = max(int(n_variables), 1)
    if method == "differential_evolution":
        return (maxiter + 1) * max(popsize * n, 5)
    if method == "nelder-mead":
        return 20 * maxiter * n * (n + 2) + n + 1
    return (maxiter * n * 2 * LINE_SEARCH_STEPS + 1) * (n + 1)


def evaluation_bounds(method: str, n_variables: int, n_float: int, maxiter: int, popsize: int,
                      polish: bool) -> tuple[int, int]:
    """``(search, polish)``: the most evaluations of the search and of differential evolution's polish.

    The polish is Nelder-Mead over the ``n_float`` float variables with the same ``maxiter``
    (0 for a local method, without ``polish`` or without float variables).  Their sum is the
    bound :func:`~exudyn_atcm.study.optimize` announces and enforces when no smaller
    ``max_evaluations`` is given.
    """
    search = max_runs(method, n_variables, maxiter, popsize)
    if method != "differential_evolution" or not polish or n_float < 1:
        return search, 0
    return search, max_runs("nelder-mead", n_float, maxiter, popsize)


def describe_evaluations(method: str, n_variables: int, n_float: int, maxiter: int, popsize: int, polish: bool,
                         max_evaluations: int | None = None, option: str = "max_evaluations") -> str:
    """What an optimisation will evaluate at most, in words (announced before it starts).

    Parameters are those of :func:`evaluation_bounds`; ``max_evaluations`` is the user's budget,
    ``option`` its name in the message (``"--max-evaluations"`` on the command line).
    """
    search, polish_bound = evaluation_bounds(method, n_variables, n_float, maxiter, popsize, polish)
    total = search + polish_bound
    if method == "differential_evolution":
        members = max(popsize * max(int(n_variables), 1), 5)
        how = (f"{search} for differential evolution (an initial population of {members}, then {maxiter} "
               f"generation{'s' if maxiter > 1 else ''} of {members})")
    elif method == "nelder-mead":
        how = f"{search} for Nelder-Mead (its simplex, then {20 * maxiter * n_variables} iterations)"
    else:
        how = f"{search} for L-BFGS-B ({maxiter * n_variables} iterations with finite-difference gradients)"
    if polish_bound:
        how += f" and {polish_bound} for its Nelder-Mead polish"
    if max_evaluations is not None and max_evaluations < total:
        return (f"at most {max_evaluations} evaluations ({option}; the method's own limits: {how}); "
                "each evaluation is at most one run of the case")
    return (f"at most {total} evaluations: {how}; it stops earlier when it converges. Each evaluation is at most "
            f"one run of the case; {option} caps them")


class RunBudget:
    """Called after every batch of runs with the runs known so far and those executed (not from a store).

    Parameters
    ----------
    bound : int
        The most runs the optimisation makes (:func:`max_runs`; a polish may add some).
    what : str
        The optimisation in the message (``"differential evolution over 2 variables"``).
    limit : float, optional
        Warn when the bound at the measured pace exceeds this [s] (default
        :data:`~exudyn_atcm.solve.run_checks.LONG_RUN_SECONDS`, a minute).
    announce : bool, optional
        Warn at all (default True).  A local method's cap is far above what it usually needs
        (Nelder-Mead: thousands of runs where tens are typical), so an estimate from it would
        mislead; :func:`exudyn_atcm.study.optimize` announces differential evolution only,
        whose generations usually run to ``maxiter``.
    """

    def __init__(self, bound: int, what: str, limit: float | None = None, announce: bool = True) -> None:
        self.bound = max(int(bound), 1)
        self.what = what
        self.announce = announce
        self.limit = LONG_RUN_SECONDS if limit is None else float(limit)
        self.start = perf_counter()
        self._first: tuple[float, int] | None = None
        self.announced = False
        #: the upper-bound estimate warned about [s] (``None`` if none)
        self.estimate: float | None = None

    def __call__(self, known: int, executed: int) -> None:
        now = perf_counter()
        if self._first is None:
            self._first = (now, executed)  # the first batch paid for the warm-up: the pace is timed after it
        elif self.announce and not self.announced and executed - self._first[1] >= min(MIN_MEASURED_RUNS, self.bound):
            self.announced = True
            measured = executed - self._first[1]
            per_run = (now - self._first[0]) / measured
            estimate = now - self.start + per_run * max(self.bound - executed, 0)
            if math.isfinite(estimate) and estimate > self.limit:
                self.estimate = estimate
                warnings.warn(
                    f"this optimisation ({self.what}) may take up to {format_duration(estimate, rough=True)}: at most "
                    f"{self.bound} runs at ~{per_run:.3g} s each (measured on {measured} runs after the first "
                    f"{self._first[1]}), before a polish if any; it stops earlier when it converges. For a quicker "
                    "answer lower maxiter or popsize, or use workers; Ctrl-C stops it",
                    RunCostWarning,
                    stacklevel=2,
                )
        self.bound = max(self.bound, known)  # a polish runs beyond the bound of the search
        report_task("optimisation runs", known, self.bound)
