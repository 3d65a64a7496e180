"""Module paths that moved, kept importable for one release.

Importing an old path (``exudyn_atcm.solve.step_record``, moved in 0.3 to
``exudyn_atcm.mbs.step_record``) returns the module at its new place and warns
:class:`DeprecationWarning` naming the new path; the paths that moved in 0.2 (the role folders:
``exudyn_atcm.simulation``, ``exudyn_atcm.beam_theory``, ...) were removed in 0.3.  The one
exception is :mod:`exudyn_atcm.signals`, part of the top-level face, which stays importable
under that name without a warning.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings

from .errors import AtcmDeprecationWarning

#: old module path -> new module path (both below ``exudyn_atcm``)
MOVED = {
    "signals": "model.signals",
    "solve.step_record": "mbs.step_record",
}

#: old paths that are part of the public face and stay without a warning
SILENT = frozenset({"signals"})

_PACKAGE = __name__.rpartition(".")[0]


class _AliasLoader(importlib.abc.Loader):
    def __init__(self, old: str, new: str) -> None:
        self.old, self.new = old, new

    def create_module(self, spec):  # noqa: D102 - importlib protocol
        return importlib.import_module(self.new)

    def exec_module(self, module) -> None:  # noqa: D102 - importlib protocol
        sys.modules[self.old] = module


class MovedModuleFinder(importlib.abc.MetaPathFinder):
    """Finds ``exudyn_atcm.<old>`` for every entry of :data:`MOVED` and returns the new module."""

    def find_spec(self, fullname: str, path=None, target=None):  # noqa: D102 - importlib protocol
        prefix = _PACKAGE + "."
        if not fullname.startswith(prefix):
            return None
        old = fullname[len(prefix):]
        new = MOVED.get(old)
        if new is None:
            return None
        if old not in SILENT:
            warnings.warn(f"{fullname} moved to {_PACKAGE}.{new}; the old path goes away in the next release "
                          f"(import from {_PACKAGE} or {_PACKAGE}.{new})", AtcmDeprecationWarning, stacklevel=2)
        return importlib.util.spec_from_loader(fullname, _AliasLoader(fullname, f"{_PACKAGE}.{new}"))


def install() -> None:
    """Put :class:`MovedModuleFinder` on ``sys.meta_path`` once."""
    if not any(isinstance(f, MovedModuleFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, MovedModuleFinder())
