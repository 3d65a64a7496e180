"""Optimisations that a user leaves running (issue 29, finding 10): a locked folder, a hopeless objective, a budget.

* Two optimisations of one case into one ``--out`` would overwrite each other's history and best
  design: the second is refused, as a second sweep on one table is (and a lock left by a killed
  process blocks nothing).
* An objective that is NaN for every design of the first population stops there with an
  error naming it and the designs, instead of searching a landscape of ``inf`` to its iteration
  limits (284 evaluations for ``--maxiter 3`` before) and then reporting "no design meets the
  constraints" for a problem without constraints.
* ``max_evaluations`` / ``--max-evaluations`` is a hard budget, honoured to the evaluation, and
  the command line says before it starts how many evaluations it makes at most.

The synthetic case (``study_cases/synthetic_study.py``) has ``y = a x^2 + n`` and writes one file
per executed run into ``log_dir``, so the runs really executed are counted independently of the
package's own counters.
"""

from __future__ import annotations

import csv
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import differential_evolution

from exudyn_atcm.study import column, optimize
from exudyn_atcm.study.options import OptimizeOptions, RunOptions
from exudyn_atcm.study.lock import StudyLockedError
from exudyn_atcm.study import ObjectiveNotFiniteError

from _cli_helpers import cli, env

SYNTHETIC = Path(__file__).resolve().parent / "study_cases" / "synthetic_study.py"

NAN_CASE = '''"""q is NaN whatever x; w = x (finite); one file per run in log_dir."""
import math
import os
import uuid
from pathlib import Path

from exudyn_atcm.casework import Case, CaseOutput, Parameter
from exudyn_atcm.io.result import Result

PARAMETERS = [Parameter("x", 0.5, "m", "design"), Parameter("log_dir", "", "-", "one file per run ('' = none)")]


def run(p, ctx):
    if p.log_dir:
        Path(p.log_dir, f"{os.getpid()}_{uuid.uuid4().hex}.run").write_text(repr(p.x))
    return CaseOutput(Result({"x": [p.x]}, {"x": "m"}), {"q": (math.nan, "m"), "w": (p.x, "m")})


CASE = Case("nan_case", __doc__, PARAMETERS, run)
'''


def _runs(log: Path) -> int:
    return len(list(log.glob("*.run")))


def _history(path: Path) -> list[dict[str, str]]:
    with open(path, encoding="utf-8") as handle:
        return list(csv.DictReader(line for line in handle if not line.startswith("#")))


def _initial_population(n_members: int) -> list[float]:
    """scipy's own initial population for one variable on [0, 1] (seed 0, Latin hypercube): a plain reference."""
    seen: list[float] = []

    def record(x):
        seen.append(float(x[0]))
        return float(x[0])

    differential_evolution(record, [(0.0, 1.0)], seed=0, popsize=15, maxiter=0, init="latinhypercube", polish=False,
                           updating="deferred", workers=lambda f, xs: list(map(f, xs)))
    assert len(seen) == n_members
    return seen


