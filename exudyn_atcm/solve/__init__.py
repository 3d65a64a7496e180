"""From a description to a result: ``simulate``, ``solve_static``, ``static_sweep``,
``eigenfrequencies``, ``step_error``, ``mechanism_feedforward``, the run checks and the set-up every time integration shares.

May import the description layers and :mod:`exudyn_atcm.mbs`; never plotting.
"""

from ..errors import SolverError
from ..model.strain_sources import InStepStrain, TableStrain
from .run_checks import SimulationInterrupted
from .run_setup import DEFAULT_STEP
from .built_system import BuiltSystem
from .simulation import eigenfrequencies, run_actuator, simulate, solve_static, static_sweep
from .step_error import StepError, step_error
from .feedforward_mechanism import FeedforwardReport, mechanism_feedforward
from .output_map import OutputMap

__all__ = ["simulate", "solve_static", "static_sweep", "eigenfrequencies", "DEFAULT_STEP", "SolverError",
           "SimulationInterrupted", "run_actuator", "InStepStrain", "TableStrain", "step_error", "StepError",
           "BuiltSystem", "mechanism_feedforward", "FeedforwardReport", "OutputMap"]
