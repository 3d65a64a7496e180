"""The closest-name suggestion for a misspelt name, shared by every layer's messages.

Like :mod:`exudyn_atcm._checks`, this module imports nothing of the package, so any layer may use it.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable

__all__ = ["close_names"]


def close_names(name: object, candidates: Iterable[object], *, n: int = 1, cutoff: float = 0.6,
                ignore_case: bool = False) -> list[str]:
    """The up to ``n`` candidates closest to a misspelt ``name`` (``difflib`` similarity >= ``cutoff``).

    With ``ignore_case``, a candidate equal to ``name`` but for case is the answer when nothing
    is close enough.  Names and candidates are compared as strings.

    >>> close_names("stpe", ["step", "t_end"])
    ['step']
    >>> close_names("PERIOD", ["period"], ignore_case=True)
    ['period']
    """
    text = str(name)
    names = [str(c) for c in candidates]
    matches = difflib.get_close_matches(text, names, n=n, cutoff=cutoff)
    if not matches and ignore_case:
        lowered = {c.lower(): c for c in names}
        if text.lower() in lowered:
            matches = [lowered[text.lower()]]
    return matches
