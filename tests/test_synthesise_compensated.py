"""Synthesis with compensation (issue 32, part 4): cases/synthesise_compensated.py.

References: a known design (the compliant_four_bar defaults) generates the precision points, computed
here by its own static sweep at the precision voltages; the synthesis must recover its dimensions;
the distances are measured here again from the simulated series at the visit times; the program's
voltages are read back from the recorded drive voltage.
"""

from __future__ import annotations

import importlib.util

import numpy as np
import pytest

from exudyn_atcm import static_sweep
from exudyn_atcm.casework import load_case

from _cli_helpers import CASES


@pytest.fixture(scope="module")
def output():
    return load_case(CASES / "synthesise_compensated.py").run()


def value(output, name):
    v = output.scalars[name]
    return float(v[0] if isinstance(v, tuple) else v)


def test_positions_met_on_both_branches_within_10_um(output):
    # the goal of issue 32, part 4: 10 um RMS on both branches (measured 0.9 um; synthesise_path's
    # voltage-timed design leaves 1.25 mm, and this design driven through the points' voltages 1.7 mm)
    assert value(output, "rms_both") <= 10e-6
    assert value(output, "rms_rising") <= 10e-6 and value(output, "rms_falling") <= 10e-6
    assert value(output, "uncompensated_rms_both") > 100.0 * value(output, "rms_both")


def test_the_known_design_is_recovered_and_the_points_are_its_own(output):
    p = load_case(CASES / "synthesise_compensated.py").resolve({})
    for name in ("rocker_pivot_height", "coupler_point_x", "coupler_point_y"):
        assert abs(value(output, f"{name}_error")) < 1e-6  # 1 um of the dimensions (measured 1e-10 m)
    # the precision points: the reference design's rising branch at the precision voltages, computed here
    spec = importlib.util.spec_from_file_location("compliant_four_bar_for_the_test", CASES / "compliant_four_bar.py")
    four_bar = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(four_bar)
    p4 = four_bar.CASE.resolve({"n_cells": p.n_cells})
    sweep = static_sweep(four_bar.build_mechanism(p4, four_bar.strain_laws("exact")["hysteresis"]),
                         sorted(p.precision_voltages))
    pts = output.tables["points"]
    n = len(p.precision_voltages)
    np.testing.assert_allclose(pts["target_x"][:n], sweep["coupler.P_x"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(pts["target_y"][:n], sweep["coupler.P_y"], rtol=0, atol=1e-12)


def test_distances_and_the_rating_margin_from_the_simulated_series(output):
    r, pts = output.result, output.tables["points"]
    x = np.interp(pts["time"], r["time"], r["coupler.P_x"])
    y = np.interp(pts["time"], r["time"], r["coupler.P_y"])
    distance = np.hypot(x - pts["target_x"], y - pts["target_y"])
    assert np.sqrt(np.mean(distance**2)) == pytest.approx(value(output, "rms_both"), rel=1e-9)
    low, high = float(r["voltage"].min()), float(r["voltage"].max())
    assert value(output, "rating_margin") == pytest.approx(min(low + 500.0, 1500.0 - high), abs=1e-6)
    assert value(output, "rating_margin") > 0.0
