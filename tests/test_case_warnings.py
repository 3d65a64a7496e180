"""Warnings only for what the user did (issue 17, part 2): a case's internal solves are silent, and the
value the user gave is checked against the ratings once per run, quoted as given.

Reference: the MFC P1's rated range, -500 ... +1500 V (Smart Material data sheet), which a 5000 V
drive exceeds and 1500 V does not.
"""

from __future__ import annotations

import warnings

import pytest

from exudyn_atcm.casework import load_case, load_cases
from exudyn_atcm.errors import AtcmWarning, InputRangeWarning

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


# ----------------------------------------------------------------------------- every case, once, as typed
#: Every shipped case, each run with the smoke settings its file declares (``Case(..., smoke=...)``: about
#: 25 s in all, measured on an idle machine). A case without settings runs on its defaults; the others are
#: shortened (fewer cycles, a rigid chain, no animation) in ways that change no check the defaults pass.
SHIPPED = sorted(p.stem for p in CASES.glob("*.py") if p.stem != "__init__")


def test_every_shipped_case_loads_with_its_declarations():
    cases, failed = load_cases(CASES, package=False)
    assert failed == []
    assert sorted(c.name for c in cases) == SHIPPED
    # the settings a smoke test needs, where the defaults are not cheap (the GIF, a six-bar chain, an optimisation)
    smoke = {c.name: c.smoke for c in cases}
    assert smoke["paper_bending_actuator"] == {"cycles": 1, "cell": "rigid", "animation": False}
    assert smoke["optimise_bender"] == {"maxiter": 3, "check_nonlinear": False}
    assert smoke["paper_stroke_table"] == {}


@pytest.mark.parametrize("name", SHIPPED)
def test_no_package_warning_on_the_defaults(name):
    case = load_case(CASES / f"{name}.py")
    with warnings.catch_warnings():
        warnings.simplefilter("error", AtcmWarning)
        case.run(case.smoke, plot=False)


@pytest.mark.parametrize("name, settings, quoted", [
    # one value typed, one warning quoting it (the ramp's or the segments' voltages used to warn one by one:
    # 2000, 3000, 4000 and 5000 V twice each; four drives each)
    ("stiffness_comparison", {"voltage": 5000.0}, "voltage=5000 V (the ramp 0 ... 5000 V): the voltage program spans "
                                                  "0 ... 5000 V: they reach 5000 V, 3500 V above the MFC's rated range"),
    ("parallel_guide", {"voltage": 5000.0}, "voltage=5000 V (the segments at +U and -U): the voltage program spans "
                                            "-5000 ... 5000 V: they reach 5000 V, 3500 V above and reach -5000 V, "
                                            "4500 V below the MFC's rated range -500 ... 1500 V"),
    # a voltage typed in kV: quoted as typed (the ramp's first solve used to report 0.3 V, optimise_bender's
    # internal solve 0.0015 V)
    ("stiffness_comparison", {"voltage": 1.5}, "voltage=1.5 V (the ramp 0 ... 1.5 V): the voltage program peaks at "
                                               "|U| = 1.5 V, below 3 V"),
    ("parallel_guide", {"voltage": 1.5}, "voltage=1.5 V (the segments at +U and -U): the voltage program peaks at "
                                         "|U| = 1.5 V, below 3 V"),
    ("optimise_bender", {"mode": "evaluate", "voltage": 1.5}, "voltage=1.5 V: the voltage program peaks at |U| = 1.5 V"),
])
def test_a_voltage_typed_is_warned_once_quoting_it(name, settings, quoted):
    with pytest.warns(InputRangeWarning) as record:
        load_case(CASES / f"{name}.py").run(settings, plot=False)
    messages = [str(w.message) for w in record]
    assert len(messages) == 1 and messages[0].startswith(quoted), messages
    advice = "multiply it by 1000" if settings["voltage"] == 1.5 else "(rated_range of the PiezoDrive)"
    assert advice in messages[0]


def test_an_optimisation_warns_once_for_all_its_designs(optimise_bender):
    # every design the optimiser evaluates is a run of the same case with the same voltage: one warning
    with pytest.warns(InputRangeWarning) as record:
        optimise_bender.run({"voltage": 5000.0, "maxiter": 1, "popsize": 2, "check_nonlinear": False}, plot=False)
    messages = [str(w.message) for w in record]
    assert len(messages) == 1 and messages[0].startswith("voltage=5000 V: the voltage program spans 5000 ... 5000 V")


def test_a_loop_beyond_the_rating_is_warned_before_the_model_refuses_it():
    # u_max = 5000 V with the paper's 500 V precision point gives r1 < 1 (not a loop): the refusal follows
    # the warning that names the typed voltages against the rating (-500 ... +1500 V)
    case = load_case(CASES / "paper_hysteresis_loop.py")
    with pytest.warns(InputRangeWarning) as record, pytest.raises(ValueError, match="y_m1 = .* lies above the straight line"):
        case.run({"u_max": 5000.0}, plot=False)
    messages = [str(w.message) for w in record]
    assert len(messages) == 1 and messages[0].startswith(
        "u_min=-500 V, u_max=5000 V: the voltage program spans -500 ... 5000 V: they reach 5000 V, 3500 V above "
        "the MFC's rated range -500 ... 1500 V"), messages


def test_a_voltage_program_in_kilovolts_is_warned_in_the_hysteresis_only_case():
    """``paper_discrete_preisach`` has no drive, so nothing checked its corners against the rating: typed in kV
    (-0.5, 1.5, 0 for -500, 1500, 0 V) the run showed a response a thousand times too small, silently."""
    case = load_case(CASES / "paper_discrete_preisach.py")
    with pytest.warns(InputRangeWarning, match=r"voltage_points=-0\.5, 1\.5, 0 V: the voltage program peaks at "
                                               r"\|U\| = 1\.5 V, below 3 V .* if the program is in kV"):
        case.run({"voltage_points": (-0.5, 1.5, 0.0)}, plot=False)
