"""Issue 7, part 1: the mechanism description and its checks (no Exudyn needed).

Each bad-input class of the issue raises a MechanismError (a ValueError) naming the parts.
References: the geometry of the described reference pose (positions, gaps computed by hand).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm import Bender, Flexure, Layer, Link, Mechanism, MechanismError, PiezoDrive, Segment, solve_static
from exudyn_atcm.mechanism.actuator import BendingActuator
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.mechanism import PointRef

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)


def crank(name="crank", **kw):
    kw.setdefault("length", 0.03)
    kw.setdefault("n_cells", 4)
    return Bender(name, width=10e-3, passive=CFC, active=MFC, drive=PiezoDrive(500.0), **{"cell": "rigid", **kw})


def four_bar():
    """Bender crank from (0,0) along +y, coupler to (0.04, 0.03), rocker link down to (0.04, 0)."""
    c = crank(angle=math.pi / 2)
    coupler = Link("coupler", {"A": (0.0, 0.03), "B": (0.04, 0.03), "P": (0.02, 0.05)}, mass=1e-3, inertia=1e-7)
    rocker = Link("rocker", {"B": (0.04, 0.03), "O": (0.04, 0.0)}, mass=1e-3, inertia=1e-7)
    m = Mechanism("four_bar").add(c, coupler, rocker)
    m.ground(c.base).pin(c.tip, coupler.point("A")).pin("coupler.B", "rocker.B").ground("rocker.O", joint="pin")
    return m


def test_valid_four_bar_passes_and_reports_positions():
    m = four_bar()
    m.check()
    # tip of a bender at angle pi/2: base + L (cos, sin)
    np.testing.assert_allclose(m.position("crank.tip"), [0.0, 0.03], atol=1e-17)
    assert m.drives.keys() == {"crank"}
    assert m.size == pytest.approx(0.05)


def test_mechanism_error_is_a_value_error():
    assert issubclass(MechanismError, ValueError)


def test_duplicate_component_names():
    with pytest.raises(MechanismError, match="duplicate component name 'crank'"):
        Mechanism().add(crank(), crank())


def test_unknown_component_with_suggestion():
    m = four_bar()
    with pytest.raises(MechanismError, match=r"unknown component 'coupeler'.*did you mean 'coupler'"):
        m.weld("coupeler.P", "rocker.O")


def test_unknown_point_lists_points_with_suggestion():
    m = four_bar()
    with pytest.raises(MechanismError, match=r"'coupler' has no point 'Q'.*its points: A, B, P"):
        m.weld("coupler.Q", "rocker.O")
    with pytest.raises(MechanismError, match=r"no point 'tpi'.*did you mean 'tip'"):
        crank().point("tpi")
    with pytest.raises(MechanismError, match="'component.point'"):
        m.weld("coupler", "rocker.O")


def test_self_connection():
    m = four_bar()
    with pytest.raises(MechanismError, match=r"weld\(coupler.A, coupler.B\) connects component 'coupler' to itself"):
        m.weld("coupler.A", "coupler.B")


def test_duplicate_and_conflicting_connections():
    m = four_bar()
    with pytest.raises(MechanismError, match=r"already joined by pin\(coupler.B, rocker.B\).*twice"):
        m.pin("rocker.B", "coupler.B")
    with pytest.raises(MechanismError, match=r"weld\(coupler.B, rocker.B\).*already joined by pin.*conflicting"):
        m.weld("coupler.B", "rocker.B")
    with pytest.raises(MechanismError, match=r"already joined by weld\(crank.base, ground\).*conflicting"):
        m.ground("crank.base", joint="pin")


def test_no_ground():
    c = crank()
    link = Link("lever", {"A": (0.03, 0.0), "B": (0.05, 0.0)}, mass=1e-3, inertia=1e-7)
    m = Mechanism("m").add(c, link).weld(c.tip, link.point("A"))
    with pytest.raises(MechanismError, match="no ground connection.*crank, lever"):
        m.check()


def test_floating_component_named():
    m = four_bar()
    extra = Link("weight", {"C": (0.1, 0.1)}, mass=1e-3, inertia=1e-7)
    m.add(extra)
    with pytest.raises(MechanismError, match=r"'weight' of mechanism 'four_bar' are not connected to the ground"):
        m.check()
    m.spring("weight.C", "coupler.P", 10.0)
    with pytest.raises(MechanismError, match="weight hang\\(s\\) on springs only"):
        m.check()


def test_loop_that_cannot_be_assembled_gives_the_gap():
    c = crank(angle=math.pi / 2)
    coupler = Link("coupler", {"A": (0.0, 0.03), "B": (0.04, 0.03)}, mass=1e-3, inertia=1e-7)
    # rocker 0.1 mm too short: its top is at y = 0.0299
    rocker = Link("rocker", {"B": (0.04, 0.0299), "O": (0.04, 0.0)}, mass=1e-3, inertia=1e-7)
    m = Mechanism().add(c, coupler, rocker)
    m.ground(c.base).pin(c.tip, "coupler.A").pin("coupler.B", "rocker.B").ground("rocker.O", joint="pin")
    with pytest.raises(MechanismError) as info:
        m.check()
    text = str(info.value)
    assert "pin(coupler.B, rocker.B) cannot be assembled" in text
    assert "(0.04, 0.03)" in text and "(0.04, 0.0299)" in text
    assert "gap 0.0001 m" in text


def test_slider_off_axis_is_refused_with_gap():
    c = crank()
    block = Link("block", {"S": (0.03, 0.001)}, mass=1e-3, inertia=1e-7)
    m = Mechanism().add(c, block)
    m.ground(c.base).slider(c.tip, "block.S", axis=(1.0, 0.0))
    with pytest.raises(MechanismError, match=r"block.S lies off the slider axis.*gap 0.001 m"):
        m.check()


def test_shared_hysteresis_operator_between_drives_is_refused():
    op = paper_strain_preisach()
    a = Bender("a", width=1e-2, passive=CFC, active=MFC, length=0.03, n_cells=2, drive=PiezoDrive(1.0, hysteresis=op), cell="rigid")
    b = Bender("b", width=1e-2, passive=CFC, active=MFC, length=0.03, n_cells=2, base=(0.0, 0.01),
               drive=PiezoDrive(1.0, hysteresis=op), cell="rigid")
    m = Mechanism().add(a, b).ground(a.base).ground(b.base)
    with pytest.raises(MechanismError, match="drives 'a' and 'b' .* sharing one hysteresis operator"):
        m.check()
    # one PiezoDrive object for both benders is allowed (one strain for both)
    d = PiezoDrive(1.0, hysteresis=paper_strain_preisach())
    a2 = Bender("a", width=1e-2, passive=CFC, active=MFC, length=0.03, n_cells=2, drive=d, cell="rigid")
    b2 = Bender("b", width=1e-2, passive=CFC, active=MFC, length=0.03, n_cells=2, base=(0.0, 0.01), drive=d, cell="rigid")
    Mechanism().add(a2, b2).ground(a2.base).ground(b2.base).check()


def test_component_arguments_are_checked():
    with pytest.raises(ValueError, match="either length, n_cells and drive, or segments"):
        Bender("b", width=1e-2, passive=CFC, active=MFC, length=0.03, segments=[Segment(0.03, 2)], cell="rigid")
    with pytest.raises(ValueError, match=r"no active layer.*segment\(s\) \[1\]"):
        Bender("b", width=1e-2, passive=CFC, length=0.03, n_cells=2, drive=PiezoDrive(1.0), cell="rigid")
    with pytest.raises(MechanismError, match="Bender name"):
        Bender("a.b", width=1e-2, passive=CFC, length=0.03, n_cells=2, cell="rigid")
    with pytest.raises(ValueError, match="active_side must be one of"):
        Bender("b", width=1e-2, passive=CFC, length=0.03, n_cells=2, active_side="top", cell="rigid")
    with pytest.raises(MechanismError, match="reserved for the ground"):
        Mechanism().add(Link("ground", {"A": (0, 0)}, mass=1.0, inertia=1.0))
    with pytest.raises(ValueError, match="gamma must be in"):
        Flexure("f", base=(0, 0), tip=(0.01, 0), width=1e-3, layer=Layer(1e-4, 1e9, 1e3),
                gamma=1.5)
    with pytest.raises(MechanismError, match="torques act on links"):
        Mechanism().add(crank()).torque("crank", 1e-3)
    with pytest.raises(MechanismError, match="duplicate name 'grip'"):
        four_bar().spring("coupler.P", "rocker.O", 10.0, name="grip").spring("coupler.A", "rocker.O", 1.0, name="grip")


def test_bender_laminate_equals_bending_actuator():
    """Same formulas as BendingActuator (shared Laminate): EI, curvature, mass, damping factor."""
    drive = PiezoDrive(500.0)
    b = Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=3, drive=drive, cell="rigid")
    act = BendingActuator(3, 0.029, 28e-3, CFC, MFC, drive, cell="rigid")
    lam = b.laminate
    assert lam.bending_stiffness == act.bending_stiffness
    assert lam.curvature_per_strain == act.curvature_per_strain
    assert lam.mass_per_length == act.mass_per_length
    assert b.stiffness_damping_factor == pytest.approx(act.stiffness_damping_factor, rel=1e-15)
    # lamination theory by hand (Timoshenko 1925): EI = E1I1 + E2I2 + a1a2/(a1+a2) e^2
    w, e = 28e-3, 0.25e-3
    a1, a2 = 70e9 * w * 0.2e-3, 30.336e9 * w * 0.3e-3
    ei = 70e9 * w * 0.2e-3**3 / 12 + 30.336e9 * w * 0.3e-3**3 / 12 + a1 * a2 / (a1 + a2) * e**2
    assert lam.bending_stiffness == pytest.approx(ei, rel=1e-14)


def test_segments_drive_names_and_geometry():
    d1, d2 = PiezoDrive(100.0), PiezoDrive(-100.0)
    s = Bender("s", width=1e-2, passive=CFC, active=MFC, segments=[Segment(0.02, 2, d1), Segment(0.01, 3, d2)],
               base=(0.01, 0.02), angle=math.pi, cell="rigid")
    assert list(s.drives) == ["s.1", "s.2"]
    assert s.n_cells == 5 and s.length == pytest.approx(0.03)
    np.testing.assert_allclose(s.cell_lengths, [0.01, 0.01, 0.01 / 3, 0.01 / 3, 0.01 / 3])
    np.testing.assert_allclose(s.points["tip"], [-0.02, 0.02], atol=1e-15)
    assert s.tip == PointRef("s", "tip")


def test_link_from_outline_rectangle():
    # 40 x 10 mm plate, 2 mm thick, 1000 kg/m^3, corner at the origin
    outline = [(0, 0), (0.04, 0), (0.04, 0.01), (0, 0.01)]
    link = Link.from_outline("plate", {"A": (0.0, 0.005)}, outline, density=1000.0, thickness=2e-3)
    m = 1000.0 * 2e-3 * 0.04 * 0.01
    assert link.mass == pytest.approx(m, rel=1e-12)
    assert link.center_of_mass == pytest.approx((0.02, 0.005), rel=1e-12)
    assert link.inertia == pytest.approx(m * (0.04**2 + 0.01**2) / 12.0, rel=1e-12)


def test_prbm_flexure_numbers():
    f = Flexure("hinge", base=(0.0, 0.0), tip=(0.0, 0.01), width=5e-3, layer=Layer(0.2e-3, 70e9, 1550.0))
    ei = 70e9 * 5e-3 * 0.2e-3**3 / 12.0
    assert f.torsion_stiffness == pytest.approx(0.8517 * 2.65 * ei / 0.01, rel=1e-14)
    # pivot at gamma L from the tip
    assert f.pivot == pytest.approx((0.0, 0.01 * (1 - 0.8517)), abs=1e-15)
    small = Flexure("p", base=(0, 0), tip=(0.01, 0), width=5e-3, layer=Layer(0.2e-3, 70e9, 1550.0), gamma=0.5, k_theta=2.0)
    assert small.torsion_stiffness == pytest.approx(ei / 0.01, rel=1e-14)


def test_joint_inside_one_rigid_group_is_refused():
    a = Link("a", {"P": (0.0, 0.0), "Q": (0.01, 0.0)}, mass=1e-3, inertia=1e-7)
    b = Link("b", {"P": (0.0, 0.0), "Q": (0.01, 0.0)}, mass=1e-3, inertia=1e-7)
    m = Mechanism().add(a, b).ground("a.P").weld("a.Q", "b.Q").pin("a.P", "b.P")
    with pytest.raises(MechanismError, match=r"pin\(a.P, b.P\) joins two points of one rigid group .*a, b, ground"):
        solve_static(m)
