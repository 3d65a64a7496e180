"""Static equilibrium with a fallback, shared by the actuator and the mechanism paths.

Exudyn's static Jacobian leaves out the derivative of the constraint forces, so under large
loads its Newton iteration converges only linearly, ever slower, and can stall (measured on the
elastica cases).  :func:`equilibrium_with_fallback` tries Exudyn's static solver first; when it
stalls, the equilibrium is found by dynamic relaxation (strongly damped implicit dynamics with a
smooth load ramp) and polished with one static step from there; a relaxation that has come to
rest (moving by less than 1e-9 of the system's size over its last period) is accepted without
the polish.  Each path supplies how its model is put on the path between the attempts.

A static solve that converges can still end on an unstable equilibrium: Newton's method does
not care about stability, and large load steps across a bifurcation land on whichever branch
is nearest (a column above its buckling load held straight, or bent against its imperfection).
Given an ``unstable`` test, a converged static solution that fails it is treated like a failed
one: the relaxation, whose damped motion can only come to rest in a stable state, follows the
loading path from the same start, and its state is polished.  When that fails the static
solution is kept (the caller warns about its stability).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from ..errors import SolverError
from ..mbs import solver_runs as runs
from .interrupts import SimulationInterrupted, is_interrupt

# equilibrium_with_fallback is the static solves' internal helper (13 parameters), not public API
__all__: list[str] = []


def equilibrium_with_fallback(model, *, static: Callable[[], None], relaxation: Callable[[], None],
                              relax_target: float, omega1: float, polish: Callable[[], None], size: float,
                              subject: str, what: str, load_steps: int, advice: str,
                              unstable: Callable[[], bool] | None = None,
                              snapshot: Callable[[], Callable[[], None]] | None = None) -> str:
    """Solve a static equilibrium; returns the method that succeeded.

    Parameters
    ----------
    model
        The built model (:class:`~exudyn_atcm.mbs.solver_runs.SolvableModel`).
    static : callable
        The first attempt: Exudyn's static solver in load steps (raises ``ExudynFailure``).
    relaxation : callable
        Puts the model on the relaxation's start (reference pose or the last state, the path).
    relax_target : float
        The path parameter the relaxation ramps to.
    omega1 : float
        Lowest angular frequency of the parts [rad/s]: the relaxation's damping and duration.
    polish : callable
        Puts the model at the end of the path and runs one static step (raises ``ExudynFailure``).
    size : float
        The system's size [m]: a relaxation moving by less than ``1e-9 * size`` is at rest.
    subject, what : str
        Who and which equilibrium, for the messages (``"mechanism 'four_bar'"``, ``"voltage 1500 V"``).
    load_steps : int
        The first attempt's load steps, for the messages.
    advice : str
        What to change when everything failed.
    unstable : callable, optional
        ``unstable()`` is True when the model's current state, a converged static solution, is an
        unstable equilibrium; then the relaxation follows the path instead (method
        ``"relaxation+static"`` or ``"relaxation"`` when it found a stable equilibrium).  When it
        finds none, the static solution is restored (method ``"static"``); the last call of
        ``unstable`` is always about the state returned when the method is ``"static"``.
    snapshot : callable, optional
        ``snapshot()`` saves the model's state and returns a function restoring it (needed with
        ``unstable``: the unstable static solution is restored when the relaxation fails).

    Raises
    ------
    SimulationInterrupted
        For Ctrl-C during the first attempt.
    SolverError
        When neither the static solver nor the relaxation found the equilibrium, saying what was tried.
    """
    try:
        static()
        if unstable is None or not unstable():
            return "static"
        restore = snapshot() if snapshot is not None else None
    except runs.ExudynFailure as exc:
        if is_interrupt(exc):
            raise SimulationInterrupted(0.0) from None
        first, restore = exc, None
    if restore is not None:  # converged, but unstable: follow the path by relaxation, else keep it
        try:
            method = _relax(model, relaxation, relax_target, omega1, polish, size, None, subject, what, load_steps,
                            advice)
            if not unstable():
                return method
        except SolverError:
            pass
        # no stable state on the path (a perfectly symmetric load has no side to go to): the static solution
        # is the equilibrium the path reaches, and the caller warns about its stability (checked again, so
        # that the last check is of the state returned)
        restore()
        unstable()
        return "static"
    return _relax(model, relaxation, relax_target, omega1, polish, size, first, subject, what, load_steps, advice)


def _relax(model, relaxation, relax_target, omega1, polish, size, first, subject, what, load_steps, advice) -> str:
    """The relaxation and its polish (``first``: the static solver's failure, ``None`` when it converged to an
    unstable equilibrium)."""
    tried = (f"Exudyn's static solver with {load_steps} load steps (stopped at load factor {first.time:.4g}: {first})"
             if first is not None else
             f"Exudyn's static solver with {load_steps} load steps (converged to an unstable equilibrium)")
    relaxation()
    try:
        # periods counted at half the lowest frequency: coarse chains of six-bar cells are softer
        change = runs.run_relaxation(model, relax_target, 0.5 * omega1, 2.0 / omega1)
    except runs.ExudynFailure as exc:
        raise SolverError(
            f"static equilibrium ({what}) of {subject} did not converge. Tried: {tried}, then dynamic relaxation "
            f"(stopped at {exc.time:.3g} of its ramp: {exc}). {advice}") from exc
    relaxed = np.array(model.coordinates())
    runs.set_current_as_initial(model, zero_velocity=True)
    try:
        polish()
        return "relaxation+static"
    except runs.ExudynFailure:
        pass
    tol = 1e-9 * size
    if change <= tol:
        runs.set_current_coordinates(model, relaxed)
        return "relaxation"
    raise SolverError(
        f"static equilibrium ({what}) of {subject} did not converge. Tried: {tried}; dynamic relaxation still moved "
        f"by {change:.3g} m over its last period "
        f"(accepted: {tol:.3g} m) and the static polish step failed. {advice}")
