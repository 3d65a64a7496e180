"""What a run depends on besides its parameter values: the files they name, the case, the versions.

A run's result depends on more than the values of its parameters: a ``record`` parameter names a
file whose *contents* the case reads, the case's source computes it and the package and Exudyn
solve it.  :func:`run_inputs` describes all of this for one run, and the run store keys the run by
it (:func:`~exudyn_atcm.study.store.run_key`), so that a changed input is a new run:

* ``files``: the value of every ``str`` parameter without ``choices`` read as a path -- a
  relative one resolved against the current directory, as the case's run resolves it -- and,
  if it names a file, the SHA-256 of its contents.  A directory counts by its name only (a
  parameter naming a directory usually says where a run writes, such as a log folder, and its
  contents change with every run); a value naming nothing (a word, a file that does not exist
  yet) has no hash, so a file that appears later is a changed input too.  Empty values are
  left out.
* ``case``: the case fingerprint (name and source text).
* ``modules``: the SHA-256 of every Python file of the user's own that the case reads (its
  helpers, a case it loads: :func:`~exudyn_atcm.study.case_modules.module_hashes`), by absolute
  path; left out when there is none (the keys of such runs are those of earlier releases).
* ``versions``: of ``exudyn_atcm`` and of Exudyn (a new version recomputes everything).

:func:`run_identity` is the run *without* these contents (case, source file, parameter values,
the files' absolute paths): two runs with one identity and different inputs are the same run of a
changed input, and :func:`changes` says in words what changed (why a stored run is stale).

Files are hashed once per process while they stay unchanged (same size, modification and
change times, inode), so the populations of an optimisation do not read a large record again.
A file modified less than :data:`RACY_SECONDS` before it is hashed is not cached: a file system
stamps times coarsely, and a rewrite of the same size within one tick would look unchanged
(git's "racily clean" files).
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .._version import __version__
from ..casework import Case
from ..mbs.solver_runs import exudyn_version
from .case_modules import module_hashes
from .file_hashes import RACY_SECONDS, file_sha256

__all__ = ["RACY_SECONDS", "plain_values", "file_sha256", "input_files", "run_inputs", "run_identity", "changes",
           "environment"]

def _absolute(value: str) -> Path | None:
    """``value`` as an absolute path (relative to the current directory), or ``None`` if it cannot be one."""
    if not value.strip() or "\0" in value:
        return None
    try:
        path = Path(value).expanduser()
        return (path if path.is_absolute() else Path.cwd() / path).resolve()
    except (OSError, ValueError, RuntimeError):  # a symlink loop, an unknown user: names no file
        return None


def input_files(case: Case, values: Mapping[str, Any]) -> dict[str, dict[str, str | None]]:
    """``{parameter: {"path": absolute path, "sha256": hex or None}}`` for the ``str`` parameter values.

    Every non-empty value of a ``str`` parameter without ``choices`` is read as a path
    (relative to the current directory); ``sha256`` is the hash of the file's contents if it
    names a readable file, ``None`` otherwise (a directory, a word, a file not there yet).
    See the module's description.
    """
    files: dict[str, dict[str, str | None]] = {}
    for parameter in case.parameters:
        if parameter.kind != "str" or parameter.choices:
            continue
        path = _absolute(str(values.get(parameter.name, parameter.default)))
        if path is None:
            continue
        digest = None
        try:
            if path.is_file():
                digest = file_sha256(path)
        except OSError:  # unreadable (permissions, a name too long): the run will say so; nothing to hash
            digest = None
        files[parameter.name] = {"path": str(path), "sha256": digest}
    return files


def environment() -> dict[str, str]:
    """The versions a run's result depends on: ``exudyn_atcm`` and Exudyn (``exudyn.__version__``)."""
    return {"exudyn_atcm": __version__, "exudyn": exudyn_version()}


def run_inputs(case: Case, fingerprint: str, values: Mapping[str, Any], versions: Mapping[str, str] | None = None) -> dict[str, Any]:
    """What a run depends on besides its parameter values (see the module's description).

    Parameters
    ----------
    case : Case
        The case (its declared parameters say which values may name files).
    fingerprint : str
        :func:`~exudyn_atcm.study.store.case_fingerprint` of the case.
    values : mapping
        All the run's parameter values.
    versions : mapping, optional
        :func:`environment` (computed once per study by the caller; default: now).
    """
    inputs = {
        "case": fingerprint,
        "versions": dict(versions if versions is not None else environment()),
        "files": input_files(case, values),
    }
    modules = module_hashes(case.source)
    if modules:
        inputs["modules"] = modules
    return inputs


def _plain(value: Any) -> Any:
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    if isinstance(value, float):
        return repr(value)  # exact: 0.1 and 0.1000000000000001 are different runs
    return value


def plain_values(values: Mapping[str, Any]) -> dict[str, Any]:
    """Parameter values as exact JSON for hashing (sorted; floats by ``repr``, tuples as lists)."""
    return {k: _plain(values[k]) for k in sorted(values)}


def run_identity(case: Case, values: Mapping[str, Any], inputs: Mapping[str, Any]) -> str:
    """SHA-256 of a run without its inputs' contents: case name and file, values, the files' paths.

    Two runs of one identity with different :func:`run_inputs` are one run whose input changed.
    """
    paths = {name: entry["path"] for name, entry in inputs.get("files", {}).items()}
    payload = json.dumps(
        {"case": case.name, "source": str(case.source or ""), "paths": paths,
         "values": plain_values(values)},
        sort_keys=True, separators=(",", ":"),
    )
    return hashlib.sha256(payload.encode("utf-8")).hexdigest()


def changes(old: Mapping[str, Any], new: Mapping[str, Any]) -> list[str]:
    """What differs between two :func:`run_inputs` descriptions, in words (empty if nothing)."""
    said: list[str] = []
    old_files, new_files = old.get("files", {}), new.get("files", {})
    for name in sorted(set(old_files) & set(new_files)):
        before, after = old_files[name].get("sha256"), new_files[name].get("sha256")
        path = new_files[name].get("path")
        if before is None and after is not None:
            said.append(f"{name} file {path!r} now exists")
        elif before is not None and after is None:
            said.append(f"{name} file {path!r} no longer exists")
        elif before != after:
            said.append(f"{name} file {path!r} changed")
    old_modules, new_modules = old.get("modules", {}), new.get("modules", {})
    for path in sorted(set(old_modules) | set(new_modules)):
        if path not in old_modules:
            said.append(f"the case now reads {path!r}")
        elif path not in new_modules:
            said.append(f"the case no longer reads {path!r}")
        elif old_modules[path] != new_modules[path]:
            said.append(f"{path!r}, which the case reads, changed")
    if old.get("case") != new.get("case"):
        said.append("the case's source changed")
    old_versions, new_versions = old.get("versions", {}), new.get("versions", {})
    for package in sorted(set(old_versions) | set(new_versions)):
        if old_versions.get(package) != new_versions.get(package):
            said.append(f"{package} {old_versions.get(package, '?')} -> {new_versions.get(package, '?')}")
    return said
