"""Keyword-only arguments with a one-release grace period for positional calls.

The solve functions take the system first and everything else by keyword
(``simulate(system, t_end, *, step=...)``).  ``step_error``'s positional ``step`` (before 0.3)
keeps working for one release: the function collects extra positional arguments in
``*legacy`` and :func:`legacy_positional` maps them onto their old names with a
:class:`DeprecationWarning`.  No wrapper function is involved, so the warnings the solve
functions issue still point at the caller's line.  :func:`keyword_signature` hides ``*legacy``
from ``inspect.signature`` (and so from the API reference).
"""

from __future__ import annotations

import inspect
import warnings
from typing import Any, Callable, TypeVar

from ..errors import AtcmDeprecationWarning

__all__ = ["legacy_positional", "keyword_signature"]

F = TypeVar("F", bound=Callable[..., Any])


def legacy_positional(function: str, legacy: tuple, given: dict[str, Any], defaults: dict[str, Any]) -> dict[str, Any]:
    """The keyword values after mapping the positional ``legacy`` values onto ``names``.

    Parameters
    ----------
    function : str
        Name of the public function (for the messages).
    legacy : tuple
        The extra positional arguments received.
    given : dict
        The keyword values received, by name, in the order the old signature took them
        positionally.
    defaults : dict
        The defaults of the function's parameters (a value still ``is`` its default when not given).

    Raises
    ------
    TypeError
        For more positional values than the old signature had, or a value given both ways.
    """
    names = tuple(given)
    if len(legacy) > len(names):
        raise TypeError(f"{function}() takes its system positionally and {', '.join(names)} by keyword; got "
                        f"{len(legacy)} extra positional arguments")
    out = dict(given)
    used = names[: len(legacy)]
    for name, value in zip(used, legacy):
        if given[name] is not defaults[name]:
            raise TypeError(f"{function}() got multiple values for argument {name!r}")
        out[name] = value
    warnings.warn(f"{function}(): pass {', '.join(f'{n}=' for n in used)} by keyword (positional use goes away in "
                  "the next release)", AtcmDeprecationWarning, stacklevel=3)
    return out


def keyword_signature(function: F) -> F:
    """Give ``function`` the signature without its ``*legacy`` catch-all (returns the same object)."""
    sig = inspect.signature(function)
    function.__signature__ = sig.replace(  # type: ignore[attr-defined]
        parameters=[p for p in sig.parameters.values() if p.kind is not inspect.Parameter.VAR_POSITIONAL])
    return function
