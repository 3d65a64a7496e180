"""Atomic file writes: a temporary file in the target directory, then ``os.replace`` (:func:`atomic_path`,
the one place of the package that does this; text, JSON, figures and GIFs all go through it)."""

from __future__ import annotations

import errno
import json
import os
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any

from ..errors import WriteError

__all__ = ["atomic_path", "write_atomic", "write_text", "write_json", "move_into_place", "make_directory",
           "describe_os_error", "write_error", "WriteError", "FILE_MODE"]


def _file_mode() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


FILE_MODE = _file_mode()


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


def write_error(path: str | os.PathLike, reason: str, exc: OSError | None = None, *,
                what: str = "write") -> WriteError:
    """A :class:`~exudyn_atcm.errors.WriteError` ``"cannot {what} {path!r}: {reason}"`` with ``filename`` set
    to the path as given and ``errno`` to that of ``exc`` (the failed call), if any.  ``what`` may end
    in ``{path}`` to place the path itself (``"write {path} into '/tmp'"``)."""
    quoted = repr(os.fspath(path))
    action = what.replace("{path}", quoted) if "{path}" in what else f"{what} {quoted}"
    error = WriteError(f"cannot {action}: {reason}")
    error.filename = os.fspath(path)
    if exc is not None:
        error.errno = exc.errno
    return error


def describe_os_error(exc: OSError) -> str:
    """The reason of an ``OSError`` in words, without errno numbers or temporary file names."""
    reason = _REASONS.get(exc.errno or -1)
    if reason is None:
        reason = (exc.strerror or type(exc).__name__).lower()
    return reason


def make_directory(path: str | os.PathLike, what: str = "output directory") -> Path:
    """Create ``path`` with its parents if missing; ``WriteError`` naming it and the reason on failure."""
    if os.fspath(path) == "":
        raise write_error(path, "the name is empty", what=f"create the {what}")
    directory = Path(path)
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except FileExistsError as exc:
        raise write_error(path, "a file of that name exists", exc, what=f"create the {what}") from None
    except OSError as exc:
        raise write_error(path, describe_os_error(exc), exc, what=f"create the {what}") from None
    return directory


@contextmanager
def atomic_path(path: str | os.PathLike, *, make_dirs: bool = False) -> Iterator[Path]:
    """A temporary file beside ``path`` to write to; renamed over ``path`` when the block ends without error.

    The one way the package writes files (text, JSON, CSV, figures, GIF animations): readers never
    see a partial file.  The temporary file is created in the target directory with the usual
    permissions (not ``mkstemp``'s 0600) and renamed over ``path`` (``os.replace``) once the
    ``with`` block is complete; on any error it is removed.

    >>> with atomic_path(target) as tmp:          # doctest: +SKIP
    ...     image.save(tmp, format="GIF")

    Parameters
    ----------
    path : str or os.PathLike
        Target file.
    make_dirs : bool, optional
        Create missing parent directories (otherwise a missing directory is a ``ValueError``).

    Raises
    ------
    ValueError
        If the directory does not exist and ``make_dirs`` is false.
    WriteError
        If the file cannot be written (also an empty path, a name too long for the file system,
        a path that is a directory); the message names ``path`` and the reason (not the
        temporary file).
    """
    if os.fspath(path) == "":
        raise write_error(path, "the file name is empty (give the name of the file to write)")
    target = Path(path)
    try:
        directory = target.resolve().parent
        missing = not directory.is_dir()
    except OSError as exc:  # a name longer than the file system allows, a loop of links ...
        raise write_error(path, describe_os_error(exc), exc) from None
    if missing:
        if not make_dirs:
            raise ValueError(f"path must be in an existing directory, got {os.fspath(path)!r}")
        make_directory(directory, "directory")
    try:
        is_directory = target.is_dir()
    except OSError as exc:
        raise write_error(path, describe_os_error(exc), exc) from None
    if is_directory:
        raise write_error(path, "it is a directory (give a file name in it)")
    try:
        fd, tmp = tempfile.mkstemp(prefix=".tmp_", suffix=target.suffix, dir=directory)
    except OSError as exc:
        raise write_error(path, describe_os_error(exc), exc, what=f"write {{path}} into {str(directory)!r}") from None
    os.close(fd)
    try:
        os.chmod(tmp, FILE_MODE)  # mkstemp makes 0600 files; give the usual permissions
        yield Path(tmp)
        os.replace(tmp, target)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError) and not isinstance(exc, WriteError):
            raise write_error(path, describe_os_error(exc), exc) from None
        raise


def write_atomic(path: str | os.PathLike, writer: Callable[[IO[str]], None], *, binary: bool = False,
                 make_dirs: bool = False) -> Path:
    """Write ``path`` through ``writer(handle)`` so that readers never see a partial file.

    The handle is opened on :func:`atomic_path`'s temporary file (text: UTF-8, ``\\n`` line ends).

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
    kwargs: dict[str, Any] = {} if binary else {"encoding": "utf-8", "newline": "\n"}
    with atomic_path(path, make_dirs=make_dirs) as tmp:
        with open(tmp, "wb" if binary else "w", **kwargs) as handle:
            writer(handle)
    return Path(path)


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (UTF-8)."""
    return write_atomic(path, lambda handle: handle.write(text))


def move_into_place(source: str | os.PathLike, target: str | os.PathLike) -> Path:
    """Move the finished file ``source`` to ``target`` in one step (``os.replace``; same file system).

    Readers see the previous ``target`` or the new one, never a mixture.

    Raises
    ------
    WriteError
        If it cannot be moved; the message names both paths and the reason.
    """
    try:
        os.replace(source, target)
    except OSError as exc:
        raise WriteError(f"cannot move {os.fspath(source)!r} to {os.fspath(target)!r}: {describe_os_error(exc)}") from None
    return Path(target)


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
