"""Several pre-step and post-step functions on one Exudyn system.

Exudyn keeps one ``PreStep`` and one ``PostStep`` user function per ``MainSystem``.  A
:class:`StepHooks` object, stored in ``mbs.variables`` and installed as both, calls every
registered function in order.  The package registers its hysteresis hooks there
(:func:`exudyn_atcm.add_to`); register your own with :func:`add_pre_step` /
:func:`add_post_step` instead of ``mbs.SetPreStepUserFunction``.

Exudyn calls ``PreStep`` before every attempted step and ``PostStep`` after every accepted
step (and once at ``t = 0``), both with the step's end time ``t``.
"""

from __future__ import annotations

from typing import Any, Callable

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
        ok = True
        for f in self.pre:
            ok = (f(mbs, t) is not False) and ok
        return ok

    def post_step(self, mbs, t: float) -> bool:
        """Exudyn's ``PostStep`` user function: runs :attr:`post` in order."""
        ok = True
        for f in self.post:
            ok = (f(mbs, t) is not False) and ok
        return ok

    def install(self, mbs) -> None:
        """Make this object the system's ``PreStep`` and ``PostStep`` user functions."""
        mbs.SetPreStepUserFunction(self.pre_step)
        mbs.SetPostStepUserFunction(self.post_step)


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
        raise ValueError(f"function must be a callable f(mbs, t) -> bool, got {function!r}")
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
        raise ValueError(f"function must be a callable f(mbs, t) -> bool, got {function!r}")
    hooks = step_hooks(mbs)
    hooks.post.append(function)
    hooks.install(mbs)
