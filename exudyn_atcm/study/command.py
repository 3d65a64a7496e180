"""The ``exudyn-atcm sweep`` and ``optimize`` commands: options, the progress bar over runs, summaries.

::

    exudyn-atcm sweep CASE --grid NAME=START:STOP:N --grid NAME=A,B,C [--samples N]
                      [--set NAME=VALUE] [--workers N | --scheduler tcp://HOST:8786]
                      [--out DIR] [--store DIR] [--retry-failed] [--no-plot]
    exudyn-atcm optimize CASE --objective NAME [--maximize] --bound NAME=LOW:HIGH
                      [--constraint "NAME>=VALUE"] [--method differential_evolution]
                      [--maxiter N] [--popsize N] [--max-evaluations N]
                      [--set NAME=VALUE] [--workers N | --scheduler ADDRESS] [--out DIR]

Ctrl-C or ``SIGTERM`` stops a sweep at once (its workers too) and says how many runs are
stored and the command that resumes; exit status 130 (Ctrl-C) or 143 (``SIGTERM``).
Exit status of ``sweep``: 0 if every run succeeded, 1 if any run failed (the study still
completes and the table holds each error), if the output directory cannot be written, or
if another sweep is writing the same table now; 2 for a usage error (unknown case or
parameter, bad grid).  Of ``optimize``: 0 if the best design satisfies the constraints,
1 if no evaluated design does, if the objective was not finite at any design of the first
population (or simplex), if the output directory cannot be written or another optimisation
of the case is writing it now; 2 for a usage error.  ``optimize`` says before it starts how
many evaluations it makes at most (``--max-evaluations`` caps them exactly).
"""

from __future__ import annotations

import argparse
import shlex
from collections import Counter
import sys
import time
from collections.abc import Sequence
from typing import IO

from ..casework.error_report import report_error as _error
from ..casework import CaseError, load_case
from ..casework.termination import StopSignal, stop_signals_as_interrupt
from .budget import describe_evaluations
from .command_options import add_optimize_parser, add_sweep_parser
from .lock import StudyLockedError
from .options import OptimizeOptions, RunOptions
from .stops import ObjectiveNotFiniteError

__all__ = ["add_sweep_parser", "sweep_command", "resume_note", "add_optimize_parser", "optimize_command", "RunProgressBar"]


class RunProgressBar:
    """``[#######.......] 12/40 runs, 1 failed, 25 s left`` on a terminal stream (nothing otherwise).

    Parameters
    ----------
    stream : file-like, optional
        Output stream (default ``sys.stderr``).
    force : bool
        Draw even if the stream is not a terminal (for tests).
    width : int
        Number of bar characters.
    """

    def __init__(self, stream: IO[str] | None = None, force: bool = False, width: int = 30) -> None:
        self.stream = stream if stream is not None else sys.stderr
        isatty = getattr(self.stream, "isatty", None)
        self.enabled = bool(force or (isatty is not None and isatty()))
        self.width = int(width)
        self._start = time.perf_counter()
        self._first: int | None = None
        self._drawn = False

    def __call__(self, done: int, total: int, failed: int) -> None:
        if not self.enabled or total <= 0:
            return
        if self._first is None:
            self._first = done  # runs answered from the store do not count for the estimate
            self._start = time.perf_counter()
        share = done / total
        filled = int(round(share * self.width))
        elapsed = time.perf_counter() - self._start
        fresh = done - self._first
        eta = f", {elapsed / fresh * (total - done):.0f} s left" if fresh > 0 and done < total else ""
        fail = f", {failed} failed" if failed else ""
        self.stream.write(f"\r[{'#' * filled}{'.' * (self.width - filled)}] {done}/{total} runs{fail}{eta}   ")
        self.stream.flush()
        self._drawn = True

    def close(self) -> None:
        """End the bar's line if anything was drawn."""
        if self._drawn:
            self.stream.write("\n")
            self.stream.flush()
            self._drawn = False


def _check_engine_options(args: argparse.Namespace, debug: bool) -> int | None:
    """Exit status 2 (with the error line) if --workers/--scheduler are invalid, else None."""
    if args.workers is not None and args.workers < 1:
        return _error(f"--workers must be an integer >= 1, got {args.workers}", debug, 2)
    if args.workers is not None and args.scheduler is not None:
        return _error("give either --workers (this machine) or --scheduler (a Dask cluster), not both", debug, 2)
    return None


