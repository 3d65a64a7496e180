"""A recording interval coarser than the voltage program warns (issue 17, part 1, second bullet).

The solution does not depend on ``record_every``, but the record and every scalar computed from
it do.  Reference: a triangle of period T has ramps of T/2; with ``record_every = r`` the record
holds (T/2)/r instants per ramp, and a ramp's peak can fall up to r/2 between two of them.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.casework import load_case
from exudyn_atcm.model import Triangle
from exudyn_atcm.solve.run_checks import MIN_RECORDS_PER_FEATURE

from _cli_helpers import CASES

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
PERIOD = 0.2  # s: ramps of 0.1 s


def actuator():
    return atcm.BendingActuator(4, 0.087 / 4, 28e-3, CFC, MFC, atcm.PiezoDrive(Triangle(500.0, 1000.0, PERIOD)),
                                cell="rigid")


@pytest.mark.parametrize("record_every, quoted", [(0.02, r"record_every = 0\.02 s keeps only 5 "),
                                                 (200, r"record_every = 200 steps \(0\.02 s\) keeps only 5 ")])
def test_a_coarse_recording_interval_warns_quoting_it(record_every, quoted):
    with pytest.warns(RuntimeWarning, match=quoted + r"recorded instants across the shortest feature") as record:
        r = atcm.simulate(actuator(), 0.2, step=1e-4, record_every=record_every)
    assert [w for w in record if "record_every" in str(w.message)][0].filename == __file__
    # the record then misses the peak: the largest recorded voltage is below the program's 1500 V
    assert r["actuator.voltage"].max() <= 1500.0


def test_an_interval_resolving_the_program_is_silent_and_keeps_the_peak():
    interval = 0.1 / MIN_RECORDS_PER_FEATURE  # exactly the limit: 10 instants per ramp
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = atcm.simulate(actuator(), 0.2, step=1e-4, record_every=interval)
    assert r["actuator.voltage"].max() == pytest.approx(1500.0, rel=1e-12)


def test_a_mechanism_run_names_the_drive():
    b = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4,
                    drive=atcm.PiezoDrive(Triangle(500.0, 1000.0, PERIOD)), cell="rigid")
    lever = atcm.Link("lever", {"A": (0.03, 0.0), "E": (0.05, 0.0)}, mass=2e-4, inertia=1e-8)
    mech = atcm.Mechanism("m").add(b, lever).ground(b.base).weld(b.tip, lever.point("A"))
    with pytest.warns(RuntimeWarning, match=r"record_every = 0\.05 s keeps only 2 .* the voltage program of drive 'crank'"):
        atcm.simulate(mech, 0.2, step=1e-4, record_every=0.05)


def test_the_issue_example_now_warns():
    """``--set record_every=10`` on the Fig. 12 case kept two instants and reported a wrong maximum, silently."""
    case = load_case(CASES / "paper_bending_actuator.py")
    with pytest.warns(RuntimeWarning, match=r"record_every = 10\.0 s keeps only 0\.05 recorded instants"):
        case.run({"cell": "rigid", "cycles": 1, "record_every": 10.0})


# ----------------------------------------------------------------------------- intervals that are not whole steps
def test_an_interval_that_is_not_a_whole_number_of_steps_warns_and_says_how_far_apart_the_records_are():
    """0.7 ms at steps of 0.5 ms: the first step at or after each multiple of 0.7 ms is recorded, so the rows are
    0.5 or 1 ms apart (counted here from the recorded times); the metadata said "every 0.0007 s"."""
    with pytest.warns(atcm.SetupWarning, match=r"record_every = 0\.0007 s is not a whole number of steps of 0\.0005 s"
                                               r".*e\.g\. 0\.0005 s"):
        r = atcm.simulate(actuator(), 0.05, step=5e-4, record_every=7e-4)
    gaps = np.unique(np.round(np.diff(r["time"]), 12))
    assert set(gaps) == {5e-4, 1e-3}
    assert r.info["recorded"] == ("the first step at or after every 0.0007 s (steps of 0.0005 s: records 0.0005 or "
                                  "0.001 s apart)")


def test_an_interval_of_whole_steps_is_even_and_silent():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = atcm.simulate(actuator(), 0.045, step=5e-4, record_every=1.5e-3)
    np.testing.assert_allclose(np.diff(r["time"]), 1.5e-3, rtol=1e-9)
    assert r.info["recorded"] == "every 0.0015 s"


def test_every_step_of_a_thinned_record_read_from_a_file_says_so(tmp_path):
    """Files do not hold every step: a result read back from a run recorded every 1 ms gave its 1 ms rows as
    ``every_step`` without a word (the audit of 2026-11-30: a peak 3.3654 mm for 3.3691 mm)."""
    r = atcm.simulate(actuator(), 0.05, step=1e-4, record_every=1e-3)
    assert r.every_step.n_rows == 501  # in memory: every step
    r.to_csv(tmp_path / "r.csv")
    back = atcm.read_csv(tmp_path / "r.csv")
    with pytest.warns(atcm.AccuracyWarning, match=r"every_step: this result holds only its recorded rows \(every "
                                                  r"0\.001 s; files do not hold every step\)"):
        rows = back.every_step
    assert rows.n_rows == 51
    full = atcm.simulate(actuator(), 0.01, step=1e-4)
    full.to_csv(tmp_path / "f.csv")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert atcm.read_csv(tmp_path / "f.csv").every_step.n_rows == 101  # every step was recorded: silent
