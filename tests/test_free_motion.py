"""A static solve of a mechanism with a motion no stiffness holds says so (not "use more cells").

A bender whose tip carries a link on a free pin: the link turns without any stiffness (its lowest
eigenfrequency about the reference pose is 1e-4 Hz against the bender's 260 Hz), so there is no
static equilibrium to find once the bender bends; the failure named the cells, the loads and a
locked mechanism.  Reference for the held variant: moment balance (a pin spring that carries no
moment leaves the link at the bender tip's angle).
"""

from __future__ import annotations

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.errors import SolverError

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)


def flapper(pin_stiffness: float = 0.0, cell: str = "rod") -> atcm.Mechanism:
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=3, cell=cell,
                    drive=atcm.PiezoDrive(1000.0))
    flap = atcm.Link("flap", {"H": (0.03, 0.0), "E": (0.05, 0.0)}, mass=1e-4, inertia=1e-8)
    return atcm.Mechanism("flapper").add(b, flap).ground(b.base).pin(b.tip, "flap.H", stiffness=pin_stiffness)


@pytest.mark.parametrize("cell", ["rod", "rigid"])
def test_a_link_on_a_free_pin_is_named_as_the_reason(cell):
    with pytest.raises(SolverError, match=r"motion without stiffness in its reference pose \(lowest eigenfrequency "
                                          r"[^;]+; moving most: flap\)") as caught:
        atcm.solve_static(flapper(cell=cell))
    assert "Use more cells" not in str(caught.value)


def test_the_link_held_by_a_pin_spring_follows_the_bender_tip():
    r = atcm.solve_static(flapper(pin_stiffness=1e-3))
    assert abs(r["b.tip_angle"][0]) > 1e-3  # the bender did bend
    np.testing.assert_allclose(r["flap.angle"][0], r["b.tip_angle"][0], rtol=0, atol=1e-8)
