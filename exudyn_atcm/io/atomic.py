"""Atomic file writes: a temporary file in the target directory, then ``os.replace``."""

from __future__ import annotations

import errno
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


FILE_MODE = _file_mode()


class WriteError(OSError):
    """A file or directory the user asked for could not be written; the message says which and why."""


_REASONS = {
    errno.EACCES: "permission denied (the directory is read-only or belongs to someone else)",
    errno.EPERM: "permission denied",
    errno.EROFS: "the file system is read-only",
    errno.ENOSPC: "the disk is full",
    errno.EDQUOT: "the disk quota is exceeded",
    errno.ENOENT: "a directory on the path does not exist",
    errno.ENOTDIR: "a part of the path is a file, not a directory",
    errno.EISDIR: "it is a directory",
    errno.ENAMETOOLONG: "the name is too long",
}


def describe_os_error(exc: OSError) -> str:
    """The reason of an ``OSError`` in words, without errno numbers or temporary file names."""
    reason = _REASONS.get(exc.errno or -1)
    if reason is None:
        reason = (exc.strerror or type(exc).__name__).lower()
    return reason


def make_directory(path: str | os.PathLike, what: str = "output directory") -> Path:
    """Create ``path`` with its parents if missing; ``WriteError`` naming it and the reason on failure."""
    directory = Path(path)
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise WriteError(f"cannot create the {what} {os.fspath(path)!r}: a file of that name exists") from None
    except OSError as exc:
        raise WriteError(f"cannot create the {what} {os.fspath(path)!r}: {describe_os_error(exc)}") from None
    return directory


def write_atomic(path: str | os.PathLike, writer: Callable[[IO[str]], None], *, binary: bool = False,
                 make_dirs: bool = False) -> Path:
    """Write ``path`` through ``writer(handle)`` so that readers never see a partial file.

    The data goes to a temporary file in the same directory, which is renamed over ``path``
    (``os.replace``) once complete; on any error the temporary file is removed.

    Parameters
    ----------
    path : str or os.PathLike
        Target file.
    writer : callable
        Writes the content to the open handle.
    binary : bool, optional
        Open the handle in binary mode.
    make_dirs : bool, optional
        Create missing parent directories (otherwise a missing directory is a ``ValueError``).

    Raises
    ------
    ValueError
        If the directory does not exist and ``make_dirs`` is false.
    WriteError
        If the file cannot be written; the message names ``path`` and the reason (not the
        temporary file).
    """
    target = Path(path)
    directory = target.resolve().parent
    if not directory.is_dir():
        if not make_dirs:
            raise ValueError(f"path must be in an existing directory, got {os.fspath(path)!r}")
        make_directory(directory, "directory")
    if target.is_dir():
        raise WriteError(f"cannot write {os.fspath(path)!r}: it is a directory")
    try:
        fd, tmp = tempfile.mkstemp(prefix=".tmp_", suffix=target.suffix, dir=directory)
    except OSError as exc:
        raise WriteError(f"cannot write {os.fspath(path)!r} into {str(directory)!r}: {describe_os_error(exc)}") from None
    try:
        os.chmod(tmp, FILE_MODE)  # mkstemp makes 0600 files; give the usual permissions
        mode = "wb" if binary else "w"
        kwargs: dict[str, Any] = {} if binary else {"encoding": "utf-8", "newline": "\n"}
        with os.fdopen(fd, mode, **kwargs) as handle:
            writer(handle)
        os.replace(tmp, target)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError) and not isinstance(exc, WriteError):
            raise WriteError(f"cannot write {os.fspath(path)!r}: {describe_os_error(exc)}") from None
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
