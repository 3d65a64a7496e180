"""The Exudyn layer: the only part of the package that imports and calls Exudyn.

Mechanisms (:class:`~exudyn_atcm.mechanism.Mechanism`) are built into a ``MainSystem`` by
:mod:`~exudyn_atcm.mbs.builder` (six-bar chains in :mod:`~exudyn_atcm.mbs.six_bar`, beam
chains in :mod:`~exudyn_atcm.mbs.beam_chain`), with step hooks shared with user code, read-outs
and linearisation; the lone :class:`~exudyn_atcm.actuator.BendingActuator` is built by
:mod:`~exudyn_atcm.mbs.actuator_chains` (rigid and six-bar chains) and its beam, ANCF and
kinematic-tree cells.  Both paths share the solver settings
(:mod:`~exudyn_atcm.mbs.solver_settings`), the solver runs (:mod:`~exudyn_atcm.mbs.solver_runs`)
and the constrained eigenfrequencies (:mod:`~exudyn_atcm.mbs.eigen`).

The public names below are loaded on first access (PEP 562), so that the solve layer can import
the submodules it builds on without loading :mod:`~exudyn_atcm.mbs.user_system`, which itself
builds on the solve layer.
"""

from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {
    "add_to": "user_system",
    "MechanismHandle": "user_system",
    "StepHooks": "hooks",
    "add_pre_step": "hooks",
    "add_post_step": "hooks",
    "step_hooks": "hooks",
    "DofReport": "linear",
}

__all__ = ["add_to", "MechanismHandle", "StepHooks", "add_pre_step", "add_post_step", "step_hooks", "DofReport"]


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
