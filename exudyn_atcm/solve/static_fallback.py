"""Static equilibrium with a fallback, shared by the actuator and the mechanism paths.

Exudyn's static Jacobian leaves out the derivative of the constraint forces, so under large
loads its Newton iteration converges only linearly, ever slower, and can stall (measured on the
elastica cases).  :func:`equilibrium_with_fallback` tries Exudyn's static solver first; when it
stalls, the equilibrium is found by dynamic relaxation (strongly damped implicit dynamics with a
smooth load ramp) and polished with one static step from there; a relaxation that has come to
rest (moving by less than 1e-9 of the system's size over its last period) is accepted without
the polish.  Each path supplies how its model is put on the path between the attempts.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from ..errors import SolverError
from ..mbs import solver_runs as runs
from .interrupts import SimulationInterrupted, is_interrupt

__all__ = ["equilibrium_with_fallback"]


def equilibrium_with_fallback(model, *, static: Callable[[], None], relaxation: Callable[[], None],
                              relax_target: float, omega1: float, polish: Callable[[], None], size: float,
                              subject: str, what: str, load_steps: int, advice: str) -> str:
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

    Raises
    ------
    SimulationInterrupted
        For Ctrl-C during the first attempt.
    SolverError
        When neither the static solver nor the relaxation found the equilibrium, saying what was tried.
    """
    try:
        static()
        return "static"
    except runs.ExudynFailure as exc:
        if is_interrupt(exc):
            raise SimulationInterrupted(0.0) from None
        first = exc
    relaxation()
    try:
        # periods counted at half the lowest frequency: coarse chains of six-bar cells are softer
        change = runs.run_relaxation(model, relax_target, 0.5 * omega1, 2.0 / omega1)
    except runs.ExudynFailure as exc:
        raise SolverError(
            f"static equilibrium ({what}) of {subject} did not converge. Tried: Exudyn's static solver with "
            f"{load_steps} load steps (stopped at load factor {first.time:.4g}: {first}), then dynamic relaxation "
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
        f"static equilibrium ({what}) of {subject} did not converge: Exudyn's static solver stopped at load factor "
        f"{first.time:.4g} ({first}); dynamic relaxation still moved by {change:.3g} m over its last period "
        f"(accepted: {tol:.3g} m) and the static polish step failed. {advice}")
