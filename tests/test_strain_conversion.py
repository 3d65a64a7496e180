"""Displacement to free strain: arrays, records and fitted models, against beam theory (issue 28, part 3).

The references: Timoshenko's bimetal curvature and the circular arc, written out in
:mod:`exudyn_atcm.theory.beam` (which shares no code with the laminate), the REF-A numbers of
``docs/theory.rst`` (L = 87 mm, b = 28 mm, CFC 0.2 mm / 70 GPa, MFC 0.3 mm / 30.336 GPa,
Λ = 1.38e-3: EI = 1.28699e-2 N m², κ = 4.13984 1/m, tip 15.667 mm linear, arc tip
(85.131, 15.499) mm), the package's geometrically exact static solution, and operators
with known parameters run side by side with their scaled copies.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.errors import AccuracyWarning
from exudyn_atcm.hysteresis import DiscretePreisach, EverettPreisach, PrandtlIshlinskii
from exudyn_atcm.hysteresis.creep import Creep, CreepHysteresis
from exudyn_atcm.hysteresis.dynamics import RateLag, WithDynamics
from exudyn_atcm.hysteresis.output_scale import scaled_output
from exudyn_atcm.io.record import Record
from exudyn_atcm.model.laminate import Laminate
from exudyn_atcm.model.parameter_sets import paper_strain_preisach, paper_stroke_preisach
from exudyn_atcm.model.strain_conversion import (ARC_TURN_LIMIT, model_to_strain, record_to_strain,
                                                 strain_from_displacement, strain_from_tip_deflection)
from exudyn_atcm.theory import beam as bt

from _actuator_geometries import REF_A

L, B = 87e-3, 28e-3
H1, E1, H2, E2 = 0.2e-3, 70e9, 0.3e-3, 30.336e9
LAMBDA = 1.38e-3
CFC = atcm.Layer(H1, E1, 1550.0)
MFC = atcm.Layer(H2, E2, 5440.0)
LAMINATE = Laminate(B, CFC, MFC)


def arc_deflection(strain, s=L):
    """Independent forward model: Timoshenko's curvature (theory.beam), the arc's y = (1 - cos ks)/k at arc length s.

    Written 2 sin²(ks/2)/k: the same arc without the cancellation of 1 - cos at small ks.
    """
    kappa = np.array([bt.free_curvature(E1, H1, E2, H2, B, e) for e in np.ravel(strain)])
    safe = np.where(kappa == 0.0, 1.0, kappa)
    return np.where(kappa == 0.0, 0.0, 2.0 * np.sin(0.5 * safe * s) ** 2 / safe)


def test_ref_a_numbers_from_beam_theory():
    assert bt.composite_bending_stiffness(E1, H1, E2, H2, B) == pytest.approx(1.28699e-2, rel=1e-5)
    assert LAMINATE.bending_stiffness == pytest.approx(1.28699e-2, rel=1e-5)
    kappa = bt.free_curvature(E1, H1, E2, H2, B, LAMBDA)
    assert kappa == pytest.approx(4.13984, rel=1e-5)
    assert LAMINATE.curvature_per_strain * LAMBDA == pytest.approx(kappa, rel=1e-14)
    assert bt.linear_tip_deflection(kappa, L) == pytest.approx(15.667e-3, abs=0.5e-6)
    x, y = bt.arc_point(kappa, L)
    assert (float(x), float(y)) == pytest.approx((85.131e-3, 15.499e-3), abs=0.5e-6)


def test_the_arc_deflection_converts_back_to_the_strain():
    # the REF-A tip, rounded to 1 um: the strain back within that rounding (0.5 um / 15.5 mm)
    assert strain_from_tip_deflection(15.499e-3, LAMINATE, L) == pytest.approx(LAMBDA, rel=4e-5)
    assert strain_from_tip_deflection(15.667e-3, LAMINATE, L, linear=True) == pytest.approx(LAMBDA, rel=4e-5)
    # exact round trip over strains from -1e-4 to a turn of 2.3 rad, also at a point before the tip
    strains = np.concatenate([-np.geomspace(1e-9, 1e-3, 7), [0.0], np.geomspace(1e-9, 2.3 / (4.13984 / LAMBDA * L), 12)])
    for s in (L, 0.6 * L):
        back = strain_from_tip_deflection(arc_deflection(strains, s), LAMINATE, s)
        np.testing.assert_allclose(back, strains, rtol=1e-12, atol=1e-22)
        kappa = LAMINATE.curvature_per_strain * strains
        line = strain_from_tip_deflection(0.5 * kappa * s**2, LAMINATE, s, linear=True)
        np.testing.assert_allclose(line, strains, rtol=1e-14, atol=1e-22)


def test_the_line_is_off_the_arc_by_kappa_squared_s_squared_over_12():
    deflection = arc_deflection(LAMBDA)
    line = strain_from_tip_deflection(deflection, LAMINATE, L, linear=True)
    theta = LAMINATE.curvature_per_strain * LAMBDA * L
    # (1 - cos t)/t = t/2 (1 - t^2/12 + t^4/360 ...): the line's strain is that much low
    assert line / LAMBDA == pytest.approx(1 - theta**2 / 12 + theta**4 / 360, rel=1e-6)
    assert 1 - line / LAMBDA == pytest.approx(0.0108, abs=1e-4)  # 1.1 % at the paper's tip


@pytest.mark.parametrize("voltage", [-500.0, 250.0, 1500.0])
def test_a_simulated_bender_tip_converts_back_to_the_model_strain(voltage):
    # the ritz cell's static shape is the exact arc (docs: "its static arc is exact")
    act = REF_A.actuator(atcm.PiezoDrive(0.0, hysteresis=paper_strain_preisach()), cell="ritz")
    r = atcm.solve_static(act, voltage=voltage)
    truth = float(paper_strain_preisach().apply([voltage])[-1])  # the model's strain from rest
    assert r["actuator.strain"][0] == pytest.approx(truth, rel=1e-14)
    # the actuator as the geometry (its laminate and length); Newton's tolerance bounds the match
    assert strain_from_tip_deflection(float(r["actuator.tip_y"][0]), act) == pytest.approx(truth, rel=1e-9)


def test_deflection_arguments_are_checked():
    limit = L * (1 - math.cos(ARC_TURN_LIMIT)) / ARC_TURN_LIMIT
    assert limit / L == pytest.approx(0.7246, abs=1e-4)
    with pytest.raises(ValueError, match=r"deflection = 0.07 m is beyond the largest deflection of a uniformly curved "
                                         r"cantilever at length = 0.087 m: 0.0630412 m"):
        strain_from_tip_deflection(0.07, LAMINATE, L)
    with pytest.raises(ValueError, match="laminate has no active layer"):
        strain_from_tip_deflection(1e-3, Laminate(B, CFC, None), L)
    with pytest.raises(ValueError, match="length must be the arc length"):
        strain_from_tip_deflection(1e-3, LAMINATE)
    with pytest.raises(ValueError, match="laminate must be a Laminate or a bender with one"):
        strain_from_tip_deflection(1e-3, "cfc", L)
    with pytest.raises(ValueError, match="gauge_length must be > 0"):
        strain_from_displacement(1e-6, 0.0)
    assert strain_from_displacement(12e-6, 29e-3) == pytest.approx(12e-6 / 29e-3, rel=1e-15)
    np.testing.assert_allclose(strain_from_displacement([1e-6, -2e-6], 0.05), [2e-5, -4e-5], rtol=1e-15)


# ---------------------------------------------------------------------------------- records
def strain_record(unit_factor, unit, deflection):
    t = np.linspace(0.0, 1.0, 401)
    u = 1000.0 * (1.0 - np.cos(2 * math.pi * 2 * t)) / 2.0 - 500.0 * (t > 2.0)
    truth = paper_strain_preisach().apply(u)
    output = deflection(truth) / unit_factor
    return Record(t, u, output, units={"time": "s", "input": "V", "output": unit},
                  names={"time": "time", "input": "voltage", "output": "tip"}), truth


def test_a_bender_record_in_micrometres_becomes_the_strain():
    rec, truth = strain_record(1e-6, "um", arc_deflection)
    out = record_to_strain(rec, laminate=LAMINATE, length=L)
    np.testing.assert_allclose(out.output, truth, rtol=1e-11, atol=1e-20)
    assert out.units == {"time": "s", "input": "V", "output": "-"} and out.names["output"] == "free strain"
    assert out.processing[-1].startswith("output converted from um: free strain from a free bender's deflection at 0.087 m (arc")
    np.testing.assert_array_equal(out.input, rec.input)


def test_a_patch_record_in_millimetres_becomes_the_strain():
    rec, truth = strain_record(1e-3, "mm", lambda e: e * 0.06)
    out = record_to_strain(rec, gauge_length=0.06)
    np.testing.assert_allclose(out.output, truth, rtol=1e-13, atol=1e-20)
    assert "displacement / gauge length 0.06 m" in out.processing[-1]


@pytest.mark.parametrize("unit, stated", [("", "not stated (unknown)"), ("-", "'-'"), ("V", "'V'")])
def test_a_record_whose_output_is_not_a_length_is_refused(unit, stated):
    rec, _ = strain_record(1.0, unit, lambda e: e)
    with pytest.raises(ValueError, match=rf"record: the output unit is {re.escape(stated)}, not a length"):
        record_to_strain(rec, gauge_length=0.05)


def test_one_conversion_must_be_given():
    rec, _ = strain_record(1.0, "m", lambda e: e)
    with pytest.raises(ValueError, match="give either gauge_length .* or laminate and length"):
        record_to_strain(rec)
    with pytest.raises(ValueError, match="give either gauge_length"):
        record_to_strain(rec, gauge_length=0.05, laminate=LAMINATE, length=L)


# ----------------------------------------------------------------------------------- models
def displacement_models():
    """Operators with known parameters, outputs in metres (a few tens of micrometres)."""
    edges = np.linspace(-500.0, 1500.0, 5)
    centres = 0.5 * (edges[1:] + edges[:-1])
    a, b = np.meshgrid(centres, centres, indexing="ij")
    keep = a >= b
    w = (1.0 + 0.1 * np.arange(keep.sum())) * 1e-6
    pi = PrandtlIshlinskii([0.0, 100.0, 300.0, 600.0], [2e-9, 1e-8, 6e-9, 3e-9], 1e-8, offset=-1e-6, input_offset=5.0)
    return {
        "discrete": DiscretePreisach(a[keep], b[keep], w, offset=-4e-6),
        "everett": EverettPreisach(edges, a[keep], b[keep], w, offset=-4e-6),
        "pi": pi,
        "continuous": paper_stroke_preisach(),
        "with_dynamics": WithDynamics(pi, Creep([0.05, 0.5], [0.04, 0.03]), RateLag(0.01)),
        "creep": CreepHysteresis(pi, Creep([0.05, 0.5], [0.04, 0.03])),
    }


def history():
    t = np.linspace(0.0, 2.0, 801)
    u = 500.0 + 1000.0 * np.sin(2 * math.pi * t) * np.exp(-t) + 200.0 * np.sin(2 * math.pi * 7 * t)
    return t, u


def outputs(model, t, u):
    return model.apply(u, t) if isinstance(model, (WithDynamics, CreepHysteresis)) else model.apply(u)


@pytest.mark.parametrize("name", ["discrete", "everett", "pi", "continuous", "with_dynamics", "creep"])
def test_a_scaled_model_gives_factor_times_the_output_for_any_history(name):
    model = displacement_models()[name]
    model.output_quantity, model.output_unit = "displacement", "m"
    model.fitted_range, model.fit_info = (-500.0, 1500.0), {"family": name, "n_fit": 801}
    t, u = history()
    gauge = 0.06
    strain_model = model_to_strain(model, gauge_length=gauge)
    assert type(strain_model) is type(model)
    np.testing.assert_allclose(outputs(strain_model, t, u), outputs(model, t, u) / gauge, rtol=1e-12, atol=1e-20)
    assert strain_model.output_quantity == "strain" and strain_model.output_unit == "-"
    assert strain_model.fitted_range == (-500.0, 1500.0)
    assert strain_model.fit_info["family"] == name and strain_model.fit_info["output_scale"]["factor"] == 1 / gauge
    assert model.output_unit == "m" and model.fit_info == {"family": name, "n_fit": 801}  # the original untouched


def test_the_paper_stroke_model_over_its_cell_is_the_paper_strain_model():
    # parameter_sets defines the strain model as the stroke over the 29 mm cell, parameter by parameter
    stroke = paper_stroke_preisach()
    strain = model_to_strain(stroke, gauge_length=29e-3, output_unit="m")
    _, u = history()
    np.testing.assert_allclose(strain.apply(u), paper_strain_preisach().apply(u), rtol=1e-13, atol=1e-20)
    assert strain.input_range == stroke.input_range


def test_a_bender_model_is_scaled_by_the_small_deflection_line_and_warns_where_it_is_off():
    stroke = paper_stroke_preisach()  # a displacement of tens of micrometres: small deflections
    _, u = history()
    deflection_model = scaled_output(stroke, 1e-3 / 40e-6)  # up to 1 mm at the tip: line off by 5e-5
    deflection_model.output_unit = "m"
    strain = model_to_strain(deflection_model, laminate=LAMINATE, length=L)  # no warning (pytest: errors)
    c = LAMINATE.curvature_per_strain
    np.testing.assert_allclose(strain.apply(u), deflection_model.apply(u) * 2 / (c * L**2), rtol=1e-13, atol=1e-20)
    np.testing.assert_allclose(strain.apply(u), strain_from_tip_deflection(deflection_model.apply(u), LAMINATE, L),
                               rtol=1e-4, atol=1e-12)
    large = scaled_output(stroke, 15.5e-3 / 40e-6)  # the paper's 15.5 mm: the line is 1.1 % low
    large.output_unit = "m"
    with pytest.warns(AccuracyWarning, match=r"reaches a deflection of 0.0155 m at 0.087 m, where the small-deflection "
                                             r"line is 1.1 % off the arc .* convert the record with record_to_strain"):
        model_to_strain(large, laminate=LAMINATE, length=L)


def test_models_that_cannot_be_converted_are_refused():
    class MyPI(PrandtlIshlinskii):
        pass

    mine = MyPI([0.0], [1e-9], 1e-8)
    mine.output_unit = "m"
    with pytest.raises(ValueError, match=r"cannot scale the output of a MyPI; scaled_output knows DiscretePreisach, "
                                         r"EverettPreisach, PrandtlIshlinskii"):
        model_to_strain(mine, gauge_length=0.05)
    with pytest.raises(ValueError, match=r"model: the output unit is not stated \(unknown\), not a length"):
        model_to_strain(PrandtlIshlinskii([0.0], [1e-9], 1e-8), gauge_length=0.05)
    with pytest.raises(ValueError, match="already gives the free strain"):
        model_to_strain(paper_strain_preisach(), gauge_length=0.05)
    with pytest.raises(ValueError, match="factor must be > 0"):
        scaled_output(paper_stroke_preisach(), -1.0)
    model = PrandtlIshlinskii([0.0], [1e-9], 1e-8)
    model.output_unit = "mm"
    with pytest.raises(ValueError, match="output_unit = 'm' conflicts with the model's own output_unit 'mm'"):
        model_to_strain(model, gauge_length=0.05, output_unit="m")
    # the model's millimetres are converted to metres, then over the gauge length
    strained = model_to_strain(model, gauge_length=0.05)
    assert strained.p0 == pytest.approx(1e-8 * 1e-3 / 0.05, rel=1e-15)

