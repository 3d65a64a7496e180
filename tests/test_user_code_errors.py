"""Errors of the user's own code during a run (issue 29, finding 8).

A voltage program that raises ``KeyError`` at t = 0.02 s was reported as "did not converge even
after reducing the step size down to 1e-08 s ... Try a smaller step", the ``KeyError`` buried in
the text; a program returning ``None`` gave a bare ``TypeError``; one returning ``"5"`` was taken as
5 V.  Now the user's exception is raised as itself (its type and message) with notes naming the
program, the drive and the simulated time, from a lone actuator, a mechanism, a controller, a load
function, the progress callback and a static solve; a value that is not a number is refused with a
``ValueError`` naming the program and the time.  In the user's own Exudyn model (``add_to``) Exudyn
reports any exception of a user function as its ``ModelError``; the user's exception is its
``__cause__``, unchanged, with the notes.

The times are known independently: with the step 1e-4 s, the first step a program that raises for
``t > 0.02005`` s sees ends at 0.0201 s (the solver asks for the end time of the step being attempted;
the thresholds lie between grid times, away from the round-off of the solver's accumulated time).
"""

from __future__ import annotations

import exudyn as exu
import numpy as np
import pytest

from exudyn_atcm import (BendingActuator, Bender, Layer, Link, Mechanism, PIDController, PiezoDrive, SolverError,
                         add_to, simulate, solve_static)
from exudyn_atcm.mbs import add_post_step, add_pre_step

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
STEP = 1e-4


def failing_program(t: float) -> float:
    """500 V, then a lookup that fails after 0.02 s (the issue's reproducer)."""
    if t > 0.02005:
        return {}["missing"]
    return 500.0


def lone_actuator(program) -> BendingActuator:
    return BendingActuator(4, 7.5e-3, 10e-3, CFC, MFC, PiezoDrive(program), cell="rigid")


def crank_mechanism(program) -> Mechanism:
    """A bender crank with a link pinned to its tip and to the ground (a closed loop)."""
    crank = Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4,
                   drive=PiezoDrive(program), cell="rigid")
    link = Link("link", {"A": (0.03, 0.0), "O": (0.03, 0.02)}, mass=1e-4, inertia=1e-8)
    return (Mechanism("crank_mech").add(crank, link).ground(crank.base).pin(crank.tip, link.point("A"))
            .ground("link.O", joint="pin"))


def notes(exc: BaseException) -> str:
    return "\n".join(getattr(exc, "__notes__", []))


@pytest.mark.parametrize("system, drive", [(lone_actuator, "'actuator'"), (crank_mechanism, "'crank'")])
def test_an_error_of_the_voltage_program_is_raised_as_itself_with_the_drive_and_the_time(system, drive):
    with pytest.raises(KeyError, match="missing") as info:
        simulate(system(failing_program), 0.05, step=STEP)
    assert not isinstance(info.value, SolverError)
    text = notes(info.value)
    assert "raised by the voltage program 'failing_program' at t = 0.0201 s" in text
    assert f"drive {drive}" in text
    # the traceback reaches the program's own line
    assert info.traceback[-1].name == "failing_program"


def test_an_error_at_the_start_names_the_drive():
    def broken(t):
        raise RuntimeError("no table loaded")

    with pytest.raises(RuntimeError, match="no table loaded") as info:
        simulate(crank_mechanism(broken), 0.01, step=STEP)
    assert "at t = 0 s" in notes(info.value) and "drive 'crank'" in notes(info.value)


@pytest.mark.parametrize("value, shown", [(None, "None (NoneType)"), ("5", "'5' (str)"), (True, "True (bool)"),
                                          (np.array([5.0, 6.0]), "(ndarray)")])
@pytest.mark.parametrize("system", [lone_actuator, crank_mechanism])
def test_a_program_returning_no_number_is_refused_naming_the_program_and_the_time(system, value, shown):
    def junk_after_start(t):
        return 0.0 if t < 0.00505 else value

    with pytest.raises(ValueError, match=r"the voltage program '.*junk_after_start' returned ") as info:
        simulate(system(junk_after_start), 0.01, step=STEP)
    message = str(info.value)
    assert shown in message and "at t = 0.0051 s" in message  # the first step after 0.00505 s
    assert "number of volts" in message


