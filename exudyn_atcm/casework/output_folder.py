"""A case's own files in its output folder: never two runs mixed, an unfinished run marked as such.

A case writes several files into one folder (``<case>.csv``, tables, ``<case>.json``, plots).
Written one after another over the files of a previous run, an interruption (Ctrl-C while the
plots are drawn, a killed job) would leave the new CSV beside the previous run's JSON, PNGs and
tables, and nothing would say so.  :class:`OutputFolder` writes a run's files in this order:

1. the marker ``<case>.partial.json`` (``"partial": true``, why, and the files it concerns);
2. the previous run's own files are removed -- the names its ``<case>.json`` lists, and those
   of an earlier unfinished run's marker; the previous JSON last, so that an interruption here
   still leaves the list.  Files the case did not write (the user's own, anything not listed)
   are never touched, and only plain names inside the folder are removed, never directories;
3. each new file is announced in the marker before it is written (:meth:`OutputFolder.add`);
   the plots are drawn into a hidden staging folder ``.<case>.plots`` and moved in once all are
   drawn, so a plot drawn half-way never appears;
4. the marker is removed when the run's last file is complete (:meth:`OutputFolder.finish`).

At any moment the folder holds the files of one run, plus the marker while that run is
unfinished.  An interrupted or failed run keeps its marker, which says why
(:meth:`OutputFolder.abandon`); a run killed outright (``SIGKILL``) keeps the marker of its
last step.  The next run into the folder removes what the marker lists.  The folder is
begun only when the run writes its first file: a run that fails before that leaves the
previous run's files as they were.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import shutil
from collections.abc import Iterable, Sequence
from pathlib import Path

from ..io.atomic import WriteError, describe_os_error, move_into_place, write_json

__all__ = ["OutputFolder", "marker_name", "own_files", "describe_stop"]


def marker_name(case: str) -> str:
    """Name of the marker of an unfinished run of ``case``: ``<case>.partial.json``."""
    return f"{case}.partial.json"


def _listed(path: Path) -> list[str]:
    """The ``files`` a JSON file lists (``[]`` if it is missing or not such a file)."""
    try:
        with open(path, encoding="utf-8") as handle:
            data = json.load(handle)
    except (OSError, ValueError):
        return []
    files = data.get("files") if isinstance(data, dict) else None
    return [f for f in files if isinstance(f, str)] if isinstance(files, list) else []


def _plain_name(name: str) -> bool:
    return bool(name) and name not in (".", "..") and "/" not in name and "\\" not in name and os.sep not in name


def own_files(directory: str | os.PathLike, case: str) -> list[str]:
    """Names of the files of ``case``'s previous runs in ``directory`` (from its JSON and marker).

    Only plain names inside the folder; the JSON itself and the marker are included when present.
    """
    directory = Path(directory)
    json_name = f"{case}.json"
    names = [*_listed(directory / json_name), *_listed(directory / marker_name(case))]
    names += [json_name] if (directory / json_name).exists() else []
    return [n for n in dict.fromkeys(names) if _plain_name(n) and n != marker_name(case)]


class OutputFolder:
    """The files of one run of a case in its output folder (see the module's description).

    Parameters
    ----------
    directory : pathlib.Path
        The output folder (exists).
    case : str
        The case's name (the stem of its files).
    """

    def __init__(self, directory: Path, case: str) -> None:
        self.directory = Path(directory)
        self.case = case
        self.marker = self.directory / marker_name(case)
        self.stage = self.directory / f".{case}.plots"
        #: names of this run's files, in the order they were announced
        self.files: list[str] = []
        self.begun = False
        self._started = _dt.datetime.now().astimezone().isoformat(timespec="seconds")

    def _mark(self, state: str, files: Iterable[str]) -> None:
        write_json(self.marker, {
            "case": self.case,
            "partial": True,
            "state": state,
            "started": self._started,
            "pid": os.getpid(),
            "files": list(dict.fromkeys(files)),
            "note": f"the files listed are of a run of {self.case} that did not finish (the state says why); "
                    "the next run of the case into this folder removes them",
        })

    def begin(self) -> None:
        """Mark the folder, remove the previous run's own files (its JSON last); once per run."""
        if self.begun:
            return
        previous = own_files(self.directory, self.case)
        self._mark("removing the previous run's files", previous)
        json_name = f"{self.case}.json"
        for name in [n for n in previous if n != json_name] + [json_name]:
            path = self.directory / name
            try:
                if path.is_file() or path.is_symlink():
                    path.unlink()
            except FileNotFoundError:
                pass
            except OSError as exc:
                raise WriteError(f"cannot remove {str(path)!r}, a file of the previous run of {self.case}: "
                                 f"{describe_os_error(exc)}") from None
        shutil.rmtree(self.stage, ignore_errors=True)
        self.begun = True
        self._mark("writing", self.files)

    def add(self, *names: str) -> None:
        """Announce files of this run before they are written (the marker lists them)."""
        self.begin()
        new = [n for n in names if n not in self.files]
        if new:
            self.files.extend(new)
            self._mark("writing", self.files)

    def plot_stage(self) -> Path:
        """An empty hidden folder for the plot function to draw into (moved in by :meth:`take_plots`)."""
        self.begin()
        shutil.rmtree(self.stage, ignore_errors=True)
        self.stage.mkdir()
        return self.stage

    def take_plots(self, returned: Sequence[str | os.PathLike]) -> list[Path]:
        """Move everything drawn into the stage into the folder; the paths of the returned files there.

        A returned path outside the stage (a plot function that wrote elsewhere) is kept as it is.
        """
        stage = self.stage.resolve()
        paths = [self.directory / Path(p).name if Path(p).resolve().parent == stage else Path(p) for p in returned]
        staged = sorted(p.name for p in self.stage.iterdir()) if self.stage.is_dir() else []
        self.add(*staged)
        for name in staged:
            source, target = self.stage / name, self.directory / name
            if source.is_dir() and target.is_dir():
                shutil.copytree(source, target, dirs_exist_ok=True)
                shutil.rmtree(source)
            else:
                move_into_place(source, target)
        shutil.rmtree(self.stage, ignore_errors=True)
        return paths

    def finish(self) -> None:
        """The run's files are complete: remove the marker."""
        shutil.rmtree(self.stage, ignore_errors=True)
        try:
            self.marker.unlink()
        except FileNotFoundError:
            pass

    def abandon(self, state: str) -> None:
        """The run stops unfinished: its marker says ``state`` and lists its files (a half-drawn plot is dropped)."""
        shutil.rmtree(self.stage, ignore_errors=True)
        if self.begun:
            self._mark(state, [n for n in self.files if (self.directory / n).exists()])


def describe_stop(exc: BaseException, step: str) -> str:
    """``"interrupted while <step>"`` for Ctrl-C / a stop signal, else ``"failed while <step>: Error: text"``."""
    if isinstance(exc, KeyboardInterrupt):
        return f"interrupted while {step}"
    text = " ".join(str(exc).split())
    return f"failed while {step}: {type(exc).__name__}" + (f": {text}" if text else "")

