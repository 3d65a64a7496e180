"""Ctrl-C while ``simulate(..., accuracy=)`` chooses the cells: a SimulationInterrupted saying so, without a result.

Before, the choice's static solves raised a plain KeyboardInterrupt or a SimulationInterrupted "at t = 0 s", as
if the run had started.  The interrupt is made here where the choice measures a count (its static sweep).
"""

from __future__ import annotations

import pytest

import exudyn_atcm as atcm
from exudyn_atcm.solve import cell_choice
from exudyn_atcm.solve.run_checks import SimulationInterrupted

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)


def test_ctrl_c_during_the_cell_choice(monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(cell_choice, "_measure", interrupted)
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells="auto", cell="rod",
                    drive=atcm.PiezoDrive(500.0))
    with pytest.raises(SimulationInterrupted, match=r"^interrupted while choosing the cells .* before any step of "
                                                    r"the run: no result$") as caught:
        atcm.simulate(atcm.Mechanism("m").add(b).ground(b.base), 0.01, accuracy=1e-3)
    assert caught.value.result is None and isinstance(caught.value, KeyboardInterrupt)
