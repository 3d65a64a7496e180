"""The case tables of the README and the docs, generated from what the case files declare
(``summary`` and ``table_order``, :mod:`exudyn_atcm.casework.declarations`).

``exudyn-atcm list --table md`` prints the README's table, ``--table rst`` the docs' one; a test
checks that both files hold exactly the table of the shipped cases.  Rows are sorted by
``table_order`` (then name); consecutive cases with the same summary share a row.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # annotations only: the command line imports TABLE_FORMATS without the case machinery
    from .case import Case

__all__ = ["TABLE_FORMATS", "table_rows", "case_table"]

#: The formats of :func:`case_table`: Markdown (README) and reStructuredText (docs).
TABLE_FORMATS = ("md", "rst")

_HEADER = ("case", "what it shows (and its reference)")


def table_rows(cases: Sequence[Case]) -> list[tuple[list[str], str]]:
    """The rows of the case table: ``(case names, summary)``, in table order.

    Raises
    ------
    ValueError
        If two cases have the same name (the first file of a name is the case: pass that one).
    """
    names = [c.name for c in cases]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise ValueError(f"cases: each name once, got {duplicates} more than once")
    rows: list[tuple[list[str], str]] = []
    for case in sorted(cases, key=lambda c: (c.table_order, c.name)):
        if rows and rows[-1][1] == case.summary:
            rows[-1][0].append(case.name)
        else:
            rows.append(([case.name], case.summary))
    return rows


def case_table(cases: Sequence[Case], fmt: str = "md") -> str:
    """The case table as text, without a trailing newline.

    Parameters
    ----------
    cases : sequence of Case
        The cases (e.g. :func:`~exudyn_atcm.casework.discovery.load_cases`).
    fmt : {"md", "rst"}
        A Markdown pipe table (the README's) or a reStructuredText ``list-table`` (the docs').

    Raises
    ------
    ValueError
        For another ``fmt`` or duplicate case names.
    """
    if fmt not in TABLE_FORMATS:
        raise ValueError(f"fmt must be one of {', '.join(TABLE_FORMATS)}, got {fmt!r}")
    rows = table_rows(cases)
    if fmt == "md":
        lines = [f"| {_HEADER[0]} | {_HEADER[1]} |", "|---|---|"]
        lines += [f"| {', '.join(f'`{n}`' for n in names)} | {summary} |" for names, summary in rows]
        return "\n".join(lines)
    lines = [".. list-table::", "   :header-rows: 1", "   :widths: 35 65", "",
             f"   * - {_HEADER[0]}", f"     - {_HEADER[1]}"]
    for names, summary in rows:
        lines += [f"   * - {', '.join(f'``{n}``' for n in names)}", f"     - {summary}"]
    return "\n".join(lines)