# ----------------------------------------------------------------------------- the lock
def test_a_second_optimisation_into_the_same_folder_is_refused_until_the_first_ends(tmp_path):
    out, log = tmp_path / "out", tmp_path / "log"
    log.mkdir()
    first = subprocess.Popen(
        [sys.executable, "-m", "exudyn_atcm", "optimize", str(SYNTHETIC), "--objective", "y", "--bound", "x=0:3",
         "--set", "delay=0.5", "--set", f"log_dir={log}", "--workers", "1", "--out", str(out), "--no-plot"],
        cwd=tmp_path, env=env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        deadline = time.monotonic() + 120.0
        while _runs(log) == 0 and first.poll() is None and time.monotonic() < deadline:
            time.sleep(0.02)
        assert first.poll() is None and _runs(log) > 0  # the first optimisation is running (and holds the folder)
        table = out / "synthetic_study_optimize_history.csv"
        with pytest.raises(StudyLockedError, match=rf"another study is writing '{re.escape(str(table))}' now "
                                                   rf"\(pid {first.pid} on .*: optimize of synthetic_study\); wait until it "
                                                   r"ends, or give this one another output directory \(--out\)"):
            optimize(SYNTHETIC, "y", {"x": (0.0, 3.0)}, options=OptimizeOptions(maxiter=1, popsize=1), run=RunOptions(workers=1, out=out))
        refused = cli(["optimize", str(SYNTHETIC), "--objective", "y", "--bound", "x=0:3", "--maxiter", "1", "--popsize", "1",
                       "--workers", "1", "--out", str(out), "--no-plot"], tmp_path)
        assert refused.returncode == 1
        assert refused.stderr.strip().splitlines()[-1].startswith(f"error: another study is writing '{table}' now (pid {first.pid}")
        assert not table.exists() and not (out / "synthetic_study_optimize.json").exists()  # nothing written by either
    finally:
        os.killpg(first.pid, signal.SIGKILL)  # a killed holder: its lock ends with it
        first.wait(timeout=30)
    assert (out / ".synthetic_study_optimize_history.lock").read_text().startswith(f"pid {first.pid} ")  # left behind
    best = optimize(SYNTHETIC, "y", {"x": (0.0, 3.0)}, options=OptimizeOptions(maxiter=2, popsize=3, rerun_best=False), run=RunOptions(workers=1, out=out))
    assert best.design["x"] == pytest.approx(0.0, abs=1e-3)  # y = x^2 + 2 is least at x = 0
    assert len(_history(out / "synthetic_study_optimize_history.csv")) == best.evaluations


def test_optimisations_of_other_cases_share_a_folder(tmp_path):
    """The lock is per case, like a sweep's per table: another case optimised into the folder is not blocked."""
    other = tmp_path / "nan_case.py"
    other.write_text(NAN_CASE)
    out = tmp_path / "out"
    holder = subprocess.Popen([sys.executable, "-c", "import sys, time\nfrom exudyn_atcm.study.lock import TableLock\n"
                               "with TableLock(sys.argv[1], 'holder'):\n    print('locked', flush=True)\n    time.sleep(120)\n",
                               str(out / "synthetic_study_optimize_history.csv")], env=env(), stdout=subprocess.PIPE, text=True,
                              start_new_session=True)
    try:
        out.mkdir()
        assert holder.stdout.readline().strip() == "locked"
        best = optimize(other, "w", {"x": (0.0, 1.0)}, options=OptimizeOptions(maxiter=2, popsize=3, rerun_best=False), run=RunOptions(workers=1, out=out))
        assert best.design["x"] == pytest.approx(0.0, abs=1e-3)  # w = x
        with pytest.raises(StudyLockedError, match="holder"):
            optimize(SYNTHETIC, "y", {"x": (0.0, 3.0)}, options=OptimizeOptions(maxiter=1, popsize=1), run=RunOptions(workers=1, out=out))
    finally:
        os.killpg(holder.pid, signal.SIGKILL)
        holder.wait(timeout=30)
        holder.stdout.close()


# ----------------------------------------------------------------------------- an objective never finite
def test_an_objective_nan_everywhere_stops_after_the_first_population_and_says_so(tmp_path):
    case = tmp_path / "nan_case.py"
    case.write_text(NAN_CASE)
    log = tmp_path / "log"
    log.mkdir()
    # an earlier optimisation of the case into the folder (objective w = x, finite): its best run is in o/best
    earlier = cli(["optimize", str(case), "--objective", "w", "--bound", "x=0:1", "--maxiter", "1", "--workers", "1",
                   "--out", "o", "--no-plot"], tmp_path)
    assert earlier.returncode == 0 and (tmp_path / "o" / "best" / "nan_case.json").is_file()
    proc = cli(["optimize", str(case), "--objective", "q", "--bound", "x=0:1", "--maxiter", "3", "--set", f"log_dir={log}",
                "--workers", "1", "--out", "o", "--no-plot"], tmp_path)
    assert proc.returncode == 1
    assert "NO DESIGN MEETS THE CONSTRAINTS" not in proc.stdout + proc.stderr  # there are none
    line = proc.stderr.strip().splitlines()[-1]
    members = 15  # scipy's population: popsize 15 x 1 variable
    assert line.startswith(f"error: the objective 'q' of case nan_case was not finite (NaN or inf) at any design of the "
                           f"initial population of differential evolution ({members} designs)")
    population = _initial_population(members)
    shown = "; ".join(f"x = {x:.6g} m gave q = nan" for x in population[:3])
    assert f"the search stops: {shown} (and {members - 3} more); check that case nan_case computes the objective" in line
    assert line.endswith("(every evaluation is in o/nan_case_optimize_history.csv)")
    # exactly the first population was run (was 284 evaluations, 158 runs before the search stopped itself)
    assert _runs(log) == members
    rows = _history(tmp_path / "o" / "nan_case_optimize_history.csv")
    assert [float(r["x [m]"]) for r in rows] == pytest.approx(population, rel=1e-12)
    assert all(math.isnan(float(r["q [m]"])) for r in rows)
    summary = json.loads((tmp_path / "o" / "nan_case_optimize.json").read_text())
    assert summary["design"] is None and summary["objective"] == "q" and summary["evaluations"] == members
    assert not (tmp_path / "o" / "best" / "nan_case.json").exists()  # the earlier best design is not left beside it


def test_a_local_method_stops_after_its_simplex_and_names_a_callable_objective():
    def nan_objective(scalars, values):
        return math.nan

    with pytest.raises(ObjectiveNotFiniteError, match=r"the objective the objective function nan_objective\(\) of case "
                                                      r"synthetic_study was not finite .* at any design of the initial simplex "
                                                      r"of Nelder-Mead \(2 designs\).*x = 1 m gave the objective = nan; "
                                                      r"x = 1.4 m gave the objective = nan;") as info:
        optimize(SYNTHETIC, nan_objective, {"x": (-1.0, 3.0)}, method="nelder-mead", run=RunOptions(workers=1))
    # the simplex: the middle of the range (u = 0.5) and 10 % of the range further (u = 0.6)
    assert [d["x"] for d, _ in info.value.designs] == pytest.approx([1.0, 1.4], rel=1e-12)


def test_runs_that_all_fail_stop_with_their_errors():
    with pytest.raises(ObjectiveNotFiniteError, match=r"x = 1 m gave the run failed \(ValueError: x = 1.0 is below "
                                                      r"fail_below = 10.0\);.*every run failed: see the errors"):
        optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, method="nelder-mead", fixed={"fail_below": 10.0}, run=RunOptions(workers=1))


