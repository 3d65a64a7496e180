"""The run store: one JSON file per finished run, named by a hash of what determines it.

A run is determined by the case (its name and the full text of its source file), the
values of *all* its parameters (defaults included, so changing a default in the case file
is a new run), the contents of every file a parameter names (a record, a saved model: see
:mod:`exudyn_atcm.study.inputs`), of every Python file of the user's own that the case imports
or loads (:mod:`exudyn_atcm.study.case_modules`) and the versions of the package and of Exudyn.
:func:`run_key` hashes these with SHA-256; the record of a finished run is written atomically
to ``STORE/<key[:2]>/<key>.json`` the moment it finishes.  A study that is interrupted
(Ctrl-C, a killed job, a crashed machine) and started again finds the finished runs there and
does not repeat them; a half-written record cannot exist.  A changed input (the record file
edited, a new Exudyn) is a new key: the run is executed again.

To *say* that a run was executed again because an input changed, the store also keeps, for
each run identity (:func:`~exudyn_atcm.study.inputs.run_identity`: case, parameter values and
the files' paths, without their contents), the key and inputs of the last run stored
(``STORE/latest/<id[:2]>/<id>.json``); :meth:`RunStore.why_stale` compares them with a run's
inputs now.
"""

from __future__ import annotations

import hashlib
import json
import os
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..io.atomic import describe_os_error, make_directory, write_json
from .._version import __version__
from ..errors import SetupWarning
from .inputs import changes, environment, plain_values

__all__ = ["RunStore", "run_key", "run_key_before_inputs", "case_fingerprint", "record_problem"]

#: Fields of a run record and the types they must have (``None`` allowed where listed).
_FIELDS: dict[str, tuple[type, ...]] = {
    "key": (str,),
    "status": (str,),
    "error": (str,),
    "scalars": (dict,),
    "scalar_units": (dict,),
    "steps": (int, type(None)),
    "wall_time": (int, float, type(None)),
}


def record_problem(record: Any, key: str) -> str | None:
    """What makes ``record`` unusable as the stored run ``key``, or ``None`` if it is usable.

    Checks that it is a JSON object with the run's ``key``, a ``status`` of ``"ok"`` or
    ``"failed"``, a string ``error``, ``scalars`` mapping names to numbers, ``scalar_units``
    mapping names to strings, ``steps`` an integer or null and ``wall_time`` a number.
    """
    if not isinstance(record, dict):
        return f"it holds a JSON {type(record).__name__}, not an object"
    if record.get("key") != key:
        return f"its key is {record.get('key')!r}, not the run's {key!r} (a file of another run?)"
    for name, types in _FIELDS.items():
        if name not in record:
            return f"the field {name!r} is missing"
        value = record[name]
        if isinstance(value, bool) or not isinstance(value, types):
            return f"the field {name!r} is {value!r} ({type(value).__name__}), expected {' or '.join(t.__name__ for t in types)}"
    if record["status"] not in ("ok", "failed"):
        return f"the field 'status' is {record['status']!r}, expected 'ok' or 'failed'"
    for name, value in record["scalars"].items():
        if not isinstance(name, str) or isinstance(value, bool) or not isinstance(value, (int, float)):
            return f"the scalar {name!r} is {value!r} ({type(value).__name__}), expected a number"
    for name, value in record["scalar_units"].items():
        if not isinstance(value, str):
            return f"the unit of scalar {name!r} is {value!r}, expected a string"
    return None


def case_fingerprint(name: str, source_text: str) -> str:
    """SHA-256 of a case's name and source text (hex)."""
    digest = hashlib.sha256()
    digest.update(name.encode("utf-8"))
    digest.update(b"\0")
    digest.update(source_text.encode("utf-8"))
    return digest.hexdigest()


