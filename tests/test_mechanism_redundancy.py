"""Over-constrained mechanisms (issue 29, finding 6): ``check()`` names dependent joints, the same check for
every cell kind, and every solve refuses them with that message instead of "did not converge ... use more
cells".

Independent references: the rank of the constraint Jacobian (three pins pairwise at one point repeat two
equations whatever the cells; a chain that cannot stretch, held straight between two clamps, repeats its
axial one, a chain of beam elements, which stretch, repeats none); Exudyn's own
``ComputeSystemDegreeOfFreedom`` (``Mechanism.degrees_of_freedom``), which must count the same
redundancy; and beam theory: a bender clamped at both ends under a uniform free curvature stays
straight (``w'' = kappa_0 + M/EI`` with ``w = w' = 0`` at both ends gives ``M = -EI kappa_0``, ``w = 0``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm import Bender, Layer, Mechanism, MechanismError, PiezoDrive, simulate, solve_static, static_sweep
from exudyn_atcm.mbs import builder as mb
from exudyn_atcm.mbs.redundancy import constraint_jacobian
from exudyn_atcm.mbs.tangent import TangentPlan

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W, L = 10e-3, 0.03


def clamped_both_ends(cell: str, n: int = 4) -> Mechanism:
    b = Bender("b", width=W, passive=CFC, active=MFC, length=L, n_cells=n, drive=PiezoDrive(1500.0), cell=cell)
    m = Mechanism("clamped").add(b)
    m.ground(b.base)
    m.ground(b.tip)
    return m


def three_benders(cell: str, third_pin: bool) -> Mechanism:
    """Bender a from the ground; b and c start at a's tip, pinned (with torsion springs) pairwise there."""
    def bender(name, base, angle):
        return Bender(name, width=W, passive=CFC, active=MFC, length=L, n_cells=4, drive=PiezoDrive(500.0),
                      cell=cell, base=base, angle=angle)

    a, b, c = bender("a", (0.0, 0.0), 0.0), bender("b", (L, 0.0), math.pi / 2), bender("c", (L, 0.0), -math.pi / 2)
    m = Mechanism("star").add(a, b, c)
    m.ground(a.base)
    m.pin(a.tip, b.base, stiffness=0.1)
    m.pin(b.base, c.base, stiffness=0.1)
    if third_pin:
        m.pin(c.base, a.tip, stiffness=0.1)
    return m


@pytest.mark.parametrize("cell", ["rigid", "six-bar", "rod"])
def test_a_chain_that_cannot_stretch_clamped_at_both_ends_is_refused_naming_the_joints(cell):
    mech = clamped_both_ends(cell)
    assert mech.degrees_of_freedom().redundant == 1  # Exudyn's count: the axial direction, fixed twice
    expected = (r"over-constrained in its reference pose: the constraints of the cells of bender 'b', "
                r"weld\(b\.base, ground\) and weld\(b\.tip, ground\) are dependent \(1 of \d+ constraint equations "
                rf"redundant\).*{cell} cells cannot stretch.*cell='beam'")
    with pytest.raises(MechanismError, match=expected):
        mech.check()
    for solve in (lambda: solve_static(mech), lambda: static_sweep(mech, [0.0, 100.0]),
                  lambda: simulate(mech, 1e-3, step=1e-4)):
        with pytest.raises(MechanismError, match="over-constrained"):
            solve()


def test_the_same_bender_of_beam_elements_is_not_redundant_and_stays_straight():
    mech = clamped_both_ends("beam", 8)
    assert mech.degrees_of_freedom().redundant == 0
    mech.check()
    result = solve_static(mech)
    # beam theory: fully restrained uniform free curvature leaves the bender straight
    angles = np.array([result[f"b.cell_angle_{j}"][-1] for j in range(1, 9)])
    assert np.max(np.abs(angles)) < 1e-9


@pytest.mark.parametrize("cell", ["rigid", "six-bar", "beam", "rod"])
def test_three_coincident_pins_are_refused_for_every_cell_kind(cell):
    mech = three_benders(cell, third_pin=True)
    assert mech.degrees_of_freedom().redundant == 2  # one pin's two equations repeat the other two pins'
    expected = (r"the constraints of pin\(a\.tip, b\.base\), pin\(b\.base, c\.base\) and pin\(c\.base, a\.tip\) are "
                r"dependent \(2 of \d+ constraint equations redundant\).*remove one of these joints")
    with pytest.raises(MechanismError, match=expected):
        mech.check()
    with pytest.raises(MechanismError, match=expected):
        solve_static(mech)


def test_two_pins_at_one_point_solve_alike_for_every_cell_kind():
    # without the repeated pin the mechanism is determinate; the kinds agree (rigid chains to their O(1/N^2))
    tips = {}
    for cell in ("rigid", "six-bar", "beam", "rod"):
        mech = three_benders(cell, third_pin=False)
        mech.check()
        result = solve_static(mech)
        tips[cell] = (result["b.tip_x"][-1], result["c.tip_x"][-1])
    spread = np.ptp(np.array(list(tips.values())), axis=0)
    assert np.all(spread < 1e-5 * L), tips


def test_the_constraint_jacobian_is_exudyns_and_matches_differences():
    # Exudyn's analytic C_q (as its ComputeSystemDegreeOfFreedom takes it) against central differences of the
    # constraint residual, for a mechanism with pins, welds and cells
    mech = three_benders("rigid", third_pin=False)
    model = mb.build(mech)
    analytic = constraint_jacobian(model.mbs)
    differences = TangentPlan(model.mbs).system(mass=False)["Cq"]
    assert analytic.shape == differences.shape
    np.testing.assert_allclose(analytic, differences, atol=1e-7 * np.max(np.abs(analytic)))


def test_degrees_of_freedom_still_reports_what_check_refuses():
    # 4 rigid cells: 12 coordinates; 3 inner joints and 2 end hinges, 10 equations; one of them dependent,
    # so 12 - (10 - 1) = 3 degrees of freedom in the reference pose (Gruebler with the redundancy)
    report = clamped_both_ends("rigid").degrees_of_freedom()
    assert (report.dof, report.coordinates, report.constraints, report.redundant) == (3, 12, 10, 1)
