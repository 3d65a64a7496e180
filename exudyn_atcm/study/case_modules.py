"""The user's own Python files a case reads: part of what a stored run depends on.

A case file often imports helpers of its own (materials, geometry, a shared builder) or loads a
case beside it (``case_module(Path(__file__).with_name("compliant_four_bar.py"))``).  Their text
decides the result as much as the case's own, so the run store keys a run by their contents too
(:func:`~exudyn_atcm.study.inputs.run_inputs`, field ``modules``): until 2026-11-30 a study
replayed the stored runs after such a helper was edited, with the old numbers.

:func:`local_modules` finds them without importing anything: every ``import`` and ``from ...
import`` of the case's source (at any depth: inside functions too) is resolved the way Python
would find it, with the case's folder first on the search path; a module counts when its file
lies outside the standard library, the installed packages (site-packages) and ``exudyn_atcm``
itself.  A ``.py`` file the source names by a string beside it counts too.  Each file found is
read the same way, to :data:`MOST_FILES` files.  Not found: a module imported under a name built
at run time (``importlib.import_module(name)``), a file named by a computed path.
"""

from __future__ import annotations

import ast
import importlib.machinery
import sys
import sysconfig
from pathlib import Path

from .. import __file__ as _PACKAGE_INIT
from .file_hashes import file_sha256

__all__ = ["local_modules", "module_hashes", "forget_modules", "MOST_FILES"]

#: Most files :func:`local_modules` follows from one case (a guard against scanning a whole project).
MOST_FILES = 200

#: Folders whose modules are not the user's own: the standard library, the installed packages, this package.
_NOT_LOCAL = tuple({Path(p).resolve() for key in ("stdlib", "platstdlib", "purelib", "platlib")
                    if (p := sysconfig.get_paths().get(key))} | {Path(_PACKAGE_INIT).resolve().parent})

#: module file -> (text's mtime_ns and size, imported names, names of .py files it mentions)
_PARSED: dict[Path, tuple[tuple[int, int], list[str], list[str]]] = {}
#: case file -> (the stamps of it and of every file found, the search path, the files found): a study asks per run
_FOUND: dict[Path, tuple[tuple, tuple[str, ...], list[Path]]] = {}


def _stamps(paths) -> tuple:
    stamps = []
    for path in paths:
        try:
            stat = path.stat()
        except OSError:
            return ()
        stamps.append((stat.st_mtime_ns, stat.st_size))
    return tuple(stamps)


def _is_local(path: Path) -> bool:
    """A file of the user's own: outside the standard library, this package and any installed packages' folder
    (``site-packages``, ``dist-packages``: the user's site and other environments' too)."""
    if any(part in ("site-packages", "dist-packages") for part in path.parts):
        return False
    return not any(path.is_relative_to(folder) for folder in _NOT_LOCAL)


def _references(path: Path) -> tuple[list[str], list[str]]:
    """The absolute module names ``path``'s source imports and the ``.py`` names its strings mention (cached)."""
    stat = path.stat()
    stamp = (stat.st_mtime_ns, stat.st_size)
    cached = _PARSED.get(path)
    if cached is not None and cached[0] == stamp:
        return cached[1], cached[2]
    try:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    except (SyntaxError, UnicodeDecodeError, ValueError):  # the run itself will say what is wrong with it
        names, files = [], []
    else:
        names, files = [], []
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names += [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.append(node.module)
                names += [f"{node.module}.{alias.name}" for alias in node.names if alias.name != "*"]
            elif isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value.endswith(".py") \
                    and "\n" not in node.value and len(node.value) < 256:
                files.append(node.value)
    _PARSED[path] = (stamp, names, files)
    return names, files


def _module_file(name: str, search: list[str]) -> Path | None:
    """The source file Python would import for the dotted ``name`` (``None``: not found, built in, or not a file)."""
    locations: list[str] | None = search
    spec = None
    for depth, part in enumerate(name.split(".")):
        spec = importlib.machinery.PathFinder.find_spec(".".join(name.split(".")[:depth + 1]), locations)
        if spec is None:
            return None
        if depth == 0 and spec.origin and not _is_local(Path(spec.origin).resolve()):
            return None  # an installed package: nothing below it is the user's
        locations = list(spec.submodule_search_locations or [])
    origin = spec.origin if spec is not None else None
    if not origin or not origin.endswith(".py"):
        return None
    return Path(origin).resolve()


def local_modules(case_file: str | Path) -> list[Path]:
    """The user's own ``.py`` files the case file reads (see the module), sorted; the case file itself not included.

    Parameters
    ----------
    case_file : str or Path
        The case's source file (its folder is searched first, as when it runs from there).
    """
    case_file = Path(case_file).resolve()
    folder = case_file.parent
    search = [str(folder)] + [p for p in sys.path if p]
    cached = _FOUND.get(case_file)
    if cached is not None and cached[1] == tuple(search) and cached[0] and \
            cached[0] == _stamps([case_file, *cached[2]]):
        return list(cached[2])
    found: set[Path] = set()
    pending = [case_file]
    while pending and len(found) < MOST_FILES:
        path = pending.pop()
        names, files = _references(path)
        candidates = [_module_file(name, search) for name in names]
        candidates += [(path.parent / name).resolve() for name in files if (path.parent / name).is_file()]
        for candidate in candidates:
            if candidate is not None and candidate != case_file and candidate not in found and _is_local(candidate):
                found.add(candidate)
                pending.append(candidate)
    result = sorted(found)
    _FOUND[case_file] = (_stamps([case_file, *result]), tuple(search), result)
    return list(result)


def module_hashes(case_file: str | Path | None) -> dict[str, str]:
    """``{absolute path: SHA-256 of the text}`` of :func:`local_modules` (empty for ``None`` or a missing file)."""
    if case_file is None or not Path(case_file).is_file():
        return {}
    hashes = {}
    for path in local_modules(case_file):
        try:
            hashes[str(path)] = file_sha256(path)  # read again only when the file changed
        except OSError:  # unreadable: the run will say so when it imports it
            continue
    return hashes


def forget_modules(paths) -> list[str]:
    """Remove from ``sys.modules`` every module loaded from one of ``paths``, so that the next import reads the file
    again (a study's process, or a worker forked from it, would otherwise run a helper as it was when first
    imported, under a run key made from its new text).  Returns the names removed."""
    wanted = {str(Path(p).resolve()) for p in paths}
    removed = []
    for name, module in list(sys.modules.items()):
        origin = getattr(module, "__file__", None)
        if origin and str(Path(origin).resolve()) in wanted:
            del sys.modules[name]
            removed.append(name)
    return removed
