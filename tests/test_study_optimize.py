"""Design optimisation: closed-form optima, constraints, parallel and resumable evaluation."""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np
import pytest

from exudyn_atcm import theory as bt
from exudyn_atcm.casework import load_case
from exudyn_atcm.study import GridError, optimize
from exudyn_atcm.study.options import OptimizeOptions, RunOptions

from _cli_helpers import CASES

SYNTHETIC = Path(__file__).resolve().parent / "study_cases" / "synthetic_study.py"


@pytest.fixture(scope="module")
def bender():
    return load_case(CASES / "optimise_bender.py")


def test_closed_form_optimum_thickness_ratio():
    # n = 1: the quartic is (t - 2)(t + 1)^3, so t* = 2 exactly (derived by hand in the case docstring)
    assert bt.optimal_thickness_ratio(1.0) == pytest.approx(2.0, rel=1e-14)
    # for other n, t* is where W = delta_free F_b of the beam-theory formulas peaks (dense evaluation)
    for n in (0.4, 2.307489, 6.0):
        t = bt.optimal_thickness_ratio(n)
        grid = np.linspace(0.5 * t, 1.5 * t, 20001)
        work = [bt.actuator_work(n * 30e9, ti * 0.3e-3, 30e9, 0.3e-3, 0.028, 1.38e-3, 0.1) for ti in grid]
        assert t == pytest.approx(grid[int(np.argmax(work))], rel=1e-4)  # grid spacing 5e-5 t


def test_local_optimiser_finds_the_closed_form_thickness_ratio(bender):
    """Nelder-Mead over h1 with the multibody model (3 rigid cells, E1 = 70 GPa): t* of beam theory.

    The rigid chain's work is the beam's divided by the compliance factor 1 + 1/(2 N^2), which
    does not depend on h1, so the optimum ratio is the same; the tolerance 1e-3 covers the
    optimiser's stopping tolerance (xatol 1e-4 of the 1.45 mm range = 5e-4 of h1*).
    """
    fixed = {"mode": "evaluate", "n_cells": 3, "passive_modulus": 70e9}
    best = optimize(bender, "work", {"passive_thickness": (0.05e-3, 1.5e-3)}, method="nelder-mead", maximize=True, fixed=fixed, options=OptimizeOptions(rerun_best=True), run=RunOptions(workers=1))
    expected = bt.optimal_thickness_ratio(70e9 / 30.336e9)
    assert best.design["passive_thickness"] / 0.3e-3 == pytest.approx(expected, rel=1e-3)
    assert best.output is not None and best.output.scalars["work"] == best.scalars["work"]
    chain = 1.0 + 1.0 / (2.0 * 3**2)
    strain = 460e-12 * 1500.0 / 0.5e-3
    closed = bt.actuator_work(70e9, expected * 0.3e-3, 30.336e9, 0.3e-3, 28e-3, strain, 3 * 29e-3) / chain
    assert best.objective == pytest.approx(closed, rel=1e-6)  # linear statics of the chain: exact to the solver tolerance


def test_optimise_bender_case_finds_the_design(bender, tmp_path):
    """The case on its defaults (2 workers): stiffest passive layer, most cells, t within 1 % of t*."""
    out = bender.run({"workers": 2}, out_dir=tmp_path, plot=True)
    s = out.scalars
    assert abs(s["thickness_ratio_error"]) < 0.01  # the goal; measured about 1e-8
    assert s["thickness_ratio_beam_theory"] == pytest.approx(bt.optimal_thickness_ratio(70e9 / 30.336e9), rel=1e-12)
    assert s["passive_modulus_optimum"] == pytest.approx(70e9, rel=1e-3)  # g(n, t*(n)) grows with n
    assert s["n_cells_optimum"] == 4  # W grows with L; 4 cells still meet f1 >= 20 Hz at t*
    assert s["first_frequency_optimum"] >= 20.0 and s["frequency_bound_active"] == 0.0
    # geometric nonlinearity at 1500 V favours thicker layers (smaller free rotation): t grows
    assert 1.0 < s["thickness_ratio_optimum_nonlinear"] / s["thickness_ratio_optimum"] < 1.05
    assert (tmp_path / "optimise_bender_work.png").is_file()
    assert "evaluations per minute per core" in out.notes["evaluation rate"]  # issue 31: the case reports its rate


