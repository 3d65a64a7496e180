"""Running a case from the command line (``python cases/<name>.py``, ``exudyn-atcm run``): the
shared options, the one-line summary and error reports, Ctrl-C and stop signals (exit status 130,
143) with what was written until then.
"""

from __future__ import annotations

import argparse
import sys
import traceback
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Protocol

from ..io.progress import ProgressBar
from ..solve.run_checks import SimulationInterrupted
from .output_folder import marker_name
from .parameters import CaseError
from .termination import StopSignal, stop_signals_as_interrupt

__all__ = ["add_run_options", "run_and_report", "RunnableCase"]


class RunnableCase(Protocol):
    """What the command line needs of a case (:class:`~exudyn_atcm.casework.case.Case` has it)."""

    name: str

    def parse_assignments(self, assignments: Sequence[str]) -> dict[str, Any]: ...

    def run(self, values: Any = None, *, out_dir: Any = None, plot: bool = True, progress: Any = None) -> Any: ...

def add_run_options(parser: argparse.ArgumentParser) -> None:
    """The options shared by ``python cases/x.py`` and ``exudyn-atcm run``."""
    parser.add_argument(
        "--set", action="append", default=[], metavar="NAME=VALUE", help="override a parameter (repeatable)"
    )
    parser.add_argument("--out", default="out", metavar="DIR", help="output directory (default: ./out)")
    parser.add_argument("--no-plot", action="store_true", help="do not write the PNG plots")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")


def run_and_report(case: RunnableCase, assignments: Sequence[str], out: str, plot: bool, debug: bool) -> int:
    """Run ``case`` with ``NAME=VALUE`` overrides, print a summary; the exit status.

    Errors are printed as one line on stderr (with the traceback when ``debug``): exit
    status 2 for a bad parameter, 1 for a failure of the run, 130 for Ctrl-C and 143 for
    SIGTERM (what was computed until then is written, marked partial).
    """
    try:
        values = case.parse_assignments(assignments)
    except CaseError as exc:
        return _fail(exc, debug, 2)
    bar = ProgressBar(sys.stdout) if sys.stdout.isatty() else None
    stop = StopSignal()
    try:
        with warnings.catch_warnings(), stop_signals_as_interrupt() as stop:
            warnings.showwarning = _show_warning
            output = case.run(values, out_dir=out, plot=plot, progress=bar)
    except KeyboardInterrupt as exc:
        if bar is not None:
            bar.close()
        return _interrupted(case, exc, out, debug, stop)
    except Exception as exc:  # noqa: BLE001 - reported as one line
        return _fail(exc, debug, 2 if isinstance(exc, CaseError) else 1)
    finally:
        if bar is not None:
            bar.close()
    print(f"{case.name}: {output.steps} steps in {output.wall_time:.3g} s")
    for name, value in output.scalars.items():
        print(f"  {name} = {value:.7g} [{output.scalar_units[name]}]")
    print(f"  wrote {len(output.files)} files to {out}")
    return 0


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """Warnings of a command-line run as one line ``warning: ...`` on stderr (no source line)."""
    print(f"warning: {' '.join(str(message).split())}", file=sys.stderr)


def _interrupted(case: RunnableCase, exc: KeyboardInterrupt, out: str, debug: bool, stop: StopSignal) -> int:
    """Report Ctrl-C or a stop signal: where the simulation stopped and what was written.

    Exit status 130 for Ctrl-C, ``128 + signal number`` for a stop signal (143 for SIGTERM).
    """
    how = "interrupted" if stop.signum is None else f"stopped by {stop.name}"
    marker = Path(out) / marker_name(case.name)
    unfinished = f"; {out} holds this unfinished run, listed in {marker}" if marker.is_file() else ""
    if isinstance(exc, SimulationInterrupted):
        files = getattr(exc, "files", [])
        rows = exc.result.n_rows if exc.result is not None else 0
        stage = exc.result.info.get("interrupted_in") if exc.result is not None else None
        where = f" in the {stage}" if stage else ""  # simulate(accuracy=): the probe's partial run is not the run
        if files:
            written = f"; wrote the {rows} recorded instants up to there (marked partial) to {files[0]}{unfinished}"
        else:
            written = "; nothing was written (no output directory, or nothing computed yet)"
        return _fail(f"{case.name}: {how} at t = {exc.time:.6g} s{where}{written}", debug, stop.exit_status)
    if unfinished:
        return _fail(f"{case.name}: {stop.describe()} before the simulation started or after it ended; the files "
                     f"written are one unfinished run, listed in {marker}", debug, stop.exit_status)
    return _fail(f"{case.name}: {stop.describe()} before the simulation started or after it ended; "
                 f"{out} holds no unfinished run (no {marker.name})", debug, stop.exit_status)


def _fail(exc: BaseException | str, debug: bool, status: int) -> int:
    if debug and isinstance(exc, BaseException):
        traceback.print_exception(type(exc), exc, exc.__traceback__)
    message = " ".join(str(exc).split()) or type(exc).__name__
    print(f"error: {message}", file=sys.stderr)
    return status
