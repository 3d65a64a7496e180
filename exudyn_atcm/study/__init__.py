"""Parameter studies and design optimisation of cases, on one machine or on a Dask cluster.

* :func:`sweep` / :func:`run_study`: a case over a full grid, samples or a list of points;
  a :class:`StudyTable` of parameters and key scalars (the same type whatever is installed); every finished run stored, so studies resume.
* :func:`optimize`: scipy.optimize over a case's parameters, evaluations run by the same
  engines and stored the same way.
* Engines (:mod:`exudyn_atcm.study.engines`): this process, a process pool (default), Dask.

See :doc:`/studies`.
"""

from .design import GridError, explicit_points, full_grid, parse_grid_spec, sample_points
from .engines import DaskEngine, ProcessEngine, SerialEngine, make_engine
from .store import RunStore, run_key
from .optimize import METHODS, OptimizationResult, optimize
from .options import OptimizeOptions, RunOptions
from .stops import ObjectiveNotFiniteError
from .sweep import StudyResult, run_study, study_points, sweep
from .table import StudyTable, column, unit_of

__all__ = [
    "sweep",
    "optimize",
    "RunOptions",
    "OptimizeOptions",
    "OptimizationResult",
    "ObjectiveNotFiniteError",
    "METHODS",
    "run_study",
    "StudyResult",
    "StudyTable",
    "study_points",
    "GridError",
    "full_grid",
    "sample_points",
    "explicit_points",
    "parse_grid_spec",
    "RunStore",
    "run_key",
    "SerialEngine",
    "ProcessEngine",
    "DaskEngine",
    "make_engine",
    "column",
    "unit_of",
]
