"""The SHA-256 of a file's contents, computed once while the file is unchanged: :func:`file_sha256`.

A study hashes the files its runs depend on for every run (a record a parameter names, the user's own modules a
case reads: :mod:`exudyn_atcm.study.inputs`, :mod:`exudyn_atcm.study.case_modules`); a file is read again only
when its size, times or inode change.  A file modified less than :data:`RACY_SECONDS` before it is hashed is not
cached: a file system stamps times coarsely, and a rewrite of the same size within one tick would look unchanged
(git's "racily clean" files).
"""

from __future__ import annotations

import hashlib
import os
import time
from pathlib import Path

__all__ = ["RACY_SECONDS", "file_sha256"]

#: (path, size, mtime_ns, ctime_ns, inode) -> SHA-256 of the contents
_HASHES: dict[tuple[str, int, int, int, int], str] = {}

#: A file changed less than this before it is hashed is hashed again next time [s].
RACY_SECONDS = 2.0


def file_sha256(path: str | os.PathLike) -> str:
    """SHA-256 (hex) of the contents of the file ``path`` (cached while the file is unchanged)."""
    resolved = Path(path).resolve()
    stat = resolved.stat()
    key = (str(resolved), stat.st_size, stat.st_mtime_ns, stat.st_ctime_ns, stat.st_ino)
    cached = _HASHES.get(key)
    if cached is None:
        digest = hashlib.sha256()
        with open(resolved, "rb") as handle:
            for block in iter(lambda: handle.read(1 << 20), b""):
                digest.update(block)
        cached = digest.hexdigest()
        if time.time_ns() - max(stat.st_mtime_ns, stat.st_ctime_ns) > RACY_SECONDS * 1e9:
            _HASHES[key] = cached
    return cached
