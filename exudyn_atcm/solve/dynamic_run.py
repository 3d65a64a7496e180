"""One guarded time integration, shared by the actuator and the mechanism paths.

:func:`integrate` runs Exudyn's implicit solver with the path's pre-step and post-step hooks
behind an :class:`~exudyn_atcm.solve.interrupts.InterruptGuard`: Ctrl-C (or SIGTERM turned into
it) stops the run cleanly, an error raised in the hooks (the user's voltage program, controller,
load function or progress callback) is raised as it was, with a note of the hook and the time
(:class:`~exudyn_atcm.mbs.solver_runs.HookErrors`), and any other solver failure becomes a :class:`~exudyn_atcm.errors.SolverError` saying when it
failed, what was tried and what to change.  :func:`mark_partial` marks the ``info`` of a run
stopped early.
"""

from __future__ import annotations

from typing import Any, Callable

from ..errors import SolverError
from ..mbs import solver_runs as runs
from .interrupts import InterruptGuard, is_interrupt

__all__ = ["integrate", "mark_partial"]


def integrate(model: Any, settings: Any, pre_step: Callable[[float], Any] | None, post_step: Callable[[float], Any], *,
              what: str, advice: str, step: float, last_time: Callable[[], float]) -> tuple[dict | None, bool]:
    """Integrate ``model`` in time; returns ``(solver statistics or None, interrupted)``.

    Parameters
    ----------
    model, settings
        The built model and its ``exudyn.SimulationSettings``.
    pre_step, post_step : callable
        ``f(t)`` before every attempted step (may be ``None``) and after every accepted step.
    what : str
        The system in the failure message (``"mechanism 'four_bar'"``).
    advice : str
        What to change, ending the failure message.
    step : float
        The step [s], quoted in the failure message.
    last_time : callable
        ``last_time()`` [s]: the last accepted step, quoted in the failure message.
    Raises
    ------
    SolverError
        When Exudyn's Newton iteration failed even at the minimum step.
    Exception
        Whatever a hook raised (the user's own code), as it is.
    """
    guard = InterruptGuard()
    try:
        return runs.run_dynamic(model, settings, guard.wrap(pre_step), guard.wrap(post_step)), guard.interrupted
    except runs.ExudynFailure as exc:
        if is_interrupt(exc):
            return None, True
        newton = settings.timeIntegration.newton
        raise SolverError(
            f"time integration of {what} failed at t = {exc.time:.6g} s (last accepted step at t = "
            f"{last_time():.6g} s, step {step:g} s): generalized-alpha with Newton (absolute tolerance "
            f"{newton.absoluteTolerance:g}) did not converge even after reducing the step size down to "
            f"{settings.timeIntegration.minimumStepSize:g} s. Exudyn said: {exc}. {advice}") from exc


def mark_partial(info: dict, t_stop: float, accepted: int) -> dict:
    """Mark the ``info`` of a run stopped at ``t_stop`` [s] after ``accepted`` steps as partial."""
    info["partial"] = True
    info["interrupted_at [s]"] = t_stop
    info.setdefault("attempted_steps", accepted)
    info.setdefault("rejected_steps", 0)
    return info
