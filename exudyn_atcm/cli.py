"""The command line ``exudyn-atcm`` (also ``python -m exudyn_atcm``).

::

    exudyn-atcm list                                   the cases, their description and parameters
    exudyn-atcm list --table md|rst                    the case table of the README (md) or the docs (rst)
    exudyn-atcm run CASE [--set NAME=VALUE ...] [--out DIR] [--no-plot]
    exudyn-atcm step-error CASE [--set NAME=VALUE ...] [--no-order-check] [--out DIR]
    exudyn-atcm sweep CASE --grid NAME=START:STOP:N [--grid NAME=A,B,C] [--samples N] [--workers N] [--out DIR]
    exudyn-atcm optimize CASE --objective NAME [--maximize] --bound NAME=LOW:HIGH [--constraint "NAME>=V"]
    exudyn-atcm bench [--quick] [--only ID ...] [--out DIR] [--update-references --reason TEXT]

Global options (before or after the command): ``--cases-dir DIR`` (where cases are looked
up by name first; the current directory's ``cases/`` is searched only when given here) and
``--debug`` (show tracebacks).  Exit status: 0 on success; 1 if a run
fails, a benchmark metric fails or ``list`` finds no case; 2 for a usage error (unknown case
or parameter, value of the wrong type, a parameter set twice, a ``--cases-dir`` that is not an
existing folder, missing ``--reason``); 130 on Ctrl-C and 143 on
``SIGTERM`` (a run writes what it computed until then, marked partial; a sweep says how many
runs are stored and the command that resumes it).  Errors are one line on stderr; a misspelt
case or parameter name is answered with the closest valid one.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path

# `--help` must not import numpy, Exudyn or the solve layers: the parser is built from light modules
# (case_table, command_options), and the faces `casework` and `study` load a name (`_cases.load_case`,
# `_study.command`) only when a command uses it (PEP 562, exudyn_atcm.lazy_names).
from . import casework as _cases
from . import study as _study
from .casework.case_table import TABLE_FORMATS
from .casework.error_report import report_error as _error
from .casework.termination import StopSignal, stop_signals_as_interrupt
from .study.command_options import add_optimize_parser, add_sweep_parser

__all__ = ["main", "build_parser"]


class _Parser(argparse.ArgumentParser):
    """Argument parser whose errors are one line (and exit status 2)."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(2, f"error: {message} (see {self.prog} --help)\n")


def _common(debug_default) -> argparse.ArgumentParser:
    parent = argparse.ArgumentParser(add_help=False)
    parent.add_argument("--debug", action="store_true", default=debug_default, help="show tracebacks of errors")
    parent.add_argument("--cases-dir", default=debug_default if debug_default is argparse.SUPPRESS else None, metavar="DIR", help="directory searched first for cases by name (the current directory is searched only when given: --cases-dir cases)")
    return parent


def build_parser() -> argparse.ArgumentParser:
    """The parser of ``exudyn-atcm``."""
    parser = _Parser(
        prog="exudyn-atcm",
        description="Multibody simulation of piezo-actuated textile-reinforced compliant mechanisms: cases and benchmarks.",
        parents=[_common(False)],
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub_common = _common(argparse.SUPPRESS)
    listing = sub.add_parser("list", help="list the cases with description and parameters", parents=[sub_common])
    listing.add_argument("--table", choices=TABLE_FORMATS, default=None,
                         help="print the case table instead (md: the README's, rst: the docs'), from the case files")
    run = sub.add_parser("run", help="run a case (a name or a path to a case file)", parents=[sub_common])
    run.add_argument("case", metavar="CASE", help="case name (see `list`) or path to a case file")
    run.add_argument("--set", action="append", default=[], metavar="NAME=VALUE", help="override a parameter (repeatable)")
    run.add_argument("--out", default="out", metavar="DIR", help="output directory (default: ./out)")
    run.add_argument("--no-plot", action="store_true", help="do not write the PNG plots")
    check = sub.add_parser("step-error", help="how much a case's key scalars depend on its time step (runs it at step, "
                           "step/2, step/4)", parents=[sub_common])
    check.add_argument("case", metavar="CASE", help="case name (see `list`) or path to a case file; it must have a "
                       "'step' parameter")
    check.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                       help="override a parameter (repeatable; --set step=... is the step examined)")
    check.add_argument("--no-order-check", action="store_true", help="two runs (step, step/2) instead of three")
    check.add_argument("--out", default=None, metavar="DIR", help="also write <case>_step_error.json there")
    bench = sub.add_parser("bench", help="run the regression benchmark suite", parents=[sub_common])
    bench.add_argument("--quick", action="store_true", help="only the quick benchmarks (< 2 min)")
    bench.add_argument("--out", default="out/bench", metavar="DIR", help="report directory (default: ./out/bench)")
    bench.add_argument("--suite", default=None, metavar="DIR", help="suite directory (default: benchmarks/regression of the checkout, or $EXUDYN_ATCM_BENCH)")
    bench.add_argument("--update-references", action="store_true", help="rewrite the stored references (needs --reason)")
    bench.add_argument("--reason", default=None, metavar="TEXT", help="why the references change (recorded)")
    bench.add_argument("--no-plots", action="store_true", help="skip the channel-against-reference plots")
    bench.add_argument("--only", nargs="+", default=None, metavar="ID", help="run only these benchmark ids (e.g. to update one reference)")
    add_sweep_parser(sub, [sub_common])  # options of sweep and optimize: exudyn_atcm.study.command_options
    add_optimize_parser(sub, [sub_common])
    return parser


