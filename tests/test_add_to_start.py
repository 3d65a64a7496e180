"""``add_to`` says when a program starting at 0 V still strains its drive at t = 0 (the hysteresis's reset state).

The system ``add_to`` builds starts undeformed; its docstring advised starting the programs at 0 V, but the
paper's strain operator gives a strain at 0 V from its reset state, so the first step applied it at once and
the bender rang (3.4 % of the run's peak for 20 ms in the audit), silently.  Reference: the operator's own
output at 0 V from its reset state.
"""

from __future__ import annotations

import warnings

import exudyn as exu
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.model import Triangle
from exudyn_atcm.model.parameter_sets import paper_strain_preisach

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)


def bender(program, hysteresis=None) -> atcm.Bender:
    return atcm.Bender("bender", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4, cell="rigid",
                       drive=atcm.PiezoDrive(program, hysteresis=hysteresis))


def test_a_program_at_0_v_with_a_strained_reset_state_is_warned():
    op = paper_strain_preisach()
    op.reset()
    at_rest = float(op.evaluate(0.0))
    assert at_rest != 0.0  # what the warning is about
    mbs = exu.SystemContainer().AddSystem()
    with pytest.warns(atcm.SetupWarning, match=rf"has the strain {at_rest:.3g} at 0 V") as caught:
        atcm.add_to(mbs, bender(Triangle(750.0, 750.0, 0.2), paper_strain_preisach()))
    assert caught[0].filename == __file__


def test_a_linear_drive_at_0_v_is_silent():
    mbs = exu.SystemContainer().AddSystem()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        atcm.add_to(mbs, bender(Triangle(750.0, 750.0, 0.2)))
