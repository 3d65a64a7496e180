"""A mechanism with a stop: the cell choice says that it does not check impacts (an AccuracyWarning).

The choice compares counts on static poses and the lowest mode; an impact rings higher modes it does not see
(the audit of 2026-11-30: a lever driven against a stop, 1e-3 asked, 2.2e-3 off, the cells' share 1.9e-3
where the choice estimated 1.1e-4).  Without stops the same mechanism's choice is silent.
"""

from __future__ import annotations

import warnings

import pytest

import exudyn_atcm as atcm
from exudyn_atcm.model import Triangle

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
L = 0.03


def lever(stop: bool) -> atcm.Mechanism:
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=L, n_cells="auto", cell="rod",
                    drive=atcm.PiezoDrive(Triangle(750.0, 750.0, 0.05)))
    rod = atcm.Link("rod", {"R0": (L, 0.0), "R1": (L, 0.01)}, mass=1e-5, inertia=1e-10)
    arm = atcm.Link("lever", {"R": (L, 0.01), "G": (0.05, 0.01), "E": (0.07, 0.01)}, mass=1e-4, inertia=1e-8)
    m = atcm.Mechanism("lever").add(b, rod, arm).ground(b.base).pin(b.tip, "rod.R0").pin("rod.R1", "lever.R")
    m.ground("lever.G", joint="pin", stiffness=0.01)
    if stop:
        m.stop("lever.E", position=(0.07, 0.01 - 0.5e-3), normal=(0.0, 1.0), stiffness=1e5, name="wall")
    return m


def test_a_stop_is_named_as_not_checked():
    with pytest.warns(atcm.AccuracyWarning, match=r"impacts against the stop 'wall' ring higher modes that this check "
                                                  r"does not see"):
        choice = atcm.choose_cells(lever(stop=True), 0.05, 1e-3)
    assert choice.line.endswith("not checked: the impacts against the stop 'wall'")


def test_without_a_stop_the_choice_is_silent():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        choice = atcm.choose_cells(lever(stop=False), 0.05, 1e-3)
    assert "stop" not in choice.line
