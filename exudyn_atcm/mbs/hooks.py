"""Several pre-step and post-step functions on one Exudyn system.

Exudyn keeps one ``PreStep`` and one ``PostStep`` user function per ``MainSystem``.  A
:class:`StepHooks` object, stored in ``mbs.variables`` and installed as both, calls every
registered function in order.  The package registers its hysteresis hooks there
(:func:`exudyn_atcm.add_to`); register your own with :func:`add_pre_step` /
:func:`add_post_step` instead of ``mbs.SetPreStepUserFunction``.

Exudyn calls ``PreStep`` before every attempted step and ``PostStep`` after every accepted
step (and once at ``t = 0``), both with the step's end time ``t``.

An exception raised by one of your step functions is passed on as it is, with a note naming the
function and ``t``; Exudyn then stops and reports it as its ``ModelError`` whose ``__cause__`` is
your exception.
"""

from __future__ import annotations

from typing import Any, Callable

from .._checks import shown
from ..errors import annotate

StepFunction = Callable[[Any, float], bool]

#: Key of the :class:`StepHooks` object in ``mbs.variables``.
VARIABLE = "exudyn_atcm.step_hooks"


class StepHooks:
    """The functions run in each step of one Exudyn system.

    Attributes
    ----------
    pre : list of callable
        ``f(mbs, t) -> bool`` run before every attempted step.
    post : list of callable
        ``f(mbs, t) -> bool`` run after every accepted step.

    Notes
    -----
    Every function runs even if an earlier one returned ``False``; the step continues only
    if all returned something other than ``False`` (Exudyn stops the simulation otherwise).
    """

    def __init__(self) -> None:
        self.pre: list[StepFunction] = []
        self.post: list[StepFunction] = []

    def pre_step(self, mbs, t: float) -> bool:
        """Exudyn's ``PreStep`` user function: runs :attr:`pre` in order."""
        return _run_all(self.pre, mbs, t, "pre")

    def post_step(self, mbs, t: float) -> bool:
        """Exudyn's ``PostStep`` user function: runs :attr:`post` in order."""
        return _run_all(self.post, mbs, t, "post")

    def install(self, mbs) -> None:
        """Make this object the system's ``PreStep`` and ``PostStep`` user functions."""
        mbs.SetPreStepUserFunction(self.pre_step)
        mbs.SetPostStepUserFunction(self.post_step)


def _run_all(functions: list[StepFunction], mbs, t: float, which: str) -> bool:
    """Run every function; an exception of the user's own passes on with a note naming it and ``t``."""
    ok = True
    for f in functions:
        try:
            ok = (f(mbs, t) is not False) and ok
        except Exception as exc:
            if not getattr(f, "__module__", "").startswith(_PACKAGE):  # the package's hooks add their own note
                name = getattr(f, "__qualname__", type(f).__name__)
                annotate(exc, f"(raised by the {which}-step function {name!r} at t = {t:.9g} s)")
            raise
    return ok


_PACKAGE = __name__.split(".")[0] + "."


def _current(getter) -> Any:
    try:
        value = getter(asDict=True)
    except Exception:  # noqa: BLE001 - an older interface: nothing to adopt
        return None
    function = value.get("function") if isinstance(value, dict) else None
    return function if callable(function) else None


def step_hooks(mbs) -> StepHooks:
    """The :class:`StepHooks` of ``mbs`` (created and installed on first use).

    A ``PreStep`` / ``PostStep`` function that was set on ``mbs`` before is kept: it becomes
    the first entry of :attr:`StepHooks.pre` / :attr:`StepHooks.post`.
    """
    hooks = mbs.variables.get(VARIABLE)
    if isinstance(hooks, StepHooks):
        return hooks
    hooks = StepHooks()
    for getter, target in ((mbs.GetPreStepUserFunction, hooks.pre), (mbs.GetPostStepUserFunction, hooks.post)):
        existing = _current(getter)
        if existing is not None:
            target.append(existing)
    mbs.variables[VARIABLE] = hooks
    hooks.install(mbs)
    return hooks


def add_pre_step(mbs, function: StepFunction) -> None:
    """Run ``function(mbs, t) -> bool`` before every attempted step, with the package's hooks.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    function : callable
        ``function(mbs, t)`` with ``t`` the end time of the step being attempted [s].
    """
    if not callable(function):
        raise ValueError(f"function must be a callable f(mbs, t) -> bool, got {shown(function)}")
    hooks = step_hooks(mbs)
    hooks.pre.append(function)
    hooks.install(mbs)


def add_post_step(mbs, function: StepFunction) -> None:
    """Run ``function(mbs, t) -> bool`` after every accepted step, with the package's hooks.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    function : callable
        ``function(mbs, t)`` with ``t`` the time reached [s].
    """
    if not callable(function):
        raise ValueError(f"function must be a callable f(mbs, t) -> bool, got {shown(function)}")
    hooks = step_hooks(mbs)
    hooks.post.append(function)
    hooks.install(mbs)


#: Key of the list of post-Newton checks in ``mbs.variables``.
POST_NEWTON_VARIABLE = "exudyn_atcm.post_newton"


def add_post_newton(mbs, check: Callable[[Any, float], float]) -> None:
    """Run ``check(mbs, t) -> error`` after every Newton solve of ``mbs`` (static and dynamic solvers).

    Exudyn keeps one ``PostNewton`` user function per system; the package installs one that
    runs every registered check and returns the largest error.  An error above Exudyn's
    ``discontinuous.iterationTolerance`` (1 by default: return a ratio to your own tolerance)
    makes the solver repeat the step's Newton solve (a "discontinuous iteration"), up to
    ``discontinuous.maxIterations`` times.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    check : callable
        ``check(mbs, t)`` with ``t`` the step's end time [s] (the load factor in static solves);
        returns a float >= 0.
    """
    if not callable(check):
        raise ValueError(f"check must be a callable check(mbs, t) -> float, got {shown(check)}")
    checks = mbs.variables.get(POST_NEWTON_VARIABLE)
    if not isinstance(checks, list):
        checks = mbs.variables[POST_NEWTON_VARIABLE] = []

        def post_newton(mbs_, t: float) -> list[float]:
            error = 0.0
            for f in checks:
                error = max(error, f(mbs_, t))
            return [error, -1.0]

        mbs.SetPostNewtonUserFunction(post_newton)
    checks.append(check)
