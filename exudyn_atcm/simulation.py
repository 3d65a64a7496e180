"""Dynamic and static solution and eigenfrequencies of a :class:`~exudyn_atcm.actuator.BendingActuator`.

Hysteresis inside the solver step
---------------------------------
The drive's hysteresis operator is evaluated from its *committed* memory for the voltage at
the time ``t`` of the step being attempted (Exudyn passes the step's end time to every hook),
and committed only in the post-step hook, which Exudyn calls for accepted steps only.  A step
that Exudyn rejects and repeats with a smaller step size therefore leaves no trace in the
memory, and the recorded strain equals the operator applied offline to the recorded
voltages (tested).  The strain is evaluated once per attempted step (cached by ``t``) and
written into the model in a pre-step hook; see :mod:`exudyn_atcm._mbs_builder` for why this
is the same as an offset user function.
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Callable

import numpy as np

from . import _mbs_builder as builder
from ._checks import finite_float, positive_float, positive_int
from .actuator import BendingActuator
from .result import Result

#: Default time step of :func:`simulate` [s] (EXUDYN_NOTES.md: converged to 2e-7 m at 10 cells).
DEFAULT_STEP = 1e-4

_STANDARD_UNITS = {
    "time": "s",
    "voltage": "V",
    "strain": "-",
    "stroke": "m",
    "tip_x": "m",
    "tip_y": "m",
    "tip_angle": "rad",
}


class SolverError(RuntimeError):
    """The multibody solver failed; the message says where, what was tried and what to change."""


# ------------------------------------------------------------------------------ strain sources

class InStepStrain:
    """Strain source with the hysteresis operator evaluated in the solver step.

    ``trial(t)`` gives the strain for the step ending at ``t`` from the committed memory
    (cached per ``t``, so one evaluation per attempted step); ``commit(t)`` accepts the step.
    """

    def __init__(self, drive) -> None:
        self.drive = drive
        self.hysteresis = drive.hysteresis
        self._t = None
        self._u = 0.0
        self._strain = 0.0
        self.evaluations = 0
        if self.hysteresis is not None:
            self.hysteresis.reset()

    def trial(self, t: float) -> float:
        if t != self._t:
            u = self.drive.voltage_at(t)
            if self.hysteresis is None:
                strain = self.drive.linear_strain(u)
            else:
                strain = float(self.hysteresis.evaluate(u))
                self.evaluations += 1
            self._t, self._u, self._strain = t, u, strain
        return self._strain

    def commit(self, t: float) -> tuple[float, float]:
        # the voltage of the accepted step was computed for its trial (same t)
        u = self._u if t == self._t else self.drive.voltage_at(t)
        if self.hysteresis is None:
            strain = self.drive.linear_strain(u)
        else:
            strain = float(self.hysteresis.commit(u))
        # the next trial at this t (none in normal operation) must see the new memory
        self._t = None
        return u, strain


class TableStrain:
    """Strain from a precomputed table of (time, voltage, strain), linearly interpolated.

    The paper's approach (its Fig. 9): the hysteresis is applied offline to the voltage
    program on a time grid and the motor follows the table.  Used by the benchmarks.
    """

    def __init__(self, times: np.ndarray, voltages: np.ndarray, strains: np.ndarray) -> None:
        self.times = np.asarray(times, dtype=float)
        self.voltages = np.asarray(voltages, dtype=float)
        self.strains = np.asarray(strains, dtype=float)
        self._t = None
        self._strain = 0.0

    @classmethod
    def from_drive(cls, drive, t_end: float, step: float) -> "TableStrain":
        n = int(math.ceil(t_end / step - 1e-9))
        times = np.linspace(0.0, n * step, n + 1)
        volts = np.array([drive.voltage_at(t) for t in times])
        if drive.hysteresis is None:
            strains = drive.linear_strain(volts)
        else:
            strains = drive.hysteresis.apply(volts)
        return cls(times, volts, strains)

    def trial(self, t: float) -> float:
        if t != self._t:
            self._t = t
            self._strain = float(np.interp(t, self.times, self.strains))
        return self._strain

    def commit(self, t: float) -> tuple[float, float]:
        return float(np.interp(t, self.times, self.voltages)), float(np.interp(t, self.times, self.strains))


# ------------------------------------------------------------------------------ argument checks

def _check_actuator(actuator: Any) -> BendingActuator:
    if not isinstance(actuator, BendingActuator):
        raise ValueError(f"actuator must be a BendingActuator, got {actuator!r}")
    return actuator


def _check_force(tip_force: Any) -> tuple[float, float]:
    try:
        fx, fy = tip_force
    except (TypeError, ValueError):
        raise ValueError(f"tip_force must be a pair (Fx, Fy) of finite numbers [N], got {tip_force!r}") from None
    return finite_float("tip_force[0]", fx), finite_float("tip_force[1]", fy)


def _strain_scale(actuator: BendingActuator, strain: float, force: tuple[float, float]) -> float:
    """Rough total tip rotation [rad] expected, for choosing load steps."""
    rot_act = abs(actuator.free_curvature(strain)) * actuator.length
    rot_force = math.hypot(*force) * actuator.length**2 / (2.0 * actuator.bending_stiffness)
    return rot_act + rot_force


# ------------------------------------------------------------------------------ recording

class _Recorder:
    """Post-step hook: commits the strain source and stores the accepted step's state."""

    def __init__(self, model, source, progress=None, t_end: float = 1.0) -> None:
        self.model = model
        self.source = source
        self.index = model.record_indices
        self.scalars: list[tuple] = []
        self.states: list[np.ndarray] = []
        self.progress = progress
        self.t_end = t_end
        self._next_report = 0.0

    def post_step(self, t: float) -> None:
        u, strain = self.source.commit(t)
        self.scalars.append((t, u, strain))
        self.states.append(self.model.coordinates()[self.index])
        if self.progress is not None and t >= self._next_report:
            self.progress(t, self.t_end)
            self._next_report = t + 0.01 * self.t_end

    @property
    def n_rows(self) -> int:
        return len(self.scalars)

    def last_time(self) -> float:
        return self.scalars[-1][0] if self.scalars else 0.0

    def result(self, actuator: BendingActuator, info: dict) -> Result:
        scalars = np.array(self.scalars, dtype=float).reshape(-1, 3)
        states = np.array(self.states, dtype=float).reshape(len(self.states), self.index.size)
        x, y, a, angles = self.model.states_from_records(states, scalars[:, 2])
        rows = np.column_stack([scalars, x, y, a])
        return _make_result(actuator, rows, angles, info)


