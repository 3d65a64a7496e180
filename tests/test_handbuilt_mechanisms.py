"""The hand-built Exudyn models of the mechanism benchmark are the package's mechanisms.

``benchmarks/handbuilt.py`` builds the compliant four-bar and the micro-gripper item by item
in Exudyn (GE beam elements, the tip part on the beam's tip node, PRBM hinges as revolute
joints with rotary springs, the hysteresis in PreStep/PostStep); the package builds them from
the case files with ``cell="beam"`` (welds as constraints, its own hooks).  Both are the same
equations, so the tracked point's paths must agree to the Newton tolerance: an independent
check that the benchmark's baseline is the same mechanism (measured 2.7e-10 and 2.3e-7 of the
travel at 8 elements over 0.05 s; the bound 1e-5 leaves room for other Exudyn builds).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"
sys.path.insert(0, str(BENCHMARKS))

import bench_systems as bm  # noqa: E402
import handbuilt  # noqa: E402

from exudyn_atcm import simulate  # noqa: E402
from exudyn_atcm.model.signals import Triangle  # noqa: E402


def test_triangle_is_the_package_triangle():
    program = Triangle(500.0, 1000.0, handbuilt.PERIOD)
    times = np.linspace(0.0, 1.3, 2601)
    assert max(abs(handbuilt.triangle(t) - float(program(t))) for t in times) < 1e-9


@pytest.mark.parametrize("name", ["four_bar", "gripper"])
def test_handbuilt_path_matches_package_beam_cells(name):
    t_end, n = 0.05, 4
    _, times, path = handbuilt.run(name, n, t_end)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        result = simulate(bm.MECHANISMS[name](n, "beam"), t_end, step=handbuilt.STEP)
    reference = bm.path(result, bm.TRACKED[name])
    assert len(times) == len(reference)
    np.testing.assert_allclose(times, result["time"], atol=1e-12)
    travel = float(np.max(np.linalg.norm(reference - reference[0], axis=1)))
    assert travel > 1e-5  # the point moves (tens of micrometres in 0.05 s)
    assert float(np.max(np.linalg.norm(path - reference, axis=1))) / travel < 1e-5


def test_record_modes_agree():
    _, t_sensor, p_sensor = handbuilt.run("four_bar", 2, 0.01, record="sensor")
    _, t_array, p_array = handbuilt.run("four_bar", 2, 0.01, record="array")
    np.testing.assert_allclose(t_sensor, t_array, atol=1e-12)
    np.testing.assert_allclose(p_sensor, p_array, rtol=0, atol=1e-12)


def test_unknown_record_mode_is_refused():
    with pytest.raises(ValueError, match="record must be"):
        handbuilt.HandBuilt(handbuilt.four_bar_numbers(), 2, record="csv")
