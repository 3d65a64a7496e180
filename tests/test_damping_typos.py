"""A damping ratio written as a percentage (issue 29, finding 3): ``damping=5`` meant as 5 % is a ratio of 500 %.

Every place that takes a modal damping ratio warns (``InputRangeWarning``) for a ratio of 1 or
more, naming the parameter and the value, once, at the user's line: ``Bender``, ``BendingActuator``
and ``Flexure`` (``damping=``), ``RayleighDamping.from_damping_ratio`` (``zeta``).  The threshold is
critical damping (ratio 1): a composite laminate has 0.005 ... 0.05, and a ratio below 1 cannot be
told from a percentage (0.5 may be 50 % or a mistyped 0.5 %).
"""

from __future__ import annotations

import math
import warnings

import pytest

from exudyn_atcm import BendingActuator, Bender, Flexure, Layer, Mechanism, PiezoDrive, RayleighDamping, simulate
from exudyn_atcm.errors import InputRangeWarning
from exudyn_atcm.physical_bounds import DAMPING_RATIO_SUSPECT

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)


def bender(damping):
    return Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4, drive=PiezoDrive(0.0),
                  damping=damping, cell="rigid")


def actuator(damping):
    return BendingActuator(4, 7.5e-3, 10e-3, CFC, MFC, PiezoDrive(0.0), cell="rigid", damping=damping)


def flexure(damping):
    return Flexure("f", base=(0.0, 0.0), tip=(0.03, 0.0), width=5e-3, layer=Layer(0.2e-3, 70e9, 1550.0), model="cells", damping=damping)


@pytest.mark.parametrize("make, owner", [(bender, "bender 'b'"), (actuator, "BendingActuator"),
                                         (flexure, "flexure 'f'")])
@pytest.mark.parametrize("ratio, percent", [(5, "500"), (1.0, "100"), (2.5, "250")])
def test_a_damping_ratio_of_one_or_more_warns_naming_damping_and_the_value(make, owner, ratio, percent):
    with pytest.warns(InputRangeWarning) as record:
        part = make(ratio)
    assert len(record) == 1
    message = str(record[0].message)
    assert message.startswith(f"{owner}: damping = {float(ratio)!r} is a damping ratio of {percent} %")
    # the percentage read as meant: 5 -> 0.05
    assert f"give damping={ratio / 100:g}" in message
    assert record[0].filename == __file__  # points at the line that made the part
    assert part.damping == float(ratio)  # warned, not changed


@pytest.mark.parametrize("make", [bender, actuator, flexure])
def test_ratios_below_critical_damping_are_quiet(make):
    # the package's default 0.02 and heavy but possible damping up to just below critical damping
    for ratio in (0.0, 0.02, 0.3, math.nextafter(DAMPING_RATIO_SUSPECT, 0.0)):
        make(ratio)  # any AtcmWarning would be an error here (setup.cfg)


def test_material_damping_from_a_ratio_warns_naming_zeta():
    with pytest.warns(InputRangeWarning, match=r"RayleighDamping\.from_damping_ratio: zeta = 3\.0 is a damping "
                                               r"ratio of 300 %.*give zeta=0\.03") as record:
        d = RayleighDamping.from_damping_ratio(3, 10.0)
    assert record[0].filename == __file__
    assert d.damping_ratio(10.0) == pytest.approx(3.0, rel=1e-14)  # the coefficient is what was asked for
    RayleighDamping.from_damping_ratio(0.02, 10.0)  # quiet
    RayleighDamping.from_log_decrement(5.0, 10.0)  # a decrement always gives a ratio below 1: quiet


def test_the_actuator_warns_once_not_again_when_it_is_simulated_or_drawn():
    # the actuator is solved as a one-bender mechanism built from its own damping: that rebuild is quiet
    with pytest.warns(InputRangeWarning, match="damping = 5.0"):
        act = actuator(5)
    with warnings.catch_warnings():
        warnings.simplefilter("error", InputRangeWarning)
        simulate(act, 2e-3, step=1e-4)


def test_a_flexure_warns_once_not_again_when_its_cells_are_built():
    with pytest.warns(InputRangeWarning, match="damping = 2.0"):
        f = flexure(2.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", InputRangeWarning)
        strip = f.as_bender()
        mech = Mechanism().add(f).ground(f.base)
        simulate(mech, 2e-3, step=1e-4)
    assert strip.damping == 2.0


@pytest.mark.parametrize("bad", [-0.5, float("nan"), "5", None])
def test_invalid_ratios_are_still_refused(bad):
    with pytest.raises(ValueError, match="damping must be"):
        bender(bad)
