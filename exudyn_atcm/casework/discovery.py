"""Finding and loading case files: by path, or by name in the case directories, in order.

See :mod:`exudyn_atcm.casework.case` for the convention and :func:`case_dirs` for the search order.
"""

from __future__ import annotations

import importlib.util
import os
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .case import Case
from .parameters import CaseError, closest
from ..errors import SetupWarning

__all__ = ["ENV_CASES", "CASE_MARKERS", "case_dirs", "case_files", "list_cases", "find_case", "case_module", "load_case",
           "follows_convention", "load_cases"]

#: Environment variable with extra case directories (``os.pathsep``-separated).
ENV_CASES = "EXUDYN_ATCM_CASES"

#: A case file mentions one of these (checked before the file is executed).
CASE_MARKERS = ("exudyn_atcm.casework", "exudyn_atcm.cases")


def case_dirs(cases_dir: str | os.PathLike | Sequence[str | os.PathLike] | None = None, *,
              package: bool = True) -> list[Path]:
    """Directories searched for cases by name, in order (existing ones only).

    ``cases_dir`` (``--cases-dir``; several in order), then ``$EXUDYN_ATCM_CASES``
    (``os.pathsep``-separated), then, with ``package``, the ``cases/`` folder of the source
    checkout beside the package (only if it is this package's checkout), then the example cases
    installed with the package (``exudyn_atcm.example_cases``).  Not the current directory's
    ``cases/`` unless given.
    """
    candidates: list[Path] = []
    if isinstance(cases_dir, (str, os.PathLike)):
        candidates.append(Path(cases_dir))
    elif cases_dir is not None:
        candidates.extend(Path(d) for d in cases_dir)
    env = os.environ.get(ENV_CASES, "")
    candidates.extend(Path(p) for p in env.split(os.pathsep) if p.strip())
    checkout = _checkout_cases_dir() if package else None
    if checkout is not None:
        candidates.append(checkout)
    installed = _installed_cases_dir() if package else None
    if installed is not None:
        candidates.append(installed)
    seen: list[Path] = []
    for path in candidates:
        resolved = path.resolve()
        if resolved.is_dir() and resolved not in seen:
            seen.append(resolved)
    return seen


def _checkout_cases_dir() -> Path | None:
    """``cases/`` beside the package if the package sits in its source checkout (not site-packages)."""
    root = Path(__file__).resolve().parents[2]
    try:
        setup = (root / "setup.cfg").read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    return root / "cases" if "name = exudyn-atcm" in setup else None


def _installed_cases_dir() -> Path | None:
    """Directory of the installed package ``exudyn_atcm.example_cases`` (``cases/`` shipped with the package)."""
    try:
        spec = importlib.util.find_spec("exudyn_atcm.example_cases")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    return Path(list(spec.submodule_search_locations)[0])


def list_cases(cases_dir: str | os.PathLike | Sequence[str | os.PathLike] | None = None, *,
               package: bool = True) -> list[Path]:
    """Case files found by name: ``*.py`` not starting with ``_``; the first of a name wins.

    ``cases_dir`` and ``package`` as for :func:`case_dirs`.
    """
    found: dict[str, Path] = {}
    for directory in case_dirs(cases_dir, package=package):
        for path in sorted(directory.glob("*.py")):
            if not path.name.startswith("_") and path.stem not in found:
                found[path.stem] = path
    return [found[name] for name in sorted(found)]


def find_case(spec: str | os.PathLike, cases_dir: str | os.PathLike | None = None) -> Path:
    """The file of a case given by path or by name.

    Raises
    ------
    CaseError
        If no such file or name exists; the message lists the cases found.
    """
    text = os.fspath(spec)
    path = Path(text)
    if text.endswith(".py") or os.sep in text or (os.altsep and os.altsep in text):
        if path.is_file():
            return path.resolve()
        raise CaseError(f"case file {text!r} does not exist")
    found = case_files(text, cases_dir)
    if found:
        if len(found) > 1:
            warnings.warn(
                f"case {text!r} is found in {len(found)} different files: using {found[0]} (the first in the search "
                f"order --cases-dir, ${ENV_CASES}, the package's cases); not using {', '.join(str(f) for f in found[1:])}",
                SetupWarning, stacklevel=3,
            )
        return found[0]
    stems = [p.stem for p in list_cases(cases_dir)]
    names = ", ".join(stems) or "none"
    dirs = ", ".join(str(d) for d in case_dirs(cases_dir)) or "none"
    raise CaseError(f"no case named {text!r}{closest(text, stems)}; available: {names} (searched {dirs})"
                    + _local_hint(text))


