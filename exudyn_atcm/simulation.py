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
        u = self.drive.voltage_at(t)
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
    def __init__(self, model, source) -> None:
        self.model = model
        self.source = source
        self.rows: list[tuple] = []
        self.angles: list[np.ndarray] = []

    def post_step(self, t: float) -> None:
        u, strain = self.source.commit(t)
        q = self.model.coordinates()
        x, y, a, ca = self.model.read_state(q, strain)
        self.rows.append((t, u, strain, x, y, a))
        self.angles.append(ca)

    def result(self, actuator: BendingActuator, info: dict) -> Result:
        rows = np.array(self.rows, dtype=float).reshape(-1, 6)
        angles = np.array(self.angles, dtype=float).reshape(len(self.angles), actuator.n_cells)
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


# ------------------------------------------------------------------------------ static solve

def _static_equilibrium(actuator, model, strain: float, force: tuple[float, float], load_steps: int | None,
                        what: str) -> None:
    """Solve the static equilibrium at ``strain`` with the tip load, stepping strain and load together."""
    if load_steps is None:
        # ~0.05 rad of tip rotation per load step, at least 4
        load_steps = int(min(400, max(4, math.ceil(_strain_scale(actuator, strain, force) / 0.05))))
    tried = []
    for steps in (load_steps, 4 * load_steps):
        settings = builder.static_settings(steps)
        try:
            builder.run_static(model, settings, lambda f: f * strain)
            return
        except builder.ExudynFailure as exc:
            tried.append((steps, exc))
            model.mbs.systemData.SetSystemState(
                systemStateList=model.mbs.systemData.GetSystemState(builder.exu.ConfigurationType.Initial),
                configuration=builder.exu.ConfigurationType.Current)
    steps, exc = tried[-1]
    raise SolverError(
        f"static equilibrium ({what}) of the {actuator.cell} actuator with {actuator.n_cells} cells did not "
        f"converge: failed at load factor {exc.time:.4g} of 1 after trying {tried[0][0]} and {steps} equal "
        f"load steps (each halved adaptively down to 1e-6) with full Newton and an absolute tolerance of "
        f"{builder.NEWTON_ABSOLUTE_TOLERANCE:g}. Exudyn said: {exc}. Reduce the load (tip rotation "
        f"estimate {_strain_scale(actuator, strain, force):.3g} rad), pass more load_steps, or use more cells."
    ) from exc


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
        0.05 rad of expected tip rotation, at least 4; if that fails, four times as many.

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
    _static_equilibrium(actuator, model, strain, force, load_steps, f"voltage {volts:g} V, tip force {force} N")
    x, y, a, ca = model.read_state(model.coordinates(), strain)
    rows = np.array([[0.0, volts, strain, x, y, a]])
    return _make_result(actuator, rows, np.asarray(ca, dtype=float).reshape(1, -1), {"solver": "static"})


# ------------------------------------------------------------------------------ dynamic solve

def simulate(
    actuator: BendingActuator,
    t_end: float,
    step: float = DEFAULT_STEP,
    tip_force: tuple[float, float] = (0.0, 0.0),
    settings: Callable[[Any], None] | dict | None = None,
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
    return _simulate(actuator, t_end, step, tip_force, settings, source=None, stroke_path="prestep")


def _simulate(actuator, t_end, step, tip_force, settings, source=None, stroke_path="prestep") -> Result:
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
        builder.set_current_as_initial(model)

    sim_settings = builder.dynamic_settings(t_end, step)
    builder.apply_user_settings(sim_settings, settings)
    recorder = _Recorder(model, source)

    if stroke_path == "prestep":
        def pre_step(t: float) -> None:
            model.set_strain(source.trial(t))
    else:
        pre_step = None
    try:
        stats = builder.run_dynamic(model, sim_settings, pre_step, recorder.post_step)
    except builder.ExudynFailure as exc:
        t_fail = exc.time
        last = recorder.rows[-1][0] if recorder.rows else 0.0
        raise SolverError(
            f"time integration of the {actuator.cell} actuator with {actuator.n_cells} cells failed at "
            f"t = {t_fail:.6g} s (last accepted step at t = {last:.6g} s, requested step {step:g} s): "
            f"generalized-alpha with Newton (absolute tolerance "
            f"{sim_settings.timeIntegration.newton.absoluteTolerance:g}) did not converge even after "
            f"reducing the step size down to {sim_settings.timeIntegration.minimumStepSize:g} s. Exudyn said: "
            f"{exc}. Try a smaller step, a slower voltage program, more cells for large deflections, or a "
            f"looser tolerance via settings={{'timeIntegration.newton.absoluteTolerance': 1e-7}}."
        ) from exc
    accepted = max(len(recorder.rows) - 1, 0)
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

def eigenfrequencies(actuator: BendingActuator, n: int = 3) -> np.ndarray:
    """Lowest eigenfrequencies [Hz] of the undamped actuator about its undeformed state.

    The motor strokes are held at zero (motors are constraints), no tip load.

    Parameters
    ----------
    actuator : BendingActuator
        The actuator.
    n : int, optional
        Number of frequencies, >= 1 (default 3).

    Returns
    -------
    numpy.ndarray
        The ``n`` lowest eigenfrequencies [Hz], ascending.  For a slender actuator these are
        its bending modes; the six-bar cell's shear and axial modes lie far above.
    """
    actuator = _check_actuator(actuator)
    n = positive_int("n", n)
    model = builder.build(actuator, (0.0, 0.0))
    freqs = builder.eigenfrequencies(model, n)
    if freqs.size < n:
        raise ValueError(f"n must be <= the number of degrees of freedom ({freqs.size}), got {n}")
    return freqs

