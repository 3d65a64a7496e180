"""exudyn_atcm: multibody simulation of active textile-reinforced compliant mechanisms on Exudyn.

>>> import exudyn_atcm as atcm
>>> layer = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550)

Top level (``__all__``): the building blocks (``Layer``, ``PiezoDrive``, ``BendingActuator``,
``Bender``, ``Segment``, ``Link``, ``Flexure``, ``Mechanism``, ``RayleighDamping``), solving (``simulate``,
``solve_static``, ``static_sweep``, ``eigenfrequencies``, ``step_error``, ``mechanism_feedforward`` (a voltage program for a mechanism output), ``add_to``, ``BuiltSystem`` to solve one
build many times), results and files
(``Result``, ``read_csv``, ``read_record``, ``preprocess``), displacement to strain (``record_to_strain``,
``model_to_strain``), closed loop (``PIDController``), the errors
(``MechanismError``, ``SolverError``, ``SimulationInterrupted``), the warning categories (``AtcmWarning``
and its subclasses, see :mod:`exudyn_atcm.errors`) and the submodules
``hysteresis`` (operators, fits, inverses; ``load_model`` reads a saved one) and ``signals`` (voltage programs).  Everything
else lives in its module (``exudyn_atcm.study``, ``exudyn_atcm.plots.mechanism``,
``exudyn_atcm.model.feedforward``, ...): see the API reference.
"""

from . import deprecated_paths, hysteresis
from .model import signals
from .hysteresis import load_model
from ._version import __version__
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
from .solve import static_sweep, step_error
from .solve import BuiltSystem
from .solve import mechanism_feedforward
from .mbs import add_to
from .cells import register_cell_kind
from .errors import (AccuracyWarning, AtcmDeprecationWarning, AtcmWarning, InputRangeWarning, OutOfReachWarning,
                     RunCostWarning, SetupWarning, StabilityWarning, SuspectFileWarning, WriteError)

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
    "mechanism_feedforward",
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


def __getattr__(name: str):
    """Old module paths (:data:`exudyn_atcm.deprecated_paths.MOVED`) as attributes, with their warning."""
    if name in deprecated_paths.MOVED:
        import importlib  # noqa: PLC0415 - only for the deprecated paths

        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
