"""Dynamic and static solution and eigenfrequencies of a :class:`~exudyn_atcm.mechanism.actuator.BendingActuator`.

Hysteresis inside the solver step
---------------------------------
The drive's hysteresis operator is evaluated from its *committed* memory for the voltage at
the time ``t`` of the step being attempted (Exudyn passes the step's end time to every hook),
and committed only in the post-step hook, which Exudyn calls for accepted steps only.  A step
that Exudyn rejects and repeats with a smaller step size therefore leaves no trace in the
memory, and the recorded strain equals the operator applied offline to the recorded
voltages (tested).  The strain is evaluated once per attempted step (cached by ``t``) and
written into the model in a pre-step hook; see :mod:`exudyn_atcm.mbs.actuation` for why this
is the same as an offset user function.  A :class:`~exudyn_atcm.mechanism.actuator.BendingActuator`
is solved as its one-bender mechanism (:mod:`exudyn_atcm.solve.as_mechanism`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, Callable

import numpy as np

from .._checks import finite_float, positive_float, positive_int, shown
from ..mechanism.actuator import BendingActuator
from ..mechanism import Mechanism
from ..io.result import Result
from ..model.strain_sources import InStepStrain
from ..mbs import builder as mb, solver_runs as runs
from . import mechanism_solve
from .as_mechanism import actuator_interrupts, actuator_result
from .bender_checks import check_benders
from .run_setup import DEFAULT_STEP
from .cell_choice import choose_cells, open_benders
from .impact_check import impacts_checked
from .step_choice import accurate_run, check_accuracy, check_step_or_accuracy


# ------------------------------------------------------------------------------ argument checks

def _mechanism_only(tip_force: Any) -> None:
    """A mechanism carries its loads itself (``mechanism.force``); ``tip_force`` is for a lone actuator."""
    if tuple(np.ravel(np.asarray(tip_force, dtype=float))) != (0.0, 0.0):
        raise ValueError(f"tip_force is for a BendingActuator; load a Mechanism with mechanism.force(point, "
                         f"(Fx, Fy)), got tip_force={tip_force!r}")


def _check_actuator(actuator: Any) -> BendingActuator:
    if not isinstance(actuator, BendingActuator):
        raise ValueError(f"actuator must be a BendingActuator, got {shown(actuator)}")
    return actuator




# ------------------------------------------------------------------------------ static solve
def solve_static(
    system: BendingActuator | Mechanism,
    *,
    voltage: float | Mapping[str, float] | None = None,
    tip_force: tuple[float, float] = (0.0, 0.0),
    load_steps: int | None = None,
) -> Result:
    """Static equilibrium at a voltage and a dead tip load (geometrically nonlinear).

    Parameters
    ----------
    system : BendingActuator or Mechanism
        The actuator; its drive gives the voltage-to-strain law.  A
        :class:`~exudyn_atcm.Mechanism` is solved with its own loads (``tip_force`` must stay
        zero) and gives the columns listed on the :doc:`/mechanisms` page.
    voltage : float or mapping, optional
        Voltage [V].  Default: the drive's voltage at ``t = 0``.  For a mechanism: a number
        for every drive, or ``{drive_name: volts}``.  With a hysteresis
        operator, the voltage is reached by a monotone ramp from the operator's reset state.
    tip_force : (float, float), optional
        Dead load ``(Fx, Fy)`` [N] at the tip, in global coordinates.
        A :class:`~exudyn_atcm.BendingActuator` only, and a shorthand: the force on the tip of its
        one-bender mechanism (``solve(actuator.as_mechanism(tip_force))`` gives the same numbers; a
        :class:`~exudyn_atcm.Mechanism` takes its loads from ``mechanism.force``).
    load_steps : int, optional
        Number of equal load steps in which strain and load are raised from zero together
        (each step is halved adaptively if Newton fails).  Default: about one step per
        0.05 rad of expected tip rotation, at least 4.  If Exudyn's static iteration stalls
        (large tip forces, see Notes), the equilibrium is found by dynamic relaxation and
        polished with one static step; ``result.info["solver"]`` says which path was taken.

    Returns
    -------
    Result
        One row, with the series of :func:`simulate` (``time`` is 0).

    Raises
    ------
    ValueError
        For a non-finite voltage or force, or a wrong argument type.
    SolverError
        If the equilibrium iteration does not converge.

    Notes
    -----
    Exudyn's static Newton Jacobian leaves out the derivative of the constraint forces; under
    large tip forces the iteration then converges ever more slowly and can stall.  A warning
    is issued when one cell turns by more than 0.5 rad against its neighbour (coarse chain).
    """
    actuator = system
    if isinstance(actuator, Mechanism):
        _mechanism_only(tip_force)

        return mechanism_solve.solve_static(actuator, voltage, load_steps)
    actuator = _check_actuator(actuator)
    mech = actuator.as_mechanism(tip_force)
    volts = None if voltage is None else finite_float("voltage", voltage)
    return actuator_result(actuator, mechanism_solve.solve_static(mech, volts, load_steps))


# ------------------------------------------------------------------------------ dynamic solve

def simulate(
    system: BendingActuator | Mechanism,
    t_end: float,
    *,
    step: float | None = None,
    tip_force: tuple[float, float] = (0.0, 0.0),
    settings: Callable[[Any], None] | dict | None = None,
    progress: Callable[[float, float], None] | None = None,
    record_every: int | float | None = None,
    accuracy: float | None = None,
) -> Result:
    """Dynamic response of the actuator to its voltage program (generalized-alpha).

    The run starts from the static equilibrium at the voltage ``U(0)`` and the tip force
    (the hysteresis operator is reset and then fed ``U(0)``), then integrates to ``t_end``.
    Every accepted step is committed to the hysteresis memory; ``record_every`` chooses which
    are recorded.

    Parameters
    ----------
    system : BendingActuator or Mechanism
        The actuator, with its drive (voltage program, optional hysteresis operator), or a
        :class:`~exudyn_atcm.Mechanism` (its own loads; ``tip_force`` must stay zero; columns
        as listed on the :doc:`/mechanisms` page).
    t_end : float
        End time [s], > 0.
    step : float, optional
        Time step [s], > 0 and <= ``t_end``; default (``None``) 1e-4, or the step ``accuracy``
        chooses.  A step that does not divide
        ``t_end`` is replaced by ``t_end / ceil(t_end / step)`` with a warning, and the step
        used is recorded (``info["step [s]"]``; the request in ``info["step_requested [s]"]``).
        Exudyn halves it temporarily when a step's Newton iteration fails (those steps are
        repeated, not recorded).
    tip_force : (float, float), optional
        Dead load ``(Fx, Fy)`` [N] at the tip, in global coordinates, constant in time.
        A :class:`~exudyn_atcm.BendingActuator` only, and a shorthand: the force on the tip of its
        one-bender mechanism (``solve(actuator.as_mechanism(tip_force))`` gives the same numbers; a
        :class:`~exudyn_atcm.Mechanism` takes its loads from ``mechanism.force``).
    settings : callable or dict, optional
        Adjusts the underlying ``exudyn.SimulationSettings`` after the package defaults are
        set: a callable receiving the settings object, or a dict of dotted names, e.g.
        ``{"timeIntegration.newton.maxIterations": 12}``.
    progress : callable, optional
        ``progress(t, t_end)`` is called with the simulated time [s] about every 1 % of
        ``t_end`` and at least every 0.5 s of wall time (for progress bars).  It may raise
        ``KeyboardInterrupt`` to stop the run (see Raises).
    record_every : int or float, optional
        Recording interval: ``None`` (default) or ``0`` records every accepted step (``0`` as
        on the command line, ``--set record_every=0``); an ``int`` ``n`` every ``n``-th accepted
        step; a ``float`` an interval in seconds (a multiple of the step gives evenly spaced
        records).  The first and the last instant are always
        recorded.  The solution is the same; only memory and output shrink.
    accuracy : float, optional
        Wanted largest error of the recorded positions (the columns in metres) relative to
        their travel [-], in [1e-6, 0.1], e.g. ``1e-3``: the step is chosen for it instead of
        given (not together with ``step``).  The lowest eigenfrequency about the start state,
        the damping and the drives' strain (corners, and the hysteresis' slope jumps at every
        reversal) predict the step through a one-mode stand-in; one probe run at twice the step
        measures the run's error (Richardson), and a missed target refines the step once
        (:mod:`exudyn_atcm.solve.step_choice`).  ``result.info["step_choice"]`` says what was
        chosen and why, ``info["accuracy"]`` the numbers; a display with ``stage`` (the command
        line's progress bar) shows it.  A mechanism's benders built with ``n_cells="auto"``
        (or ``cell="auto"``) get their cells chosen first, for 0.3 of ``accuracy``
        (:func:`~exudyn_atcm.choose_cells`; ``info["cell_choice"]``), and the step for what twice
        their estimated error leaves (at least 0.7 of it).

    Returns
    -------
    Result
        A lone actuator: its one-bender mechanism's series (``time``, ``actuator.voltage``,
        ``actuator.strain``, ``actuator.base_x`` ... ``actuator.tip_y``, ``actuator.tip_angle``,
        ``actuator.cell_angle_1..N``) plus ``actuator.stroke``; the names before 0.3.0 (``tip_y``,
        ...) are readable for one release with an :class:`~exudyn_atcm.AtcmDeprecationWarning`.
        ``result.info`` holds the step used, the number of
        accepted, attempted and rejected steps, the recording interval (and, in closed loop,
        the controller's ``summary()`` under ``"controller"``).

    Closed loop: if the drive holds a controller (:mod:`exudyn_atcm.model.control`), it is reset at
    the start, the voltage of every attempted step is its ``voltage_at(t)``, and after each
    accepted step (hysteresis committed) it observes the step's tip deflection ``actuator.tip_y``
    (a mechanism: the result column declared with
    :meth:`Mechanism.feedback <exudyn_atcm.Mechanism.feedback>`; a controller without one
    is refused).
    A ``RuntimeWarning`` says when its output was held at a limit.

    Raises
    ------
    ValueError
        For ``step`` and ``accuracy`` together, an ``accuracy`` outside [1e-6, 0.1],
        non-positive or non-finite ``t_end``/``step``, a bad ``tip_force``, ``settings``
        or ``record_every``, or a step too coarse for the voltage program (fewer than
        :data:`~exudyn_atcm.solve.run_checks.MIN_STEPS_PER_FEATURE` steps across its shortest
        ramp, half period or dwell).
    SolverError
        If the time integration fails; the message gives the time reached.
    SimulationInterrupted
        On Ctrl-C (``KeyboardInterrupt`` in the solver's hooks, the voltage program or
        ``progress``): a ``KeyboardInterrupt`` whose ``result`` holds the steps computed so
        far (``info["partial"]`` True, ``info["interrupted_at [s]"]``).  With ``accuracy``, the
        message and ``info["interrupted_in"]`` say which run of the choice stopped (the probe at
        twice the step, the run, or its refinement) and at which step.

    Warns
    -----
    RuntimeWarning
        A step that resolves the voltage program or the first bending mode only coarsely, a
        step that does not divide ``t_end``, a run predicted to take long, voltages outside
        the hysteresis operator's input range or the MFC's rating, a non-zero program that
        peaks below 0.2 % of the rating (3 V: written in kV?), a program whose shortest
        feature lasts more than 100 runs (a period in ms?), implausible strains.
    AccuracyWarning
        With ``accuracy``: when the run's estimated error still misses it after one refinement.

    Notes
    -----
    Defaults: generalized-alpha with spectral radius 0.8, modified Newton, absolute Newton
    tolerance 1e-8 (SI units), sparse linear solver, adaptive step reduction on Newton failure.
    The step checks and their thresholds are described in :mod:`exudyn_atcm.solve.run_checks`.
    """
    if check_step_or_accuracy(step, accuracy) is not None:
        return _accurate(system, t_end, accuracy, tip_force, settings, progress, record_every)
    step = DEFAULT_STEP if step is None else step
    actuator = system
    if isinstance(actuator, Mechanism):
        _mechanism_only(tip_force)

        result = mechanism_solve.simulate(actuator, t_end, step, settings, progress, record_every)
        check_benders(actuator, result, stacklevel=3)  # every bender's cell-kind checks; warnings at the caller
        return result
    actuator = _check_actuator(actuator)
    if progress is not None and not callable(progress):
        raise ValueError(f"progress must be None or a callable progress(t, t_end), got {shown(progress)}")
    # the mechanism solve is called from here (and from run_actuator) directly: as many frames between the
    # caller and the run checks as for a mechanism, so their warnings point at the caller's line
    mech = actuator.as_mechanism(tip_force)
    with actuator_interrupts(actuator):
        result = mechanism_solve.simulate(mech, t_end, step, settings, progress, record_every)
    return _finish_actuator_run(actuator, mech, result, "prestep")


def _accurate(system: Any, t_end: Any, accuracy: Any, tip_force: Any, settings: Any, progress: Any,
              record_every: Any) -> Result:
    """:func:`simulate` with ``accuracy``: the step chosen by :func:`~exudyn_atcm.solve.step_choice.accurate_run`."""
    accuracy = check_accuracy(accuracy)
    t_end = positive_float("t_end", t_end)
    if progress is not None and not callable(progress):
        raise ValueError(f"progress must be None or a callable progress(t, t_end), got {shown(progress)}")
    choice = None
    if isinstance(system, Mechanism):
        _mechanism_only(tip_force)
        if open_benders(system):  # the cells first, with their share of the accuracy; the step gets the rest
            choice = choose_cells(system, t_end, accuracy, progress=progress)
            system = choice.mechanism
        mech = system
    else:
        actuator = _check_actuator(system)
        mech = actuator.as_mechanism(tip_force)
    # one build (the cells' choice's, or a new one): the prediction, the probe and the run start from its built state
    model = choice.built if choice is not None and choice.built is not None else mb.build(mech)
    initial = runs.save_state(model)

    def fresh() -> mb.MechanismModel:
        runs.restore_state(model, initial)
        return model

    if isinstance(system, Mechanism):
        def run(h: float, prog: Any, t_stop: float) -> Result:
            result = mechanism_solve.simulate(system, t_stop, h, settings, prog, record_every, built=fresh())
            check_benders(system, result, stacklevel=5)
            return result
    else:
        def run(h: float, prog: Any, t_stop: float) -> Result:
            with actuator_interrupts(actuator):
                result = mechanism_solve.simulate(mech, t_stop, h, settings, prog, record_every, built=fresh())
            return _finish_actuator_run(actuator, mech, result, "prestep")
    if choice is None:
        return accurate_run(run, mech, t_end, accuracy, progress, stacklevel=4, record_every=record_every, built=fresh)
    result = accurate_run(run, mech, t_end, choice.step_target(accuracy), progress, stacklevel=4,
                          record_every=record_every, built=fresh)
    return choice.noted(impacts_checked(choice, result, accuracy, t_end, settings, record_every), accuracy)


def run_actuator(actuator, t_end, step, tip_force, settings, source=None, stroke_path="prestep",
                 progress=None, record_every=None) -> Result:
    """:func:`simulate` of a lone actuator with the choices tests and benchmarks compare.

    Internal API (documented for tests and benchmarks): ``source`` is the strain source
    (:class:`~exudyn_atcm.model.strain_sources.InStepStrain` by default, or a
    :class:`~exudyn_atcm.model.strain_sources.TableStrain`) and ``stroke_path`` how the strain reaches
    the model (:attr:`exudyn_atcm.cells.CellKind.stroke_paths`).
    The other arguments are those of :func:`simulate`, all positional here.
    """
    actuator = _check_actuator(actuator)
    controller = getattr(actuator.drive, "controller", None)
    if controller is not None and source is not None and not isinstance(source, InStepStrain):
        raise ValueError(
            f"a drive with a controller needs the in-step strain source, got {type(source).__name__}: "
            "the voltage depends on the simulated response and cannot be tabulated beforehand"
        )
    mech = actuator.as_mechanism(tip_force)
    with actuator_interrupts(actuator):
        result = mechanism_solve.simulate(mech, t_end, step, settings, progress, record_every,
                                          sources=None if source is None else [source], stroke_path=stroke_path)
    return _finish_actuator_run(actuator, mech, result, stroke_path)


def _finish_actuator_run(actuator: BendingActuator, mech: Mechanism, result: Result, stroke_path: str) -> Result:
    """The actuator's result of its one-bender mechanism's run, checked by its cell kind as any bender is."""
    result.info["stroke_path"] = stroke_path
    check_benders(mech, result, stacklevel=4)  # the caller of simulate
    return actuator_result(actuator, result)


# ------------------------------------------------------------------------------ quasi-static sweep

def static_sweep(system: BendingActuator | Mechanism, voltages: Sequence[float] | Mapping[str, Sequence[float]], *,
                 tip_force: tuple[float, float] = (0.0, 0.0), method: str = "continuation") -> Result:
    """Quasi-static path over a voltage sequence, following the hysteresis.

    Each point continues from the previous equilibrium and the previous hysteresis memory
    (the operators are reset before the first point; between points the voltage is taken to
    change monotonically, so each point commits its voltage once).  No dynamics: for path and
    function generation.

    Parameters
    ----------
    system : BendingActuator or Mechanism
        The actuator, or a mechanism with its loads (held constant along the sweep).
    voltages : sequence of float, or mapping of drive name to sequence
        Voltages [V] of all drives at each point, or per drive (equal lengths; drives not
        named follow their program at t = 0 throughout).
    tip_force : (float, float), optional
        Dead tip load [N], constant along the sweep.
        A :class:`~exudyn_atcm.BendingActuator` only, and a shorthand: the force on the tip of its
        one-bender mechanism (``solve(actuator.as_mechanism(tip_force))`` gives the same numbers; a
        :class:`~exudyn_atcm.Mechanism` takes its loads from ``mechanism.force``).
    method : {"continuation", "points"}, optional
        ``"continuation"`` (default): the system is built once and every point after the first is
        one static load step from the previous equilibrium (halved by the solver where its Newton
        iteration fails), with the Newton tolerances of a single solve; a point where that step
        fails or ends unstable is solved as its own equilibrium, as ``"points"`` does, and
        ``result.info["fallback_points"]`` says which and why.  ``"points"``: every point is its
        own static solve in load steps from the previous equilibrium (the sweep before the
        continuation; slower, the same equilibria within the solver tolerance).

    Returns
    -------
    Result
        One row per point; the first column ``point [-]`` holds the point's index (0, 1, 2, ...;
        a sweep has no time), then the columns of :func:`exudyn_atcm.simulate` for the
        mechanism (``{drive}.voltage [V]`` holds each point's voltage), or for the actuator.

    Warns
    -----
    RuntimeWarning
        Once per drive, naming it, for voltages outside its hysteresis operator's input range
        or its rating, and implausible free strains (as for an actuator).
    """
    if isinstance(system, Mechanism):
        _mechanism_only(tip_force)
        return mechanism_solve.static_sweep(system, voltages, method=method)
    if not isinstance(system, BendingActuator):
        raise ValueError(f"static_sweep takes a Mechanism or a BendingActuator, got {shown(system)}")
    mech = system.as_mechanism(tip_force)
    return actuator_result(system, mechanism_solve.static_sweep(mech, voltages, method=method))


# ------------------------------------------------------------------------------ eigenfrequencies

def eigenfrequencies(
    system: BendingActuator | Mechanism,
    *,
    n: int = 3,
    voltage: float | None = None,
    tip_force: tuple[float, float] = (0.0, 0.0),
) -> np.ndarray:
    """Lowest eigenfrequencies [Hz] of the undamped actuator about a static equilibrium.

    Without ``voltage`` and ``tip_force`` the equilibrium is the undeformed state (motor
    strokes zero, no load).  With them, the static equilibrium at that voltage and dead tip
    load is found first (as :func:`solve_static` does) and the actuator is linearised about
    it, with the drive strain held at its equilibrium value.

    Parameters
    ----------
    system : BendingActuator or Mechanism
        The actuator, or a mechanism.
    n : int, optional
        Number of frequencies, >= 1 (default 3).
    voltage : float or mapping, optional
        Operating voltage [V] (a mechanism: a number for every drive or ``{drive_name: volts}``);
        default: no actuation (strain 0, not the program's ``U(0)``).  With a hysteresis
        operator the strain is the one reached by a monotone ramp from the operator's reset
        state, as in :func:`solve_static`.
    tip_force : (float, float), optional
        Dead load ``(Fx, Fy)`` [N] at the tip, in global coordinates.
        A :class:`~exudyn_atcm.BendingActuator` only, and a shorthand: the force on the tip of its
        one-bender mechanism (``solve(actuator.as_mechanism(tip_force))`` gives the same numbers; a
        :class:`~exudyn_atcm.Mechanism` takes its loads from ``mechanism.force``).

    Returns
    -------
    numpy.ndarray
        The ``n`` lowest eigenfrequencies [Hz], ascending.  For a slender actuator these are
        its bending modes; the six-bar cell's shear and axial modes lie far above.  An
        unstable equilibrium (e.g. a buckling compressive tip load) gives negative values
        and a ``RuntimeWarning``.

    Raises
    ------
    ValueError
        For ``n < 1`` or more than the degrees of freedom, a non-finite voltage or force.
    SolverError
        If the static equilibrium does not converge.

    Notes
    -----
    The tangent stiffness includes the geometric stiffness of the joints' constraint forces,
    which Exudyn's ``ComputeODE2Eigenvalues`` leaves out: about a bent six-bar chain (joints
    carrying the layers' axial forces, ~50 N at 1500 V on the reference bender) or any chain
    under a tip load, Exudyn's routine gives wrong frequencies (-67 % at 4 cells, +151 % at
    16 cells at 1500 V).  See :mod:`exudyn_atcm.mbs.eigen`.
    """
    actuator = system
    if isinstance(actuator, Mechanism):
        _mechanism_only(tip_force)

        return mechanism_solve.eigenfrequencies(actuator, n, voltage)
    actuator = _check_actuator(actuator)
    n = positive_int("n", n)
    mech = actuator.as_mechanism(tip_force)
    volts = None if voltage is None else finite_float("voltage", voltage)
    return mechanism_solve.eigenfrequencies(mech, n, volts, loaded=bool(mech.forces))
