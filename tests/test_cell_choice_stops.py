"""A mechanism with a stop: the accuracy run checks its cells at the impacts (the next count at the same step).

The cell choice compares counts on static poses and the lowest mode; an impact rings higher modes it does not see
(the audit of 2026-11-30: a lever driven against a stop, 1e-3 asked, 2.2e-3 off, the cells' share 1.9e-3 where
the choice estimated 1.1e-4, silently).  Reference: the run of the next count at the run's step, made and
compared here by hand (the largest difference of the position columns over the travel).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.model import Triangle

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
L = 0.03


def lever(stop: bool, n_cells="auto") -> atcm.Mechanism:
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=L, n_cells=n_cells, cell="rod",
                    drive=atcm.PiezoDrive(Triangle(750.0, 750.0, 0.05)))
    rod = atcm.Link("rod", {"R0": (L, 0.0), "R1": (L, 0.01)}, mass=1e-5, inertia=1e-10)
    arm = atcm.Link("lever", {"R": (L, 0.01), "G": (0.05, 0.01), "E": (0.07, 0.01)}, mass=1e-4, inertia=1e-8)
    m = atcm.Mechanism("lever").add(b, rod, arm).ground(b.base).pin(b.tip, "rod.R0").pin("rod.R1", "lever.R")
    m.ground("lever.G", joint="pin", stiffness=0.01)
    if stop:
        m.stop("lever.E", position=(0.07, 0.01 - 0.5e-3), normal=(0.0, 1.0), stiffness=1e5, name="wall")
    return m


def by_hand(a: atcm.Result, b: atcm.Result) -> float:
    names = [n for n in a.names if a.unit(n) == "m"]
    travel = max(float(np.ptp(a[n])) for n in names)  # the finer run's travel, as the check takes it
    return max(float(np.max(np.abs(a[n] - b[n]))) for n in names) / travel


def test_the_impacts_are_checked_with_the_next_count_and_a_miss_is_warned():
    with pytest.warns(atcm.AccuracyWarning, match=r"miss it at the impacts against the stop 'wall': the run with the next "
                                                  r"count \('b' (\d+)\) at the same step differs by"):
        r = atcm.simulate(lever(stop=True), 0.05, accuracy=1e-2)
    n = int(r.info["accuracy"]["cells"]["b"].split()[0])
    step = r.info["step [s]"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        finer = atcm.simulate(lever(stop=True, n_cells=n + 1), 0.05, step=step)
    measured = by_hand(finer, r)
    assert r.info["accuracy"]["cells_error_at_impacts"] == pytest.approx(measured, rel=1e-9)
    assert measured > 0.3 * 1e-2  # beyond the cells' share: the warning was due
    assert measured > 3 * r.info["accuracy"]["cells_estimated_error"]  # what the static choice could not see
    assert f"checked at the impacts against the stop 'wall': the next count ('b' {n + 1})" in r.info["cell_choice"]


def test_without_a_stop_nothing_more_is_run():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = atcm.simulate(lever(stop=False), 0.05, accuracy=1e-2)
    assert "cells_error_at_impacts" not in r.info["accuracy"] and "stop" not in r.info["cell_choice"]