def _make_result(actuator: BendingActuator, rows: np.ndarray, angles: np.ndarray, info: dict) -> Result:
    series = {
        "time": rows[:, 0],
        "voltage": rows[:, 1],
        "strain": rows[:, 2],
        "stroke": rows[:, 2] * actuator.cell_length,
        "tip_x": rows[:, 3],
        "tip_y": rows[:, 4],
        "tip_angle": rows[:, 5],
    }
    units = dict(_STANDARD_UNITS)
    for j in range(actuator.n_cells):
        series[f"cell_angle_{j + 1}"] = angles[:, j]
        units[f"cell_angle_{j + 1}"] = "rad"
    info = dict(info)
    info.setdefault("exudyn_version", builder.exudyn_version())
    _warn_coarse_cells(actuator, angles)
    result = Result(series, units, parameters=actuator.parameters(), info=info)
    for name in result:
        values = result[name]
        if values.size and not np.all(np.isfinite(values)):
            bad = int(np.argmax(~np.isfinite(values)))
            raise SolverError(
                f"the solution contains a non-finite {name} at row {bad} (t = {rows[bad, 0]!r} s); "
                "the solver diverged. Try a smaller step or more cells."
            )
    return result


#: Largest rotation of one cell relative to its neighbour [rad] before a warning is issued.
MAX_CELL_ROTATION = 0.5


