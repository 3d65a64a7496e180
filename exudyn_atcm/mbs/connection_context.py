"""Deprecated: the connection context is the one build context (:mod:`exudyn_atcm.mbs.build_context`).

``ConnectionContext`` is kept for one release as an alias of
:class:`~exudyn_atcm.mbs.build_context.BuildContext` (with an
:class:`~exudyn_atcm.AtcmDeprecationWarning` when it is imported); its methods are the build context's
(``add_hinge(p, q, ...)`` with points is now ``add_pin``, ``body(point)`` is ``body_at(point).item``,
``system`` is ``mbs``).
"""

from __future__ import annotations

import warnings
from typing import Any

from ..errors import AtcmDeprecationWarning
from .build_context import BuildContext

__all__: list[str] = []


def deprecated_alias(module: str, name: str) -> Any:
    """``BuildContext`` for the old name ``ConnectionContext`` (warns :class:`~exudyn_atcm.AtcmDeprecationWarning`)."""
    if name != "ConnectionContext":
        raise AttributeError(f"module {module!r} has no attribute {name!r}")
    warnings.warn(f"{module}.ConnectionContext is deprecated: connections realise into the one build context, "
                  "exudyn_atcm.mbs.BuildContext (add_hinge(p, q, ...) is now add_pin); the old name goes away in "
                  "the next release", AtcmDeprecationWarning, stacklevel=3)
    return BuildContext


def __getattr__(name: str) -> Any:
    return deprecated_alias(__name__, name)
