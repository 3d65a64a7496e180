"""One-line error reports of the command line (``exudyn-atcm`` and its study subcommands)."""

from __future__ import annotations

import sys
import traceback

__all__ = ["report_error"]


def report_error(exc: BaseException | str, debug: bool, status: int) -> int:
    """Print ``error: <text>`` on stderr (the traceback first if ``debug``) and return ``status``.

    Parameters
    ----------
    exc : BaseException or str
        The exception (its text on one line, or its type name if empty) or a message.
    debug : bool
        Print the exception's traceback before the line (``--debug``).
    status : int
        Exit status to return (2 usage error, 1 failure, 130 interrupt).
    """
    if debug and isinstance(exc, BaseException):
        traceback.print_exception(type(exc), exc, exc.__traceback__)
    text = exc if isinstance(exc, str) else (" ".join(str(exc).split()) or type(exc).__name__)
    print(f"error: {text}", file=sys.stderr)
    return status
