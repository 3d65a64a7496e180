"""Module paths that moved in 0.2 (the role folders), kept importable for one release (until 0.3).

Importing an old path (``exudyn_atcm.simulation``, ``exudyn_atcm.beam_theory``, ...) returns the
module at its new place and warns :class:`DeprecationWarning` naming the new path.  The one
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
    "_atomic": "io.atomic",
    "_cli_errors": "casework.error_report",
    "actuator": "mechanism.actuator",
    "beam_theory": "theory",
    "cases": "casework",
    "cell_drawing": "plots.cells",
    "control": "model.control",
    "csv_io": "io",
    "drive": "model.drive",
    "feedforward": "model.feedforward",
    "four_bar": "theory.four_bar",
    "hysteresis_plots": "plots.hysteresis",
    "identification_plots": "plots.identification",
    "laminate": "model.laminate",
    "materials": "model.materials",
    "measurements": "io.measurements",
    "mechanism_plots": "plots.mechanism",
    "mechanism_run_checks": "solve.mechanism_checks",
    "mechanism_shapes": "plots.mechanism_shapes",
    "mbs.ancf_chain": "mbs.chains.ancf",
    "mbs.beam_chain": "mbs.chains.beam",
    "mbs.rigid_chain": "mbs.chains.rigid",
    "mbs.ritz_bender": "mbs.chains.ritz",
    "mbs.six_bar": "mbs.chains.six_bar",
    "mechanism_solve": "solve.mechanism_solve",
    "parameter_sets": "model.parameter_sets",
    "plot_style": "plots.style",
    "plotting": "plots.result",
    "progress": "io.progress",
    "recording": "model.recording",
    "reference_record": "model.reference_record",
    "regression": "casework",
    "result": "io.result",
    "ritz_beam": "theory.ritz_beam",
    "run_checks": "solve.run_checks",
    "run_setup": "solve.run_setup",
    "signals": "model.signals",
    "simulation": "solve.simulation",
    "strain_sources": "model.strain_sources",
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
