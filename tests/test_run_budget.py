"""An optimisation announces itself when it may take long, and shows its progress by runs.

The synthetic case (``study_cases/synthetic_study.py``) sleeps ``delay`` seconds per run, so the
pace the budget measures is known: 5 ms per run.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from exudyn_atcm.errors import RunCostWarning
from exudyn_atcm.io.progress import reporting
from exudyn_atcm.study import optimize
from exudyn_atcm.study.options import OptimizeOptions, RunOptions
from exudyn_atcm.study import budget as budget_module
from exudyn_atcm.study.budget import max_runs

SYNTHETIC = Path(__file__).resolve().parent / "study_cases" / "synthetic_study.py"


class Tasks:
    """A progress display that keeps what it was told."""

    def __init__(self) -> None:
        self.calls: list[tuple[str, int, int | None]] = []

    def __call__(self, t: float, t_end: float) -> None:  # the simulated-time interface (unused here)
        pass

    def task(self, label: str, done: int, total: int | None) -> None:
        self.calls.append((label, done, total))


def test_the_bound_is_the_methods_iteration_limit():
    # differential evolution: initial population and maxiter generations of popsize * n (at least 5)
    assert max_runs("differential_evolution", 2, 3, 5) == 4 * 5 * 2
    assert max_runs("differential_evolution", 1, 3, 4) == 4 * 5
    # Nelder-Mead: at most 20 maxiter n iterations of n + 2 runs, plus its simplex
    assert max_runs("nelder-mead", 2, 3, 5) == 20 * 3 * 2 * 4 + 3
    # L-BFGS-B: maxiter n iterations, each at most two line searches (one restart) of scipy's maxls = 20 steps,
    # every step a value and a finite-difference gradient (n + 1 evaluations); plus the start
    assert max_runs("l-bfgs-b", 2, 3, 5) == (3 * 2 * 2 * 20 + 1) * 3


@pytest.mark.parametrize("method, kwargs", [("differential_evolution", {"maxiter": 4, "popsize": 4, "polish": False}),
                                            ("nelder-mead", {"maxiter": 5}), ("l-bfgs-b", {"maxiter": 5})])
def test_an_optimisation_never_exceeds_its_bound_and_reports_every_batch(method, kwargs):
    display = Tasks()
    with reporting(display):
        best = optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, method=method, fixed={"n": 2},
                        options=OptimizeOptions(rerun_best=False, **kwargs), run=RunOptions(workers=1))
    bound = max_runs(method, 1, kwargs["maxiter"], kwargs.get("popsize", 15))
    runs = [c for c in display.calls if c[0] == "optimisation runs"]
    assert best.executed <= bound  # the search stays within its bound (the DE polish, off here, would add runs)
    assert runs and all(total == bound for _, _, total in runs)
    done = [d for _, d, _ in runs]
    # every distinct design is run once (no store): the last report counts them all
    assert done == sorted(done) and done[-1] == best.executed <= best.evaluations


def test_a_long_optimisation_is_announced_once_with_its_bound(monkeypatch):
    """5 ms per run, at most (4 + 1) * 5 = 25 runs of differential evolution (scipy keeps at least 5 members,
    popsize 4 x 1 variable would be 4): at least 0.125 s, over a 0.05 s limit."""
    monkeypatch.setattr(budget_module, "LONG_RUN_SECONDS", 0.05)
    display = Tasks()
    with warnings.catch_warnings(record=True) as caught, reporting(display):
        warnings.simplefilter("always")
        optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, fixed={"n": 2, "delay": 0.005}, options=OptimizeOptions(maxiter=4, popsize=4, polish=False, rerun_best=False), run=RunOptions(workers=1))
    announced = [w for w in caught if issubclass(w.category, RunCostWarning)]
    assert len(announced) == 1
    text = str(announced[0].message)
    # timed on the first generation (5 runs), after the initial population that paid for the warm-up
    assert "may take up to" in text and "at most 25 runs" in text and "measured on 5 runs after the first 5" in text
    # the pace measured is at least the 5 ms each run sleeps
    per_run = float(text.split("at ~")[1].split(" s each")[0])
    assert per_run >= 0.005


def test_a_local_method_is_not_announced_from_its_loose_cap(monkeypatch):
    """Nelder-Mead's cap (20 maxiter n iterations) is far above the tens of runs it needs: no estimate from it."""
    monkeypatch.setattr(budget_module, "LONG_RUN_SECONDS", 0.05)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RunCostWarning)
        best = optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, method="nelder-mead", fixed={"n": 2, "delay": 0.005}, options=OptimizeOptions(rerun_best=False), run=RunOptions(workers=1))
    assert best.executed < 100 < max_runs("nelder-mead", 1, 100, 15)


def test_the_pace_is_not_taken_from_one_slow_first_run(monkeypatch):
    """A first batch of one run that also paid for loading the case must not set the pace alone."""
    clock = {"now": 0.0}
    monkeypatch.setattr(budget_module, "perf_counter", lambda: clock["now"])
    budget = budget_module.RunBudget(1000, "a test", limit=60.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RunCostWarning)
        clock["now"] = 0.1  # one run of 0.1 s: 1000 x 0.1 s = 100 s if trusted
        budget(1, 1)
        clock["now"] = 0.2  # then 30 runs in 0.1 s: 0.2 s + 969 x 3.3 ms, about 3.4 s for the bound
        budget(31, 31)
    assert budget.announced and budget.estimate is None


def test_a_quick_optimisation_says_nothing():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RunCostWarning)
        optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, fixed={"n": 2}, options=OptimizeOptions(maxiter=2, popsize=3, rerun_best=False), run=RunOptions(workers=1))
