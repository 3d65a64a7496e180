"""The package's layers: which folder may import which (issue 14, part 4).

Imports are read from the source with ``ast`` (module level and inside functions), relative
imports resolved, so that a rule cannot be dodged by an import inside a function.  The layers,
bottom up: the argument checks and errors; ``theory`` and ``hysteresis``; ``model``;
``io``; the description (``mechanism``, ``cells``); ``mbs`` (the only Exudyn layer); ``solve``;
``plots``; ``casework``; ``study``; the command line.  The description never imports ``mbs``,
``solve`` or plotting.
"""

from __future__ import annotations

import ast
import pathlib
import subprocess
import sys

import pytest

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "exudyn_atcm"

#: folder -> folders (or top-level modules) it must never import, also not inside a function
FORBIDDEN = {
    "theory": {"model", "io", "mechanism", "cells", "mbs", "solve", "plots", "casework", "study", "cli", "hysteresis"},
    "io": {"model", "mechanism", "cells", "mbs", "solve", "casework", "study", "cli", "hysteresis", "theory"},
    "hysteresis": {"model", "mechanism", "cells", "mbs", "solve", "plots", "casework", "study", "cli"},
    "model": {"mechanism", "mbs", "solve", "plots", "casework", "study", "cli"},
    "cells": {"model", "mechanism", "mbs", "solve", "plots", "casework", "study", "cli", "io"},
    "mechanism": {"mbs", "solve", "plots", "casework", "study", "cli"},
    "mbs": {"solve", "plots", "casework", "study", "cli"},
    "solve": {"plots", "casework", "study", "cli"},
    "plots": {"solve", "casework", "study", "cli", "mbs"},
    "casework": {"study", "cli"},
    "study": {"cli"},
}


def _module_name(path: pathlib.Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _imports(path: pathlib.Path) -> list[tuple[int, str]]:
    """(line, absolute module) of every import in ``path``, functions included."""
    name = _module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            found.append((node.lineno, module))
            # "from . import x" imports the submodule x
            found += [(node.lineno, f"{module}.{alias.name}") for alias in node.names]
    return found


def _layer(module: str) -> str | None:
    parts = module.split(".")
    if parts[0] != "exudyn_atcm" or len(parts) < 2:
        return None
    return parts[1]


def _violations() -> list[str]:
    out = []
    for path in sorted(PACKAGE.rglob("*.py")):
        layer = _layer(_module_name(path))
        forbidden = FORBIDDEN.get(layer or "", set())
        for line, module in _imports(path):
            target = _layer(module)
            if target in forbidden:
                out.append(f"{path.relative_to(PACKAGE)}:{line} ({layer}) imports {module}")
    return out


def test_layers_import_only_downwards():
    assert _violations() == []


def test_the_check_sees_a_violation(tmp_path, monkeypatch):
    """The scan is not blind: a description module importing the solve layer is reported."""
    fake = PACKAGE / "mechanism" / "zz_layer_probe.py"
    fake.write_text("def f():\n    from ..solve import simulate\n    return simulate\n")
    try:
        found = _violations()
    finally:
        fake.unlink()
    assert found == ["mechanism/zz_layer_probe.py:2 (mechanism) imports exudyn_atcm.solve"] or \
        "mechanism/zz_layer_probe.py:2 (mechanism) imports exudyn_atcm.solve" in found


def test_at_most_a_few_top_level_modules():
    """Role folders, not flat modules: at most 12 top-level modules besides the package files."""
    top = sorted(p.name for p in PACKAGE.glob("*.py") if p.name not in ("__init__.py", "__main__.py", "_version.py"))
    assert len(top) <= 12, top


def test_every_folder_says_what_it_holds_and_may_import():
    for init in sorted(PACKAGE.glob("*/__init__.py")):
        doc = ast.get_docstring(ast.parse(init.read_text())) or ""
        assert doc, f"{init.parent.name}/__init__.py has no docstring"


def _cycles() -> list[list[str]]:
    graph: dict[str, set[str]] = {}
    modules = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    for name, path in modules.items():
        deps = set()
        for _, module in _imports(path):
            while module and module not in modules:
                module = module.rpartition(".")[0]
            # "from . import x" names the package itself too: not an arrow to its __init__
            if module and module != name and not name.startswith(module + "."):
                deps.add(module)
        graph[name] = deps
    # Tarjan's strongly connected components
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in graph:
        if v not in index:
            visit(v)
    return out


def test_no_import_cycles():
    """No circle of imports between the package's modules (package __init__ re-exports aside)."""
    assert _cycles() == []


@pytest.mark.parametrize("folder", ["theory", "cells", "hysteresis", "model", "mechanism"])
def test_description_layers_load_without_exudyn_or_matplotlib(folder):
    """Block Exudyn and matplotlib in a fresh interpreter: the description layers still import."""
    code = f"""
import sys, types, importlib, pathlib
sys.modules['exudyn'] = None
sys.modules['matplotlib'] = None
pkg = types.ModuleType('exudyn_atcm'); pkg.__path__ = [{str(PACKAGE)!r}]; sys.modules['exudyn_atcm'] = pkg
for path in sorted(pathlib.Path({str(PACKAGE)!r}, {folder!r}).glob('*.py')):
    name = 'exudyn_atcm.{folder}' + ('' if path.stem == '__init__' else '.' + path.stem)
    importlib.import_module(name)
print('ok')
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip() == "ok"
