"""The readable API page (issue 30, part 6): ``docs/api_summary.rst`` lists every public name.

Checked without Sphinx: the committed page equals what ``docs/make_api_summary.py`` writes now (so
it is current), and independently of that script every name in ``exudyn_atcm.__all__`` and in each
subpackage's ``__all__`` has its row, under its module's heading, with the signature that
``inspect`` gives for it.
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import pkgutil
from pathlib import Path

import exudyn_atcm

DOCS = Path(__file__).resolve().parents[1] / "docs"


def _script():
    spec = importlib.util.spec_from_file_location("make_api_summary", DOCS / "make_api_summary.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_page_is_what_the_script_writes_now():
    committed = (DOCS / "api_summary.rst").read_text(encoding="utf-8")
    assert committed == _script().page(), "docs/api_summary.rst is stale: run python docs/make_api_summary.py"


def _sections(text: str) -> dict[str, list[str]]:
    """Row names per ``exudyn_atcm...`` heading of the page (its own small reader of the rst)."""
    out: dict[str, list[str]] = {}
    lines = text.splitlines()
    current = None
    for k, line in enumerate(lines):
        if k + 1 < len(lines) and set(lines[k + 1]) == {"-"} and line.startswith("``exudyn_atcm"):
            current = line.strip("`")
            out[current] = []
        elif current and line.startswith("   * - ``"):
            out[current].append(line[len("   * - ``"):-2])
    return out


def test_every_public_name_of_every_subpackage_has_a_row():
    sections = _sections((DOCS / "api_summary.rst").read_text(encoding="utf-8"))
    subpackages = [m.name for m in pkgutil.iter_modules(exudyn_atcm.__path__) if m.ispkg]
    expected = {"exudyn_atcm": [n for n in exudyn_atcm.__all__ if n != "__version__"]}
    for name in subpackages:
        module = importlib.import_module(f"exudyn_atcm.{name}")
        assert hasattr(module, "__all__"), f"exudyn_atcm.{name} has no __all__"
        expected[f"exudyn_atcm.{name}"] = list(module.__all__)
    assert set(sections) == set(expected)
    for module, names in expected.items():
        assert sections[module] == names, module


def test_a_function_row_carries_its_parameters():
    text = (DOCS / "api_summary.rst").read_text(encoding="utf-8")
    params = inspect.signature(exudyn_atcm.simulate).parameters
    row = text[text.index("   * - ``simulate``"):].split("   * - ")[1]
    for name in params:
        assert name in row, name
    assert "*, step=None" in row  # the keyword-only marker and a default as repr gives it
