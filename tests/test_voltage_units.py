"""Issue 9, part 1, leftovers: a voltage program written in kV, a period written in ms.

References: the MFC P1 rating -500 ... +1500 V (a program in kV peaks at 1/1000 of that, at
most 1.5 V); the linear piezo law (Eq. 3: strain proportional to the voltage) for the size of
the response; the triangle of Eq. 11 (peak ``u_med + u_amp`` at half the period).  The small
programs that must stay silent are the package's own small-deflection program (a 1 % triangle,
-5 ... 15 V, benchmarks/bench_discretisation.py) and a program that is zero throughout.
"""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

from exudyn_atcm import Bender, BendingActuator, Layer, Mechanism, PiezoDrive, simulate, solve_static, static_sweep
from exudyn_atcm.errors import InputRangeWarning
from exudyn_atcm.model.drive import KV_SUSPECT_FRACTION, MFC_P1_RATED_RANGE
from exudyn_atcm.solve.run_checks import SLOW_PROGRAM_FACTOR
from exudyn_atcm.model.signals import Constant, PiecewiseLinear, Sine, Triangle

from _cli_helpers import cli

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W = 28e-3
KV = "multiply it by 1000"


def actuator(program, **kw) -> BendingActuator:
    return BendingActuator(3, 29e-3, W, CFC, MFC, PiezoDrive(program, **kw), cell="rigid")


def _messages(record, text):
    return [str(w.message) for w in record if issubclass(w.category, RuntimeWarning) and text in str(w.message)]


def _run_quietly(fn, *args, **kw):
    """Run ``fn`` and return the messages of every RuntimeWarning it gave."""
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        out = fn(*args, **kw)
    return out, [str(w.message) for w in record if issubclass(w.category, RuntimeWarning)]


# ----------------------------------------------------------------------------- kV

def test_threshold_lies_between_a_kv_program_and_the_smallest_deliberate_program():
    rated = max(abs(v) for v in MFC_P1_RATED_RANGE)
    limit = KV_SUSPECT_FRACTION * rated
    assert limit == pytest.approx(3.0)
    assert rated / 1000.0 < limit < 15.0  # a kV program at the rating (1.5 V) < 3 V < the 1 % triangle's 15 V


def test_triangle_in_kv_warns_once_with_the_peak_the_range_and_the_fix():
    # Triangle(0.5, 1.0, T) meant as -0.5 ... 1.5 kV: it peaks at 1.5 V at t = T/2
    act = actuator(Triangle(0.5, 1.0, 0.1))
    with pytest.warns(RuntimeWarning) as record:
        r = simulate(act, 0.1, step=1e-3)
    hits = _messages(record, KV)
    assert len(hits) == 1
    assert "peaks at |U| = 1.5 V" in hits[0] and "-500 ... 1500 V" in hits[0] and "below 3 V" in hits[0]
    assert r["actuator.voltage"].max() == pytest.approx(1.5)
    # and the answer is indeed ~1000x too small: Eq. 3 gives the strain of 1.5 V, not 1.5 kV
    assert r["actuator.strain"].max() == pytest.approx(460e-12 * 1.5 / 0.5e-3, rel=1e-12)


def test_constant_in_kv_warns_for_a_static_solve():
    with pytest.warns(RuntimeWarning, match=r"peaks at \|U\| = 1\.5 V.*multiply it by 1000"):
        solve_static(actuator(1.5))


@pytest.mark.parametrize("program", [Triangle(5.0, 10.0, 0.1), Constant(0.0), 0.0, Triangle(500.0, 1000.0, 0.1)],
                         ids=["one-percent-triangle", "Constant(0)", "zero", "paper-triangle"])
def test_small_zero_and_full_programs_stay_silent(program):
    _, messages = _run_quietly(simulate, actuator(program), 0.1, step=1e-3)
    assert not [m for m in messages if KV in m], messages


def test_no_rating_no_kv_check():
    _, messages = _run_quietly(solve_static, actuator(1.5, rated_range=None))
    assert not [m for m in messages if KV in m]


