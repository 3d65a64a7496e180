"""Each distinct warning once per case run: :func:`warnings_once`.

A case may call the solver many times (a sweep of static solves, a time run per design, the
same check for each drive): a warning about what the user gave then comes once per call, and a
user who sees the same line five times learns to skip them all.  :meth:`Case.run
<exudyn_atcm.casework.case.Case.run>` shows each distinct warning (same category, same text up
to white space) the first time it is issued and counts the repeats in
:attr:`WarningTally.counts`; the filters in force still apply (an ``error`` filter still
raises at the first one, an ``ignore`` filter still hides it).
"""

from __future__ import annotations

import warnings
from collections import Counter
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

__all__ = ["WarningTally", "warnings_once"]


@dataclass
class WarningTally:
    """How often each distinct warning was issued during a run.

    ``counts`` maps ``(category, text)`` (white space collapsed) to the number of times it was
    issued; only the first was shown.
    """

    counts: Counter = field(default_factory=Counter)

    def repeated(self) -> dict[tuple[type, str], int]:
        """The warnings issued more than once, with their counts."""
        return {key: n for key, n in self.counts.items() if n > 1}


@contextmanager
def warnings_once() -> Iterator[WarningTally]:
    """Within the block, show each distinct warning once (to whatever showed warnings before).

    Yields
    ------
    WarningTally
        Filled while the block runs.
    """
    tally = WarningTally()
    with warnings.catch_warnings():
        previous = warnings.showwarning

        def show(message, category, filename, lineno, file=None, line=None) -> None:
            key = (category, " ".join(str(message).split()))
            tally.counts[key] += 1
            if tally.counts[key] == 1:
                previous(message, category, filename, lineno, file, line)

        warnings.showwarning = show
        yield tally