def _study_command(args: argparse.Namespace) -> int:
    command = _study.command  # exudyn_atcm.study.command, imported here on first use
    return command.sweep_command(args) if args.command == "sweep" else command.optimize_command(args)


def _list(cases_dir: str | None, table: str | None = None) -> int:
    files = _cases.list_cases(cases_dir)
    if not files:
        dirs = ", ".join(str(d) for d in _cases.case_dirs(cases_dir)) or "none"
        return _error(f"no cases found (searched: {dirs}); pass --cases-dir DIR or set ${_cases.ENV_CASES}", False, 1)
    if table is not None:
        cases, failed = _cases.load_cases(cases_dir)
        if failed:
            return _error("; ".join(f"{path}: cannot be loaded: {message}" for path, message in failed), False, 1)
        print(_cases.case_table(cases, table))
        return 0
    for path in files:
        try:
            case = _cases.load_case(path)
        except _cases.CaseError as exc:
            print(f"{path.stem}\n    cannot be loaded: {exc}\n")
            continue
        print(f"{case.name}  ({path})")
        for other in _cases.case_files(path.stem, cases_dir)[1:]:
            print(f"    also {other} (not used: the first file of a name wins)")
        print(f"    {case.description}")
        for parameter in case.parameters:
            print(f"    --set {parameter.describe()}")
        if case.smoke:
            print("    smoke test: " + " ".join(f"--set {k}={v}" for k, v in case.smoke.items()))
        if case.benchmarks:
            print("    regression benchmarks: " + ", ".join(b["id"] for b in case.benchmarks))
        print()
    return 0


def _bench(args: argparse.Namespace) -> int:
    if args.update_references and not (args.reason and args.reason.strip()):
        return _error("--update-references needs --reason TEXT (why the references change; it is recorded)", args.debug, 2)
    if args.reason and not args.update_references:
        return _error("--reason is only used with --update-references", args.debug, 2)
    try:
        report = _cases.run_suite(
            args.suite,
            args.out,
            quick=args.quick,
            update=args.update_references,
            reason=args.reason,
            plots=not args.no_plots,
            only=args.only,
            echo=print,
            cases_dir=args.cases_dir,
        )
    except Exception as exc:  # noqa: BLE001 - one-line error
        return _error(exc, args.debug, 2 if isinstance(exc, ValueError) else 1)
    print()
    print(report.table())
    print(f"\nreport: {args.out}/report.md, {args.out}/report.json")
    if report.updated:
        print(f"references updated ({', '.join(report.updated)}): {args.reason}")
    return 0 if report.passed else 1


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``exudyn-atcm``; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)  # to print the command that resumes a sweep
    debug = bool(getattr(args, "debug", False))
    if args.command is None:
        parser.print_help()
        return 2
    stop = StopSignal()
    try:
        with stop_signals_as_interrupt() as stop, warnings.catch_warnings():
            warnings.showwarning = _one_line_warning
            return _dispatch(args, debug)
    except KeyboardInterrupt:
        return _error("interrupted" if stop.signum is None else stop.describe(), debug, stop.exit_status)
    except BrokenPipeError:  # output piped into e.g. `head`: stop quietly
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    except Exception as exc:  # noqa: BLE001 - last resort: still one line
        return _error(exc, debug, 1)


def _one_line_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """Warnings of the command line as one line ``warning: ...`` on stderr (no source line)."""
    print(f"warning: {' '.join(str(message).split())}", file=sys.stderr)


def _dispatch(args: argparse.Namespace, debug: bool) -> int:
    """Run the command of ``args``; its exit status."""
    cases_dir = getattr(args, "cases_dir", None)
    if cases_dir is not None and not Path(cases_dir).is_dir():
        what = "is a file, not a folder" if Path(cases_dir).exists() else "does not exist"
        return _error(f"--cases-dir {cases_dir}: {what} (resolved: {Path(cases_dir).resolve()}); give an "
                      f"existing folder of case files", debug, 2)
    if args.command == "list":
        return _list(args.cases_dir, args.table)
    if args.command == "run":
        try:
            case = _cases.load_case(args.case, args.cases_dir)
        except _cases.CaseError as exc:
            return _error(exc, debug, 2)
        return _cases.run_and_report(case, args.set, args.out, not args.no_plot, debug)
    if args.command in ("sweep", "optimize"):
        return _study_command(args)
    if args.command == "step-error":
        return _step_error(args, debug)
    return _bench(args)


def _step_error(args: argparse.Namespace, debug: bool) -> int:
    try:
        case = _cases.load_case(args.case, args.cases_dir)
        step_check = _cases.step_check  # exudyn_atcm.casework.step_check, imported here on first use
        step, rows = step_check.case_step_error(case, args.set, check_order=not args.no_order_check)
    except _cases.CaseError as exc:
        return _error(exc, debug, 2)
    print(step_check.format_step_errors(case.name, step, rows))
    if args.out is not None:
        path = Path(args.out) / f"{case.name}_step_error.json"
        path.parent.mkdir(parents=True, exist_ok=True)
        step_check.write_step_errors(path, case.name, step, rows)
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