def test_numbers_of_any_real_type_are_volts():
    for value in (5, 5.0, np.float32(5.0), np.int64(5), np.array(5.0)):
        assert PiezoDrive(lambda t, v=value: v).voltage_at(0.1) == 5.0
    with pytest.raises(ValueError, match="voltage must be a finite number"):
        PiezoDrive("500")  # the constant form was refused already; the program form now too (above)


class BrokenController(PIDController):
    """A PID controller whose observation fails after 2 ms (a user's subclass with a bug)."""

    def observe(self, t: float, tip_deflection: float) -> None:
        if t > 2.05e-3:
            raise ZeroDivisionError("gain schedule divided by zero")
        super().observe(t, tip_deflection)


def test_an_error_of_a_controller_is_raised_as_itself_naming_it():
    controller = BrokenController(1e4, 0.0, 0.0, sample_time=1e-4, setpoint=1e-4)
    act = BendingActuator(4, 7.5e-3, 10e-3, CFC, MFC, PiezoDrive(controller), cell="rigid")
    with pytest.raises(ZeroDivisionError, match="gain schedule") as info:
        simulate(act, 0.01, step=STEP)
    assert "BrokenController.observe at t = 0.0021 s" in notes(info.value)


def test_an_error_of_the_progress_callback_is_raised_as_itself():
    def progress(t, t_end):
        if t > 0.004:
            raise OSError("the log file is gone")

    with pytest.raises(OSError, match="the log file is gone") as info:
        simulate(lone_actuator(500.0), 0.01, step=STEP, progress=progress)
    assert "progress callback" in notes(info.value)


def test_an_error_of_a_load_function_is_raised_as_itself_dynamic_and_static():
    def force(t):
        if t > 0.00305:
            raise IndexError("force table ends at 3 ms")
        return (0.0, 1e-3)

    mech = crank_mechanism(0.0).force("link.A", force)
    with pytest.raises(IndexError, match="force table") as info:
        simulate(mech, 0.01, step=STEP)
    assert "t = 0.0031 s" in notes(info.value)

    def always(t):
        raise LookupError("no load case selected")

    static = crank_mechanism(0.0).force("link.A", always)
    with pytest.raises(LookupError, match="no load case selected"):
        solve_static(static)  # was a SolverError after a failed static solve and a failed relaxation


# ----------------------------------------------------------------------------- the user's own Exudyn model

def own_system(bender: Bender, adder=None, step_function=None):
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    mbs.variables["test.container"] = sc  # keep the container alive with the system
    add_to(mbs, bender)
    if adder is not None:
        adder(mbs, step_function)
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime = 0.005
    settings.timeIntegration.numberOfSteps = 50  # step 1e-4 s
    settings.solution.file.write = False
    return mbs, settings


def solve_own(mbs, settings) -> BaseException:
    exu.config.printToConsole = False
    try:
        with pytest.raises(Exception) as info:
            mbs.SolveDynamic(settings)
    finally:
        exu.config.printToConsole = True
    return info.value


def test_in_the_users_own_model_the_program_error_is_the_cause_with_its_notes():
    def program(t):
        if t > 0.00205:
            return {}["missing"]
        return 0.0

    bender = Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4, drive=PiezoDrive(program), cell="rigid")
    error = solve_own(*own_system(bender))
    # Exudyn reports a user function's exception as its own ModelError; the user's is its cause
    assert isinstance(error.__cause__, KeyError)
    text = notes(error.__cause__)
    assert "raised by the voltage program" in text and "at t = 0.0021 s" in text
    assert "drive 'b' added by exudyn_atcm.add_to" in text
    assert "drive 'b'" in str(error)  # Exudyn's own message quotes the notes


@pytest.mark.parametrize("adder", [add_pre_step, add_post_step])
def test_in_the_users_own_model_a_step_function_error_is_the_cause_naming_the_function(adder):
    def my_step(mbs, t):
        if t > 0.00105:
            raise RuntimeError("my sensor is offline")
        return True

    bender = Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4, drive=PiezoDrive(0.0), cell="rigid")
    error = solve_own(*own_system(bender, adder, my_step))
    assert isinstance(error.__cause__, RuntimeError) and str(error.__cause__) == "my sensor is offline"
    which = "pre" if adder is add_pre_step else "post"
    assert f"raised by the {which}-step function" in notes(error.__cause__)
    assert "my_step" in notes(error.__cause__) and "t = 0.0011 s" in notes(error.__cause__)
