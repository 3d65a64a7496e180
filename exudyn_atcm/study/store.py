"""The run store: one JSON file per finished run, named by a hash of what determines it.

A run is determined by the case (its name and the full text of its source file), the
values of *all* its parameters (defaults included, so changing a default in the case file
is a new run), and the package version.  :func:`run_key` hashes these with SHA-256; the
record of a finished run is written atomically to ``STORE/<key[:2]>/<key>.json`` the moment
it finishes.  A study that is interrupted (Ctrl-C, a killed job, a crashed machine) and
started again finds the finished runs there and does not repeat them; a half-written record
cannot exist.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..io.atomic import write_json
from .._version import __version__

__all__ = ["RunStore", "run_key", "case_fingerprint"]


def case_fingerprint(name: str, source_text: str) -> str:
    """SHA-256 of a case's name and source text (hex)."""
    digest = hashlib.sha256()
    digest.update(name.encode("utf-8"))
    digest.update(b"\0")
    digest.update(source_text.encode("utf-8"))
    return digest.hexdigest()


def _plain(value: Any) -> Any:
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    if isinstance(value, float):
        return repr(value)  # exact: 0.1 and 0.1000000000000001 are different runs
    return value


def run_key(fingerprint: str, values: Mapping[str, Any], version: str = __version__) -> str:
    """The key of one run: SHA-256 over the case fingerprint, the parameter values and the version.

    Parameters
    ----------
    fingerprint : str
        :func:`case_fingerprint` of the case.
    values : mapping
        The values of all the case's parameters (sorted by name before hashing).
    version : str
        Package version (a new version recomputes everything).
    """
    payload = json.dumps(
        {"case": fingerprint, "values": {k: _plain(values[k]) for k in sorted(values)}, "version": version},
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
        self.directory = Path(directory)
        self.directory.mkdir(parents=True, exist_ok=True)

    def path(self, key: str) -> Path:
        """File of the record of ``key``."""
        return self.directory / key[:2] / f"{key}.json"

    def load(self, key: str) -> dict[str, Any] | None:
        """The stored record of ``key``, or ``None`` if the run has not finished (or the file is unreadable)."""
        path = self.path(key)
        try:
            with open(path, encoding="utf-8") as handle:
                record = json.load(handle)
        except (OSError, ValueError):
            return None
        return record if isinstance(record, dict) and record.get("key") == key else None

    def save(self, record: Mapping[str, Any]) -> Path:
        """Write ``record`` (which holds its ``key``) atomically; returns the file."""
        key = str(record["key"])
        path = self.path(key)
        path.parent.mkdir(parents=True, exist_ok=True)
        return write_json(path, dict(record))

    def __contains__(self, key: object) -> bool:
        return isinstance(key, str) and self.path(key).is_file()

    def __repr__(self) -> str:
        return f"RunStore({str(self.directory)!r})"