def resume_note(case_name: str, exc: BaseException, argv: Sequence[str] | None) -> str:
    """What an interrupted sweep leaves: runs stored, and the command that resumes (one line).

    Parameters
    ----------
    case_name : str
        The case.
    exc : BaseException
        The ``KeyboardInterrupt`` from :func:`~exudyn_atcm.study.run_study` (with
        ``stored_runs``, ``distinct_runs`` and ``store_directory`` if the runs had started).
    argv : sequence of str, optional
        The command's arguments after ``exudyn-atcm`` (``None``: not known).
    """
    command = ("exudyn-atcm " + shlex.join(argv)) if argv else "the same command"
    store = getattr(exc, "store_directory", None)
    if store is None:
        return f"{case_name}: sweep stopped before any run was stored; {command} starts it again"
    return (f"{case_name}: sweep stopped with {exc.stored_runs} of {exc.distinct_runs} runs stored in {store}; "
            f"to resume (stored runs are not repeated): {command}")


def sweep_command(args: argparse.Namespace) -> int:
    """Run ``exudyn-atcm sweep``; returns the exit status."""
    from .design import GridError, parse_grid_spec
    from .plots import plot_study
    from .sweep import run_study

    debug = bool(getattr(args, "debug", False))
    status = _check_engine_options(args, debug)
    if status is not None:
        return status
    if args.samples is not None and args.samples < 1:
        return _error(f"--samples must be an integer >= 1, got {args.samples}", debug, 2)
    try:
        case = load_case(args.case, getattr(args, "cases_dir", None))
        grid, bounds = {}, {}
        for text in args.grid:
            name, values = parse_grid_spec(case, text, ranges=args.samples is not None)
            if name in grid or name in bounds:
                raise GridError(f"--grid {name}: given twice")
            (bounds if isinstance(values, tuple) else grid)[name] = values
        if args.samples is not None and not bounds:
            raise GridError("--samples needs at least one range --grid NAME=START:STOP to sample in")
        if not grid and not bounds:
            raise GridError("nothing to vary: give --grid NAME=START:STOP:N or NAME=A,B,C")
        fixed = case.parse_assignments(args.set)
    except (CaseError, ValueError) as exc:
        return _error(exc, debug, 2)
    bar = RunProgressBar(sys.stderr)
    stop = StopSignal()
    try:
        with stop_signals_as_interrupt() as stop:
            result = run_study(
                case, grid or None, samples=args.samples, bounds=bounds or None, method=args.sampling, seed=args.seed,
                fixed=fixed, run=RunOptions(workers=args.workers, scheduler=args.scheduler, out=args.out,
                                            store=args.store, retry_failed=args.retry_failed, progress=bar),
            )
    except KeyboardInterrupt as exc:
        bar.close()
        print(resume_note(case.name, exc, getattr(args, "argv", None)), file=sys.stderr)
        return _error("interrupted" if stop.signum is None else stop.describe(), debug, stop.exit_status)
    except (CaseError, ValueError) as exc:
        bar.close()
        return _error(exc, debug, 2)
    except ImportError as exc:
        bar.close()
        return _error(exc, debug, 2)
    except (OSError, StudyLockedError) as exc:  # an output directory that cannot be written, a second sweep
        bar.close()
        return _error(exc, debug, 1)
    bar.close()
    files = list(result.files)
    if not args.no_plot:
        names = [c.name for c in result.columns]
        scalars = names[1 + len(case.parameters):names.index("status")]
        files += plot_study(result.table, result.varied, scalars, args.out, f"{case.name}_sweep_", grid=args.samples is None)
    total = len(result.records)
    print(f"{case.name}: {total} runs ({result.executed} executed, {result.reused} from the store, "
          f"{result.failed} failed) in {result.wall_time:.3g} s on {result.engine} ({result.workers} worker{'s' if result.workers != 1 else ''})")
    if result.stale:
        reasons = Counter(r["stale"] for r in {r["key"]: r for r in result.records if r["stale"]}.values())
        print(f"  {result.stale} stale run{'s' if result.stale > 1 else ''} executed again (the store held results "
              f"of the same values from other inputs): " + "; ".join(f"{n} x {why}" for why, n in reasons.items()))
    for record in result.records:
        if record["status"] != "ok":
            print(f"  run {record['index']} failed: {record['error']}")
            break
    print(f"  table: {result.csv_path}")
    print(f"  wrote {len(files)} files to {args.out}")
    return 1 if result.failed else 0


