"""Runs on one build share their start equilibrium (solved once, kept on the model).

An accuracy run's prediction, probe, run and refinement, and every solve of a BuiltSystem, started with the
same static solve and stability probe from the reference pose.  Reference: the same runs on fresh builds
(the results must be equal to the last bit), and a load whose value at t = 0 changes between runs (then the
start is solved again, and equals a fresh build's).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.model import Triangle
from exudyn_atcm.solve import mechanism_static

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
PUSH = {"N": 0.02}  # the tip load [N], read at every call of the load function


def cantilever() -> atcm.Mechanism:
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=3, cell="rod",
                    drive=atcm.PiezoDrive(Triangle(500.0, 1000.0, 0.02)))  # starts at -500 V: a bent start
    return atcm.Mechanism("m").add(b).ground(b.base).force(b.tip, lambda t: (0.0, -PUSH["N"]))


@pytest.fixture
def counted(monkeypatch):
    calls = []
    original = mechanism_static.equilibrium

    def counting(mech, model, start, end, from_reference, *args, **kwargs):
        calls.append(from_reference)
        return original(mech, model, start, end, from_reference, *args, **kwargs)

    monkeypatch.setattr(mechanism_static, "equilibrium", counting)
    return calls


def test_a_built_system_solves_its_start_once_and_repeats_the_fresh_result(counted):
    built = atcm.BuiltSystem(cantilever())
    first = built.simulate(0.01, step=2.5e-4)
    again = built.simulate(0.01, step=2.5e-4)
    assert counted == [True]  # the second run took the kept start
    fresh = atcm.simulate(cantilever(), 0.01, step=2.5e-4)
    for name in ("b.tip_x", "b.tip_y", "b.tip_angle"):
        np.testing.assert_array_equal(again[name], first[name])
        np.testing.assert_array_equal(again[name], fresh[name])


def test_an_accuracy_run_solves_its_start_once(counted):
    r = atcm.simulate(cantilever(), 0.02, accuracy=1e-3)
    assert sum(counted) == 1, counted  # prediction, probe and run: one static solve of the start
    assert r.info["accuracy"]["estimated_error"] <= 1e-3


def test_a_load_that_changed_is_solved_again(counted):
    built = atcm.BuiltSystem(cantilever())
    before = built.simulate(0.005, step=2.5e-4)
    PUSH["N"] = 0.05
    try:
        after = built.simulate(0.005, step=2.5e-4)
        fresh = atcm.simulate(cantilever(), 0.005, step=2.5e-4)
    finally:
        PUSH["N"] = 0.02
    assert counted == [True, True, True]
    assert after["b.tip_y"][0] < before["b.tip_y"][0] - 1e-6  # pushed further down at t = 0
    np.testing.assert_array_equal(after["b.tip_y"], fresh["b.tip_y"])
    assert math.isfinite(after["b.tip_y"][-1])
