"""A case shipped to the processes that run it: :class:`CaseSpec` (picklable) and :func:`load_spec`.

A study's worker processes (and Dask workers) load the case from its source text, not from its
file; the user's own modules the case reads travel as their hashes, so that a process loads the
case again, with those modules read again, when they change
(:mod:`exudyn_atcm.study.case_modules`).
"""

from __future__ import annotations

import sys
import types
from dataclasses import dataclass
from pathlib import Path

from ..casework import Case, CaseError
from .case_modules import forget_modules, module_hashes
from .store import case_fingerprint

__all__ = ["CaseSpec", "case_spec", "load_spec"]


@dataclass(frozen=True)
class CaseSpec:
    """A picklable description of a case: enough to load it in any worker process.

    Attributes
    ----------
    name : str
        Case name.
    path : str
        The case file (used as ``__file__``; it need not exist on the worker).
    source : str
        The full text of the case file.
    fingerprint : str
        :func:`~exudyn_atcm.study.store.case_fingerprint` of name and text.
    modules : tuple of (str, str)
        The user's own files the case reads, with their SHA-256 (:mod:`~exudyn_atcm.study.case_modules`).
    """

    name: str
    path: str
    source: str
    fingerprint: str
    modules: tuple = ()


def case_spec(case: Case) -> CaseSpec:
    """The :class:`CaseSpec` of a loaded case (from its source file).

    Raises
    ------
    CaseError
        If the case has no readable source file (e.g. a ``Case`` made interactively):
        worker processes load cases from their file.
    """
    if not isinstance(case, Case):
        raise CaseError(f"case must be an exudyn_atcm Case (see load_case), got {type(case).__name__}")
    if case.source is None or not Path(case.source).is_file():
        raise CaseError(f"case {case.name}: studies need the case's source file (got {case.source!r}); define the case in a file and load it with load_case")
    text = Path(case.source).read_text(encoding="utf-8")
    modules = tuple(sorted(module_hashes(case.source).items()))
    return CaseSpec(case.name, str(case.source), text, case_fingerprint(case.name, text), modules)


_LOADED: dict[tuple[str, tuple], Case] = {}


def load_spec(spec: CaseSpec) -> Case:
    """The case of ``spec``, executed from its source text once per process and version of its own modules (cached:
    the modules it reads are read again when they change)."""
    case = _LOADED.get((spec.fingerprint, spec.modules))
    if case is not None:
        return case
    forget_modules(path for path, _ in spec.modules)  # imported again by the case as they are now
    module_name = f"exudyn_atcm_study_case_{spec.name}_{spec.fingerprint[:12]}"
    module = types.ModuleType(module_name)
    module.__file__ = spec.path
    sys.modules[module_name] = module  # dataclasses and pickling look modules up here
    try:
        exec(compile(spec.source, spec.path, "exec"), module.__dict__)  # noqa: S102 - the user's own case file
    except Exception as exc:
        del sys.modules[module_name]
        raise CaseError(f"{spec.path}: import failed: {type(exc).__name__}: {exc}") from exc
    case = module.__dict__.get("CASE")
    if not isinstance(case, Case):
        raise CaseError(f"{spec.path}: defines no CASE = exudyn_atcm.casework.Case(...)")
    case.source = Path(spec.path)
    _LOADED[(spec.fingerprint, spec.modules)] = case
    return case
