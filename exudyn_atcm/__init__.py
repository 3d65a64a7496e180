"""exudyn_atcm: multibody simulation of active textile-reinforced compliant mechanisms on Exudyn.

>>> import exudyn_atcm as atcm
>>> layer = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550)

Top level (``__all__``): the building blocks (``Layer``, ``PiezoDrive``, ``BendingActuator``,
``Bender``, ``Segment``, ``Link``, ``Flexure``, ``Mechanism``, ``RayleighDamping``), solving (``simulate``,
``solve_static``, ``static_sweep``, ``eigenfrequencies``, ``add_to``), results and files
(``Result``, ``read_csv``, ``read_record``), closed loop (``PIDController``), the errors
(``MechanismError``, ``SolverError``, ``SimulationInterrupted``) and the submodules
``hysteresis`` (operators, fits, inverses) and ``signals`` (voltage programs).  Everything
else lives in its module (``exudyn_atcm.study``, ``exudyn_atcm.mechanism_plots``,
``exudyn_atcm.feedforward``, ...): see the API reference.
"""

from . import hysteresis, signals
from ._version import __version__
from .actuator import BendingActuator
from .control import PIDController
from .csv_io import read_csv
from .damping import RayleighDamping
from .drive import PiezoDrive
from .materials import Layer
from .measurements import read_record
from .mechanism import Bender, Flexure, Link, Mechanism, MechanismError, Segment
from .result import Result
from .run_checks import SimulationInterrupted
from .simulation import SolverError, eigenfrequencies, simulate, solve_static
from .mechanism_solve import static_sweep
from .mbs import add_to

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
    "add_to",
    "eigenfrequencies",
    "Result",
    "SolverError",
    "SimulationInterrupted",
    "read_csv",
    "read_record",
    "PIDController",
]