def test_differential_evolution_with_integer_and_constraint_parallel_and_resumable(tmp_path):
    """max z = n sin(x) subject to y = x^2 + n <= 3: n = 2, x = 1 (n = 1 gives sin(sqrt 2) < 1, n = 3 gives 0)."""
    kwargs = dict(maximize=True, constraints={"y": (None, 3.0)}, options=OptimizeOptions(maxiter=40))
    bounds = {"x": (0.0, 3.0), "n": (1, 3)}
    called = time.perf_counter()
    first = optimize(SYNTHETIC, "z", bounds, run=RunOptions(workers=2, out=tmp_path), **kwargs)
    called = time.perf_counter() - called
    assert first.design["n"] == 2 and first.design["x"] == pytest.approx(1.0, abs=1e-3)
    # the rate per core: the runs executed over the cores held, two workers for the generations and one for
    # the polish (a pool of one forked worker: one design at a time), each times its stage's wall time
    assert first.cores == 2 and 0.0 < first.search_time <= called
    assert [w for w, _ in first.stages] == [2, 1] and sum(t for _, t in first.stages) <= first.search_time
    assert first.core_seconds == pytest.approx(2.0 * first.stages[0][1] + first.stages[1][1], rel=1e-12)
    assert first.search_time < first.core_seconds < 2.0 * first.search_time
    assert first.evaluation_rate == pytest.approx(first.executed / first.core_seconds, rel=1e-12)
    assert first.describe_rate().startswith(f"{60.0 * first.evaluation_rate:.0f} evaluations per minute per core "
                                            f"({first.executed} runs executed in")
    assert "on 2 workers for" in first.describe_rate() and ", then 1 worker for" in first.describe_rate()
    # the polish's runs (the last evaluations; the generations' come first) all ran in one worker process
    records = [json.loads(p.read_text()) for p in (tmp_path / "runs").rglob("*.json") if p.parent.parent.name != "latest"]
    worker_of = {r["key"]: r["worker"] for r in records if "worker" in r}
    keys = [k for k in first.history["key"] if k in worker_of]
    polish_workers = {worker_of[k] for k in keys[-5:]}
    assert len(polish_workers) == 1 and not polish_workers & {worker_of[k] for k in keys[:5]}
    assert first.feasible and first.objective == pytest.approx(2.0 * math.sin(1.0), rel=1e-3)
    assert first.executed > 0 and (tmp_path / "synthetic_study_optimize_history.csv").is_file()
    # the same optimisation again: every evaluation comes from the store, same answer, in one process
    again = optimize(SYNTHETIC, "z", bounds, run=RunOptions(workers=1, out=tmp_path), **kwargs)
    assert again.executed == 0 and again.design == first.design and again.evaluations == first.evaluations
    assert math.isnan(again.evaluation_rate) and again.cores == 1  # nothing executed: no rate
    assert again.describe_rate().startswith("no run executed")


def test_lbfgsb_with_finite_differences_and_a_callable_objective():
    best = optimize(SYNTHETIC, lambda scalars, values: (values["x"] - 0.7) ** 2 + scalars["y"] * 0.0, {"x": (-1.0, 2.0)}, method="l-bfgs-b", run=RunOptions(workers=1))
    assert best.design["x"] == pytest.approx(0.7, abs=1e-5)


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"bounds": {"xx": (0, 1)}}, GridError, "did you mean 'x'?"),
        ({"bounds": {"x": (1, 1)}}, GridError, "low < high"),
        ({"bounds": {"mode": (0, 1)}}, GridError, "must be float or int"),
        ({"bounds": {"delay": (-1.0, 1.0)}}, GridError,
         "bounds: delay must be >= 0 [s], got -1.0 (the case's declared range)"),
        ({"bounds": {"n": (1, 3)}, "method": "nelder-mead"}, ValueError, "need method='differential_evolution'"),
        ({"bounds": {"x": (0, 1)}, "method": "newton"}, ValueError, "method must be one of"),
        ({"bounds": {"x": (0, 1)}, "options": OptimizeOptions(fatol=-1.0)}, ValueError, "fatol must be a number in [0, inf)"),
        ({"bounds": {"x": (0, 1)}, "options": OptimizeOptions(xatol=2.0)}, ValueError, "xatol must be a number in [0, 1)"),
        ({"bounds": {"x": (0, 1)}, "constraints": {"y": (None, None)}}, ValueError, "give a lower or an upper limit"),
        ({"bounds": {"x": (0, 1)}, "constraints": {"f1": (1.0, None)}}, ValueError,
         "constraints: 'f1' is not a key scalar of case synthetic_study; its key scalars: y, z"),
    ],
)
def test_bad_optimisation_input(kwargs, error, message):
    with pytest.raises(error, match=None) as info:
        optimize(SYNTHETIC, "y", run=RunOptions(workers=1), **kwargs)
    assert message in str(info.value)


