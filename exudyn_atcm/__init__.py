"""exudyn_atcm: multibody simulation of active textile-reinforced compliant mechanisms on Exudyn.

>>> import exudyn_atcm as atcm
>>> layer = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550)

Top level (``__all__``): the building blocks (``Layer``, ``PiezoDrive``, ``BendingActuator``,
``Bender``, ``Segment``, ``Link``, ``Flexure``, ``Mechanism``, ``RayleighDamping``), solving (``simulate``,
``solve_static``, ``static_sweep``, ``eigenfrequencies``, ``step_error``, ``choose_cells`` (cells for an accuracy), ``mechanism_feedforward`` (a voltage program for a mechanism output), ``add_to``, ``BuiltSystem`` to solve one
build many times), results and files
(``Result``, ``read_csv``, ``read_record``, ``preprocess``), displacement to strain (``record_to_strain``,
``model_to_strain``), closed loop (``PIDController``), the errors
(``MechanismError``, ``SolverError``, ``SimulationInterrupted``), the warning categories (``AtcmWarning``
and its subclasses, see :mod:`exudyn_atcm.errors`) and the submodules
``hysteresis`` (operators, fits, inverses; ``load_model`` reads a saved one) and ``signals`` (voltage programs).  Everything
else lives in its module (``exudyn_atcm.study``, ``exudyn_atcm.plots.mechanism``,
``exudyn_atcm.model.feedforward``, ...): see the API reference.

Start-up: ``import exudyn_atcm`` imports only the errors; every other top-level name is imported on first
use (PEP 562, :mod:`exudyn_atcm.lazy_names`), so Exudyn, numpy and scipy load when a name that needs them is
used.  To add a public name: one line ``"name": (".module", "name"),`` in ``_LAZY`` below (read:
``from .module import name``), the name in ``__all__`` and the same import under ``TYPE_CHECKING``;
``tests/test_lazy_names.py`` checks that the three agree.  Never an eager ``from .module import name`` here:
it would load that module's imports (numpy, Exudyn) at ``import exudyn_atcm``.
"""

from typing import TYPE_CHECKING

from . import deprecated_paths
from ._version import __version__
from .errors import (AccuracyWarning, AtcmDeprecationWarning, AtcmWarning, InputRangeWarning, OutOfReachWarning,
                     RunCostWarning, SetupWarning, StabilityWarning, SuspectFileWarning, WriteError)
from .lazy_names import lazy_face

# The public names below load on first use (PEP 562, exudyn_atcm.lazy_names): name -> (module, attribute).
# To add a public name: one line here, the name in __all__, and the same import under TYPE_CHECKING
# (tests/test_lazy_names.py checks that the three agree and that `import exudyn_atcm` stays light).
_LAZY = {
    "hysteresis": (".hysteresis", None),
    "signals": (".model.signals", None),
    "load_model": (".hysteresis", "load_model"),
    "BendingActuator": (".mechanism.actuator", "BendingActuator"),
    "PIDController": (".model.control", "PIDController"),
    "read_csv": (".io.result", "read_csv"),
    "PiezoDrive": (".model.drive", "PiezoDrive"),
    "Layer": (".model.materials", "Layer"),
    "preprocess": (".io.measurements", "preprocess"),
    "read_record": (".io.measurements", "read_record"),
    "model_to_strain": (".model.strain_conversion", "model_to_strain"),
    "record_to_strain": (".model.strain_conversion", "record_to_strain"),
    "RayleighDamping": (".model.damping", "RayleighDamping"),
    "Bender": (".mechanism", "Bender"),
    "Flexure": (".mechanism", "Flexure"),
    "Link": (".mechanism", "Link"),
    "Mechanism": (".mechanism", "Mechanism"),
    "MechanismError": (".mechanism", "MechanismError"),
    "Segment": (".mechanism", "Segment"),
    "Result": (".io.result", "Result"),
    "SimulationInterrupted": (".solve", "SimulationInterrupted"),
    "SolverError": (".solve", "SolverError"),
    "eigenfrequencies": (".solve", "eigenfrequencies"),
    "simulate": (".solve", "simulate"),
    "solve_static": (".solve", "solve_static"),
    "static_sweep": (".solve", "static_sweep"),
    "step_error": (".solve", "step_error"),
    "choose_cells": (".solve", "choose_cells"),
    "BuiltSystem": (".solve", "BuiltSystem"),
    "LinearModel": (".solve", "LinearModel"),
    "Modes": (".solve", "Modes"),
    "linearise": (".solve", "linearise"),
    "modes": (".solve", "modes"),
    "mechanism_feedforward": (".solve", "mechanism_feedforward"),
    "add_to": (".mbs", "add_to"),
    "register_cell_kind": (".cells", "register_cell_kind"),
}

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from . import hysteresis
    from .model import signals
    from .hysteresis import load_model
    from .mechanism.actuator import BendingActuator
    from .model.control import PIDController
    from .io.result import read_csv
    from .model.drive import PiezoDrive
    from .model.materials import Layer
    from .io.measurements import preprocess, read_record
    from .model.strain_conversion import model_to_strain, record_to_strain
    from .model.damping import RayleighDamping
    from .mechanism import Bender, Flexure, Link, Mechanism, MechanismError, Segment
    from .io.result import Result
    from .solve import SimulationInterrupted
    from .solve import SolverError, eigenfrequencies, simulate, solve_static
    from .solve import static_sweep, step_error, choose_cells
    from .solve import BuiltSystem
    from .solve import LinearModel, Modes, linearise, modes
    from .solve import mechanism_feedforward
    from .mbs import add_to
    from .cells import register_cell_kind

__all__ = [
    "__version__",
    "hysteresis",
    "signals",
    "Layer",
    "PiezoDrive",
    "BendingActuator",
    "Bender",
    "Segment",
    "Link",
    "Flexure",
    "Mechanism",
    "MechanismError",
    "RayleighDamping",
    "simulate",
    "solve_static",
    "static_sweep",
    "BuiltSystem",
    "add_to",
    "register_cell_kind",
    "eigenfrequencies",
    "step_error",
    "choose_cells",
    "modes",
    "mechanism_feedforward",
    "Modes",
    "linearise",
    "LinearModel",
    "Result",
    "SolverError",
    "SimulationInterrupted",
    "WriteError",
    "read_csv",
    "load_model",
    "read_record",
    "preprocess",
    "record_to_strain",
    "model_to_strain",
    "PIDController",
    "AtcmWarning",
    "InputRangeWarning",
    "AccuracyWarning",
    "StabilityWarning",
    "OutOfReachWarning",
    "RunCostWarning",
    "SetupWarning",
    "SuspectFileWarning",
    "AtcmDeprecationWarning",
]


deprecated_paths.install()

# names of _LAZY, and any submodule by name (`exudyn_atcm.solve` after `import exudyn_atcm`, as before)
__getattr__, __dir__ = lazy_face(__name__, _LAZY, submodules=True)
