"""A static sweep's points as the load steps of one Exudyn static solve.

A quasi-static sweep visits equilibria whose strains are known ahead (each voltage held for ever,
:meth:`~exudyn_atcm.mbs.stepping.Stepping.hold_path`).  :func:`solve_points` continues from the
equilibrium of one point through the next ones in *one* call of Exudyn's static solver: load-step
time ``j`` is the ``j``-th point after the start, the pre-step hook moves the strains linearly
from one point's to the next within each unit of time (so the solver's adaptive halving of a
failed step works inside a point as it does in a point's own solve), and the post-step hook, which
Exudyn calls only for accepted steps, hands every point's equilibrium to the caller.  The solver,
its settings and its assembled system are set up once for the whole path instead of once per
point: on the README four-bar a cycle of 100 points costs about a third of 100 one-step solves
(``benchmarks/bench_static_sweep.py``), with the same equilibria (the same equations and Newton
tolerances; ``tests/test_sweep_solve.py``).

The caller's ``on_point(k, solver)`` may stop the solve at point ``k`` (return ``False``): a
sweep does when the cheap stability proof from the running solver's Jacobian fails
(:meth:`~exudyn_atcm.mbs.stability.StabilityProbe.proved_in_solve`), checks that state in full
outside the solve, and continues with a new call.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import exudyn as exu
import numpy as np

from .continuation_settings import continuation_settings
from .model import MechanismModel
from .solver_runs import (ExudynFailure, HookErrors, apply_static_tolerances, quiet_console, restore_console,
                          set_current_as_initial, solver_time)

__all__ = ["PointsSolved", "solve_points", "set_state", "system_state"]

#: distance [load-step time] within which the solver's time counts as a point's (the times are sums of
#: halved unit steps: exact in binary unless the step was halved below 2^-40)
_ON_POINT = 1e-9


@dataclass
class PointsSolved:
    """The outcome of :func:`solve_points`.

    Attributes
    ----------
    last : int
        The last point whose equilibrium was reached (``first - 1`` when none was); the model holds
        its state (current and initial) and strains.
    stopped : bool
        Whether ``on_point`` stopped the solve at ``last``.
    failure : ExudynFailure or None
        Exudyn's failure on the way to point ``last + 1`` (its ``time`` is the load-step time reached
        after ``last``, in points), ``None`` when the solve ended or was stopped.
    """

    last: int
    stopped: bool = False
    failure: ExudynFailure | None = None


def system_state(model: MechanismModel) -> list:
    """The model's current system state (coordinates, velocities, multipliers, data), copied."""
    return model.mbs.systemData.GetSystemState()


def set_state(model: MechanismModel, state: list, strains: np.ndarray) -> None:
    """Put ``state`` (:func:`system_state`) back as the current and initial state, with ``strains`` [-] written."""
    sd = model.mbs.systemData
    for configuration in (exu.ConfigurationType.Current, exu.ConfigurationType.Initial):
        sd.SetSystemState(systemStateList=state, configuration=configuration)
    model.load_factor = 1.0
    model.set_path(strains, strains, ramp_loads=False)
    model.set_strain(1.0)


def solve_points(model: MechanismModel, strains: np.ndarray, first: int,
                 on_point: Callable[[int, object], bool], *, connector_derivative: bool = False) -> PointsSolved:
    """Continue from point ``first - 1``'s equilibrium through points ``first, ..., len(strains) - 1`` in one static solve.

    Parameters
    ----------
    model : MechanismModel
        A built model in the equilibrium of point ``first - 1`` (its current state), with that
        point's strains written; the loads in full (load factor 1).
    strains : numpy.ndarray
        Every point's strains [-], shape ``(points, sources)``.
    first : int
        The first point to solve (``>= 1``).
    on_point : callable
        ``on_point(k, solver) -> bool``, called in the post-step hook at the equilibrium of every
        point ``k`` reached (the model's current state; ``solver`` the running
        ``exudyn.MainSolverStatic``): ``False`` stops the solve there.  An exception it raises
        is raised by this function as it is.
    connector_derivative : bool
        Solve with the connectors' analytic derivative in the Newton Jacobian (the constraint
        forces' geometric stiffness): needed for the stability proof from the running solver's
        Jacobian (:meth:`~exudyn_atcm.mbs.solver_jacobian.SolverJacobian.running_system`).

    Returns
    -------
    PointsSolved
        How far the solve came; the model holds that point's equilibrium as its current and
        initial state (velocities zero), with its strains written.
    """
    n = len(strains)
    if not 1 <= first < n:
        raise ValueError(f"first: expected a point in 1 ... {n - 1}, got {first!r}")
    steps = n - first
    settings = continuation_settings(model)
    static = settings.staticSolver
    static.numberOfLoadSteps = steps
    static.loadStepDuration = float(steps)  # one unit of load-step time per point
    if connector_derivative:
        static.newton.numericalDifferentiation.jacobianConnectorDerivative = True
    apply_static_tolerances(model, settings)
    mbs = model.mbs
    errors = HookErrors("Exudyn's static solver (a static sweep's continuation)")
    reached = {"point": first - 1, "state": system_state(model), "stopped": False}
    segment = [-1]  # the point whose path the model holds
    solver = exu.MainSolverStatic()

    def pre(mbs_, t):
        try:
            j = min(max(math.ceil(t - _ON_POINT), 1), steps)
            k = first - 1 + j
            if segment[0] != k:
                model.set_path(strains[k - 1], strains[k], ramp_loads=False)
                segment[0] = k
            model.set_strain(min(max(t - (j - 1), 0.0), 1.0))
        except Exception as exc:
            errors.keep(exc, "pre-step", f"load-step time {t:.6g} (points)")
            raise
        return True

    def post(mbs_, t):
        j = round(t)
        if j < 1 or abs(t - j) > _ON_POINT:
            return True  # the initial state, or a halved step inside a point
        k = first - 1 + j
        try:
            reached["point"], reached["state"] = k, system_state(model)
            go_on = bool(on_point(k, solver))
        except Exception as exc:
            errors.keep(exc, "post-step", f"point {k}")
            raise
        reached["stopped"] = not go_on
        return go_on

    model.load_factor = 1.0
    mbs.SetPreStepUserFunction(pre)
    mbs.SetPostStepUserFunction(post)
    saved_uf = model.uf_strains  # the user functions read the strains the pre-step hook set
    model.uf_strains = None
    failure = None
    quiet_console()
    try:
        ok = solver.SolveSystem(mbs, settings)
    except Exception as exc:  # noqa: BLE001 - any Exudyn failure is reported with context
        errors.raise_first()
        within = solver_time(solver) - (reached["point"] - first + 1)  # the load-step time into the failed point
        ok, failure = False, ExudynFailure(f"{type(exc).__name__}: {exc}", within)
    finally:
        restore_console()
        mbs.SetPreStepUserFunction(0)
        mbs.SetPostStepUserFunction(0)
        model.uf_strains = saved_uf
    errors.raise_first()
    last = reached["point"]
    if not ok and failure is None and not reached["stopped"]:
        failure = ExudynFailure("static Newton iteration did not converge", solver_time(solver) - (last - first + 1))
    set_state(model, reached["state"], strains[last] if last >= 0 else strains[0])
    set_current_as_initial(model, zero_velocity=True)
    return PointsSolved(last, reached["stopped"], failure)
