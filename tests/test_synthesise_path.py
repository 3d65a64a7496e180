"""Path synthesis of the compliant four-bar (cases/synthesise_path.py): a known design recovered, hysteresis costs.

Independent references: the reference design that generated the precision points (its
dimensions are known), the rigid four-bar's loop closure, and the paper's hysteresis-loop
numbers (stroke -4 ... 40 µm over -500 ... 1500 V; 12 µm ascending and 28 µm descending at
U_m = 500 V), through the branch formulas x1 = x_min + Δx ((U - U_min)/ΔU)^r1 and
x2 = x_max - Δx ((U_max - U)/ΔU)^r2 of the paper, with r1, r2 fixed by those two points.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm.casework import load_case

from _cli_helpers import CASES

VOLTAGES = np.array([-500.0, 0.0, 500.0, 1000.0, 1500.0])  # the case's default precision voltages
X_MIN, X_MAX, X_ASC, X_DESC = -4.0, 40.0, 12.0, 28.0  # µm, the paper's loop


def paper_branches(voltages):
    """Rising and falling branch of the paper's loop as fractions of the stroke (0 at -500 V, 1 at 1500 V)."""
    r1 = math.log((X_ASC - X_MIN) / (X_MAX - X_MIN)) / math.log(0.5)
    r2 = math.log((X_MAX - X_DESC) / (X_MAX - X_MIN)) / math.log(0.5)
    s = (np.asarray(voltages) + 500.0) / 2000.0
    return s**r1, 1.0 - (1.0 - s) ** r2


@pytest.fixture(scope="module")
def case():
    return load_case(CASES / "synthesise_path.py")


@pytest.fixture(scope="module")
def synthesis(case):
    """Reduced configuration: 2 crank cells, Nelder-Mead from the middle of the bounds, in this process."""
    return case.run({"method": "nelder-mead", "maxiter": 8, "n_cells": 2, "workers": 1, "path_steps": 8, "animation": False},
                    plot=False)


def test_reference_design_is_recovered_from_the_middle_of_the_bounds(case, synthesis):
    s = synthesis.scalars
    history = synthesis.tables["history_hysteresis"]
    bounds = synthesis.result.parameters["bounds [m]"]
    assert list(bounds) == ["rocker_pivot_height", "coupler_point_x", "coupler_point_y"]
    # the start: the middle of the bounds, 5 mm from the reference in every variable, 0.8 mm RMS from the points
    for name, (low, high) in bounds.items():
        assert history[name][0] == pytest.approx(0.5 * (low + high), abs=1e-15)
        assert abs(history[name][0] - case.resolve()[f"reference_{name}"]) >= 4.9e-3
    assert history["rms_rising"][0] > 5e-4
    # the precision points are the same model's output at the reference design, so the minimum is
    # exactly that design; Nelder-Mead's tolerances are 1e-5 of each range (<= 0.6 µm) and 1e-6 of the
    # ~1 mm RMS distance on the initial simplex (~1 nm): it stops there, not at its iteration cap
    assert s["design_error_max"] < 1e-6
    assert s["distance_rms"] < 1e-8
    assert s["rocker_pivot_height_optimum"] == pytest.approx(0.02, abs=1e-6)
    assert s["coupler_point_x_optimum"] == pytest.approx(0.025, abs=1e-6)
    assert s["coupler_point_y_optimum"] == pytest.approx(0.02, abs=1e-6)


def test_synthesised_mechanism_follows_the_rigid_four_bar(synthesis):
    # rigid coupler and rocker, PRBM pivots are pins: loop closure exact up to the static solver tolerance
    assert synthesis.scalars["rigid_four_bar_error"] < 1e-6


def test_loop_width_follows_the_paper_loop(synthesis):
    """Rising and falling coupler points at 500 V are 16/44 of the travel apart.

    The coupler point moves along a nearly straight path nearly in proportion to the crank's
    free strain (the crank tip's rotation stays below 0.13 rad: the arc's tip displacement is
    linear in the curvature up to theta^2/12 = 0.15 %), so the distance of the two branches at a
    voltage is the travel times the branches' strain difference; 1 % covers the path's curvature.
    """
    r = synthesis.result
    rising, falling = paper_branches(VOLTAGES)
    k = int(np.flatnonzero(r["voltage"] == 500.0)[0])
    width = math.hypot(r["hysteresis.rising_x"][k] - r["hysteresis.falling_x"][k],
                       r["hysteresis.rising_y"][k] - r["hysteresis.falling_y"][k])
    expected = synthesis.scalars["coupler_travel"] * (falling[2] - rising[2])
    assert falling[2] - rising[2] == pytest.approx(16.0 / 44.0, rel=1e-12)
    assert width == pytest.approx(expected, rel=0.01)


