"""No private arguments in the public API (they would show in the API reference)."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import exudyn_atcm
from exudyn_atcm import hysteresis

API_RST = Path(__file__).resolve().parents[1] / "docs" / "api.rst"
#: Public modules whose ``__all__`` is plumbing of the command line or the optimiser, not user API.
INTERNAL = {"exudyn_atcm.cli", "exudyn_atcm.casework.error_report", "exudyn_atcm.study.command", "exudyn_atcm.study.command_options",
            "exudyn_atcm.lazy_names", "exudyn_atcm.study.problem", "exudyn_atcm.study.case_spec"}
#: Names exported for the package's own modules (workers, progress plumbing; the mechanism's DOF
#: count is documented as Mechanism.degrees_of_freedom).
INTERNAL_NAMES = {"exudyn_atcm.study.design.check_point", "exudyn_atcm.study.engines.CaseSpec",
                  "exudyn_atcm.study.engines.case_spec", "exudyn_atcm.study.sweep.StudyProgress",
                  "exudyn_atcm.mbs.linear.degrees_of_freedom"}


def _public_modules():
    """The package and every module or subpackage without a private (``_``) part, with an ``__all__``."""
    yield exudyn_atcm
    for info in pkgutil.walk_packages(exudyn_atcm.__path__, "exudyn_atcm."):
        parts = info.name.split(".")[1:]
        if any(p.startswith("_") for p in parts) or "example_cases" in parts:
            continue
        module = importlib.import_module(info.name)
        if hasattr(module, "__all__"):
            yield module


def _public_callables():
    for module in _public_modules():
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name)
            if inspect.isclass(obj):
                for attr, member in inspect.getmembers(obj, callable):
                    if not attr.startswith("_") or attr == "__init__":
                        yield f"{module.__name__}.{name}.{attr}", member
            elif callable(obj):
                yield f"{module.__name__}.{name}", obj


@pytest.mark.parametrize("qualname, member", list(_public_callables()), ids=lambda v: v if isinstance(v, str) else "")
def test_no_private_parameters(qualname, member):
    try:
        parameters = inspect.signature(member).parameters
    except (TypeError, ValueError):  # builtins without a signature
        return
    private = [p for p in parameters if p.startswith("_")]
    assert not private, f"{qualname} has private parameters {private}"


def test_evaluate_and_commit_take_only_the_input():
    for cls in (hysteresis.ContinuousPreisach, hysteresis.DiscretePreisach, hysteresis.StaircasePreisach):
        for method in ("evaluate", "commit"):
            assert list(inspect.signature(getattr(cls, method)).parameters) == ["self", "u"], (cls, method)


def _documented_names() -> set[str]:
    """Dotted names the API reference documents (directives, and their ``:members:`` lists)."""
    documented: set[str] = set()
    current = None
    for line in API_RST.read_text(encoding="utf-8").splitlines():
        directive = re.match(r"\.\. auto(?:class|function|module|data|exception):: (\S+)", line)
        if directive:
            current = directive.group(1)
            documented.add(current)
            continue
        members = re.match(r"\s+:members:\s*(.*)", line)
        if members and current:
            names = [n for n in re.split(r"[,\s]+", members.group(1).strip()) if n]
            if not names:  # bare :members: documents the whole __all__ of a module
                try:
                    names = list(getattr(importlib.import_module(current), "__all__", []))
                except ImportError:  # a class: its members are documented with it
                    names = []
            documented.update(f"{current}.{n}" for n in names)
        elif current and re.match(r"\s{6,}\S", line):  # continued :members: list
            documented.update(f"{current}.{n}" for n in re.split(r"[,\s]+", line.strip()) if n)
    return documented


def test_api_reference_covers_the_public_names():
    """Every name in the ``__all__`` of a user-facing module is in docs/api.rst (under any module
    that exports it); module constants (UPPER_CASE) are described in the text of their module."""
    documented = _documented_names()
    short = {d.rsplit(".", 1)[-1] for d in documented}
    missing = []
    for module in _public_modules():
        if module.__name__ in INTERNAL:
            continue
        for name in module.__all__:
            if name.isupper() or name.startswith("__") or f"{module.__name__}.{name}" in INTERNAL_NAMES:
                continue
            obj = getattr(module, name)
            homes = {f"{module.__name__}.{name}", f"{getattr(obj, '__module__', '')}.{name}"}
            if not homes & documented and name not in short:
                missing.append(f"{module.__name__}.{name}")
    assert not missing, f"public names missing from docs/api.rst: {missing}"


def test_top_level_all_is_consistent():
    """``from exudyn_atcm import *`` gives exactly ``__all__``, each name resolves, none twice,
    and the names the mechanism API and the issues promise are there."""
    namespace: dict = {}
    exec("from exudyn_atcm import *", namespace)
    exported = {k for k in namespace if k != "__builtins__"}
    assert exported == set(exudyn_atcm.__all__)
    assert len(exudyn_atcm.__all__) == len(set(exudyn_atcm.__all__))
    for name in ("Bender", "Segment", "Link", "Flexure", "Mechanism", "MechanismError", "add_to", "static_sweep",
                 "simulate", "solve_static", "eigenfrequencies", "SimulationInterrupted", "read_record", "PIDController"):
        assert name in exudyn_atcm.__all__, name
    assert exudyn_atcm.PIDController is importlib.import_module("exudyn_atcm.model.control").PIDController
