"""Case scripts (declared parameters, one run function, standard outputs), the regression suite
and the command line's error reports.

The face: ``from exudyn_atcm.casework import Case, CaseOutput, Parameter`` is all a case file
needs (the convention is in :mod:`exudyn_atcm.casework.case`).  The modules:

* :mod:`~exudyn_atcm.casework.parameters`: :class:`Parameter`, :class:`Parameters`, :class:`CaseError`;
* :mod:`~exudyn_atcm.casework.outputs`: :class:`RunContext`, :class:`CaseOutput`, :func:`versions`
  (and, from :mod:`exudyn_atcm.solve.run_plan`, :class:`PlannedRun` / :class:`RunPlan` for a run of
  several simulations);
* :mod:`~exudyn_atcm.casework.case`: :class:`Case`; :mod:`~exudyn_atcm.casework.run_command`: running
  and reporting from the command line;
* :mod:`~exudyn_atcm.casework.declarations`: what a case declares besides its parameters (smoke
  settings, regression benchmarks, its row in the case tables); :mod:`~exudyn_atcm.casework.case_table`:
  the README's and the docs' case tables, :func:`case_table`;
* :mod:`~exudyn_atcm.casework.discovery`: :func:`case_dirs`, :func:`list_cases`, :func:`find_case`,
  :func:`load_case`, :func:`case_module`, :func:`load_cases`;
* :mod:`~exudyn_atcm.casework.regression` (with :mod:`~exudyn_atcm.casework.metrics`): the
  regression suite, :func:`run_suite`;
* :mod:`~exudyn_atcm.casework.dynamic_runs`: a case's dynamic run at its ``step`` or at the step
  chosen for its ``accuracy`` (:func:`case_dynamic_run`, :func:`step_notes`);
* :mod:`~exudyn_atcm.casework.step_check`: a case's key scalars at step, step/2 and step/4
  (``exudyn-atcm step-error``).

May import everything below it; :mod:`exudyn_atcm.study` and the command line build on it.
"""

from typing import TYPE_CHECKING

from ..lazy_names import lazy_face

# The names load on first use (PEP 562, exudyn_atcm.lazy_names): name -> (module, attribute), read as
# `from module import attribute`.  To add a public name: one line here, the name in __all__ and the same
# import under TYPE_CHECKING (tests/test_lazy_names.py checks that the three agree).
_LAZY = {
    "Case": (".case", "Case"),
    "PlotFunction": (".case", "PlotFunction"),
    "RunFunction": (".case", "RunFunction"),
    "add_run_options": (".case", "add_run_options"),
    "run_and_report": (".case", "run_and_report"),
    "TABLE_FORMATS": (".case_table", "TABLE_FORMATS"),
    "case_table": (".case_table", "case_table"),
    "check_benchmark": (".declarations", "check_benchmark"),
    "STEP_GRID": (".dynamic_runs", "STEP_GRID"),
    "case_dynamic_run": (".dynamic_runs", "case_dynamic_run"),
    "step_notes": (".dynamic_runs", "step_notes"),
    "CASE_MARKERS": (".discovery", "CASE_MARKERS"),
    "ENV_CASES": (".discovery", "ENV_CASES"),
    "case_dirs": (".discovery", "case_dirs"),
    "case_files": (".discovery", "case_files"),
    "case_module": (".discovery", "case_module"),
    "find_case": (".discovery", "find_case"),
    "follows_convention": (".discovery", "follows_convention"),
    "list_cases": (".discovery", "list_cases"),
    "load_case": (".discovery", "load_case"),
    "load_cases": (".discovery", "load_cases"),
    "MetricRow": (".metrics", "MetricRow"),
    "CaseOutput": (".outputs", "CaseOutput"),
    "PlannedRun": (".outputs", "PlannedRun"),
    "RunContext": (".outputs", "RunContext"),
    "RunPlan": (".outputs", "RunPlan"),
    "versions": (".outputs", "versions"),
    "CaseError": (".parameters", "CaseError"),
    "CellChoices": (".parameters", "CellChoices"),
    "Parameter": (".parameters", "Parameter"),
    "Parameters": (".parameters", "Parameters"),
    "closest": (".parameters", "closest"),
    "ENV_SUITE": (".regression", "ENV_SUITE"),
    "SuiteReport": (".regression", "SuiteReport"),
    "default_suite_dir": (".regression", "default_suite_dir"),
    "load_suite": (".regression", "load_suite"),
    "run_suite": (".regression", "run_suite"),
}

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from .case import Case, PlotFunction, RunFunction, add_run_options, run_and_report
    from .case_table import TABLE_FORMATS, case_table
    from .declarations import check_benchmark
    from .dynamic_runs import STEP_GRID, case_dynamic_run, step_notes
    from .discovery import (CASE_MARKERS, ENV_CASES, case_dirs, case_files, case_module, find_case, follows_convention,
                            list_cases, load_case, load_cases)
    from .metrics import MetricRow
    from .outputs import CaseOutput, PlannedRun, RunContext, RunPlan, versions
    from .parameters import CaseError, CellChoices, Parameter, Parameters, closest
    from .regression import ENV_SUITE, SuiteReport, default_suite_dir, load_suite, run_suite

__all__ = [
    "Case",
    "case_dynamic_run",
    "step_notes",
    "STEP_GRID",
    "CaseOutput",
    "Parameter",
    "CellChoices",
    "Parameters",
    "RunContext",
    "PlannedRun",
    "RunPlan",
    "CaseError",
    "RunFunction",
    "PlotFunction",
    "versions",
    "case_dirs",
    "list_cases",
    "find_case",
    "case_files",
    "load_case",
    "case_module",
    "load_cases",
    "follows_convention",
    "case_table",
    "TABLE_FORMATS",
    "check_benchmark",
    "add_run_options",
    "run_and_report",
    "closest",
    "ENV_CASES",
    "CASE_MARKERS",
    "MetricRow",
    "SuiteReport",
    "default_suite_dir",
    "load_suite",
    "run_suite",
    "ENV_SUITE",
]

__getattr__, __dir__ = lazy_face(__name__, _LAZY, submodules=True)