def _parse_constraint(text: str) -> tuple[str, tuple[float | None, float | None]]:
    import re

    match = re.fullmatch(r"\s*([A-Za-z_]\w*)\s*(>=|<=)\s*(\S+)\s*", text)
    if match is None:
        raise ValueError(f"--constraint expects NAME>=VALUE or NAME<=VALUE, got {text!r}")
    name, op, value = match.groups()
    try:
        number = float(value)
    except ValueError:
        raise ValueError(f"--constraint {name}: VALUE must be a number, got {value!r}") from None
    return name, ((number, None) if op == ">=" else (None, number))


def optimize_command(args: argparse.Namespace) -> int:
    """Run ``exudyn-atcm optimize``; returns the exit status."""
    from .design import GridError, case_parameter, parse_grid_spec
    from .optimize import optimize

    debug = bool(getattr(args, "debug", False))
    status = _check_engine_options(args, debug)
    if status is not None:
        return status
    for name in ("maxiter", "popsize", "max_evaluations"):
        if getattr(args, name) is not None and getattr(args, name) < 1:
            return _error(f"--{name.replace('_', '-')} must be an integer >= 1, got {getattr(args, name)}", debug, 2)
    try:
        case = load_case(args.case, getattr(args, "cases_dir", None))
        if not args.bound:
            raise GridError("give at least one design variable: --bound NAME=LOW:HIGH")
        bounds = {}
        for text in args.bound:
            name = text.partition("=")[0].strip()
            if name and "=" in text:
                kind = case_parameter(case, name, "--bound").kind
                if kind not in ("float", "int"):
                    raise GridError(f"--bound {name}: {name} is a {kind} parameter; design variables must be float or int "
                                    "(fix it with --set instead)")
            name, values = parse_grid_spec(case, text, ranges=True, option="--bound")
            if not isinstance(values, tuple):
                raise GridError(f"--bound {name}: expects NAME=LOW:HIGH, got {text!r}")
            if name in bounds:
                raise GridError(f"--bound {name}: given twice")
            bounds[name] = values
        constraints = {}
        for text in args.constraint:
            name, (low, high) = _parse_constraint(text)
            old_low, old_high = constraints.get(name, (None, None))
            constraints[name] = (low if low is not None else old_low, high if high is not None else old_high)
        fixed = case.parse_assignments(args.set)
    except (CaseError, ValueError) as exc:
        return _error(exc, debug, 2)
    kinds = [case_parameter(case, name, "--bound").kind for name in bounds]
    n = len(bounds)
    print(f"{case.name}: {args.method} over {n} variable{'s' if n > 1 else ''}: "
          + describe_evaluations(args.method, n, kinds.count("float"), args.maxiter, args.popsize, True, args.max_evaluations,
                                 "--max-evaluations") + f"; then the best design runs once more for its files in {args.out}/best",
          flush=True)
    try:
        best = optimize(
            case, args.objective, bounds, method=args.method, maximize=args.maximize, constraints=constraints,
            fixed=fixed, options=OptimizeOptions(seed=args.seed, maxiter=args.maxiter, popsize=args.popsize,
                                                 plot=not args.no_plot, max_evaluations=args.max_evaluations),
            run=RunOptions(workers=args.workers, scheduler=args.scheduler, out=args.out, store=args.store),
        )
    except (CaseError, ValueError, ImportError) as exc:
        return _error(exc, debug, 2)
    except (OSError, StudyLockedError, ObjectiveNotFiniteError) as exc:  # unwritable output, a second run, nothing finite
        return _error(exc, debug, 1)
    units = {p.name: p.unit for p in case.parameters}
    sense = "maximum" if args.maximize else "minimum"
    print(f"{case.name}: {sense} of {args.objective} = {best.objective:.7g} after {best.evaluations} evaluations "
          f"({best.executed} runs executed){' - NO DESIGN MEETS THE CONSTRAINTS' if constraints and not best.feasible else ''}")
    for name, value in best.design.items():
        print(f"  {name} = {value:.7g} [{units[name]}]")
    for name, (low, high) in constraints.items():
        value = best.scalars.get(name, float("nan"))
        limit = f">= {low:g}" if low is not None else ""
        limit += (" and " if low is not None and high is not None else "") + (f"<= {high:g}" if high is not None else "")
        print(f"  constraint {name} = {value:.7g} ({limit})")
    print(f"  {best.message}")
    print(f"  wrote {len(best.files)} files to {args.out}")
    return 0 if best.feasible else 1
