"""Lazy package faces (PEP 562, :mod:`exudyn_atcm.lazy_names`; issue 31, part 4), checked by structure, never by
a clock (the timings are in ``benchmarks/bench_import.py``).

``import exudyn_atcm`` and ``exudyn-atcm --help`` must not load Exudyn, numpy, scipy, h5py or matplotlib; every
public name still resolves to the object its module defines, ``dir()`` lists them before they load, and each
face's table, ``__all__`` and ``TYPE_CHECKING`` imports agree (so that adding a name is one line in each).
The probes run in fresh interpreters, since this test process has long imported everything.
"""

from __future__ import annotations

import ast
import importlib
import json
import subprocess
import sys
from pathlib import Path

import pytest

from exudyn_atcm.lazy_names import lazy_face

PACKAGE = Path(__file__).resolve().parents[1] / "exudyn_atcm"
#: The faces whose names load on first use (the plots face has its own older table).
LAZY_FACES = ("exudyn_atcm", "exudyn_atcm.io", "exudyn_atcm.solve", "exudyn_atcm.casework", "exudyn_atcm.study")
#: What start-up must not load: Exudyn alone takes about 0.2 s, numpy 0.1 s, scipy and matplotlib more.
HEAVY = ("exudyn", "numpy", "scipy", "h5py", "matplotlib")


def _run(code: str) -> str:
    """Stdout of ``code`` in a fresh interpreter (fails the test with stderr if it fails)."""
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def _heavy_after(code: str) -> list[str]:
    """The top-level packages of ``HEAVY`` that a fresh interpreter holds after running ``code``."""
    probe = f"{code}\nimport json, sys\nprint(json.dumps(sorted(m for m in {HEAVY!r} if m in sys.modules)))"
    return json.loads(_run(probe).strip().splitlines()[-1])


def test_import_package_loads_no_exudyn_nor_numpy():
    # on the eager face of 0.3 this loaded exudyn, numpy and h5py (0.5 s)
    assert _heavy_after("import exudyn_atcm") == []


def test_errors_and_version_come_without_heavy_modules():
    code = ("import warnings\nfrom exudyn_atcm import AtcmWarning, SetupWarning, __version__\n"
            "assert issubclass(SetupWarning, AtcmWarning) and issubclass(AtcmWarning, Warning)\n"
            "assert __version__.count('.') >= 1")
    assert _heavy_after(code) == []


def test_cli_help_loads_no_exudyn_nor_numpy():
    code = ("import contextlib, io, sys\nsys.argv = ['exudyn-atcm', '--help']\nfrom exudyn_atcm.cli import main\n"
            "out = io.StringIO()\nwith contextlib.redirect_stdout(out):\n    try:\n        main()\n"
            "    except SystemExit as exc:\n        assert exc.code in (0, None), exc.code\n"
            "text = out.getvalue()\n"
            "assert all(c in text for c in ('list', 'run', 'step-error', 'sweep', 'optimize', 'bench')), text\n")
    assert _heavy_after(code) == []


@pytest.mark.parametrize("command", ["sweep", "optimize", "list"])
def test_subcommand_help_loads_no_exudyn_nor_numpy(command):
    code = ("import contextlib, io, sys\nfrom exudyn_atcm.cli import main\nout = io.StringIO()\n"
            f"with contextlib.redirect_stdout(out):\n    try:\n        main([{command!r}, '--help'])\n"
            "    except SystemExit as exc:\n        assert exc.code in (0, None), exc.code\n"
            f"assert 'usage: exudyn-atcm {command}' in out.getvalue(), out.getvalue()\n")
    assert _heavy_after(code) == []


def test_probe_sees_heavy_modules_once_a_name_is_used():
    # the probe can fail: the first use of a solving name loads Exudyn and numpy
    assert set(_heavy_after("import exudyn_atcm\nexudyn_atcm.simulate")) >= {"exudyn", "numpy"}


@pytest.mark.parametrize("face", LAZY_FACES)
def test_lazy_names_are_the_objects_of_their_modules(face):
    module = importlib.import_module(face)
    for name, (where, attribute) in module._LAZY.items():
        source = importlib.import_module(where, face)
        expected = source if attribute is None else getattr(source, attribute)
        assert getattr(module, name) is expected, f"{face}.{name}"


