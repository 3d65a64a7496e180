"""Why a design search ends before its optimiser does: the evaluation budget, an objective never finite.

Raised by :class:`~exudyn_atcm.study.problem.Problem` and handled by
:func:`~exudyn_atcm.study.optimize` (see :doc:`/studies`).
"""

from __future__ import annotations

from typing import Any

__all__ = ["SearchStopped", "ObjectiveNotFiniteError"]


class SearchStopped(Exception):
    """The evaluation budget is spent: the search ends here (caught by :func:`~exudyn_atcm.study.optimize`)."""


class ObjectiveNotFiniteError(RuntimeError):
    """The objective (or a constraint's scalar) was not finite at any design of the first batch.

    Attributes
    ----------
    designs : list of (dict, str)
        Each design tried (its design variables) and what it gave, in the order evaluated.
    """

    def __init__(self, message: str, designs: list[tuple[dict[str, Any], str]]) -> None:
        super().__init__(message)
        self.designs = designs