def test_linear_drive_design_misses_the_points_as_the_affine_fit_predicts(synthesis):
    """A design made with a linear drive: its error follows from the paper's branch in closed form.

    In the proportional straight-path model, a design can shift and scale the coupler point's
    position along the path (s = a + g eps); the points lie at the reference's rising-branch
    fractions rho(U).  With the linear law eps = lambda(U) the best design is the least-squares
    fit a + g lambda ~ rho (RMS residual e_lin); evaluated with the hysteretic drive it sits at
    a + g rho, off by a + (g - 1) rho.  Tolerances 3 % and 5 %: the model ignores the path's
    curvature and the gain's dependence on the design (measured 0.5 % and 2 %).
    """
    s = synthesis.scalars
    rho, _ = paper_branches(VOLTAGES)
    lam = (VOLTAGES + 500.0) / 2000.0
    A = np.stack([np.ones_like(lam), lam], axis=1)
    (a, g), *_ = np.linalg.lstsq(A, rho, rcond=None)
    travel = s["coupler_travel"]
    e_lin = math.sqrt(np.mean((a + g * lam - rho) ** 2)) * travel
    e_hyst = math.sqrt(np.mean((a + (g - 1.0) * rho) ** 2)) * travel
    assert s["linear_design_distance_rms_linear_drive"] == pytest.approx(e_lin, rel=0.03)
    assert s["linear_design_distance_rms"] == pytest.approx(e_hyst, rel=0.05)
    assert s["hysteresis_path_error"] == pytest.approx(s["linear_design_distance_rms"] - s["distance_rms"], abs=1e-15)
    assert s["hysteresis_path_error"] > 0.4e-3  # half a millimetre lost by designing without hysteresis


def test_both_branch_design_respects_the_loop_width_bound(synthesis):
    """Meeting the points on both branches: no design beats the triangle-inequality bound.

    At each voltage d_rising + d_falling >= w (the branches' distance), so
    rms_both >= sqrt(sum w^2 / (4 n)) with w = travel (falling - rising) of the paper's loop
    (proportional model: 2 % allowance).  The optimiser must improve on the rising-branch design.
    """
    s = synthesis.scalars
    rising, falling = paper_branches(VOLTAGES)
    bound = s["coupler_travel"] * math.sqrt(np.sum((falling - rising) ** 2) / (4 * VOLTAGES.size))
    assert s["both_design_distance_rms_both_branches"] >= 0.98 * bound
    assert s["both_design_distance_rms_both_branches"] < s["distance_rms_both_branches"]
    assert s["distance_rms_both_branches"] == pytest.approx(math.sqrt(np.mean((falling - rising) ** 2) / 2) * s["coupler_travel"],
                                                             rel=0.02)  # exact on rising: all the error on the falling branch


def test_differential_evolution_in_parallel_writes_plots_and_resumes(case, tmp_path):
    """Process pool of 2 workers, few generations; a second run replays every run from the store."""
    values = {"maxiter": 4, "popsize": 4, "n_cells": 2, "workers": 2, "compare": False, "path_steps": 8}
    first = case.run(values, out_dir=tmp_path, plot=True)
    s = first.scalars
    assert s["design_error_max"] < 1e-6  # polished by Nelder-Mead to the reference (same tolerance as above)
    assert s["runs_executed"] > 0
    assert "evaluations per minute per core" in first.notes["evaluation rate"]  # issue 31: the case reports its rate
    for suffix in ("_paths.png", "_history.png", "_animation.gif", ".csv", "_history_hysteresis.csv", "_path.csv"):
        assert (tmp_path / f"synthesise_path{suffix}").is_file(), suffix
    again = case.run(values, out_dir=tmp_path, plot=False)
    assert again.scalars["runs_executed"] == 0
    assert again.notes["evaluation rate"].startswith("no run executed")
    assert again.scalars["design_error_max"] == s["design_error_max"]


@pytest.mark.parametrize("values, message", [
    ({"precision_points": (0.02, 0.08, 0.03)}, r"precision_points must be 10 finite coordinates .* got 3 values"),
    ({"precision_voltages": (0.0, 1600.0)}, r"precision_voltages must be at least 2 distinct voltages within \[-500, 1500\] V, got \(0.0, 1600.0\)"),
    ({"precision_voltages": (0.0, 0.0)}, r"precision_voltages must be at least 2 distinct"),
    ({"n_steps": 3}, r"n_steps must be an even integer >= 2, got 3"),
    ({"rocker_pivot_height": 0.07}, r"rocker_pivot_height must be in .* got 0.07"),
    ({"reference_cells": -1}, r"reference_cells must be >= 0 \(0: n_cells\), got -1"),
])
def test_bad_input_is_refused_with_the_parameter_named(case, values, message):
    with pytest.raises(ValueError, match=message):
        case.run({"mode": "evaluate", **values}, plot=False)


def test_explicit_empty_precision_points_mean_the_reference_design(case):
    """``precision_points=()`` (or ``--set precision_points=``) is the default: the reference design's points."""
    assert case.resolve({"precision_points": ()})["precision_points"] == ()
    assert case.resolve({"precision_points": []})["precision_points"] == ()
    values = {"mode": "evaluate", "n_cells": 2, "path_steps": 8, "animation": False}
    default = case.run(values, plot=False).scalars
    explicit = case.run({**values, "precision_points": ()}, plot=False).scalars
    assert explicit == default
    assert default["rms_rising"] == 0.0  # the reference design meets its own points exactly (same model)