def test_a_constraint_never_finite_is_named(tmp_path):
    case = tmp_path / "nan_case.py"
    case.write_text(NAN_CASE)
    with pytest.raises(ObjectiveNotFiniteError, match=r"the objective 'w' and the constraints \('q'\) of case nan_case were "
                                                      r"never all finite .*x = 0.5 m gave w = 0.5 but q = nan"):
        optimize(case, "w", {"x": (0.0, 1.0)}, constraints={"q": (1.0, None)}, method="nelder-mead", run=RunOptions(workers=1))


def test_one_finite_design_in_the_first_population_is_enough():
    """Finite only for 0.6 <= x <= 0.8 of [0, 3]: one of the 15 Latin-hypercube strata (width 0.2) lies there."""

    def band(scalars, values):
        x = values["x"]
        return (x - 0.7) ** 2 if 0.6 <= x <= 0.8 else math.nan

    best = optimize(SYNTHETIC, band, {"x": (0.0, 3.0)}, options=OptimizeOptions(maxiter=20, rerun_best=False), run=RunOptions(workers=1))
    assert best.design["x"] == pytest.approx(0.7, abs=1e-3) and best.feasible


def test_constraints_that_no_design_meets_keep_their_message(tmp_path, capsys):
    """y = x^2 + n >= 2 everywhere: y <= 1 is finite but never met (not a non-finite problem)."""
    from exudyn_atcm.cli import main

    assert main(["optimize", str(SYNTHETIC), "--objective", "z", "--bound", "x=0:3", "--constraint", "y<=1",
                 "--maxiter", "2", "--workers", "1", "--out", str(tmp_path)]) == 1
    assert "NO DESIGN MEETS THE CONSTRAINTS" in capsys.readouterr().out


