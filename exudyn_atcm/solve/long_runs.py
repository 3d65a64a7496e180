"""The announcement of a long run: its wording, and the scope in which it was already made up front.

A single time integration announces itself
(:func:`~exudyn_atcm.solve.run_checks.warn_if_long`); a run made of several simulations (a
case that runs four controllers one after the other) announces the sum of their estimates
once, before the first starts (:class:`~exudyn_atcm.solve.run_plan.RunPlan`).  Inside the
plan's ``with`` block (:func:`announced_up_front`), the single simulations do not announce
themselves again.  Both use :func:`long_run_message`, so the wording is the same.
"""

from __future__ import annotations

import contextlib
import contextvars
from collections.abc import Iterator

from ..io.progress import format_duration

__all__ = ["long_run_message", "announced_up_front", "is_announced"]

_ANNOUNCED: contextvars.ContextVar[bool] = contextvars.ContextVar("exudyn_atcm_long_run_announced", default=False)


def long_run_message(estimate: float, detail: str) -> str:
    """The warning text of a run predicted to take ``estimate`` [s]; ``detail`` says what it consists of.

    >>> long_run_message(840.0, "4 simulations")[:60]
    'this run is predicted to take about 14 min (4 simulations). '
    """
    return (f"this run is predicted to take about {format_duration(estimate, rough=True)} ({detail}). For a "
            "quicker answer use a larger step (within the voltage program's limits), fewer cells or a shorter "
            "t_end; record_every reduces the memory; Ctrl-C stops the run and keeps what was computed")


@contextlib.contextmanager
def announced_up_front() -> Iterator[None]:
    """Within this block a long run was announced as a whole: single simulations stay quiet about it."""
    token = _ANNOUNCED.set(True)
    try:
        yield
    finally:
        _ANNOUNCED.reset(token)


def is_announced() -> bool:
    """True inside :func:`announced_up_front`."""
    return _ANNOUNCED.get()