def _warn_coarse_cells(actuator: BendingActuator, angles: np.ndarray) -> None:
    """Warn when a cell turns by more than :data:`MAX_CELL_ROTATION` (coarse discretisation)."""
    if angles.size == 0:
        return
    # passive bar j sits at the mean of its interfaces: the first bar turns half a cell
    padded = np.concatenate([-angles[:, :1], angles], axis=1)
    per_cell = float(np.max(np.abs(np.diff(padded, axis=1))))
    if per_cell > MAX_CELL_ROTATION:
        warnings.warn(
            f"a cell of the {actuator.cell} actuator turns by {per_cell:.3g} rad relative to its "
            f"neighbour (more than {MAX_CELL_ROTATION} rad): with {actuator.n_cells} cells the chain is a "
            "coarse discretisation of the bent actuator; use more cells",
            RuntimeWarning,
            stacklevel=3,
        )


# ------------------------------------------------------------------------------ static solve

def _static_equilibrium(actuator, model, strain: float, force: tuple[float, float], load_steps: int | None,
                        what: str) -> str:
    """Solve the static equilibrium at ``strain`` with the tip load; returns the method that succeeded.

    First Exudyn's static solver with strain and load raised together in equal load steps.
    Exudyn's static Jacobian leaves out the derivative of the constraint forces, so under
    large tip forces its Newton iteration converges only linearly, ever slower, and can stall
    (measured on the elastica cases).  Then the equilibrium is found by dynamic relaxation
    (strongly damped implicit dynamics with a smooth load ramp) and polished with one static
    step from there.
    """
    if load_steps is None:
        # ~0.05 rad of tip rotation per load step, at least 4
        load_steps = int(min(400, max(4, math.ceil(_strain_scale(actuator, strain, force) / 0.05))))
    try:
        builder.run_static(model, builder.static_settings(load_steps), lambda f: f * strain)
        return "static"
    except builder.ExudynFailure as exc:
        first = exc
    builder.reset_to_reference(model)
    omega1 = 2.0 * math.pi * actuator.first_frequency_estimate
    try:
        # periods counted at half the beam frequency: coarse chains of six-bar cells are softer
        change = builder.run_relaxation(model, strain, 0.5 * omega1, 2.0 / omega1)
    except builder.ExudynFailure as exc:
        raise SolverError(
            f"static equilibrium ({what}) of the {actuator.cell} actuator with {actuator.n_cells} cells did not "
            f"converge. Tried: Exudyn's static solver with {load_steps} load steps (stopped at load factor "
            f"{first.time:.4g}: {first}), then dynamic relaxation (stopped at {exc.time:.3g} of its ramp: {exc}). "
            f"The expected tip rotation is {_strain_scale(actuator, strain, force):.3g} rad, "
            f"{_strain_scale(actuator, strain, force) / actuator.n_cells:.3g} rad per cell. Use more cells "
            "(the six-bar cell is a discretisation for small rotations per cell), reduce the load, or pass "
            "load_steps."
        ) from exc
    relaxed = np.array(model.coordinates())
    builder.set_current_as_initial(model, zero_velocity=True)
    try:
        builder.run_static(model, builder.static_settings(1), lambda f: strain)
        return "relaxation+static"
    except builder.ExudynFailure:
        pass
    tol = 1e-9 * actuator.length
    if change <= tol:
        model.mbs.systemData.SetODE2Coordinates(relaxed, configuration=builder.exu.ConfigurationType.Current)
        return "relaxation"
    raise SolverError(
        f"static equilibrium ({what}) of the {actuator.cell} actuator with {actuator.n_cells} cells did not "
        f"converge: Exudyn's static solver stopped at load factor {first.time:.4g} ({first}); dynamic "
        f"relaxation still moved by {change:.3g} m over its last period (accepted: {tol:.3g} m) and the "
        "static polish step failed. Use more cells, reduce the load, or pass more load_steps."
    )


