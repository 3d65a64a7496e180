"""The four mechanism cases against their independent references (closed forms, the paper's
precision points, symmetry); each case on its defaults."""

from __future__ import annotations

import json
import math
import re
import warnings

import pytest

from exudyn_atcm import theory as bt
from exudyn_atcm.casework import load_case
from exudyn_atcm.model.parameter_sets import PAPER_LOOP

from _cli_helpers import CASES, run

# the paper's laminate (independent of the cases' code)
E1, H1, E2, H2 = 70e9, 0.2e-3, 30.336e9, 0.3e-3
# static solves converge to Exudyn's Newton tolerance: positions agree to ~1e-8 m at worst
STATIC_TOL = 1e-8  # m


def _quiet_run(name):
    """The case on its defaults; any RuntimeWarning fails (a case must not warn on its defaults)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        return load_case(CASES / f"{name}.py").run()


@pytest.fixture(scope="module")
def four_bar():
    return _quiet_run("compliant_four_bar")


@pytest.fixture(scope="module")
def gripper():
    return _quiet_run("micro_gripper")


@pytest.fixture(scope="module")
def guide():
    return _quiet_run("parallel_guide")


@pytest.fixture(scope="module")
def lever():
    return _quiet_run("bender_with_lever")


# ----------------------------------------------------------------------------- four-bar
def test_four_bar_coupler_point_follows_the_rigid_four_bar(four_bar):
    s = four_bar.scalars
    # links and PRBM pivots are rigid and exact: the rigid four-bar through the pivots must
    # hold to the static solver's tolerance, far inside the 1e-3 goal
    assert s["reference_error"] < 1e-6
    assert s["reference_error_linear"] < 1e-6
    assert s["rocker_joint_error_abs"] < STATIC_TOL
    assert s["coupler_travel"] > 1e-3  # the mechanism moves (mm), so the check is not vacuous
    # in dynamics too (triangle wave, hysteresis in the solver step): the loop closure of the
    # rigid coupler and rocker holds at every recorded instant
    assert s["reference_error_dynamic"] < 1e-6
    assert s["dynamic_travel"] > 1e-3


def test_four_bar_hysteresis_path_error(four_bar):
    r = four_bar.result
    s = four_bar.scalars
    n = len(r["voltage"])
    half = (n - 1) // 2
    # the crank's free strain at 500 V on the rising / falling branch is the paper's precision
    # point 12 um / 28 um of stroke of a 29 mm cell (exact exponents); linear law: midway
    cell = PAPER_LOOP["cell_length [m]"]
    k500 = int(round(half / 2))
    assert r["voltage"][k500] == pytest.approx(500.0)
    assert r["hysteresis.strain"][k500] == pytest.approx(12e-6 / cell, rel=1e-9)
    assert r["hysteresis.strain"][n - 1 - k500] == pytest.approx(28e-6 / cell, rel=1e-9)
    assert r["linear.strain"][k500] == pytest.approx(18e-6 / cell, rel=1e-9)
    # same end points of the law: both runs meet at -500 V and 1500 V
    for row in (0, half, n - 1):
        assert r["path_error"][row] < STATIC_TOL
    # without hysteresis the rising and falling half-cycles coincide; with it they do not
    assert s["loop_width_linear"] < 1e-6 * s["coupler_travel"]
    assert s["loop_width_max"] > 0.2 * s["coupler_travel"]
    assert s["hysteresis_path_error_rel"] > 0.1


def test_four_bar_degrees_of_freedom_follow_gruebler(four_bar):
    # rigid bodies: N crank cells, the crank-side segment of hinge_B, the coupler group
    # (hinge_B tip segment + coupler + hinge_C base segment), the rocker group (hinge_C tip
    # segment + rocker + hinge_D base segment); revolute joints: clamp, N - 1 between cells,
    # crank tip weld, three PRBM pivots.  Gruebler: 3 (N + 3) - 2 (N + 4) = N + 1.
    n = four_bar.parameters["n_cells"]
    assert four_bar.notes["degrees_of_freedom"] == n + 1


def test_four_bar_is_built_in_under_30_lines():
    text = (CASES / "compliant_four_bar.py").read_text(encoding="utf-8")
    body = text.split("--- user code:")[1].split("--- end of user code")[0].splitlines()[1:]
    lines = [line for line in body if line.strip() and not line.strip().startswith("#")]
    stated = int(re.search(r"takes the (\d+) lines below", text).group(1))
    assert len(lines) == stated < 30


# ----------------------------------------------------------------------------- gripper
def test_gripper_is_symmetric_and_its_free_jaw_follows_the_arc(gripper):
    s = gripper.scalars
    assert s["mirror_error"] < 1e-12
    # arc + rigid jaw; the chain polygon shifts the jaw by (kappa Lc)^2/24 of its distance
    # from the base: 2e-5 of the travel at 24 cells
    assert s["free_jaw_error"] < 1e-4
    assert s["free_jaw_error_chain_polygon"] < 1e-5  # static solver tolerance
    assert s["gap_initial"] == pytest.approx(10e-3)


def test_gripper_force_matches_the_blocked_force_closed_form(gripper):
    s = gripper.scalars
    for label in ("object", "stiff"):
        # the recorded spring force equals the spring law on the simulated jaw distance
        assert s[f"force_column_difference_{label}"] < 1e-9
        assert s[f"force_error_closed_form_{label}"] < 1e-3
        assert s[f"force_error_chain_closed_form_{label}"] < 1e-3
        assert s[f"force_error_large_deflection_{label}"] < 1e-3
    # the paper laminate at 1500 V, 10 mm wide, L = 40 mm, a = 5 mm: EI kappa (L/2 + a)/(L²/3 + L a + a²)
    b, L, a = 10e-3, 0.04, 5e-3
    ei = bt.composite_bending_stiffness(E1, H1, E2, H2, b)
    kappa = bt.free_curvature(E1, H1, E2, H2, b, PAPER_LOOP["x_max [m]"] / PAPER_LOOP["cell_length [m]"])
    fb = ei * kappa * (L / 2 + a) / (L**2 / 3 + L * a + a**2)
    assert s["blocked_force_closed_form_1500V"] == pytest.approx(fb, rel=1e-12)
    # stiff object (2 k c ~ 1300): within 1.5e-3 of the blocked force
    assert s["force_max_stiff"] == pytest.approx(fb, rel=1.5e-3)


# ----------------------------------------------------------------------------- parallel guide
def test_parallel_guide_translates_by_the_s_blade_value(guide):
    s = guide.scalars
    # exact large-deflection S-blade: only the chain polygon factor remains (5e-5 of the translation)
    assert s["translation_error"] < 1e-4
    assert s["translation_error_chain_polygon"] < 1e-9
    assert s["rotation_max"] < 1e-12
    assert s["strain_antisymmetry_error"] == 0.0
    # kappa L²/4 is off by 1 - sinc²(kappa L/4) ~ (kappa L)²/48 at the largest voltage
    kappa = bt.free_curvature(E1, H1, E2, H2, 10e-3, bt.piezo_strain(500.0))
    L = 0.06
    assert s["translation_y_small_deflection_max"] == pytest.approx(kappa * L**2 / 4, rel=1e-12)
    expected = (kappa * L**2 / 4) * (1 - (math.sin(kappa * L / 4) / (kappa * L / 4)) ** 2)
    assert s["translation_error_small_deflection"] * s["translation_y_reference_max"] == pytest.approx(
        expected, rel=1e-2)


# ----------------------------------------------------------------------------- lever
def test_lever_end_is_tip_plus_a_along_the_tip_tangent(lever):
    s = lever.scalars
    assert s["lever_error"] < 1e-12  # weld: exact rigid-body kinematics, at every recorded instant
    assert s["lever_end_travel"] > 0.02  # it moves by centimetres
    # statics: the free shape is the arc; the 6-cell chain lies on the inscribed polygon
    assert s["static_error_chain_polygon"] < 1e-9
    assert s["static_error_arc"] < 1e-3
    assert s["static_tip_angle_error"] < 1e-12


# ----------------------------------------------------------------------------- standalone
def test_mechanism_case_runs_standalone_with_files(tmp_path):
    proc = run([str(CASES / "parallel_guide.py"), "--out", "out", "--set", "n_steps=8"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    out = tmp_path / "out"
    names = {p.name for p in out.iterdir()}
    assert {"parallel_guide.csv", "parallel_guide.json", "parallel_guide_sweep.csv",
            "parallel_guide_translation.png", "parallel_guide_mechanism.png", "parallel_guide_animation.gif"} <= names
    assert (out / "parallel_guide_animation.gif").read_bytes()[:6] == b"GIF89a"
    record = json.loads((out / "parallel_guide.json").read_text())
    assert record["scalars"]["translation_error"]["value"] < 1e-4
    assert not list(out.glob(".tmp_*"))


def test_parallel_guide_large_deflection_value_is_what_the_model_gives():
    # a 0.4 m stage: kappa L = 0.55 rad at 500 V, kappa L²/4 is off by 6e-3; the model follows
    # the exact S-blade to the chain polygon factor and the polygon itself to round-off
    out = load_case(CASES / "parallel_guide.py").run({"length": 0.4, "n_cells": 16, "spacing": 0.05})
    s = out.scalars
    assert s["translation_error_small_deflection"] > 5e-3
    assert s["translation_error"] < 1e-4
    assert s["translation_error_chain_polygon"] < 1e-9
    assert s["rotation_max"] < 1e-12


def test_gripper_with_inward_jaws_needs_the_large_deflection_reference():
    # jaw point 2 mm towards the axis: the moment arm a cos(theta) - c sin(theta) changes to
    # first order in the tip rotation, which the small-deflection closed form ignores
    out = load_case(CASES / "micro_gripper.py").run({"jaw_offset": 2e-3, "half_spacing": 7e-3, "n_steps": 8})
    s = out.scalars
    assert s["mirror_error"] < 1e-12
    assert s["force_error_closed_form_object"] > 1e-3
    assert s["force_error_large_deflection_object"] < 1e-3
    assert s["force_error_large_deflection_stiff"] < 1e-3


def test_gripper_with_rod_benders_meets_the_arc_and_the_large_deflection_force():
    # the rod bends exactly into the arc under actuation for any number of modes, and its modes
    # converge exponentially under the jaw force: 4 modes against the shooting solution of the
    # large-deflection rod (the default, 24 rigid cells, misses it by 4e-4 to 6e-4: its cell polygon)
    out = load_case(CASES / "micro_gripper.py").run({"cell": "rod", "n_cells": 4, "n_steps": 8}, plot=False)
    s = out.scalars
    assert s["mirror_error"] < 1e-12
    assert s["free_jaw_error"] < 1e-10
    assert s["force_error_large_deflection_object"] < 1e-6
    assert s["force_error_large_deflection_stiff"] < 1e-6
    assert s["force_column_difference_object"] < 1e-10


@pytest.mark.parametrize(
    ("case", "values", "message"),
    [
        ("compliant_four_bar", {"n_steps": 7}, "n_steps must be an even integer >= 4, got 7"),
        ("compliant_four_bar", {"rocker_pivot_height": 0.07}, r"rocker_pivot_height must be in .* = \[0, 0.056\) m .*got 0.07"),
        ("micro_gripper", {"n_steps": 2}, "n_steps must be an even integer >= 4, got 2"),
        ("parallel_guide", {"n_steps": 10}, "n_steps must be a multiple of 4, >= 4, got 10"),
        ("bender_with_lever", {"cycles": 0}, "cycles must be >= 1, got 0"),
    ],
)
def test_bad_case_parameters_are_refused_with_the_value(case, values, message):
    with pytest.raises(ValueError, match=message):
        load_case(CASES / f"{case}.py").run(values)
