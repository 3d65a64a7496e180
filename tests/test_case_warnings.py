"""Warnings only for what the user did (issue 17, part 2): a case's internal solves are silent, and the
value the user gave is checked against the ratings once per run, quoted as given.

Reference: the MFC P1's rated range, -500 ... +1500 V (Smart Material data sheet), which a 5000 V
drive exceeds and 1500 V does not.
"""

from __future__ import annotations

import warnings

import pytest

from exudyn_atcm.casework import load_case

from _cli_helpers import CASES


@pytest.fixture(scope="module")
def optimise_bender():
    return load_case(CASES / "optimise_bender.py")


@pytest.mark.parametrize("kinematics", ["linear", "nonlinear"])
def test_evaluating_a_design_on_its_defaults_gives_no_warning(optimise_bender, kinematics):
    """The linear solve at 1/1000 of the voltage (1.5 V) used to warn 'if the program is in kV'."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = optimise_bender.run({"mode": "evaluate", "kinematics": kinematics})
    assert out.scalars["tip_deflection"] > 0.0


def test_a_voltage_beyond_the_rating_is_warned_once_quoting_it(optimise_bender):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        optimise_bender.run({"mode": "evaluate", "voltage": 5000.0})
    messages = [str(w.message) for w in record if issubclass(w.category, RuntimeWarning)]
    assert len(messages) == 1, messages
    assert "voltage=5000 V" in messages[0] and "rated range -500 ... 1500 V" in messages[0]
