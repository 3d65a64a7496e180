"""A part's laminate and Rayleigh damping are kept between uses, and made anew when an input changes.

Reference: the same quantities of a part made fresh with the changed inputs (the cache must never
hand out a value of the part's former inputs).
"""

from __future__ import annotations

import pytest

import exudyn_atcm as atcm
from exudyn_atcm import Flexure, Layer

CFC, MFC = Layer(0.2e-3, 70e9, 1550.0), Layer(0.3e-3, 30.336e9, 5440.0)


def flexure(**changes) -> Flexure:
    values = dict(base=(0.0, 0.0), tip=(0.03, 0.0), width=5e-3, layer=Layer(0.2e-3, 70e9, 1550.0), damping=0.02)
    values.update(changes)
    return Flexure("f", **values)


def test_a_flexure_keeps_its_laminate_and_remakes_it_when_an_input_changes():
    f = flexure()
    assert f.laminate is f.laminate and f.rayleigh_damping is f.rayleigh_damping
    ei, beta = f.bending_stiffness, f.rayleigh_damping.beta
    f.thickness = 0.4e-3
    fresh = flexure(layer=Layer(0.4e-3, 70e9, 1550.0))
    assert f.bending_stiffness == pytest.approx(fresh.bending_stiffness, rel=1e-15)
    assert f.bending_stiffness == pytest.approx(8.0 * ei, rel=1e-12)  # t^3
    assert f.rayleigh_damping.beta == pytest.approx(fresh.rayleigh_damping.beta, rel=1e-15)
    assert f.rayleigh_damping.beta != pytest.approx(beta, rel=1e-3)
    f.damping = 0.05
    assert f.rayleigh_damping.beta == pytest.approx(flexure(layer=Layer(0.4e-3, 70e9, 1550.0), damping=0.05)
                                                    .rayleigh_damping.beta, rel=1e-15)


def test_a_bender_remakes_its_laminate_when_a_layer_or_the_width_changes():
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=2, drive=atcm.PiezoDrive(0.0))
    first = b.laminate
    assert b.laminate is first
    b.passive = Layer(0.4e-3, 70e9, 1550.0)
    fresh = atcm.Bender("b", width=10e-3, passive=Layer(0.4e-3, 70e9, 1550.0), active=MFC, length=0.03, n_cells=2,
                        drive=atcm.PiezoDrive(0.0))
    assert b.laminate.bending_stiffness == pytest.approx(fresh.laminate.bending_stiffness, rel=1e-15)
    b.width = 20e-3
    assert b.laminate.bending_stiffness == pytest.approx(2.0 * fresh.laminate.bending_stiffness, rel=1e-12)
