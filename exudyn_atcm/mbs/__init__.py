"""The Exudyn layer: the only part of the package that imports and calls Exudyn.

One builder (:mod:`~exudyn_atcm.mbs.builder`) adds a :class:`~exudyn_atcm.mechanism.Mechanism`
to a ``MainSystem``; a lone :class:`~exudyn_atcm.mechanism.actuator.BendingActuator` is built as
the one-bender mechanism it is.  Each cell kind adds its bender through the realisation
registered for its class (the contract :mod:`~exudyn_atcm.mbs.realisation`, written through
:mod:`~exudyn_atcm.mbs.build_context`, the one build context that connections and loads write
through too): rigid chains
(:mod:`~exudyn_atcm.mbs.chains.rigid`), six-bar chains (:mod:`~exudyn_atcm.mbs.chains.six_bar`), beam
chains (:mod:`~exudyn_atcm.mbs.chains.beam`), ANCF chains (:mod:`~exudyn_atcm.mbs.chains.ancf`)
assumed modes (:mod:`~exudyn_atcm.mbs.chains.ritz`) and the geometrically exact rod
(:mod:`~exudyn_atcm.mbs.chains.rod`).  Around the builder: the model
handle with its read-outs (:mod:`~exudyn_atcm.mbs.model`, :mod:`~exudyn_atcm.mbs.recording`),
step hooks shared with user code, the solver settings and runs
(:mod:`~exudyn_atcm.mbs.solver_settings`, :mod:`~exudyn_atcm.mbs.solver_runs`) and the
constrained eigenfrequencies (:mod:`~exudyn_atcm.mbs.eigen`).

On import it registers its degrees-of-freedom count and its check of dependent joints
(:mod:`~exudyn_atcm.mbs.redundancy`) with the description layer
(:mod:`exudyn_atcm.mechanism.realisation`), which never imports this one.
"""

from __future__ import annotations

from ..mechanism.realisation import register_dof_counter, register_redundancy_check
from .build_context import BuildContext
from .builder import build
from .connection_context import deprecated_alias
from .hooks import StepHooks, add_post_newton, add_post_step, add_pre_step, step_hooks
from .linear import DofReport, degrees_of_freedom
from .node_chain import NodeEnds
from .realisation import CellRealisation, HingedEnds, register_realisation
from .user_system import MechanismHandle, add_to

__all__ = ["add_to", "MechanismHandle", "StepHooks", "add_pre_step", "add_post_step", "add_post_newton", "step_hooks",
           "DofReport", "CellRealisation", "HingedEnds", "NodeEnds", "BuildContext",
           "register_realisation"]


def _count(mechanism) -> DofReport:
    return degrees_of_freedom(build(mechanism, refuse_dependent=False))


def _refuse_dependent(mechanism) -> None:
    build(mechanism)  # refuses dependent constraints, naming the joints


register_dof_counter(_count)
register_redundancy_check(_refuse_dependent)


def __getattr__(name: str):
    # ConnectionContext: the deprecated name of BuildContext, for one release
    return deprecated_alias(__name__, name)
