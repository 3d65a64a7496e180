"""Exudyn solver runs of a built model.

Static solve (:func:`run_static`), dynamic relaxation (:func:`run_relaxation`, the fallback
when the static Newton iteration fails), time integration (:func:`run_dynamic`), state resets
and eigenfrequencies about the current state.  A run works on any built model with the
attributes of :class:`SolvableModel` (:class:`~exudyn_atcm.mbs.model.MechanismModel`);
Exudyn's failures are raised as
:class:`ExudynFailure` with the time or load factor reached.

An exception raised inside the runs' step hooks (the user's voltage program, controller or load
function, or anything the hooks call) is not a solver failure: Exudyn catches it and gives up the
step (reporting a Newton failure after reducing the step), so the hooks keep the first one
(:class:`HookErrors`) and the run raises it as it is, its type and message unchanged, with a note
saying in which hook and at which time it arose.
"""

from __future__ import annotations

import math
from typing import Any, Callable, Protocol

import exudyn as exu
import numpy as np

from ..errors import annotate
from .eigen import constrained_eigenfrequencies
from .solver_settings import dynamic_settings
from .step_grid import GridKeeper


class SolvableModel(Protocol):
    """What the runs read and call on a built model."""

    mbs: Any
    uf_strains: Any
    sources: list
    springs: list
    newton_tolerance_floor: float
    static_relative_tolerance: float | None

    def set_strain(self, strain: float) -> None: ...

    def scale_loads(self, factor: float) -> None: ...

    def coordinates(self) -> np.ndarray: ...

    def adjust_settings(self, settings: Any) -> None: ...


class ExudynFailure(RuntimeError):
    """Exudyn's solver stopped; carries the time / load factor reached."""

    def __init__(self, message: str, time: float):
        super().__init__(message)
        self.time = time


class HookErrors:
    """The first exception raised in a solve's step hooks, to be raised as itself after the solve.

    Use :meth:`keep` in each hook's ``except Exception`` clause (then re-raise, which makes Exudyn
    stop) and :meth:`raise_first` where the solve's own failure is handled.
    """

    def __init__(self, solve: str) -> None:
        self.solve = solve
        self.first: Exception | None = None

    def keep(self, exc: Exception, hook: str, where: str) -> None:
        """Remember ``exc`` (the first one only) with a note naming the hook and ``where`` (``"t = 0.02 s"``)."""
        if self.first is None:
            self.first = exc
            annotate(exc, f"(in the {hook} hook of {self.solve} at {where}; the solve stopped there)")

    def raise_first(self) -> None:
        """Raise the exception kept, if any, as it is (not chained to Exudyn's report of it)."""
        if self.first is not None:
            raise self.first from None


def quiet_console():
    """Silence Exudyn's console output (solver messages) until :func:`restore_console`."""
    exu.config.printToConsole = False


def restore_console():
    """Let Exudyn print to the console again."""
    exu.config.printToConsole = True


def _apply_tolerance_floor(model: SolvableModel, newton) -> None:
    if newton.absoluteTolerance < model.newton_tolerance_floor:
        newton.absoluteTolerance = model.newton_tolerance_floor


def apply_static_tolerances(model: SolvableModel, settings) -> None:
    """The model's Newton tolerances for a static solve written into ``settings`` (its floor, its own values)."""
    _apply_tolerance_floor(model, settings.staticSolver.newton)
    if model.static_relative_tolerance is not None:
        settings.staticSolver.newton.relativeTolerance = model.static_relative_tolerance
    if getattr(model, "static_absolute_tolerance", None) is not None:
        settings.staticSolver.newton.absoluteTolerance = model.static_absolute_tolerance


def run_static(model: SolvableModel, settings, strain_at_factor: Callable[[float], float]) -> None:
    """Solve statically; the strain follows the load factor ``f`` in [0, 1] via ``strain_at_factor``."""
    mbs = model.mbs
    errors = HookErrors("Exudyn's static solver")
    last_factor = [math.nan]  # the factor whose strains the model holds

    def pre(mbs_, t):
        try:
            last_factor[0] = min(max(t, 0.0), 1.0)
            model.set_strain(strain_at_factor(last_factor[0]))
        except Exception as exc:
            errors.keep(exc, "pre-step", f"load factor {t:.6g}")
            raise
        return True

    apply_static_tolerances(model, settings)
    mbs.SetPreStepUserFunction(pre)
    model.set_strain(strain_at_factor(0.0))
    saved_uf = model.uf_strains  # the user functions read the strains the pre-step hook set
    model.uf_strains = None
    solver = exu.MainSolverStatic()
    quiet_console()
    try:
        ok = solver.SolveSystem(mbs, settings)
    except Exception as exc:  # noqa: BLE001 - any Exudyn failure is reported with context
        errors.raise_first()
        t = solver_time(solver)
        raise ExudynFailure(f"{type(exc).__name__}: {exc}", t) from exc
    finally:
        restore_console()
        mbs.SetPreStepUserFunction(0)
        model.uf_strains = saved_uf
    if not ok:
        errors.raise_first()
        raise ExudynFailure("static Newton iteration did not converge", solver_time(solver))
    # the static solver ends at load factor 1: make sure the final strain is exact (written again
    # only when the last step's pre-step hook did not write exactly it)
    if last_factor[0] != 1.0:
        model.set_strain(strain_at_factor(1.0))