def test_mechanism_names_the_drive_in_kv_and_spares_the_others():
    a = Bender("a", width=W, passive=CFC, active=MFC, length=0.087, n_cells=3, drive=PiezoDrive(Triangle(0.5, 1.0, 0.1)), cell="rigid")
    b = Bender("b", width=W, passive=CFC, active=MFC, length=0.087, n_cells=3, drive=PiezoDrive(Triangle(5.0, 10.0, 0.1)),
               base=(0.0, 0.05), cell="rigid")
    c = Bender("c", width=W, passive=CFC, active=MFC, length=0.087, n_cells=3, drive=PiezoDrive(0.0), base=(0.0, 0.1), cell="rigid")
    mech = Mechanism("three").add(a, b, c).ground(a.base).ground(b.base).ground(c.base)
    _, messages = _run_quietly(simulate, mech, 0.1, step=1e-3)
    hits = [m for m in messages if KV in m]
    assert len(hits) == 1 and hits[0].startswith("drive 'a':") and "peaks at |U| = 1.5 V" in hits[0]
    _, messages = _run_quietly(static_sweep, mech, {"a": [0.0, 1.2, 0.0]})
    hits = [m for m in messages if KV in m]
    assert len(hits) == 1 and "drive 'a'" in hits[0] and "|U| = 1.2 V" in hits[0]


def test_cli_set_of_a_case_voltage_in_kv_warns(tmp_path):
    proc = cli(["run", "parallel_guide", "--set", "voltage=0.5", "--set", "animation=false", "--no-plot",
                "--out", "o"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    # the case drives four segments with +-0.5 V from one value typed: one warning quoting it (issue 17:
    # once per run, as typed; it was one warning per drive)
    hits = [line for line in proc.stderr.splitlines() if KV in line]
    assert len(hits) == 1 and hits[0].startswith("warning: voltage=0.5 V (the segments at +U and -U):")
    assert "peaks at |U| = 0.5 V" in hits[0]
    proc = cli(["run", "parallel_guide", "--set", "animation=false", "--no-plot", "--out", "o"], tmp_path)
    assert proc.returncode == 0 and KV not in proc.stderr


# ----------------------------------------------------------------------------- ms

@pytest.mark.parametrize("program, feature, swing, also", [
    # a 500 ms period written as 500 (s): the triangle rises from -500 V at 4 * 1000 V / 500 s
    (Triangle(500.0, 1000.0, 500.0), 250.0, 4 * 1000.0 * 0.2 / 500.0, None),
    (Sine(500.0, 1000.0, 500.0), 250.0, 1000.0 * np.sin(2 * np.pi * 0.2 / 500.0), None),
    # a 300 ms ramp to 1500 V written as 300 (s): in 0.2 s it reaches 1 V, which the kV check reports too
    (PiecewiseLinear([0.0, 300.0], [0.0, 1500.0]), 300.0, 1500.0 * 0.2 / 300.0, r"peaks at \|U\| = 1 V, below 3 V"),
])
def test_period_or_ramp_in_ms_warns(program, feature, swing, also):
    t_end = 0.2
    assert feature > SLOW_PROGRAM_FACTOR * t_end
    with pytest.warns(InputRangeWarning) as record:  # all of them: the test checks each below
        r = simulate(actuator(program), t_end, step=1e-3)
    msg = _messages(record, "hardly changes during the run")[0]
    assert f"lasts {feature:g} s" in msg and "divide them by 1000" in msg
    others = [str(w.message) for w in record if "hardly changes" not in str(w.message)]
    assert len(others) == (0 if also is None else 1), others
    assert also is None or re.search(also, others[0])
    # what the run sees of the program: a few volts of its 2000 V swing
    assert np.ptp(r["actuator.voltage"]) == pytest.approx(swing, rel=1e-9)


def test_a_run_over_part_of_a_period_stays_silent():
    # a quarter period (1 ms step, 0.05 s run, period 0.2 s): a deliberate rising ramp
    _, messages = _run_quietly(simulate, actuator(Triangle(500.0, 1000.0, 0.2)), 0.05, step=1e-3)
    assert not [m for m in messages if "hardly changes" in m]


def test_mechanism_period_in_ms_names_the_drive():
    a = Bender("a", width=W, passive=CFC, active=MFC, length=0.087, n_cells=3,
               drive=PiezoDrive(Triangle(500.0, 1000.0, 500.0)), cell="rigid")
    mech = Mechanism("one").add(a).ground(a.base)
    with pytest.warns(RuntimeWarning, match=r"the voltage program of drive 'a' hardly changes during the run"):
        simulate(mech, 0.2, step=1e-3)
