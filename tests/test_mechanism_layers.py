"""Issue 7, layout: Exudyn is imported only in the multibody layer ``exudyn_atcm/mbs/``.

Every other module of the package (the mechanism description ``exudyn_atcm/mechanism/``, the
solve modules, results, I/O, cases) works through it.  Checked on the source text (imports,
also inside functions) and by importing the description in a fresh interpreter without Exudyn
on the path.
"""

from __future__ import annotations

import pathlib
import re
import subprocess
import sys

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "exudyn_atcm"
IMPORT = re.compile(r"^\s*(import exudyn\b|from exudyn\b)", re.MULTILINE)


def test_only_the_mbs_layer_imports_exudyn():
    """No module outside ``exudyn_atcm/mbs/`` imports Exudyn (at module level or in a function)."""
    outside = [f for f in sorted(PACKAGE.rglob("*.py")) if f.relative_to(PACKAGE).parts[0] != "mbs"]
    assert len(outside) > 20  # the scan sees the package (guards against a wrong PACKAGE path)
    offenders = [str(f.relative_to(PACKAGE)) for f in outside if IMPORT.search(f.read_text())]
    assert offenders == []
    # and the layer itself does import it (the pattern would find an import if there were one)
    inside = sorted((PACKAGE / "mbs").glob("*.py"))
    assert any(IMPORT.search(f.read_text()) for f in inside)


def test_description_layer_imports_without_exudyn():
    """Block 'exudyn' in a fresh interpreter: the description modules load and describe a mechanism."""
    code = f"""
import sys, types, importlib.util, pathlib
sys.modules['exudyn'] = None  # any 'import exudyn' now fails
pkg = types.ModuleType('exudyn_atcm'); pkg.__path__ = [{str(PACKAGE)!r}]; sys.modules['exudyn_atcm'] = pkg
from exudyn_atcm.mechanism import Bender, Link, Mechanism
from exudyn_atcm.model.materials import Layer
b = Bender('b', width=1e-2, passive=Layer(2e-4, 7e10, 1550.0), length=0.03, n_cells=3)
m = Mechanism().add(b).ground(b.base)
m.check()
print('ok')
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