# ----------------------------------------------------------------------------- the evaluation budget
@pytest.mark.parametrize("budget", [22, 70])
def test_the_evaluation_budget_is_honoured_exactly(tmp_path, budget):
    """22 stops inside the second generation (15 + 7), 70 inside the polish (the search takes (3 + 1) x 15 = 60)."""
    log = tmp_path / "log"
    log.mkdir()
    kwargs = dict(fixed={"n": 2}, run=RunOptions(workers=1), options=OptimizeOptions(maxiter=3, rerun_best=False))
    free = optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, **kwargs)
    assert free.evaluations > 70  # unbounded it goes further (measured 78)
    best = optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, **{
        **kwargs, "fixed": {"n": 2, "log_dir": str(log)},
        "options": OptimizeOptions(maxiter=3, rerun_best=False, max_evaluations=budget)})
    assert best.evaluations == budget and len(best.history) == budget
    assert best.executed == _runs(log) <= budget  # no run started beyond the budget
    assert best.max_evaluations == budget
    assert best.message == f"stopped after {budget} evaluations: max_evaluations = {budget} reached"
    # the same path as the unbounded run (DE is seeded), cut after `budget` evaluations; the best of those is
    # the one with the least y = x^2 + 2 (closed form, from the designs alone)
    xs = column(best.history, "x")
    np.testing.assert_array_equal(xs, column(free.history, "x")[:budget])
    assert best.objective == pytest.approx(min(x * x + 2.0 for x in xs), rel=1e-12)


def test_the_command_line_announces_the_evaluations_and_keeps_to_the_budget(tmp_path):
    log = tmp_path / "log"
    log.mkdir()
    proc = cli(["optimize", str(SYNTHETIC), "--objective", "y", "--bound", "x=-1:3", "--maxiter", "3", "--max-evaluations",
                "37", "--set", f"log_dir={log}", "--workers", "1", "--out", "o", "--no-plot"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    first, summary = proc.stdout.splitlines()[:2]
    # the methods' own limits: (maxiter + 1) x 15 for the search, 20 maxiter n iterations of n + 2 plus n + 1 for the polish
    assert first == ("synthetic_study: differential_evolution over 1 variable: at most 37 evaluations (--max-evaluations; "
                     "the method's own limits: 60 for differential evolution (an initial population of 15, then 3 "
                     "generations of 15) and 182 for its Nelder-Mead polish); each evaluation is at most one run of the case; "
                     "then the best design runs once more for its files in o/best")
    assert summary.startswith("synthetic_study: minimum of y = ") and summary.endswith("after 37 evaluations (37 runs executed)")
    assert len(_history(tmp_path / "o" / "synthetic_study_optimize_history.csv")) == 37
    assert _runs(log) == 37 + 1  # and the announced run of the best design, for o/best
    assert (tmp_path / "o" / "best" / "synthetic_study.json").is_file()
    unbounded = cli(["optimize", str(SYNTHETIC), "--objective", "y", "--bound", "x=-1:3", "--maxiter", "3", "--workers", "1",
                     "--out", "o2", "--no-plot"], tmp_path)
    assert unbounded.stdout.splitlines()[0].endswith(
        "at most 242 evaluations: 60 for differential evolution (an initial population of 15, then 3 generations of 15) "
        "and 182 for its Nelder-Mead polish; it stops earlier when it converges. Each evaluation is at most one run of "
        "the case; --max-evaluations caps them; then the best design runs once more for its files in o2/best")
    assert int(re.search(r"after (\d+) evaluations", unbounded.stdout).group(1)) <= 242


@pytest.mark.parametrize("value", [0, -3, 2.5, True, "10"])
def test_a_bad_budget_is_refused_naming_it(value, capsys):
    with pytest.raises(ValueError, match=rf"max_evaluations must be an integer >= 1 \(the most objective evaluations\), "
                                         rf"got {re.escape(repr(value))}"):
        optimize(SYNTHETIC, "y", {"x": (0.0, 1.0)}, options=OptimizeOptions(max_evaluations=value), run=RunOptions(workers=1))
    if value == 0:
        from exudyn_atcm.cli import main

        assert main(["optimize", str(SYNTHETIC), "--objective", "y", "--bound", "x=0:1", "--max-evaluations", "0"]) == 2
        assert capsys.readouterr().err.strip() == "error: --max-evaluations must be an integer >= 1, got 0"


def test_a_budget_below_the_first_population_still_reports_the_best():
    """5 evaluations of a 15-member population: the best of those five, not an error."""
    best = optimize(SYNTHETIC, "y", {"x": (0.0, 1.0)}, fixed={"n": 2}, options=OptimizeOptions(max_evaluations=5, rerun_best=False), run=RunOptions(workers=1))
    population = _initial_population(15)[:5]
    assert best.evaluations == 5
    assert best.design["x"] == pytest.approx(min(population), rel=1e-12)  # y = x^2 + 2 grows with x >= 0
    assert best.objective == pytest.approx(min(population) ** 2 + 2.0, rel=1e-12)
