"""``cell="rod"`` for benders of several segments: each segment's modes on its own length.

Independent references: the piecewise arc of piecewise constant free curvature (closed form);
two single-segment rods welded end to end (the composition already validated against one rod
of the summed length in ``test_mechanism_rod.py``), which has the same kinematics and inertia by
construction of a different Exudyn system; the parallel guide's exact S-blade translation
(:func:`exudyn_atcm.theory.beam_mechanisms.s_blade_end`); polynomials for the quadrature.
"""

from __future__ import annotations

import math
import pathlib

import exudyn as exu
import numpy as np
import pytest

from exudyn_atcm import (Bender, Layer, Mechanism, PiezoDrive, RayleighDamping, Segment, add_to, eigenfrequencies,
                         simulate, solve_static)
from exudyn_atcm.mbs import solver_settings
from exudyn_atcm.casework import load_case
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.theory import rotation_rod as rr

CASES = pathlib.Path(__file__).resolve().parents[1] / "cases"
CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W = 10e-3
#: one damping for every bender: the default, a damping ratio at each bender's own first mode, differs
#: between one bender and its two halves (documented; the composition identity needs the same beta)
DAMPING = RayleighDamping(0.0, 2e-5)


def segmented(name, segments):
    return Bender(name, width=W, passive=CFC, active=MFC, segments=segments, cell="rod", damping=DAMPING)


def welded_pair(modes, lengths, drives, force=None):
    """Two single-segment rods, the second on the first one's tip."""
    a = Bender("a", width=W, passive=CFC, active=MFC, length=lengths[0], n_cells=modes[0], drive=drives[0],
               cell="rod", damping=DAMPING)
    b = Bender("b", width=W, passive=CFC, active=MFC, length=lengths[1], n_cells=modes[1], drive=drives[1],
               base=(lengths[0], 0.0), cell="rod", damping=DAMPING)
    m = Mechanism("pair").add(a, b).ground(a.base).weld(a.tip, b.base)
    if force is not None:
        m.force(b.tip, force)
    return m


def one_rod(modes, lengths, drives, force=None):
    s = segmented("s", [Segment(a, n, d) for n, a, d in zip(modes, lengths, drives)])
    m = Mechanism("one").add(s).ground(s.base)
    if force is not None:
        m.force(s.tip, force)
    return m


def test_composite_quadrature_integrates_piecewise_polynomials_and_one_segment_is_the_plain_rod():
    shapes = rr.rod_shapes(5, 0.07, (2, 3), (0.03, 0.04))
    s = np.concatenate([0.03 * rr.quadrature(rr.rule_points(2))[0],
                        0.03 + 0.04 * rr.quadrature(rr.rule_points(3))[0]]) / 0.07  # points in units of L
    # f = a different polynomial on each segment (degree 9 < the rules' 12 and 14 points)
    f = np.where(s < 0.03 / 0.07, s**9, 3.0 * s**2 - s)
    cut = 0.03 / 0.07
    primitive = np.where(s < cut, s**10 / 10, cut**10 / 10 + (s**3 - s**2 / 2) - (cut**3 - cut**2 / 2))
    np.testing.assert_allclose(shapes.integration @ f, primitive, rtol=0, atol=1e-15)
    assert shapes.weights.sum() == pytest.approx(1.0, abs=1e-15)
    # the rotation is continuous: the first segment's end rotation (its first mode) carries into the second
    # (phi_i(1) = 0 for i >= 2 to round-off)
    np.testing.assert_allclose(shapes.phi[12:, :2], np.tile([1.0, 0.0], (14, 1)), rtol=0, atol=1e-15)
    np.testing.assert_allclose(shapes.phi_tip, [1.0, 0.0, 1.0, 0.0, 0.0], rtol=0, atol=1e-15)
    # block-diagonal stiffness: each segment's ritz stiffness EI / (L_j (2i - 1))
    np.testing.assert_allclose(np.diag(shapes.stiffness_matrix(2.0)), [2 / 0.03, 2 / (3 * 0.03), 2 / 0.04,
                                                                       2 / (3 * 0.04), 2 / (5 * 0.04)], rtol=1e-14)
    plain, single = rr.rod_shapes(4, 0.06), rr.rod_shapes(4, 0.06, (4,), (0.06,))
    for name in ("phi", "weights", "integration", "phi_tip", "phi_hat", "phi_hat_tip"):
        np.testing.assert_array_equal(getattr(plain, name), getattr(single, name))


def _arc(start, kappa, length):
    """Chord (dx, dy) of an arc of curvature ``kappa`` [1/m] and ``length`` [m] starting at direction ``start``."""
    if kappa == 0.0:
        return length * math.cos(start), length * math.sin(start)
    end = start + kappa * length
    return (math.sin(end) - math.sin(start)) / kappa, (math.cos(start) - math.cos(end)) / kappa