@pytest.mark.parametrize("face", LAZY_FACES)
def test_table_all_and_type_checking_imports_agree(face):
    """The table, ``__all__`` and the ``TYPE_CHECKING`` imports name the same things from the same modules."""
    module = importlib.import_module(face)
    path = Path(module.__file__)
    tree = ast.parse(path.read_text(encoding="utf-8"))
    checking = next(node for node in tree.body if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING")
    eager_for_checkers = {}
    for node in checking.body:
        assert isinstance(node, ast.ImportFrom) and node.level >= 1, ast.unparse(node)
        for alias in node.names:
            if node.module is None:  # from . import hysteresis: the module itself
                eager_for_checkers[alias.asname or alias.name] = ("." * node.level + alias.name, None)
            else:
                eager_for_checkers[alias.asname or alias.name] = ("." * node.level + node.module, alias.name)
    table = dict(module._LAZY)
    assert set(eager_for_checkers) == set(table)
    for name, (where, attribute) in eager_for_checkers.items():  # same object, however the import is spelt
        source = importlib.import_module(where, face)
        assert (source if attribute is None else getattr(source, attribute)) is getattr(module, name), name
    eager = {n for n in vars(module) if not n.startswith("_")} | {"__version__"} & set(vars(module))
    assert set(module.__all__) <= set(table) | eager
    assert set(table) <= set(module.__all__), "a lazy name that is not public belongs in its module, not the face"
    assert len(module.__all__) == len(set(module.__all__))


@pytest.mark.parametrize("face", LAZY_FACES)
def test_dir_lists_names_before_they_load_and_star_import_gives_all(face):
    code = (f"import importlib, sys\nm = importlib.import_module({face!r})\n"
            "listed = set(dir(m))\nmissing = [n for n in m.__all__ if n not in listed]\nassert not missing, missing\n"
            f"namespace = {{}}\nexec('from {face} import *', namespace)\n"
            "assert set(namespace) - {'__builtins__'} == set(m.__all__), set(namespace) ^ set(m.__all__)\n")
    _run(code)


def test_name_that_is_also_a_submodule_stays_the_function():
    # solve.step_error is a function and a submodule; importing the submodule (as casework.step_check does)
    # binds the module on the face, which must keep the function, as the eager face of 0.3 did
    code = ("import exudyn_atcm.solve.step_error\nimport exudyn_atcm.study.sweep, exudyn_atcm.study.optimize\n"
            "import exudyn_atcm.solve as s, exudyn_atcm.study as st, inspect\n"
            "assert inspect.isfunction(s.step_error), s.step_error\n"
            "assert inspect.isfunction(st.sweep) and inspect.isfunction(st.optimize), (st.sweep, st.optimize)\n"
            "from exudyn_atcm.solve import step_error\nassert inspect.isfunction(step_error)\n")
    _run(code)


def test_submodules_and_unknown_names_of_the_top_level():
    code = ("import exudyn_atcm as a, types\nassert isinstance(a.mbs, types.ModuleType) and a.mbs.__name__ == "
            "'exudyn_atcm.mbs'\nassert a.signals.__name__ == 'exudyn_atcm.model.signals'\n"
            "assert not hasattr(a, 'not_a_name')\ntry:\n    a.not_a_name\nexcept AttributeError as exc:\n"
            "    assert \"no attribute 'not_a_name'\" in str(exc), exc\nelse:\n    raise AssertionError('no error')\n")
    _run(code)


def test_lazy_face_refuses_a_malformed_table():
    with pytest.raises(ValueError, match=r"entry 'Thing' must be .*got \('model', 'Thing'\)"):
        lazy_face("exudyn_atcm", {"Thing": ("model", "Thing")})  # no leading dot: not a relative module
    with pytest.raises(ValueError, match=r"entry 'Thing'"):
        lazy_face("exudyn_atcm", {"Thing": ".model.Thing"})  # type: ignore[dict-item]
