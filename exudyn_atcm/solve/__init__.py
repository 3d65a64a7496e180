"""From a description to a result: ``simulate``, ``solve_static``, ``static_sweep``,
``eigenfrequencies``, ``step_error``, ``mechanism_feedforward``, the run checks and the set-up every time integration shares.

May import the description layers and :mod:`exudyn_atcm.mbs`; never plotting.
"""

from typing import TYPE_CHECKING

from ..lazy_names import lazy_face

# The names load on first use (PEP 562, exudyn_atcm.lazy_names): name -> (module, attribute), read as
# `from module import attribute`.  To add a public name: one line here, the name in __all__ and the same
# import under TYPE_CHECKING (tests/test_lazy_names.py checks that the three agree).
_LAZY = {
    "SolverError": ("..errors", "SolverError"),
    "InStepStrain": ("..model.strain_sources", "InStepStrain"),
    "TableStrain": ("..model.strain_sources", "TableStrain"),
    "SimulationInterrupted": (".run_checks", "SimulationInterrupted"),
    "DEFAULT_STEP": (".run_setup", "DEFAULT_STEP"),
    "BuiltSystem": (".built_system", "BuiltSystem"),
    "eigenfrequencies": (".simulation", "eigenfrequencies"),
    "run_actuator": (".simulation", "run_actuator"),
    "simulate": (".simulation", "simulate"),
    "solve_static": (".simulation", "solve_static"),
    "static_sweep": (".simulation", "static_sweep"),
    "StepError": (".step_error", "StepError"),
    "step_error": (".step_error", "step_error"),
    "choose_cells": (".cell_choice", "choose_cells"),
    "CellChoice": (".cell_choice", "CellChoice"),
    "NoEquilibriumError": (".linear_state", "NoEquilibriumError"),
    "linearise": (".linearise", "linearise"),
    "Modes": (".modes", "Modes"),
    "modes": (".modes", "modes"),
    "LinearModel": (".state_space", "LinearModel"),
    "FeedforwardReport": (".feedforward_mechanism", "FeedforwardReport"),
    "mechanism_feedforward": (".feedforward_mechanism", "mechanism_feedforward"),
    "OutputMap": (".output_map", "OutputMap"),
    "ACCURACY_RANGE": (".step_choice", "ACCURACY_RANGE"),
    "accurate_run": (".step_choice", "accurate_run"),
}

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from ..errors import SolverError
    from ..model.strain_sources import InStepStrain, TableStrain
    from .run_checks import SimulationInterrupted
    from .run_setup import DEFAULT_STEP
    from .built_system import BuiltSystem
    from .simulation import eigenfrequencies, run_actuator, simulate, solve_static, static_sweep
    from .step_error import StepError, step_error
    from .cell_choice import CellChoice, choose_cells
    from .linear_state import NoEquilibriumError
    from .linearise import linearise
    from .modes import Modes, modes
    from .state_space import LinearModel
    from .feedforward_mechanism import FeedforwardReport, mechanism_feedforward
    from .output_map import OutputMap
    from .step_choice import ACCURACY_RANGE, accurate_run

__all__ = ["simulate", "solve_static", "static_sweep", "eigenfrequencies", "DEFAULT_STEP", "SolverError",
           "SimulationInterrupted", "run_actuator", "InStepStrain", "TableStrain", "step_error", "StepError", "choose_cells", "CellChoice",
           "BuiltSystem", "modes", "Modes", "linearise", "LinearModel", "NoEquilibriumError",
           "mechanism_feedforward", "FeedforwardReport", "OutputMap", "accurate_run", "ACCURACY_RANGE"]

__getattr__, __dir__ = lazy_face(__name__, _LAZY, submodules=True)
