"""Atomic file writes: a temporary file in the target directory, then ``os.replace``."""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any


def _file_mode() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


_FILE_MODE = _file_mode()


def write_atomic(path: str | os.PathLike, writer: Callable[[IO[str]], None], *, binary: bool = False) -> Path:
    """Write ``path`` through ``writer(handle)`` so that readers never see a partial file.

    The data goes to a temporary file in the same directory, which is renamed over ``path``
    (``os.replace``) once complete; on any error the temporary file is removed.
    """
    target = Path(path)
    directory = target.resolve().parent
    if not directory.is_dir():
        raise ValueError(f"path must be in an existing directory, got {os.fspath(path)!r}")
    fd, tmp = tempfile.mkstemp(prefix=".tmp_", suffix=target.suffix, dir=directory)
    try:
        os.chmod(tmp, _FILE_MODE)  # mkstemp makes 0600 files; give the usual permissions
        mode = "wb" if binary else "w"
        kwargs: dict[str, Any] = {} if binary else {"encoding": "utf-8", "newline": "\n"}
        with os.fdopen(fd, mode, **kwargs) as handle:
            writer(handle)
        os.replace(tmp, target)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    return target


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (UTF-8)."""
    return write_atomic(path, lambda handle: handle.write(text))


def write_json(path: str | os.PathLike, data: Any) -> Path:
    """Write ``data`` as indented JSON to ``path`` atomically."""
    return write_text(path, json.dumps(data, indent=2, default=_json_default) + "\n")


def _json_default(value: Any) -> Any:
    try:
        import numpy as np

        if isinstance(value, np.generic):
            return value.item()
        if isinstance(value, np.ndarray):
            return value.tolist()
    except ImportError:  # pragma: no cover
        pass
    if isinstance(value, Path):
        return str(value)
    return repr(value)