def _local_hint(name: str) -> str:
    """A note if ``./cases/<name>.py`` exists: the current directory is searched only when asked."""
    local = Path("cases") / f"{name}.py"
    if not local.is_file():
        return ""
    return (f"; {local} exists here, but the current directory is searched only when asked: "
            f"give --cases-dir cases or the path {local}")


def case_files(name: str, cases_dir: str | os.PathLike | None = None) -> list[Path]:
    """Every file that defines case ``name`` in the search order of :func:`case_dirs`, the one used first.

    Files with the same content (the checkout's case and its installed copy) count once.
    """
    files: list[Path] = []
    if name.startswith("_"):
        return files
    contents: list[bytes] = []
    for directory in case_dirs(cases_dir):
        path = directory / f"{name}.py"
        if not path.is_file():
            continue
        try:
            content = path.read_bytes()
        except OSError:
            content = b""
        if content not in contents:
            files.append(path)
            contents.append(content)
    return files


def case_module(spec: str | os.PathLike, cases_dir: str | os.PathLike | None = None) -> Any:
    """Import a case file (by path or name) as a module: its ``CASE`` and its functions (a case that
    builds on another case's builder, such as ``synthesise_path`` on ``compliant_four_bar``).

    A file that does not mention ``CASE`` and the case framework (``exudyn_atcm.casework``, or the
    deprecated ``exudyn_atcm.cases``) is refused without being executed (a plain script may run a
    whole simulation when imported).

    Raises
    ------
    CaseError
        If the file is missing, does not follow the case convention or fails to import.
    """
    path = find_case(spec, cases_dir)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise CaseError(f"{path}: cannot be read: {exc}") from None
    if not follows_convention(text):
        # not executed: a plain script might run a whole simulation on import
        raise CaseError(f"{path}: does not follow the case convention (no CASE = exudyn_atcm.casework.Case(...))")
    module_name = f"exudyn_atcm_case_{path.stem}"
    spec_ = importlib.util.spec_from_file_location(module_name, path)
    if spec_ is None or spec_.loader is None:  # pragma: no cover
        raise CaseError(f"{path}: cannot be imported")
    module = importlib.util.module_from_spec(spec_)
    try:
        spec_.loader.exec_module(module)
    except Exception as exc:  # noqa: BLE001
        message = " ".join(str(exc).split())
        raise CaseError(f"{path}: import failed: {type(exc).__name__}: {message}") from exc
    module.__file__ = str(path)
    return module


def load_case(spec: str | os.PathLike, cases_dir: str | os.PathLike | None = None) -> Case:
    """Import a case file (by path or name, :func:`case_module`) and return its ``CASE``.

    Raises
    ------
    CaseError
        If the file is missing, does not follow the case convention, fails to import, or defines
        no ``CASE``.
    """
    module = case_module(spec, cases_dir)
    path = Path(module.__file__)
    case = getattr(module, "CASE", None)
    if not isinstance(case, Case):
        raise CaseError(f"{path}: defines no CASE = exudyn_atcm.casework.Case(...)")
    case.source = path
    return case


def follows_convention(text: str) -> bool:
    """Whether a case file's text mentions ``CASE`` and the case framework (:data:`CASE_MARKERS`).

    Read before a file is executed: a file that does not is not a case (a helper module, a plain script).
    """
    return "CASE" in text and any(marker in text for marker in CASE_MARKERS)


def load_cases(cases_dir: str | os.PathLike | Sequence[str | os.PathLike] | None = None, *,
               package: bool = True) -> tuple[list[Case], list[tuple[Path, str]]]:
    """Every case found by name (:func:`list_cases`) loaded: the cases, and the files that failed.

    Files that do not follow the convention (:func:`follows_convention`) are not cases and are left
    out unexecuted; a case file whose import or declarations fail is returned with the error message
    (the regression suite reports it as a failed run, the smoke test fails on it).
    """
    cases: list[Case] = []
    failed: list[tuple[Path, str]] = []
    for path in list_cases(cases_dir, package=package):
        try:
            if not follows_convention(path.read_text(encoding="utf-8")):
                continue
            cases.append(load_case(path))
        except (OSError, UnicodeDecodeError, CaseError) as exc:
            failed.append((path, " ".join(str(exc).split())))
    return cases, failed
