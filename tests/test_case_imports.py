"""Cases import from the package's faces only (issue 14, part 4).

A case is what a user copies to start their own, so it must show the supported way in: names from
the top level ``exudyn_atcm`` or from a documented subpackage face, each name in that face's
``__all__``; no deep module path (``exudyn_atcm.plots.style``), no private name.  The imports are read
with ``ast`` (module level and inside functions).
"""

from __future__ import annotations

import ast
import importlib
import pathlib

import pytest

import exudyn_atcm

ROOT = pathlib.Path(__file__).resolve().parents[1]
CASE_FILES = sorted((ROOT / "cases").glob("*.py")) + sorted((ROOT / "cases").glob("*/*.py"))

#: the documented subpackage faces a case may import from
FACES = ("exudyn_atcm.casework", "exudyn_atcm.plots", "exudyn_atcm.theory", "exudyn_atcm.model",
         "exudyn_atcm.hysteresis", "exudyn_atcm.signals", "exudyn_atcm.study", "exudyn_atcm.cells",
         "exudyn_atcm.solve")


def _exported(face: str) -> set[str]:
    return set(importlib.import_module(face).__all__)


def violations(source: str, filename: str = "<case>") -> list[str]:
    """One line per import of ``source`` that is not from a face, or not of a name the face exports."""
    out = []
    for node in ast.walk(ast.parse(source, filename)):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("exudyn_atcm") and alias.name != "exudyn_atcm" and alias.name not in FACES:
                    out.append(f"{filename}:{node.lineno}: import {alias.name} (a deep module path)")
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level or not module.startswith("exudyn_atcm"):
                continue
            if module != "exudyn_atcm" and module not in FACES:
                out.append(f"{filename}:{node.lineno}: from {module} import ... (a deep module path)")
                continue
            allowed = _exported(module)
            if module == "exudyn_atcm":
                allowed |= {face.rpartition(".")[2] for face in FACES}
            for alias in node.names:
                if alias.name.startswith("_"):
                    out.append(f"{filename}:{node.lineno}: private name {module}.{alias.name}")
                elif alias.name not in allowed:
                    out.append(f"{filename}:{node.lineno}: {module}.{alias.name} is not in {module}.__all__")
    return out


def test_there_are_cases():
    assert len(CASE_FILES) >= 14, CASE_FILES


@pytest.mark.parametrize("path", CASE_FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_case_imports_only_from_faces(path):
    assert violations(path.read_text(encoding="utf-8"), str(path.relative_to(ROOT))) == []


@pytest.mark.parametrize("source, expected", [
    ("from exudyn_atcm.plots.style import new_figure\n", "from exudyn_atcm.plots.style import ... (a deep module path)"),
    ("import exudyn_atcm.io.atomic\n", "import exudyn_atcm.io.atomic (a deep module path)"),
    ("def f():\n    from exudyn_atcm.solve.simulation import simulate\n",
     "from exudyn_atcm.solve.simulation import ... (a deep module path)"),
    ("from exudyn_atcm.casework import _plain\n", "private name exudyn_atcm.casework._plain"),
    ("from exudyn_atcm.plots import chain_polygon\n", "exudyn_atcm.plots.chain_polygon is not in exudyn_atcm.plots.__all__"),
    ("from exudyn_atcm import deprecated_paths\n", "exudyn_atcm.deprecated_paths is not in exudyn_atcm.__all__"),
])
def test_the_scan_sees_a_violation(source, expected):
    """The scan is not blind: each kind of forbidden import is reported."""
    assert [v.split(": ", 1)[1] for v in violations(source)] == [expected]


def test_faces_are_importable_and_complete():
    """Every face has an ``__all__`` whose names resolve (so a case's name check means something)."""
    for face in FACES + ("exudyn_atcm",):
        module = importlib.import_module(face)
        missing = [n for n in module.__all__ if not hasattr(module, n)]
        assert missing == [], (face, missing)
    assert "theory" not in exudyn_atcm.__all__  # a face module, allowed by name above
