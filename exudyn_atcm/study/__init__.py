"""Parameter studies and design optimisation of cases, on one machine or on a Dask cluster.

* :func:`sweep` / :func:`run_study`: a case over a full grid, samples or a list of points;
  a :class:`StudyTable` of parameters and key scalars (the same type whatever is installed); every finished run stored, so studies resume.
* :func:`optimize`: scipy.optimize over a case's parameters, evaluations run by the same
  engines and stored the same way.
* Engines (:mod:`exudyn_atcm.study.engines`): this process, a process pool (default), Dask.

See :doc:`/studies`.
"""

from typing import TYPE_CHECKING

from ..lazy_names import lazy_face

# The names load on first use (PEP 562, exudyn_atcm.lazy_names): name -> (module, attribute), read as
# `from module import attribute`.  To add a public name: one line here, the name in __all__ and the same
# import under TYPE_CHECKING (tests/test_lazy_names.py checks that the three agree).
_LAZY = {
    "GridError": (".design", "GridError"),
    "explicit_points": (".design", "explicit_points"),
    "full_grid": (".design", "full_grid"),
    "parse_grid_spec": (".design", "parse_grid_spec"),
    "sample_points": (".design", "sample_points"),
    "DaskEngine": (".engines", "DaskEngine"),
    "ProcessEngine": (".engines", "ProcessEngine"),
    "SerialEngine": (".engines", "SerialEngine"),
    "make_engine": (".engines", "make_engine"),
    "RunStore": (".store", "RunStore"),
    "run_key": (".store", "run_key"),
    "METHODS": (".optimize", "METHODS"),
    "OptimizationResult": (".optimize", "OptimizationResult"),
    "optimize": (".optimize", "optimize"),
    "OptimizeOptions": (".options", "OptimizeOptions"),
    "RunOptions": (".options", "RunOptions"),
    "ObjectiveNotFiniteError": (".stops", "ObjectiveNotFiniteError"),
    "StudyResult": (".sweep", "StudyResult"),
    "run_study": (".sweep", "run_study"),
    "study_points": (".sweep", "study_points"),
    "sweep": (".sweep", "sweep"),
    "StudyTable": (".table", "StudyTable"),
    "column": (".table", "column"),
    "unit_of": (".table", "unit_of"),
}

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
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

__getattr__, __dir__ = lazy_face(__name__, _LAZY, submodules=True)
