"""One description of a bender (issue 30, part 1): the lone actuator is a one-bender mechanism.

The reference of each test is the same bender built by hand with :class:`~exudyn_atcm.Bender` and
:class:`~exudyn_atcm.Mechanism` and solved as a mechanism: the actuator's results must be that
mechanism's, bit for bit, under the mechanism's column names too.
"""

from __future__ import annotations

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm import Bender, BendingActuator, Layer, Mechanism, PiezoDrive
from exudyn_atcm.cells import SixBarCell
from exudyn_atcm.mechanism import actuator as actuator_module
from exudyn_atcm.mechanism import bender as bender_module
from exudyn_atcm.plots.mechanism import actuator_as_mechanism, draw_mechanism
from exudyn_atcm.plots.style import new_figure

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
L, N, W = 0.087, 3, 28e-3  # the paper actuator: 3 cells of 29 mm, 28 mm wide


class MySixBar(SixBarCell):
    """A kind defined outside the package: the paper's six-bar cell under another name and joint label."""

    name = "my-six-bar"
    joint_label = "my six-bar joints"


def _by_hand(cell: str, drive: PiezoDrive, force=(0.0, 0.0)) -> Mechanism:
    b = Bender("actuator", width=W, passive=CFC, active=MFC, length=L, n_cells=N, drive=drive, cell=cell)
    mech = Mechanism("actuator").add(b).ground(b.base)
    if force != (0.0, 0.0):
        mech.force(b.tip, force)
    return mech


@pytest.mark.parametrize("cell", ["rigid", "beam"])
def test_a_static_actuator_is_its_one_bender_mechanism_under_both_names(cell):
    drive = PiezoDrive(0.0)
    act = BendingActuator(N, L / N, W, CFC, MFC, drive, cell=cell)
    force = (0.0, -0.05)
    r = atcm.solve_static(act, voltage=1000.0, tip_force=force)
    ref = atcm.solve_static(_by_hand(cell, drive, force), voltage=1000.0)
    for column in ("tip_x", "tip_y", "tip_angle", "cell_angle_3"):
        assert r[f"actuator.{column}"][0] == ref[f"actuator.{column}"][0]  # the same model, bit for bit
        assert r.unit(f"actuator.{column}") == ref.unit(f"actuator.{column}")
    assert r["actuator.base_x"][0] == 0.0 and "actuator.base_y" in r
    # the mechanism's columns, named as the mechanism names them, with the stroke of one cell after the strain
    k = ref.names.index("actuator.strain") + 1
    assert r.names == ref.names[:k] + ["actuator.stroke"] + ref.names[k:]
    # the tip load is a mechanism force at the bender's tip
    mech = act.as_mechanism(force)
    assert [(str(f.point), f.force) for f in mech.forces] == [("actuator.tip", force)]
    assert mech.benders[0].cell == act.cell and mech.benders[0].n_cells == N


def test_a_simulated_actuator_keeps_the_mechanism_columns_also_every_step():
    drive = PiezoDrive(lambda t: 1500.0 * t / 0.01)
    act = BendingActuator(N, L / N, W, CFC, MFC, drive, cell="rigid")
    r = atcm.simulate(act, 0.01, step=1e-3, record_every=2)
    ref = atcm.simulate(_by_hand("rigid", drive), 0.01, step=1e-3, record_every=2)
    np.testing.assert_array_equal(r["actuator.tip_y"], ref["actuator.tip_y"])
    np.testing.assert_array_equal(r.every_step["actuator.tip_y"], ref.every_step["actuator.tip_y"])
    assert r.every_step.n_rows == 11 and r.n_rows == 6


def test_cell_types_has_one_meaning():
    assert actuator_module.CELL_TYPES == bender_module.CELL_TYPES == bender_module.mechanism_cells()


def test_the_drawing_of_an_actuator_draws_its_own_cell_kind():
    # main drew every actuator as a rigid chain (its own conversion made a default-cell Bender):
    # the legend named "cell joints", not the kind's joint label
    act = BendingActuator(N, L / N, W, CFC, MFC, PiezoDrive(500.0), cell=MySixBar())
    r = atcm.solve_static(act)
    mech, drawn = actuator_as_mechanism(act, r)
    assert mech.benders[0].cell is act.cell
    fig, (ax,) = new_figure(1, 1)
    draw_mechanism(ax, mech, drawn, -1)
    labels = ax.get_legend_handles_labels()[1]
    assert "my six-bar joints" in labels and "cell joints" not in labels
    with pytest.raises(ValueError, match="name must be 'actuator'.*got 'b'"):
        actuator_as_mechanism(act, r, name="b")


def test_one_default_cell_for_a_lone_actuator_and_a_bender_the_rod():
    # lamination theory by hand (Timoshenko): EI = E1 I1 + E2 I2 + a1 a2 / (a1 + a2) e^2, per unit width b
    h1, e1, r1, h2, e2, r2 = 0.2e-3, 70e9, 1550.0, 0.3e-3, 30.336e9, 5440.0
    a1, a2, e = e1 * W * h1, e2 * W * h2, (h1 + h2) / 2
    ei = e1 * W * h1**3 / 12 + e2 * W * h2**3 / 12 + a1 * a2 / (a1 + a2) * e**2
    mu = W * (r1 * h1 + r2 * h2)
    f1 = 1.8751040687119611**2 / (2 * np.pi * L**2) * np.sqrt(ei / mu)  # clamped-free Euler-Bernoulli beam
    act = BendingActuator(N, L / N, W, CFC, MFC, PiezoDrive(0.0))
    bender = Bender("b", width=W, passive=CFC, active=MFC, length=L, n_cells=N)
    assert act.cell == bender.cell == "rod"
    # 3 assumed modes of the rotation field converge from above: +2.8e-4 (Rayleigh-Ritz; the benchmark's figure,
    # bench_discretisation.py), against the six-bar cell's +1.2e-1 at 4 cells that was the actuator's default
    for system in (act, Mechanism("m").add(bender).ground(bender.base)):
        rel = atcm.eigenfrequencies(system, n=1)[0] / f1 - 1.0
        assert 0.0 < rel < 5e-4
