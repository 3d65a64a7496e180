"""The Exudyn layer of mechanisms: building a :class:`~exudyn_atcm.mechanism.Mechanism` into a
``MainSystem``, step hooks shared with user code, read-outs and linearisation.

With :mod:`exudyn_atcm._mbs_builder` this is the only part of the package that calls Exudyn.
"""

from .hooks import StepHooks, add_post_step, add_pre_step, step_hooks
from .linear import DofReport
from .user_system import MechanismHandle, add_to

__all__ = ["add_to", "MechanismHandle", "StepHooks", "add_pre_step", "add_post_step", "step_hooks", "DofReport"]