def solver_time(solver) -> float:
    try:
        return float(solver.it.currentTime)
    except Exception:  # noqa: BLE001
        return float("nan")


def set_current_as_initial(model: SolvableModel, zero_velocity: bool = False) -> None:
    mbs = model.mbs
    state = mbs.systemData.GetSystemState()
    mbs.systemData.SetSystemState(systemStateList=state, configuration=exu.ConfigurationType.Initial)
    if zero_velocity:
        n = len(mbs.systemData.GetODE2Coordinates_t())
        zeros = np.zeros(n)
        mbs.systemData.SetODE2Coordinates_t(zeros, configuration=exu.ConfigurationType.Initial)
        mbs.systemData.SetODE2Coordinates_tt(zeros, configuration=exu.ConfigurationType.Initial)


_RESTORED = (exu.ConfigurationType.Initial, exu.ConfigurationType.Current, exu.ConfigurationType.StartOfStep)


def save_state(model: SolvableModel) -> list:
    """The system's initial state (every coordinate, velocity, algebraic and data coordinate), for :func:`restore_state`."""
    sd = model.mbs.systemData
    state = sd.GetSystemState(configuration=exu.ConfigurationType.Initial)
    return [np.array(v, dtype=float) for v in state] + [np.array(sd.GetODE2Coordinates_tt(
        configuration=exu.ConfigurationType.Initial), dtype=float)]


def restore_state(model: SolvableModel, saved: list) -> None:
    """Put a state :func:`save_state` took back as the initial, current and start-of-step state at time 0.

    The actuation and loads are reset too: zero strains, load factor 1, no static path, the loads
    written at ``t = 0``; a built model is then as :func:`~exudyn_atcm.mbs.builder.build` left it.
    """
    sd = model.mbs.systemData
    state, accelerations = [v.copy() for v in saved[:-1]], saved[-1]
    for cfg in _RESTORED:
        sd.SetSystemState(systemStateList=state, configuration=cfg)
        sd.SetODE2Coordinates_tt(accelerations.copy(), configuration=cfg)
        sd.SetTime(0.0, cfg)
    n = len(model.sources)
    model.uf_strains = None
    model.path_from, model.path_to = np.zeros(n), np.zeros(n)
    model.ramp_loads, model.load_factor, model.time = True, 1.0, 0.0
    model.set_strains(np.zeros(n))
    model.scale_loads(1.0)


def reset_to_reference(model: SolvableModel) -> None:
    """Put the undeformed state back as initial and current state."""
    mbs = model.mbs
    sd = mbs.systemData
    n = len(sd.GetODE2Coordinates())
    zeros = np.zeros(n)
    for cfg in (exu.ConfigurationType.Initial, exu.ConfigurationType.Current):
        sd.SetODE2Coordinates(zeros, configuration=cfg)
        sd.SetODE2Coordinates_t(zeros, configuration=cfg)
        sd.SetODE2Coordinates_tt(zeros, configuration=cfg)


def run_relaxation(model: SolvableModel, strain: float, omega1: float, damping_factor: float,
                   periods_ramp: float = 2.0, periods_total: float = 10.0,
                   steps_per_period: int = 60) -> float:
    """Static equilibrium by dynamic relaxation (fallback when the static Newton iteration fails).

    Exudyn's static solver leaves out the constraint forces' derivative in its Jacobian
    (measured: linear convergence whose rate tends to 1 under large tip forces).  The
    implicit dynamic solver adds ``M/(beta h²)`` to the Jacobian, which keeps it contractive.
    Strain and loads (``model.scale_loads``) are ramped smoothly over ``periods_ramp`` periods of the first mode,
    with every spring damped at ``damping_factor * k`` (critical damping of the first mode for
    ``2/omega1``), then held until ``periods_total``.  Returns the largest coordinate change
    over the last period (a measure of the remaining motion).
    """
    mbs = model.mbs
    period = 2.0 * math.pi / omega1
    t_ramp = periods_ramp * period
    t_end = periods_total * period
    h = period / steps_per_period
    tail = {"q": None, "t_mark": t_end - period, "change": 0.0}

    def ramp(t):
        x = min(max(t / t_ramp, 0.0), 1.0)
        return x * x * (3.0 - 2.0 * x)

    errors = HookErrors("the dynamic relaxation of a static solve")

    def pre(mbs_, t):
        f = ramp(t)
        try:
            model.set_strain(f * strain)
            model.scale_loads(f)
        except Exception as exc:
            errors.keep(exc, "pre-step", f"ramp {f:.6g}")
            raise
        return True

    def post(mbs_, t):
        if t >= tail["t_mark"]:
            q = np.array(mbs_.systemData.GetODE2Coordinates(copy=False))
            if tail["q"] is None:
                tail["q"] = q
            else:
                tail["change"] = max(tail["change"], float(np.max(np.abs(q - tail["q"]))))
        return True

    saved = [(item, name, mbs.GetObjectParameter(item, name)) for item, _, name in model.springs]
    for item, k, name in model.springs:
        mbs.SetObjectParameter(item, name, damping_factor * k)
    settings = dynamic_settings(t_end, h)
    model.adjust_settings(settings)  # e.g. a mass matrix written each step is read each step
    _apply_tolerance_floor(model, settings.timeIntegration.newton)
    settings.timeIntegration.newton.useModifiedNewton = False
    settings.timeIntegration.newton.maxIterations = 25
    mbs.SetPreStepUserFunction(pre)
    mbs.SetPostStepUserFunction(post)
    solver = exu.MainSolverImplicitSecondOrder()
    saved_uf = model.uf_strains
    model.uf_strains = None
    quiet_console()
    try:
        ok = solver.SolveSystem(mbs, settings)
    except Exception as exc:  # noqa: BLE001
        errors.raise_first()
        raise ExudynFailure(f"{type(exc).__name__}: {exc}", solver_time(solver) / t_end) from exc
    finally:
        restore_console()
        mbs.SetPreStepUserFunction(0)
        mbs.SetPostStepUserFunction(0)
        model.uf_strains = saved_uf
        for item, name, d in saved:
            mbs.SetObjectParameter(item, name, d)
        model.scale_loads(1.0)
    if not ok:
        errors.raise_first()
        raise ExudynFailure("dynamic relaxation did not converge", solver_time(solver) / t_end)
    model.set_strain(strain)
    return tail["change"]


