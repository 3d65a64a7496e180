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

__all__ = ["RunBudget", "max_runs", "MIN_MEASURED_RUNS"]

#: Runs timed before the pace is trusted.  They are counted after the first batch, which also
#: pays for loading the case and starting the workers (a first batch of one run, as scipy's
#: constraint handling makes, gave a pace 10 times too slow).
MIN_MEASURED_RUNS = 5


def max_runs(method: str, n_variables: int, maxiter: int, popsize: int) -> int:
    """The runs an optimisation makes at most before its polish (the methods' iteration limits).

    Differential evolution: ``(maxiter + 1) * max(popsize * n, 5)`` (initial population and
    ``maxiter`` generations; scipy keeps at least 5 members); its Nelder-Mead polish is not
    counted (it usually takes tens of runs, its cap is far looser).  Nelder-Mead: at most
    ``20 * maxiter * n`` iterations of ``n + 2`` runs, plus the simplex; L-BFGS-B ``maxiter * n``
    iterations of ``n + 1`` runs (finite-difference gradients).
    """
    n = max(int(n_variables), 1)
    if method == "differential_evolution":
        return (maxiter + 1) * max(popsize * n, 5)
    if method == "nelder-mead":
        return 20 * maxiter * n * (n + 2) + n + 1
    return maxiter * n * (n + 1) + 1


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
