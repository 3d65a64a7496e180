"""A drive's small-signal gain that is zero (a Preisach operator just after a reversal) is warned about.

The paper's strain operator leaves a reversal horizontally for hundreds of volts: on the reversal branch at
750 V the gain over 1 or 20 V was 0 and ``linearise`` returned a model without that input, silently (a PID
tuned as ``kp = 0.5 / K0`` then divides by zero).  Reference: the operator's own outputs along the branch's
history (equal at 750 V and 730 V), and the ascending branch's non-zero gain at the same voltage.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.model.drive_gain import drive_gain
from exudyn_atcm.model.parameter_sets import paper_strain_preisach

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)


def drive() -> atcm.PiezoDrive:
    return atcm.PiezoDrive(0.0, hysteresis=paper_strain_preisach())


def test_a_flat_reversal_branch_is_warned_and_the_ascending_one_is_not():
    op = paper_strain_preisach()
    y = np.asarray(op.apply([-500.0, 750.0, 730.0]))
    assert y[1] == y[2]  # flat over the 20 V after the reversal: the gain the warning is about is 0
    with pytest.warns(atcm.AccuracyWarning, match=r"drive 'd': its small-signal gain on the reversal branch at 750 V "
                                                  r"over voltage_step 20 V is 0") as caught:
        gain = drive_gain(drive(), 750.0, "reversal", voltage_step=20.0, name="d")
    assert gain.gain == 0.0 and caught[0].filename == __file__
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert drive_gain(drive(), 750.0, "ascending", voltage_step=20.0, name="d").gain > 0.0


def test_linearise_on_the_flat_branch_warns_at_its_caller():
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=3, cell="rod", drive=drive())
    m = atcm.Mechanism("m").add(b).ground(b.base)
    with pytest.warns(atcm.AccuracyWarning, match=r"is 0: the hysteresis operator is flat there") as caught:
        lin = atcm.linearise(m, voltage=750.0, outputs=["b.tip_y"], branch="reversal", voltage_step=20.0)
    assert [w.filename for w in caught if issubclass(w.category, atcm.AccuracyWarning)] == [__file__]
    assert np.all(lin.dc_gain() == 0.0)