def run_dynamic(model: SolvableModel, settings, pre_step: Callable[[float], None] | None,
                post_step: Callable[[float], None]) -> dict:
    """Integrate in time; ``pre_step(t)`` before each attempted step, ``post_step(t)`` after each accepted one.

    Every instant of the run's grid (``endTime / numberOfSteps`` apart) is a step's end, also after
    Exudyn reduced a step (:class:`~exudyn_atcm.mbs.step_grid.GridKeeper`).

    A hook returning ``False`` stops the integration cleanly (Exudyn ends the run).  An exception
    raised in a hook is raised as it is after Exudyn stops (:class:`HookErrors`), not as a failure.

    Returns solver statistics.
    """
    mbs = model.mbs
    counts = {"attempts": 0}
    errors = HookErrors("the time integration")
    grid = GridKeeper(mbs, settings)  # after a reduced step, no step passes over an instant k h of the run's grid
    watch = grid.watch

    if pre_step is not None:
        def pre(mbs_, t):
            counts["attempts"] += 1
            try:
                watch(t)
                return pre_step(t) is not False  # False: stop the run (e.g. Ctrl-C caught in the hook)
            except Exception as exc:
                errors.keep(exc, "pre-step", f"t = {t:.9g} s (the step being attempted)")
                raise
    else:
        def pre(mbs_, t):
            counts["attempts"] += 1
            watch(t)
            return True

    def post(mbs_, t):
        try:
            return post_step(t) is not False
        except Exception as exc:
            errors.keep(exc, "post-step", f"t = {t:.9g} s (an accepted step)")
            raise

    _apply_tolerance_floor(model, settings.timeIntegration.newton)
    mbs.SetPreStepUserFunction(pre)
    mbs.SetPostStepUserFunction(post)
    solver = exu.MainSolverImplicitSecondOrder()
    quiet_console()
    try:
        ok = solver.SolveSystem(mbs, settings)
    except Exception as exc:  # noqa: BLE001
        errors.raise_first()
        raise ExudynFailure(f"{type(exc).__name__}: {exc}", solver_time(solver)) from exc
    finally:
        restore_console()
        mbs.SetPreStepUserFunction(0)
        mbs.SetPostStepUserFunction(0)
        grid.restore()
    if not ok:
        errors.raise_first()
        raise ExudynFailure("Newton iteration did not converge even at the minimum step size",
                            solver_time(solver))
    it = solver.it
    return {
        "pre_step_calls": counts["attempts"],
        "newton_steps": int(it.newtonStepsCount),
        "rejected_steps": int(getattr(it, "rejectedModifiedNewtonSteps", 0)),
        "discontinuous_iterations": int(it.discontinuousIterationsCount),
        "steps_sent_to_the_grid": grid.refused,
    }


def eigenfrequencies(model: SolvableModel, n: int) -> np.ndarray:
    """Lowest ``n`` undamped eigenfrequencies [Hz] about the model's current (equilibrium) state.

    Includes the constraint forces' geometric stiffness, which Exudyn's
    ``ComputeODE2Eigenvalues`` leaves out (see :mod:`exudyn_atcm.mbs.eigen`).
    """
    return constrained_eigenfrequencies(model.mbs, n)


def set_current_coordinates(model: SolvableModel, q: np.ndarray) -> None:
    """Write the ODE2 coordinates ``q`` into the model's current state."""
    model.mbs.systemData.SetODE2Coordinates(q, configuration=exu.ConfigurationType.Current)


def exudyn_version() -> str:
    """Version of the Exudyn library the runs use."""
    return str(exu.__version__)