def solve_static(
    actuator: BendingActuator,
    voltage: float | None = None,
    tip_force: tuple[float, float] = (0.0, 0.0),
    load_steps: int | None = None,
) -> Result:
    """Static equilibrium at a voltage and a dead tip load (geometrically nonlinear).

    Parameters
    ----------
    actuator : BendingActuator
        The actuator; its drive gives the voltage-to-strain law.
    voltage : float, optional
        Voltage [V].  Default: the drive's voltage at ``t = 0``.  With a hysteresis
        operator, the voltage is reached by a monotone ramp from the operator's reset state.
    tip_force : (float, float), optional
        Dead load ``(Fx, Fy)`` [N] at the tip, in global coordinates.
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
    actuator = _check_actuator(actuator)
    force = _check_force(tip_force)
    if voltage is None:
        volts = actuator.drive.voltage_at(0.0)
    else:
        volts = finite_float("voltage", voltage)
    if load_steps is not None:
        load_steps = positive_int("load_steps", load_steps)
    strain = actuator.drive.static_strain(volts)
    model = builder.build(actuator, force)
    method = _static_equilibrium(actuator, model, strain, force, load_steps,
                                 f"voltage {volts:g} V, tip force {force} N")
    x, y, a, ca = model.read_state(model.coordinates(), strain)
    rows = np.array([[0.0, volts, strain, x, y, a]])
    return _make_result(actuator, rows, np.asarray(ca, dtype=float).reshape(1, -1),
                        {"solver": method, "load_steps": load_steps if load_steps is not None else "auto"})


# ------------------------------------------------------------------------------ dynamic solve

def simulate(
    actuator: BendingActuator,
    t_end: float,
    step: float = DEFAULT_STEP,
    tip_force: tuple[float, float] = (0.0, 0.0),
    settings: Callable[[Any], None] | dict | None = None,
    progress: Callable[[float, float], None] | None = None,
) -> Result:
    """Dynamic response of the actuator to its voltage program (generalized-alpha).

    The run starts from the static equilibrium at the voltage ``U(0)`` and the tip force
    (the hysteresis operator is reset and then fed ``U(0)``), then integrates to ``t_end``.
    Every accepted step is recorded.

    Parameters
    ----------
    actuator : BendingActuator
        The actuator, with its drive (voltage program, optional hysteresis operator).
    t_end : float
        End time [s], > 0.
    step : float, optional
        Time step [s], > 0 and <= ``t_end``; default 1e-4.  Exudyn halves it temporarily
        when a step's Newton iteration fails (those steps are repeated, not recorded).
    tip_force : (float, float), optional
        Dead load ``(Fx, Fy)`` [N] at the tip, in global coordinates, constant in time.
    settings : callable or dict, optional
        Adjusts the underlying ``exudyn.SimulationSettings`` after the package defaults are
        set: a callable receiving the settings object, or a dict of dotted names, e.g.
        ``{"timeIntegration.newton.maxIterations": 12}``.
    progress : callable, optional
        ``progress(t, t_end)`` is called with the simulated time [s] about every 1 % of
        ``t_end`` (for progress bars).

    Returns
    -------
    Result
        Series ``time``, ``voltage``, ``strain``, ``stroke``, ``tip_x``, ``tip_y``,
        ``tip_angle``, ``cell_angle_1..N``; ``result.info`` holds the number of attempted and
        rejected steps.

    Raises
    ------
    ValueError
        For non-positive or non-finite ``t_end``/``step``, a bad ``tip_force`` or ``settings``.
    SolverError
        If the time integration fails; the message gives the time reached.

    Notes
    -----
    Defaults: generalized-alpha with spectral radius 0.8, modified Newton, absolute Newton
    tolerance 1e-8 (SI units), sparse linear solver, adaptive step reduction on Newton failure.
    """
    actuator = _check_actuator(actuator)
    if progress is not None and not callable(progress):
        raise ValueError(f"progress must be None or a callable progress(t, t_end), got {progress!r}")
    return _simulate(actuator, t_end, step, tip_force, settings, source=None, stroke_path="prestep",
                     progress=progress)


def _simulate(actuator, t_end, step, tip_force, settings, source=None, stroke_path="prestep",
              progress=None) -> Result:
    t_end = positive_float("t_end", t_end)
    step = positive_float("step", step)
    if step > t_end:
        raise ValueError(f"step must be <= t_end = {t_end!r} s, got {step!r}")
    force = _check_force(tip_force)
    if settings is not None and not callable(settings) and not isinstance(settings, dict):
        raise ValueError(f"settings must be None, a callable or a dict of dotted names, got {settings!r}")
    if source is None:
        source = InStepStrain(actuator.drive)
    model = builder.build(actuator, force, stroke_path=stroke_path)
    model.uf_strain = source.trial

    # initial equilibrium at U(0) (the hysteresis memory takes U(0) at the t = 0 post-step)
    strain0 = source.trial(0.0)
    if strain0 != 0.0 or force != (0.0, 0.0):
        _static_equilibrium(actuator, model, strain0, force, None, "initial state at t = 0")
        builder.set_current_as_initial(model, zero_velocity=True)

    sim_settings = builder.dynamic_settings(t_end, step)
    builder.apply_user_settings(sim_settings, settings)
    recorder = _Recorder(model, source, progress, t_end)

    if stroke_path != "user_function":
        def pre_step(t: float) -> None:
            model.set_strain(source.trial(t))
    else:
        pre_step = None
    try:
        stats = builder.run_dynamic(model, sim_settings, pre_step, recorder.post_step)
    except builder.ExudynFailure as exc:
        t_fail = exc.time
        last = recorder.last_time()
        raise SolverError(
            f"time integration of the {actuator.cell} actuator with {actuator.n_cells} cells failed at "
            f"t = {t_fail:.6g} s (last accepted step at t = {last:.6g} s, requested step {step:g} s): "
            f"generalized-alpha with Newton (absolute tolerance "
            f"{sim_settings.timeIntegration.newton.absoluteTolerance:g}) did not converge even after "
            f"reducing the step size down to {sim_settings.timeIntegration.minimumStepSize:g} s. Exudyn said: "
            f"{exc}. Try a smaller step, a slower voltage program, more cells for large deflections, or a "
            f"looser tolerance via settings={{'timeIntegration.newton.absoluteTolerance': 1e-7}}."
        ) from exc
    accepted = max(recorder.n_rows - 1, 0)
    info = {
        "solver": "generalized-alpha",
        "step [s]": step,
        "accepted_steps": accepted,
        "attempted_steps": stats["pre_step_calls"],
        "rejected_steps": max(stats["pre_step_calls"] - accepted, 0),
        "newton_steps": stats["newton_steps"],
        "stroke_path": stroke_path,
    }
    if isinstance(source, InStepStrain):
        info["hysteresis_evaluations"] = source.evaluations
    return recorder.result(actuator, info)


# ------------------------------------------------------------------------------ eigenfrequencies

def eigenfrequencies(
    actuator: BendingActuator,
    n: int = 3,
    *,
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
    actuator : BendingActuator
        The actuator.
    n : int, optional
        Number of frequencies, >= 1 (default 3).
    voltage : float, optional
        Operating voltage [V]; default: no actuation (strain 0, not the program's ``U(0)``).
        With a hysteresis operator the strain is the one reached by a monotone ramp from the
        operator's reset state, as in :func:`solve_static`.
    tip_force : (float, float), optional
        Dead load ``(Fx, Fy)`` [N] at the tip, in global coordinates.

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
    16 cells at 1500 V).  See :mod:`exudyn_atcm._eigen`.
    """
    actuator = _check_actuator(actuator)
    n = positive_int("n", n)
    force = _check_force(tip_force)
    volts = None if voltage is None else finite_float("voltage", voltage)
    strain = 0.0 if volts is None else actuator.drive.static_strain(volts)
    model = builder.build(actuator, force)
    if strain != 0.0 or force != (0.0, 0.0):
        _static_equilibrium(actuator, model, strain, force, None,
                            f"voltage {volts!r} V, tip force {force} N, for eigenfrequencies")
    return builder.eigenfrequencies(model, n)
