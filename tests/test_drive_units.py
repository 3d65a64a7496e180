"""A drive takes the free strain only: displacement-valued models are refused with how to convert them (issue 28, part 3).

The issue's reproducer: a model identified on a displacement record in metres (a free patch's
elongation over 60 mm) was accepted as a strain and gave a tip deflection 1/0.06 = 17 times too
small.  The truth here is a Prandtl-Ishlinskii operator with known weights; its PI fit on the
displacement record is exact up to the fit's play grid.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.errors import SetupWarning
from exudyn_atcm.hysteresis import PrandtlIshlinskii
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.model.strain_conversion import model_to_strain

from _actuator_geometries import REF_A

GAUGE = 0.06  # [m]: the patch's elongation is measured over 60 mm


def truth() -> PrandtlIshlinskii:
    """A strain operator: 1.4e-3 at 1500 V from rest at 0 V, loops of a few per cent."""
    return PrandtlIshlinskii([0.0, 150.0, 375.0, 600.0], [1.5e-7, 2e-7, 1e-7, 5e-8], 4.6e-7).with_output_quantity("strain")


def displacement_model():
    t = np.linspace(0.0, 3.0, 3001)
    u = 750.0 * (1.0 - np.cos(2 * math.pi * t))  # 0 ... 1500 V from rest
    y = GAUGE * truth().apply(u)  # the elongation [m]
    model, _ = PrandtlIshlinskii.fit(u, y, 21)
    model.output_quantity, model.output_unit = "displacement", "m"  # what the fits state (issue 28, part 3)
    return model


def tip(hysteresis, voltage=1200.0):
    act = REF_A.actuator(PiezoDrive(0.0, hysteresis=hysteresis), cell="ritz")
    return float(atcm.solve_static(act, voltage=voltage)["actuator.tip_y"][0])


def test_a_displacement_model_is_refused_and_its_conversion_drives_like_the_truth():
    model = displacement_model()
    with pytest.raises(ValueError) as info:
        PiezoDrive(0.0, hysteresis=model)
    message = str(info.value)
    assert "output is 'displacement' [m]" in message
    assert "model_to_strain(model, gauge_length=l0)" in message and "record_to_strain(record, ...)" in message
    # taken as strain (what main did), the tip is GAUGE times the truth's: 17 times too small
    model.output_quantity, model.output_unit = None, ""
    with pytest.warns(SetupWarning, match="output unit is unknown"):  # a fitted model of unstated unit
        taken_as_strain = tip(model)
    expected = tip(truth())
    # (1/16.6; not exactly GAUGE: the arc tip is not linear in the strain, 0.6 % at this 12 mm)
    assert taken_as_strain / expected == pytest.approx(GAUGE, rel=0.01)
    # converted, it drives like the truth, to the fit's accuracy (PI fit on 21 plays; measured 7e-5)
    model.output_quantity, model.output_unit = "displacement", "m"
    assert tip(model_to_strain(model, gauge_length=GAUGE)) == pytest.approx(expected, rel=2e-3)


def test_a_model_in_a_length_unit_is_refused_even_without_a_stated_quantity():
    model = PrandtlIshlinskii([0.0], [1e-9], 1e-8)
    model.output_unit = "um"
    with pytest.raises(ValueError, match=r"output unit is 'um', a length: it was identified on a displacement; "
                                         r"convert it with exudyn_atcm.model.strain_conversion.model_to_strain"):
        PiezoDrive(0.0, hysteresis=model)


def test_a_fitted_model_of_unknown_output_unit_is_taken_as_strain_with_a_warning():
    model = PrandtlIshlinskii([0.0], [1e-7], 5e-7)
    model.fit_info = {"family": "prandtl_ishlinskii"}  # fitted (the fits set it) on a record of unknown unit
    with pytest.warns(SetupWarning, match=r"fitted on a record whose output unit is unknown; the drive takes its "
                                          r"output as the free strain"):
        PiezoDrive(0.0, hysteresis=model)


def test_strain_models_and_models_built_by_hand_are_taken_silently():
    # pytest turns every AtcmWarning into an error: a warning here fails the test
    PiezoDrive(0.0, hysteresis=paper_strain_preisach())
    PiezoDrive(0.0, hysteresis=PrandtlIshlinskii([0.0], [1e-7], 5e-7))  # unstated: the user's word
    model = PrandtlIshlinskii([0.0], [1e-7], 5e-7)
    model.output_unit, model.fit_info = "-", {"family": "prandtl_ishlinskii"}
    PiezoDrive(0.0, hysteresis=model)
