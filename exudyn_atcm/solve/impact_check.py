"""The cells of a mechanism with stops, checked in the accuracy run itself: :func:`impacts_checked`.

The cell choice (:mod:`exudyn_atcm.solve.cell_choice`) compares counts on static poses and the lowest mode; an
impact against a stop rings higher modes it does not see (a lever driven against a stop: 1.7e-3 of the travel
between 3 and 4 rod modes where the choice estimated 1.1e-4).  For a mechanism with stops ``simulate(...,
accuracy=)`` therefore also runs the next count at the chosen step and says how far the two differ.
"""

from __future__ import annotations

import warnings
from typing import Any

from ..errors import AccuracyWarning
from ..io.result import Result
from . import mechanism_solve
from .cell_choice import SPACE_SHARE, CellChoice
from .step_choice import position_error

__all__ = ["impacts_checked"]


def impacts_checked(choice: CellChoice, result: Result, accuracy: float, t_end: float, settings: Any = None,
                    record_every: Any = None) -> Result:
    """For a mechanism with stops: ``result`` (the accuracy run) compared with the next count's run at its step.

    The choice compares counts on static poses and the lowest mode; an impact against a stop rings higher modes
    it does not see.  The next count's run at the same step (its time error nearly the same) differs from
    ``result`` by about the cells' error in the run: recorded in ``info["accuracy"]["cells_error_at_impacts"]``
    and in ``choice.line``, and an :class:`~exudyn_atcm.AccuracyWarning` says when it exceeds the cells' share
    (:data:`~exudyn_atcm.solve.cell_choice.SPACE_SHARE` of ``accuracy``) and what to fix.  Costs one run with more cells."""
    stops = choice.mechanism.stops
    if not stops or not choice.cells:
        return result
    names = ", ".join(repr(stop.name) for stop in stops)
    plural = "s" if len(stops) > 1 else ""
    if choice.finer is None:
        choice.line += f"; the impacts against the stop{plural} {names} not checked (no count above the one taken)"
        return result
    step = float(result.info["step [s]"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the check's own run: its messages are the accuracy run's
        other = mechanism_solve.simulate(choice.finer, t_end, step, settings, None, record_every)
    error = position_error(other, result, step)
    share = SPACE_SHARE * accuracy
    said = ", ".join(f"{name!r} {choice.finer.components[name].n_cells}" for name in choice.cells)
    result.info["accuracy"]["cells_error_at_impacts"] = error
    chosen = choice.line.split(" for ")[0]
    choice.line += (f"; checked at the impacts against the stop{plural} {names}: the next count ({said}) at the "
                    f"run's step differs by {error:.2g} of the travel")
    if error > share:
        warnings.warn(f"the cells chosen for the accuracy ({chosen}) miss it at the impacts against the stop{plural} "
                      f"{names}: the run with the next count ({said}) at the same step differs by {error:.2g} of the "
                      f"travel, against the cells' share {share:.2g} (the static poses and the lowest mode estimated "
                      f"{choice.estimated_error:.2g}). Fix n_cells at the next count or more and compare the runs",
                      AccuracyWarning, stacklevel=4)
    return result
