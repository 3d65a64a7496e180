"""The Exudyn layer: the only part of the package that imports and calls Exudyn.

Mechanisms (:class:`~exudyn_atcm.mechanism.Mechanism`) are built into a ``MainSystem`` by
:mod:`~exudyn_atcm.mbs.builder` (six-bar chains in :mod:`~exudyn_atcm.mbs.six_bar`, beam
chains in :mod:`~exudyn_atcm.mbs.beam_chain`), with step hooks shared with user code, read-outs
and linearisation; the lone :class:`~exudyn_atcm.mechanism.actuator.BendingActuator` is built by
:mod:`~exudyn_atcm.mbs.actuator_chains` (rigid and six-bar chains) and its beam, ANCF and
kinematic-tree cells.  Both paths share the solver settings
(:mod:`~exudyn_atcm.mbs.solver_settings`), the solver runs (:mod:`~exudyn_atcm.mbs.solver_runs`)
and the constrained eigenfrequencies (:mod:`~exudyn_atcm.mbs.eigen`).

On import it registers its degrees-of-freedom count with the description layer
(:mod:`exudyn_atcm.mechanism.realisation`), which never imports this one.
"""

from __future__ import annotations

from ..mechanism.realisation import register_dof_counter
from .builder import build
from .hooks import StepHooks, add_post_step, add_pre_step, step_hooks
from .linear import DofReport, degrees_of_freedom
from .user_system import MechanismHandle, add_to

__all__ = ["add_to", "MechanismHandle", "StepHooks", "add_pre_step", "add_post_step", "step_hooks", "DofReport"]


def _count(mechanism) -> DofReport:
    return degrees_of_freedom(build(mechanism))


register_dof_counter(_count)
