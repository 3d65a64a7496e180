"""A static sweep's points as the load steps of one Exudyn static solve.

A quasi-static sweep visits equilibria whose strains are known ahead (each voltage held for ever,
:meth:`~exudyn_atcm.mbs.stepping.Stepping.hold_path`).  :func:`solve_points` continues from the
equilibrium of one point through the next ones in *one* call of Exudyn's static solver: load-step
time ``j`` is the ``j``-th point after the start, the pre-step hook moves the strains linearly
from one point's to the next within each unit of time (so the solver's adaptive reduction of
a failed step works inside a point as it does in a point's own solve), and the post-step hook, which
Exudyn calls only for accepted steps, hands every point's equilibrium to the caller.  The solver,
its settings and its assembled system are set up once for the whole path instead of once per
point: on the README four-bar a cycle of 100 points costs about a third of 100 one-step solves
(``benchmarks/bench_static_sweep.py``), with the same equilibria (the same equations and Newton
tolerances; ``tests/test_sweep_solve.py``).

Each point's Newton iteration starts from a secant prediction (continuation's predictor step): the
last two points' coordinates and multipliers extrapolated along the strain path, in proportion to the
strain step (:func:`secant_steps`).  The mechanics at given strains is elastic, so the equilibrium is a
smooth function of the strains along a branch, and a reversal of the voltage (the strain steps back)
predicts a return along the branch.  The prediction is only the iteration's start: the equations and
tolerances are those of a point's own solve.  On the README four-bar's 100-point cycle it takes the
Newton iterations from 393 to 105 and the rod's passes from two per point to one (the tie linearised
at the predicted state is already within its tolerance).  Where the solver had to reduce a point's
step, the reduced steps start from the last point's equilibrium, without a prediction.

Where Exudyn's Newton iteration fails on a point's step, the solver reduces the step (to a quarter,
as often as needed) and is not let grow it again (:data:`~exudyn_atcm.mbs.continuation_settings.NEVER_GROW`:
grown from inside a point, a step could end beyond the next point, which would be passed over); the
solve stops at the point so reached, and the caller goes on with a new solve.  A step that ended
beyond a point anyway is reported as a failure at that point (never a point left out).

The caller's ``on_point(k, solver, state)`` may stop the solve at point ``k`` (return ``False``): a
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

from .._checks import shown
from .continuation_settings import continuation_settings
from .model import MechanismModel
from .solver_runs import (ExudynFailure, HookErrors, apply_static_tolerances, quiet_console, restore_console,
                          set_current_as_initial, solver_time)

__all__ = ["PointsSolved", "solve_points", "set_state", "system_state", "secant_steps", "LARGEST_SECANT_RATIO"]

#: distance [load-step time] within which the solver's time counts as a point's (the times are sums of
#: reduced unit steps: exact in binary unless a step was reduced below 2^-40)
_ON_POINT = 1e-9
#: largest ratio of a point's strain step to the last one (in its direction) for which the point's iteration
#: starts from the secant prediction; beyond it (an uneven grid, a jump in the strains) from the last point
LARGEST_SECANT_RATIO = 2.0


@dataclass
class PointsSolved:
    """The outcome of :func:`solve_points`.

    Attributes
    ----------
    last : int
        The last point whose equilibrium was reached (``first - 1`` when none was); the model holds
        its state (current and initial) and strains.
    stopped : bool
        Whether the solve stopped at ``last`` before the end: ``on_point`` asked, or the solver reached
        that point with steps it had reduced (after a failed one); a new solve from there takes whole
        steps again.
    failure : ExudynFailure or None
        Exudyn's failure on the way to point ``last + 1`` (its ``time`` is the load-step time reached
        after ``last``, in points), ``None`` when the solve ended or was stopped.
    """

    last: int
    stopped: bool = False
    failure: ExudynFailure | None = None


def system_state(model: MechanismModel) -> list:
    """The model's current system state, copied: Exudyn's list ``[ODE2 coordinates, their velocities, ODE1
    coordinates, algebraic coordinates (the multipliers), data coordinates]``."""
    return model.mbs.systemData.GetSystemState()


def set_state(model: MechanismModel, state: list, strains: np.ndarray) -> None:
    """Put ``state`` (:func:`system_state`) back as the current and initial state, with ``strains`` [-] written."""
    sd = model.mbs.systemData
    for configuration in (exu.ConfigurationType.Current, exu.ConfigurationType.Initial):
        sd.SetSystemState(systemStateList=state, configuration=configuration)
    model.load_factor = 1.0
    model.set_path(strains, strains, ramp_loads=False)
    model.set_strain(1.0)


def secant_steps(strains: np.ndarray) -> np.ndarray:
    """The secant predictor's step of every point: how many times the last strain step (point ``k - 2`` to
    ``k - 1``, rows of ``strains`` [-], one column per source) point ``k``'s step goes along it (its
    projection: ``1`` on an even grid, ``-1`` at its reversals); ``nan`` where no prediction is made (points 0
    and 1, a last step of zero, a ratio beyond :data:`LARGEST_SECANT_RATIO`).  One entry per row."""
    e = np.asarray(strains, dtype=float).reshape(len(strains), -1)
    out = np.full(len(e), np.nan)
    if len(e) < 3:
        return out
    last, step = e[1:-1] - e[:-2], e[2:] - e[1:-1]
    norm = np.einsum("ij,ij->i", last, last)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.einsum("ij,ij->i", step, last) / norm
    out[2:] = np.where((norm > 0.0) & (np.abs(ratio) <= LARGEST_SECANT_RATIO), ratio, np.nan)
    return out


def solve_points(model: MechanismModel, strains: np.ndarray, first: int,
                 on_point: Callable[[int, object, list], bool], *, connector_derivative: bool = False) -> PointsSolved:
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
        ``on_point(k, solver, state) -> bool``, called in the post-step hook at the equilibrium of every
        point ``k`` reached (the model's current state; ``solver`` the running
        ``exudyn.MainSolverStatic``; ``state`` that state as :func:`system_state` gives it, a copy the
        callee may keep): ``False`` stops the solve there.  An exception it raises
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
        raise ValueError(f"first: expected a point in 1 ... {n - 1}, got {shown(first)}")
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
    reached = {"point": first - 1, "state": system_state(model), "stopped": False, "passed": False}
    attempts = [0]  # the steps attempted since the last point (more than one: the solver reduced a failed step)
    segment = [-1]  # the point whose path the model holds
    solver = exu.MainSolverStatic()
    sd = mbs.systemData
    current = exu.ConfigurationType.Current
    # the last two points reached: (index, coordinates, multipliers); the first is the start's (and the secant
    # predictor's step from them into the point being solved: (both points' coordinates, their multipliers, the
    # secant step, the coordinates and multipliers predicted at the point), or None)
    start = reached["state"]
    points: list[tuple] = [(first - 1, start[0], start[3])]
    predictor: list = [None]

    ratios = secant_steps(strains).tolist()  # nan: no prediction

    def predict(k: int) -> tuple | None:
        ratio = ratios[k]
        if ratio != ratio or len(points) < 2 or points[0][0] != k - 2:
            return None
        (_, q0, a0), (_, q1, a1) = points
        return q0, q1, a0, a1, ratio, q1 + ratio * (q1 - q0), a1 + ratio * (a1 - a0)

    def pre(mbs_, t):
        attempts[0] += 1
        try:
            j = min(max(math.ceil(t - _ON_POINT), 1), steps)
            k = first - 1 + j
            if segment[0] != k:
                model.set_path(strains[k - 1], strains[k], ramp_loads=False)
                segment[0] = k
                predictor[0] = predict(k)
            else:  # the point's step again: a reduced step after a failure; from the last point, without a prediction
                predictor[0] = None
            f = min(max(t - (j - 1), 0.0), 1.0)
            if predictor[0] is not None:  # the iteration's start (Exudyn keeps the step's start for a repeat)
                q0, q1, a0, a1, ratio, q_end, a_end = predictor[0]
                if f == 1.0:  # a point's whole step: its prediction made once
                    sd.SetODE2Coordinates(q_end, current)
                    sd.SetAECoordinates(a_end, current)
                else:
                    sd.SetODE2Coordinates(q1 + (f * ratio) * (q1 - q0), current)
                    sd.SetAECoordinates(a1 + (f * ratio) * (a1 - a0), current)
            model.set_strain(f)
        except Exception as exc:
            errors.keep(exc, "pre-step", f"load-step time {t:.6g} (points)")
            raise
        return True

    def post(mbs_, t):
        if t > reached["point"] - first + 2 + _ON_POINT:  # beyond the next point without a stop on it
            reached["passed"] = True
            return False
        j = round(t)
        if j < 1 or abs(t - j) > _ON_POINT:
            return True  # the initial state, or a reduced step inside a point
        k = first - 1 + j
        whole, attempts[0] = attempts[0] == 1, 0
        try:
            state = system_state(model)
            reached["point"], reached["state"] = k, state
            points[:] = [points[-1], (k, state[0], state[3])]
            go_on = bool(on_point(k, solver, state)) and whole
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
    if reached["passed"] and failure is None:
        failure = ExudynFailure(f"the solver's step went beyond point {last + 1} without stopping on it",
                                solver_time(solver) - (last - first + 1))
    elif not ok and failure is None and not reached["stopped"]:
        failure = ExudynFailure("static Newton iteration did not converge", solver_time(solver) - (last - first + 1))
    set_state(model, reached["state"], strains[last] if last >= 0 else strains[0])
    set_current_as_initial(model, zero_velocity=True)
    return PointsSolved(last, reached["stopped"], failure)
