"""Issue 9 for the static mechanism solves: the sweep's base column and the per-drive range checks.

References: the MFC P1 rating (-500 ... +1500 V), the operator's input range, and the point
index of a sweep (a sweep has no time, so no column may claim seconds).
"""

from __future__ import annotations

import warnings

import pytest

from exudyn_atcm import Bender, Layer, Mechanism, PiezoDrive, eigenfrequencies, solve_static, static_sweep
from exudyn_atcm.model.parameter_sets import paper_strain_preisach

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)


def pair(drive_a, drive_b):
    a = Bender("a", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=3, drive=drive_a, cell="rigid")
    b = Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=3, drive=drive_b, base=(0.0, 0.05), cell="rigid")
    return Mechanism("pair").add(a, b).ground(a.base).ground(b.base)


def _messages(record):
    return [str(w.message) for w in record if issubclass(w.category, RuntimeWarning)]


def test_sweep_base_column_is_the_point_index_not_seconds():
    r = static_sweep(pair(PiezoDrive(0.0), PiezoDrive(0.0)), [0.0, 300.0, 600.0])
    assert r.names[0] == "point" and r.unit("point") == "-"
    assert r["point"].tolist() == [0.0, 1.0, 2.0]
    assert "time" not in r.names
    assert r["a.voltage"].tolist() == [0.0, 300.0, 600.0]


@pytest.mark.parametrize("solve", ["solve_static", "static_sweep", "eigenfrequencies"])
def test_static_solves_warn_per_drive_beyond_the_rating(solve):
    mech = pair(PiezoDrive(0.0), PiezoDrive(0.0))
    with pytest.warns(RuntimeWarning) as record:
        if solve == "solve_static":
            solve_static(mech, voltage={"a": 300.0, "b": 1800.0})
        elif solve == "static_sweep":
            static_sweep(mech, {"a": [0.0, 300.0], "b": [0.0, 1800.0]})
        else:
            eigenfrequencies(mech, n=1, voltage={"a": 300.0, "b": 1800.0})
    hits = [m for m in _messages(record) if "rated range" in m]
    assert len(hits) == 1 and hits[0].startswith("drive 'b': the voltage program spans")
    assert "reach 1800 V, 300 V above" in hits[0]


def test_static_solve_beyond_the_operator_range_warns_that_it_saturates():
    op = paper_strain_preisach()
    low, high = op.input_range
    mech = pair(PiezoDrive(0.0, hysteresis=op, rated_range=None), PiezoDrive(0.0))
    with pytest.warns(RuntimeWarning, match=rf"drive 'a'.*reach {high + 1000:g} V, 1000 V above the hysteresis operator's input range"):
        solve_static(mech, voltage={"a": high + 1000.0, "b": 0.0})


def test_implausible_strain_in_a_static_solve_names_the_drive():
    mech = pair(PiezoDrive(0.0, d33=5.5e-8), PiezoDrive(0.0))  # 0.011 at 100 V
    with pytest.warns(RuntimeWarning, match=r"the free strain of drive 'a' reaches a free strain of 0\.011"):
        # that strain curls the 3-cell bender: the coarse-chain check of every bender says so too
        with pytest.warns(RuntimeWarning, match=r"a cell of the rigid bender 'a' turns by .* coarse discretisation"):
            solve_static(mech, voltage={"a": 100.0, "b": 0.0})


def test_static_solves_within_the_ranges_are_quiet():
    mech = pair(PiezoDrive(0.0, hysteresis=paper_strain_preisach()), PiezoDrive(0.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        solve_static(mech, voltage={"a": 1500.0, "b": -500.0})
        static_sweep(mech, [0.0, 1500.0, -500.0])