def test_nelder_mead_stops_at_its_tolerances_on_a_smooth_problem():
    """Nelder-Mead stops by its tolerances (xatol and the relative fatol), long before the cap.

    y = x^2 + 2 on x in [-1, 3]: the cap is maxiter * n * 20 = 2000 evaluations; from the
    middle the 1-D simplex needs about log2(4 / 4e-4) ~ 14 halvings after a few expansions,
    so 100 evaluations is ample.  At the stop the best vertex is within a few xatol * range of
    the minimum x = 0.  A kink |x - 0.7123| + 0.5 (whose values on the simplex only become
    equal at machine precision) shows the function tolerance: with fatol = 0 it runs until the
    simplex collapses to rounding, with the default 1e-4 (relative) it stops far sooner.
    """
    best = optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, method="nelder-mead", fixed={"n": 2}, options=OptimizeOptions(rerun_best=False), run=RunOptions(workers=1))
    assert best.scipy_result.status == 0  # "Optimization terminated successfully", not the cap (status 1/2)
    assert best.evaluations < 100
    assert abs(best.design["x"]) < 4 * 1e-4 * 4.0

    def kink(scalars, values):
        return abs(values["x"] - 0.7123) + 0.5

    runs = {fatol: optimize(SYNTHETIC, kink, {"x": (-1.0, 3.0)}, method="nelder-mead", fixed={"n": 2}, options=OptimizeOptions(rerun_best=False, fatol=fatol), run=RunOptions(workers=1)) for fatol in (0.0, 1e-4)}
    assert runs[1e-4].evaluations < 0.5 * runs[0.0].evaluations  # measured 24 against 104
    assert abs(runs[1e-4].design["x"] - 0.7123) < 4 * 1e-4 * 4.0  # still within the x tolerance
    # the polish after differential evolution stops too: DE (4 generations) + polish well under the polish's cap
    de = optimize(SYNTHETIC, "y", {"x": (-1.0, 3.0)}, fixed={"n": 2}, options=OptimizeOptions(maxiter=4, popsize=4, rerun_best=False), run=RunOptions(workers=1))
    assert de.scipy_result.status == 0
    assert de.evaluations < 4 * 5 * 4 + 100  # DE: at most (maxiter + 1) * popsize * n runs; polish < 100
    assert abs(de.design["x"]) < 4 * 1e-4 * 4.0


def test_unknown_objective_scalar():
    with pytest.raises(ValueError, match="objective 'w' is not a key scalar of case synthetic_study; its key scalars: y, z"):
        optimize(SYNTHETIC, "w", {"x": (0.0, 1.0)}, method="nelder-mead", run=RunOptions(workers=1))


def test_scipy_constraints_in_differential_evolution():
    """The same problem with scipy's NonlinearConstraint (feasibility rules), population vectorised."""
    best = optimize(SYNTHETIC, "z", {"x": (0.0, 3.0), "n": (1, 3)}, maximize=True, constraints={"y": (None, 3.0)}, options=OptimizeOptions(constraint_handling="scipy", maxiter=40), run=RunOptions(workers=2))
    assert best.design["n"] == 2 and best.design["x"] == pytest.approx(1.0, abs=1e-3)
    assert best.feasible and best.scalars["y"] <= 3.0


def test_cli_optimize(tmp_path, capsys):
    from exudyn_atcm.cli import main

    args = ["optimize", str(SYNTHETIC), "--objective", "z", "--maximize", "--bound", "x=0:3", "--bound", "n=1:3",
            "--constraint", "y<=3", "--maxiter", "40", "--workers", "1", "--out", str(tmp_path)]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "synthetic_study: maximum of z = 1.68" in out and "  n = 2 [-]" in out  # 2 sin(1) = 1.683
    assert (tmp_path / "synthetic_study_optimize_history.csv").is_file()
    # no design can meet y = x^2 + n <= 0.5 (n >= 1): exit status 1, said on the first line
    assert main(args[:-8] + ["--constraint", "y<=0.5", "--maxiter", "3", "--workers", "1", "--out", str(tmp_path / "b")]) == 1
    assert "NO DESIGN MEETS THE CONSTRAINTS" in capsys.readouterr().out
    assert main(["optimize", str(SYNTHETIC), "--objective", "y", "--bound", "x=0:1:3"]) == 2
    assert capsys.readouterr().err.strip() == "error: --bound x: expects NAME=LOW:HIGH, got 'x=0:1:3'"


@pytest.mark.parametrize(
    ("bound", "message"),
    [
        ("x=1:0", "error: --bound x: empty range '1:0' (START > STOP)"),
        ("mode=0:1", "error: --bound mode: mode is a str parameter; design variables must be float or int "
                     "(fix it with --set instead)"),
        ("xx=0:1", "error: --bound: unknown parameter 'xx' for case synthetic_study; did you mean 'x'?"),
    ],
)
def test_cli_bound_errors_name_the_bound_option(bound, message, capsys):
    """Errors of --bound say --bound (they said --grid, an option optimize does not have)."""
    from exudyn_atcm.cli import main

    assert main(["optimize", str(SYNTHETIC), "--objective", "y", "--bound", bound]) == 2
    assert capsys.readouterr().err.strip().startswith(message)


def test_malformed_scheduler_address_names_the_parameter():
    pytest.importorskip("dask.distributed")
    with pytest.raises(ValueError, match=r"scheduler must be a Dask scheduler address such as 'tcp://HOST:8786', got 'foo'"):
        optimize(SYNTHETIC, "y", {"x": (0.0, 1.0)}, run=RunOptions(scheduler="foo"))