@pytest.mark.parametrize("modes, second", [((1, 1), -400.0), ((2, 3), -400.0), ((2, 2), None)])
def test_free_actuation_of_two_segments_is_the_exact_piecewise_arc(modes, second):
    lengths = (0.025, 0.035)
    drives = (PiezoDrive(1200.0), None if second is None else PiezoDrive(second))
    r = solve_static(one_rod(modes, lengths, drives))
    per_strain = Bender("ref", width=W, passive=CFC, active=MFC, length=0.01, n_cells=1, cell="rod",
                        drive=drives[0]).laminate.curvature_per_strain
    k1, k2 = (0.0 if d is None else per_strain * d.linear_strain(d.voltage_at(0.0)) for d in drives)
    t1 = k1 * lengths[0]
    t2 = t1 + k2 * lengths[1]
    (x1, y1), (x2, y2) = _arc(0.0, k1, lengths[0]), _arc(t1, k2, lengths[1])
    assert t1 > 0.05 and (second is None or t2 - t1 < -0.02)  # a real kink in the curvature
    # the static Newton tolerance (relative 1e-10, absolute 1e-12 EI/L), as for one segment
    assert r["s.tip_angle"][0] == pytest.approx(t2, abs=1e-10)
    assert r["s.tip_x"][0] == pytest.approx(x1 + x2, abs=1e-10 * 0.06)
    assert r["s.tip_y"][0] == pytest.approx(y1 + y2, abs=1e-10 * 0.06)
    # each segment's cells: mean rotations of its equal parts
    n1, n2 = modes
    expected = [(j + 0.5) * t1 / n1 for j in range(n1)] + [t1 + (j + 0.5) * (t2 - t1) / n2 for j in range(n2)]
    got = [r[f"s.cell_angle_{j + 1}"][0] for j in range(n1 + n2)]
    np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-12)


def test_two_segments_equal_two_rods_welded_statics_and_frequencies():
    modes, lengths = (6, 5), (0.03, 0.04)
    drives = (PiezoDrive(1000.0), PiezoDrive(-300.0))
    force = (0.1, -0.5)  # N: tip turned by about 0.3 rad
    one, pair = solve_static(one_rod(modes, lengths, drives, force)), solve_static(welded_pair(modes, lengths, drives,
                                                                                                force))
    # the same kinematics and inertia, two different Exudyn systems: the Newton tolerance apart
    for axis in ("x", "y"):
        assert one[f"s.tip_{axis}"][0] == pytest.approx(pair[f"b.tip_{axis}"][0], abs=1e-11)
    assert one["s.tip_angle"][0] == pytest.approx(pair["b.tip_angle"][0], abs=1e-10)
    assert abs(one["s.tip_angle"][0]) > 0.2
    cells = [one[f"s.cell_angle_{j + 1}"][0] for j in range(11)]
    welded = [pair[f"a.cell_angle_{j + 1}"][0] for j in range(6)] + [pair[f"b.cell_angle_{j + 1}"][0] for j in range(5)]
    np.testing.assert_allclose(cells, welded, rtol=0, atol=1e-10)
    f_one = eigenfrequencies(one_rod(modes, lengths, drives, force), n=4, voltage={"s.1": 1000.0, "s.2": -300.0})
    f_pair = eigenfrequencies(welded_pair(modes, lengths, drives, force), n=4, voltage={"a": 1000.0, "b": -300.0})
    np.testing.assert_allclose(f_one, f_pair, rtol=1e-9)


def test_two_segments_equal_two_rods_welded_in_a_dynamic_run():
    modes, lengths = (3, 3), (0.03, 0.03)
    drives = (PiezoDrive(Triangle(500.0, 1000.0, 0.02)), PiezoDrive(Triangle(0.0, 500.0, 0.01)))
    one = simulate(one_rod(modes, lengths, drives), 0.02, step=1e-4)
    pair = simulate(welded_pair(modes, lengths, drives), 0.02, step=1e-4)
    assert one.n_rows == pair.n_rows == 201
    travel = np.ptp(pair["b.tip_y"])
    assert travel > 1e-4
    # the same equations, two time discretisations: each rod linearises its tip and mass matrix at its own
    # predicted state, so the pair's second rod rides on a predicted tip node, the segmented rod on its exact
    # tip pose.  Measured 1.1e-5 of the travel here (1.4e-6 at step 2.5e-5 s); with 6 + 6 modes both are 1.1e-3 from a beam
    # of 96 elements at step 2.5e-5 s, the time step's own error, 100 times more
    np.testing.assert_allclose(one["s.tip_y"], pair["b.tip_y"], rtol=0, atol=5e-5 * travel)
    np.testing.assert_allclose(one["s.tip_angle"], pair["b.tip_angle"], rtol=0, atol=5e-5 * np.ptp(pair["b.tip_angle"]))
    np.testing.assert_allclose(one["s.2.strain"], pair["b.strain"], rtol=0, atol=1e-15)


def test_parallel_guide_with_rods_is_the_exact_s_blade():
    case = load_case(CASES / "parallel_guide.py")
    out = case.run({"cell": "rod", "n_cells": 1, "n_steps": 8, "animation": False})
    s = out.scalars
    # one mode per segment represents the S exactly (cells and beam elements: the polygon, 5e-5 at 8 cells)
    assert s["translation_error"] < 1e-8
    assert s["rotation_max"] < 1e-12


def test_a_segmented_rod_works_through_add_to_with_the_users_solver():
    """add_to, the user's Assemble and SolveDynamic: the same run as simulate (the segments' actuation
    loads and the rod's updates run in the package's hooks, which the user's solve calls)."""
    modes, lengths = (2, 3), (0.03, 0.03)
    # programs starting at 0 V: simulate starts from the static state at U(0), the user's run from the reference
    drives = (PiezoDrive(Triangle(500.0, 500.0, 0.02)), PiezoDrive(Triangle(250.0, 250.0, 0.01)))
    ref = simulate(one_rod(modes, lengths, drives), 0.005, step=1e-4)
    mbs = exu.SystemContainer().AddSystem()
    handle = add_to(mbs, one_rod(modes, lengths, drives))
    mbs.Assemble()
    mbs.SolveDynamic(solver_settings.dynamic_settings(0.005, 1e-4))
    r = handle.result()
    for name in ("s.tip_x", "s.tip_y", "s.tip_angle", "s.cell_angle_3"):
        np.testing.assert_allclose(r[name], ref[name], rtol=0, atol=1e-12, err_msg=name)
    assert np.ptp(r["s.tip_y"]) > 1e-5  # it moved