def run_key(fingerprint: str, values: Mapping[str, Any], version: str = __version__, *,
            inputs: Mapping[str, Any] | None = None) -> str:
    """The key of one run: SHA-256 over the case, the parameter values, the input files and the versions.

    Parameters
    ----------
    fingerprint : str
        :func:`case_fingerprint` of the case.
    values : mapping
        The values of all the case's parameters (sorted by name before hashing).
    version : str
        Package version (a new version recomputes everything).
    inputs : mapping, optional
        :func:`~exudyn_atcm.study.inputs.run_inputs` of the run: the SHA-256 of every file a
        parameter names, of the user's own modules the case reads and Exudyn's version are hashed too.  Default: no files, Exudyn's
        version now.
    """
    inputs = inputs if inputs is not None else {"versions": environment(), "files": {}}
    content = {"case": fingerprint, "values": plain_values(values), "version": version,
               "versions": {str(k): str(v) for k, v in inputs.get("versions", {}).items()},
               "files": {name: entry["sha256"] for name, entry in inputs.get("files", {}).items()}}
    if inputs.get("modules"):  # only then: a case without helpers keeps the keys of earlier releases
        content["modules"] = dict(inputs["modules"])
    payload = json.dumps(content, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(payload.encode("utf-8")).hexdigest()


#: The last release whose run store keyed runs by case, values and package version only.
VERSION_BEFORE_INPUTS = "0.2.0"


def run_key_before_inputs(fingerprint: str, values: Mapping[str, Any], version: str = VERSION_BEFORE_INPUTS) -> str:
    """The key exudyn_atcm ``version`` (default 0.2.0, the last such) gave a run before the key covered
    input files and Exudyn's version (issue 29).

    Only to say that a run stored under it is stale (:meth:`RunStore.why_stale`); never reused.
    """
    payload = json.dumps(
        {"case": fingerprint, "values": plain_values(values), "version": version},
        sort_keys=True,
        separators=(",", ":"),
    )
    return hashlib.sha256(payload.encode("utf-8")).hexdigest()


class RunStore:
    """Directory of finished runs, one atomic JSON record per run key.

    Parameters
    ----------
    directory : str or os.PathLike
        Store directory (created if missing).  Several studies of the same or different
        cases may share one store.
    """

    def __init__(self, directory: str | os.PathLike) -> None:
        self.directory = make_directory(directory, "run store")

    def path(self, key: str) -> Path:
        """File of the record of ``key``."""
        return self.directory / key[:2] / f"{key}.json"

    def load(self, key: str) -> dict[str, Any] | None:
        """The stored record of ``key``, or ``None`` if the run has not finished.

        A record that exists but cannot be used (not JSON, another key, a field of the wrong
        type: a damaged or hand-edited file) is also ``None``, so the run is executed again and
        the record replaced; a ``RuntimeWarning`` names the file and what is wrong with it.
        """
        path = self.path(key)
        try:
            with open(path, encoding="utf-8") as handle:
                record = json.load(handle)
        except FileNotFoundError:
            return None
        except (OSError, ValueError) as exc:
            reason = describe_os_error(exc) if isinstance(exc, OSError) else f"not valid JSON ({exc})"
            self._unusable(path, reason)
            return None
        problem = record_problem(record, key)
        if problem is not None:
            self._unusable(path, problem)
            return None
        return record

    @staticmethod
    def _unusable(path: Path, reason: str) -> None:
        warnings.warn(f"run store record {str(path)!r} cannot be used: {reason}; the run is executed again "
                      "and the record replaced", SetupWarning, stacklevel=4)

    def save(self, record: Mapping[str, Any]) -> Path:
        """Write ``record`` (which holds its ``key``) atomically; returns the file."""
        key = str(record["key"])
        path = self.path(key)
        path.parent.mkdir(parents=True, exist_ok=True)
        return write_json(path, dict(record))

    def latest_path(self, identity: str) -> Path:
        """File of the last stored run of ``identity`` (its key and inputs)."""
        return self.directory / "latest" / identity[:2] / f"{identity}.json"

    def remember(self, identity: str, key: str, inputs: Mapping[str, Any]) -> None:
        """Note ``key`` and its ``inputs`` as the last stored run of ``identity`` (atomic)."""
        path = self.latest_path(identity)
        path.parent.mkdir(parents=True, exist_ok=True)
        write_json(path, {"identity": identity, "key": key, "inputs": dict(inputs)})

    def why_stale(self, identity: str, key: str, inputs: Mapping[str, Any], key_before_inputs: str | None = None) -> str:
        """Why the store holds an older result of the run ``key`` (not found under it), or ``""``.

        The last run stored with the same ``identity`` (case, values, file paths) had other
        inputs: the message lists what changed (``"record file '/d/rec.csv' changed"``,
        ``"exudyn 1.13.5 -> 1.13.6"``).  A run stored under ``key_before_inputs``
        (:func:`run_key_before_inputs`) was stored before the key covered input files.
        """
        if key in self:
            return ""
        try:
            with open(self.latest_path(identity), encoding="utf-8") as handle:
                latest = json.load(handle)
        except (OSError, ValueError):
            latest = None
        if isinstance(latest, dict) and latest.get("key") != key and isinstance(latest.get("inputs"), dict):
            said = changes(latest["inputs"], inputs)
            if said:
                return "; ".join(said)
        if key_before_inputs is not None and key_before_inputs in self:
            return "stored before the run key covered input files and Exudyn's version"
        return ""

    def __contains__(self, key: object) -> bool:
        return isinstance(key, str) and self.path(key).is_file()

    def __repr__(self) -> str:
        return f"RunStore({str(self.directory)!r})"
