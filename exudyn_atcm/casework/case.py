"""Case scripts: declared parameters, one run function, standard outputs.

A *case* is a plain Python file (in ``cases/`` of the source checkout, or anywhere) that
declares its parameters and builds and runs one scenario with the public API.  The file
runs on its own (``python cases/my_case.py --set period=2``) and through the command line
(``exudyn-atcm run my_case --set period=2``), with the same options, and writes the same
files::

    DIR/<case>.csv          the main Result (time series), `#` metadata lines, `name [unit]` header
    DIR/<case>_<table>.csv  further tables, if the case returns any
    DIR/<case>.json         parameters, versions, platform, wall time, steps, key scalars, files
    DIR/<case>_*.png        the plots (unless --no-plot)

The convention, in full (see ``cases/paper_stroke_table.py`` for a short example)::

    \"\"\"One-line description shown by `exudyn-atcm list`.

    Longer explanation (what the case reproduces, which figure of the paper).
    \"\"\"
    from exudyn_atcm.casework.case import Case, CaseOutput, Parameter

    PARAMETERS = [
        Parameter("period", 1.0, "s", "period T of the triangle input"),
        Parameter("n_points", 21, "-", "table points per period"),
        Parameter("exponents", "rounded", "-", "paper exponents", choices=("rounded", "exact")),
    ]

    def run(p, ctx):
        # p.period, p["n_points"], ...: typed values; ctx.progress(t, t_end) for long runs
        ...
        return CaseOutput(result, scalars={"peak_stroke": (40e-6, "m")}, steps=len(t))

    def plot(output, p, out_dir):          # optional; returns the PNG paths written
        ...

    CASE = Case("paper_stroke_table", __doc__, PARAMETERS, run, plot)

    if __name__ == "__main__":
        raise SystemExit(CASE.main())

Cases are found (:func:`find_case`) by path, or by name in, in this order: the directory
given with ``--cases-dir``, the directories in the environment variable
``EXUDYN_ATCM_CASES`` (``os.pathsep``-separated), the ``cases/`` folder of the source
checkout beside the package, and the example cases installed with the package
(``exudyn_atcm.example_cases``, built from ``cases/``), so that ``exudyn-atcm list`` works
from any directory of any installation.  The current directory is searched only when asked
(``--cases-dir cases``, or a path such as ``cases/my_case.py``): running the command line
inside someone else's unpacked archive does not execute its files.  A name found in two
different files is taken from the first and a ``RuntimeWarning`` names both
(:func:`case_files`).

Ctrl-C during a run stops the simulation cleanly: what was computed so far is written (the
CSV and JSON marked ``partial``), the message says ``interrupted at t = ... s``, and the exit
status is 130.  ``SIGTERM`` (``timeout``, batch schedulers, ``docker stop``) and ``SIGHUP`` are
handled the same way (:mod:`exudyn_atcm.casework.termination`): ``stopped by SIGTERM at t = ... s``,
exit status 143 (129 for ``SIGHUP``).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import difflib
import importlib.util
import math
import os
import platform
import sys
import time
import traceback
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..io.atomic import make_directory, write_json
from .._version import __version__
from ..io.progress import ProgressBar, ProgressCallback, no_progress, reporting
from ..io.result import Result
from ..solve.run_checks import SimulationInterrupted
from .termination import StopSignal, stop_signals_as_interrupt

__all__ = [
    "Parameter",
    "Parameters",
    "Case",
    "CaseOutput",
    "RunContext",
    "CaseError",
    "case_dirs",
    "find_case",
    "case_files",
    "list_cases",
    "load_case",
    "versions",
    "ENV_CASES",
]

#: Environment variable with extra case directories (``os.pathsep``-separated).
ENV_CASES = "EXUDYN_ATCM_CASES"

_TYPES = ("float", "int", "bool", "str", "floats")
_TRUE = {"true", "yes", "on", "1"}
_FALSE = {"false", "no", "off", "0"}


class CaseError(ValueError):
    """A case could not be found, loaded or configured (message is one line)."""


def closest(name: str, candidates: Sequence[str]) -> str:
    """`` (did you mean 'x'?)`` for the candidate closest to a misspelt ``name``, else ``""``."""
    match = difflib.get_close_matches(name, list(candidates), n=1, cutoff=0.6)
    if not match:
        lowered = {c.lower(): c for c in candidates}
        match = [lowered[name.lower()]] if name.lower() in lowered else []
    return f" (did you mean {match[0]!r}?)" if match else ""


# ----------------------------------------------------------------------------- parameters
def _infer_type(default: Any) -> str:
    if isinstance(default, bool):
        return "bool"
    if isinstance(default, int):
        return "int"
    if isinstance(default, float):
        return "float"
    if isinstance(default, str):
        return "str"
    if isinstance(default, (tuple, list)) and all(
        isinstance(v, (int, float)) and not isinstance(v, bool) for v in default
    ):
        return "floats"
    raise ValueError(
        f"default must be a float, int, bool, str or tuple of floats, got {default!r} "
        f"of type {type(default).__name__}"
    )


@dataclass(frozen=True)
class Parameter:
    """One declared parameter of a case.

    Parameters
    ----------
    name : str
        Identifier used in ``--set NAME=VALUE`` and as ``p.name`` in the run function.
    default : float, int, bool, str or tuple of float
        Default value; its Python type fixes the parameter's type (``1.0`` is a float,
        ``1`` an int, a tuple of numbers is a comma-separated list of floats).  A list
        parameter whose default is the empty tuple ``()`` also accepts an empty value
        (``--set NAME=`` or ``()``), which then means the same as its default (the help
        text says what, e.g. "empty: from the reference design"); any other list parameter
        needs at least one number.
    unit : str
        SI unit of the value (``"-"`` if unit-free).
    help : str
        One-line description.
    choices : tuple, optional
        Allowed values (for ``str`` parameters, typically).
    """

    name: str
    default: Any
    unit: str = "-"
    help: str = ""
    choices: tuple | None = None
    kind: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise ValueError(f"name must be a Python identifier, got {self.name!r}")
        object.__setattr__(self, "kind", _infer_type(self.default))
        if self.kind == "floats":
            object.__setattr__(self, "default", tuple(float(v) for v in self.default))
        if self.choices is not None:
            object.__setattr__(self, "choices", tuple(self.choices))
            if self.default not in self.choices:
                raise ValueError(f"default of {self.name!r} must be one of {self.choices}, got {self.default!r}")

    def describe(self) -> str:
        """``name = default [unit] (type): help``."""
        default = ",".join(repr(v) for v in self.default) if self.kind == "floats" else repr(self.default)
        choices = f", one of {'/'.join(map(str, self.choices))}" if self.choices else ""
        return f"{self.name} = {default} [{self.unit}] ({self.kind}{choices}): {self.help}"

    def parse(self, text: str) -> Any:
        """Convert the text of ``--set NAME=TEXT`` to the parameter's type.

        Raises
        ------
        ValueError
            If the text is not a value of the parameter's type (or not one of the choices).
        """
        raw = text.strip()
        try:
            if self.kind == "float":
                value: Any = float(raw)
            elif self.kind == "int":
                value = int(raw)
            elif self.kind == "bool":
                low = raw.lower()
                if low not in _TRUE | _FALSE:
                    raise ValueError
                value = low in _TRUE
            elif self.kind == "floats":
                value = tuple(float(v) for v in raw.split(",") if v.strip() != "")
                if not value and not self._empty_allowed():
                    raise ValueError
            else:
                value = text
        except ValueError:
            raise ValueError(f"{self.name} must be {self._kind_text()}, got {text!r}") from None
        return self.check(value)

    def check(self, value: Any) -> Any:
        """Check a Python value for this parameter and return it (ints accepted for floats)."""
        ok = True
        if self.kind == "float":
            ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
            value = float(value) if ok else value
        elif self.kind == "int":
            ok = isinstance(value, int) and not isinstance(value, bool)
        elif self.kind == "bool":
            ok = isinstance(value, bool)
        elif self.kind == "str":
            ok = isinstance(value, str)
        elif self.kind == "floats":
            try:
                value = tuple(float(v) for v in value)
                ok = all(math.isfinite(v) for v in value) and (len(value) > 0 or self._empty_allowed())
            except (TypeError, ValueError):
                ok = False
        if not ok:
            raise ValueError(f"{self.name} must be {self._kind_text()}, got {value!r}")
        if self.choices is not None and value not in self.choices:
            raise ValueError(f"{self.name} must be one of {', '.join(map(str, self.choices))}, got {value!r}")
        return value

    def _empty_allowed(self) -> bool:
        return self.kind == "floats" and len(self.default) == 0

    def _kind_text(self) -> str:
        if self._empty_allowed():
            return f"comma-separated finite real numbers [{self.unit}], or empty"
        return {
            "float": f"a finite real number [{self.unit}]",
            "int": "an integer",
            "bool": "true or false",
            "str": "a string",
            "floats": f"comma-separated finite real numbers [{self.unit}]",
        }[self.kind]


class Parameters(Mapping):
    """The resolved, typed parameter values of one run: ``p.name`` or ``p["name"]``."""

    def __init__(self, declared: Sequence[Parameter], values: Mapping[str, Any]) -> None:
        self._declared = {d.name: d for d in declared}
        self._values = dict(values)

    def __getitem__(self, name: str) -> Any:
        return self._values[name]

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self._values[name]
        except KeyError:
            raise AttributeError(f"no parameter {name!r}; declared: {', '.join(self._values)}") from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def unit(self, name: str) -> str:
        """Unit of parameter ``name``."""
        return self._declared[name].unit

    def with_units(self) -> dict[str, Any]:
        """``{"name [unit]": value}``, as written into CSV metadata."""
        return {f"{n} [{self._declared[n].unit}]": _plain(v) for n, v in self._values.items()}

    def __repr__(self) -> str:
        return "Parameters(" + ", ".join(f"{k}={v!r}" for k, v in self._values.items()) + ")"


def _plain(value: Any) -> Any:
    return list(value) if isinstance(value, tuple) else value


# ----------------------------------------------------------------------------- outputs
@dataclass
class RunContext:
    """What the runner gives a case's ``run`` function besides the parameters.

    Attributes
    ----------
    case : str
        Case name.
    out_dir : pathlib.Path or None
        Output directory (``None`` when the run writes no files).
    plot : bool
        Whether plots will be written (a case may skip plot-only work otherwise).
    progress : callable
        ``progress(t, t_end)``: report simulated time [s]; draws a bar on terminals.
    """

    case: str
    out_dir: Path | None = None
    plot: bool = True
    progress: ProgressCallback = no_progress


@dataclass
class CaseOutput:
    """What a case's ``run`` function returns; the runner fills in the rest.

    Parameters
    ----------
    result : Result
        The main time series (written as ``<case>.csv``).
    scalars : mapping of str to float or (float, str)
        Key scalar results, each a value in SI units or a ``(value, unit)`` pair.
    steps : int, optional
        Number of time steps or recorded instants (default: the rows of ``result``).
    tables : mapping of str to Result, optional
        Further tables, written as ``<case>_<name>.csv``.
    notes : mapping, optional
        Extra JSON-serialisable information written into ``<case>.json``.

    Attributes
    ----------
    case : str
        Case name (set by the runner).
    parameters : Parameters
        The parameters of the run (set by the runner).
    wall_time : float
        Wall time of ``run`` [s] (set by the runner; plotting excluded).
    files : list of pathlib.Path
        Files written (set by the runner).
    """

    result: Result
    scalars: Mapping[str, Any] = field(default_factory=dict)
    steps: int | None = None
    tables: Mapping[str, Result] = field(default_factory=dict)
    notes: Mapping[str, Any] = field(default_factory=dict)
    case: str = ""
    parameters: Parameters | None = None
    wall_time: float = float("nan")
    plot_time: float = 0.0
    files: list[Path] = field(default_factory=list)
    scalar_units: dict[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.result, Result):
            raise ValueError(f"result must be an exudyn_atcm Result, got {type(self.result).__name__}")
        values: dict[str, float] = {}
        units = dict(self.scalar_units)
        for name, item in dict(self.scalars).items():
            if isinstance(item, tuple):
                value, unit = item
                units[name] = str(unit)
            else:
                value = item
                units.setdefault(name, "-")
            values[name] = float(value)
        self.scalars = values
        self.scalar_units = units
        if self.steps is None:
            self.steps = self.result.n_rows
        for name, table in dict(self.tables).items():
            if not isinstance(table, Result):
                raise ValueError(f"tables[{name!r}] must be an exudyn_atcm Result, got {type(table).__name__}")

    def scalar(self, name: str) -> float:
        """Value of key scalar ``name`` (SI units)."""
        return self.scalars[name]

    def to_dict(self) -> dict[str, Any]:
        """The JSON record of the run (``<case>.json``)."""
        params = self.parameters or Parameters([], {})
        return {
            "case": self.case,
            "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
            "parameters": {n: {"value": _plain(params[n]), "unit": params.unit(n)} for n in params},
            "scalars": {n: {"value": v, "unit": self.scalar_units[n]} for n, v in self.scalars.items()},
            "steps": self.steps,
            "wall_time [s]": self.wall_time,
            "plot_time [s]": self.plot_time,
            "series": [{"name": n, "unit": self.result.unit(n)} for n in self.result.names],
            "versions": versions(),
            "platform": platform.platform(),
            "notes": dict(self.notes),
            "files": [p.name for p in self.files],
        }


def versions() -> dict[str, str]:
    """Versions of this package, Exudyn, Python and NumPy."""
    import numpy

    try:
        from ..mbs.solver_runs import exudyn_version

        exu = exudyn_version()
    except Exception:  # pragma: no cover - exudyn is a dependency
        exu = "unavailable"
    return {
        "exudyn_atcm": __version__,
        "exudyn": exu,
        "python": platform.python_version(),
        "numpy": numpy.__version__,
    }


# ----------------------------------------------------------------------------- the case
RunFunction = Callable[[Parameters, RunContext], CaseOutput]
PlotFunction = Callable[[CaseOutput, Parameters, Path], Sequence[Path]]


class Case:
    """A declared case: name, description, parameters, run and plot functions.

    Parameters
    ----------
    name : str
        Case name; also the stem of the output files.  Conventionally the file name.
    description : str
        The module docstring; its first line is the one-line description.
    parameters : sequence of Parameter
        Declared parameters (unique names).
    run : callable
        ``run(p, ctx) -> CaseOutput`` with ``p`` the typed :class:`Parameters` and ``ctx`` a
        :class:`RunContext`.
    plot : callable, optional
        ``plot(output, p, out_dir) -> list of paths`` writing PNG files.
    """

    def __init__(
        self,
        name: str,
        description: str | None,
        parameters: Sequence[Parameter],
        run: RunFunction,
        plot: PlotFunction | None = None,
    ) -> None:
        if not isinstance(name, str) or not name or any(c in name for c in "/\\ "):
            raise ValueError(f"name must be a non-empty name without spaces or slashes, got {name!r}")
        names = [p.name for p in parameters]
        duplicates = sorted({n for n in names if names.count(n) > 1})
        if duplicates:
            raise ValueError(f"parameters: duplicate names {duplicates}")
        if not callable(run):
            raise ValueError(f"run must be callable, got {run!r}")
        self.name = name
        self.doc = (description or "").strip()
        self.description = self.doc.split("\n\n")[0].replace("\n", " ").strip()
        self.parameters: tuple[Parameter, ...] = tuple(parameters)
        self._run = run
        self._plot = plot
        caller = sys._getframe(1).f_globals.get("__file__")
        self.source: Path | None = Path(caller).resolve() if caller else None

    def __repr__(self) -> str:
        return f"Case({self.name!r}, {len(self.parameters)} parameters)"

    # -- parameters --------------------------------------------------------------------
    def parameter_list(self) -> str:
        """The valid parameters on one line, for error messages."""
        return "; ".join(p.describe().split(":")[0] for p in self.parameters) or "(none)"

    def parse_assignments(self, assignments: Sequence[str]) -> dict[str, Any]:
        """Parse ``NAME=VALUE`` strings (from ``--set``) into typed values.

        Raises
        ------
        CaseError
            For a malformed assignment, an unknown name or a value of the wrong type; the
            message lists the valid parameters.
        """
        values: dict[str, Any] = {}
        declared = {p.name: p for p in self.parameters}
        for text in assignments:
            name, sep, value = text.partition("=")
            name = name.strip()
            if not sep or not name:
                raise CaseError(f"--set expects NAME=VALUE, got {text!r}; valid parameters of {self.name}: {self.parameter_list()}")
            if name not in declared:
                raise CaseError(f"unknown parameter {name!r} for case {self.name}{closest(name, list(declared))}; "
                                f"valid parameters: {self.parameter_list()}")
            try:
                values[name] = declared[name].parse(value)
            except ValueError as exc:
                raise CaseError(f"case {self.name}: {exc}; valid parameters: {self.parameter_list()}") from None
        return values

    def resolve(self, values: Mapping[str, Any] | Sequence[str] | None = None) -> Parameters:
        """Typed parameters: the defaults updated by ``values``.

        Parameters
        ----------
        values : mapping or sequence of str, optional
            Python values by name, or ``NAME=VALUE`` strings.

        Raises
        ------
        CaseError
            For an unknown name or a value of the wrong type.
        """
        if values is None:
            given: dict[str, Any] = {}
        elif isinstance(values, Mapping):
            given = {}
            declared = {p.name: p for p in self.parameters}
            for name, value in values.items():
                if name not in declared:
                    raise CaseError(f"unknown parameter {name!r} for case {self.name}{closest(name, list(declared))}; "
                                    f"valid parameters: {self.parameter_list()}")
                try:
                    given[name] = declared[name].parse(value) if isinstance(value, str) and declared[name].kind != "str" else declared[name].check(value)
                except ValueError as exc:
                    raise CaseError(f"case {self.name}: {exc}; valid parameters: {self.parameter_list()}") from None
        else:
            given = self.parse_assignments(list(values))
        return Parameters(self.parameters, {p.name: given.get(p.name, p.default) for p in self.parameters})

    # -- running -------------------------------------------------------------------------
    def run(
        self,
        values: Mapping[str, Any] | Sequence[str] | None = None,
        *,
        out_dir: str | os.PathLike | None = None,
        plot: bool = True,
        progress: ProgressCallback | None = None,
    ) -> CaseOutput:
        """Run the case and, with ``out_dir``, write its CSV, JSON and PNG files.

        Parameters
        ----------
        values : mapping or sequence of str, optional
            Parameter overrides (see :meth:`resolve`).
        out_dir : str or os.PathLike, optional
            Output directory, created if missing; ``None`` writes nothing.
        plot : bool
            Write the plots (only with ``out_dir``).
        progress : callable, optional
            ``progress(t, t_end)`` handed to the case as ``ctx.progress``.

        Returns
        -------
        CaseOutput
            With ``case``, ``parameters``, ``wall_time`` and ``files`` filled in.
        """
        params = self.resolve(values)
        directory = Path(out_dir) if out_dir is not None else None
        if directory is not None:
            make_directory(directory)
        ctx = RunContext(self.name, directory, bool(plot and directory is not None), progress or no_progress)
        start = time.perf_counter()
        with reporting(ctx.progress):
            try:
                output = self._run(params, ctx)
            except SimulationInterrupted as exc:
                self._write_partial(exc, params, directory, time.perf_counter() - start)
                raise
            wall = time.perf_counter() - start
            if not isinstance(output, CaseOutput):
                raise CaseError(f"case {self.name}: run() must return a CaseOutput, got {type(output).__name__}")
            output.case = self.name
            output.parameters = params
            output.wall_time = wall
            if directory is not None:
                self._write(output, params, directory, ctx.plot)
        return output

    def _write_partial(self, exc: SimulationInterrupted, params: Parameters, directory: Path | None, wall: float) -> None:
        """Write what an interrupted run computed (CSV and JSON, marked partial); ``exc.files`` lists them."""
        exc.files = []
        if directory is None or exc.result is None:
            return
        partial = CaseOutput(exc.result, notes={"partial": True, "interrupted_at [s]": exc.time})
        partial.case = self.name
        partial.parameters = params
        partial.wall_time = wall
        self._write(partial, params, directory, plot=False)
        exc.files = list(partial.files)

    def _write(self, output: CaseOutput, params: Parameters, directory: Path, plot: bool) -> None:
        vers = versions()
        metadata = {"case": self.name, **params.with_units()}
        info = {
            **output.result.info,
            "exudyn_version": vers["exudyn"],
            "wall_time [s]": round(output.wall_time, 6),
            "steps": output.steps,
        }
        main = Result(output.result, output.result.units, parameters={**metadata, **output.result.parameters}, info=info)
        path = directory / f"{self.name}.csv"
        main.to_csv(path)
        files = [path]
        for name, table in output.tables.items():
            tpath = directory / f"{self.name}_{name}.csv"
            Result(table, table.units, parameters={**metadata, **table.parameters}, info={"exudyn_version": vers["exudyn"], **table.info}).to_csv(tpath)
            files.append(tpath)
        if plot and self._plot is not None:
            start = time.perf_counter()
            written = self._plot(output, params, directory) or []
            output.plot_time = time.perf_counter() - start
            files.extend(Path(p) for p in written)
        output.files = files
        json_path = directory / f"{self.name}.json"
        output.files = files + [json_path]
        write_json(json_path, {"description": self.description, "source": str(self.source or ""), **output.to_dict()})

    # -- standalone entry point -------------------------------------------------------------
    def argument_parser(self, prog: str | None = None) -> argparse.ArgumentParser:
        """The parser of ``python cases/<name>.py`` (same options as ``exudyn-atcm run``)."""
        epilog = "parameters:\n" + "\n".join(f"  {p.describe()}" for p in self.parameters)
        parser = argparse.ArgumentParser(
            prog=prog or f"python {self.source.name if self.source else self.name + '.py'}",
            description=self.description,
            epilog=epilog,
            formatter_class=argparse.RawDescriptionHelpFormatter,
        )
        add_run_options(parser)
        return parser

    def main(self, argv: Sequence[str] | None = None) -> int:
        """Run from the command line: ``--set NAME=VALUE``, ``--out DIR``, ``--no-plot``, ``--debug``.

        Returns the exit status: 0 on success, 2 for bad parameters, 1 if the run fails.
        """
        parser = self.argument_parser()
        args = parser.parse_args(argv)
        return run_and_report(self, args.set, args.out, not args.no_plot, args.debug)


def add_run_options(parser: argparse.ArgumentParser) -> None:
    """The options shared by ``python cases/x.py`` and ``exudyn-atcm run``."""
    parser.add_argument(
        "--set", action="append", default=[], metavar="NAME=VALUE", help="override a parameter (repeatable)"
    )
    parser.add_argument("--out", default="out", metavar="DIR", help="output directory (default: ./out)")
    parser.add_argument("--no-plot", action="store_true", help="do not write the PNG plots")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")


def run_and_report(case: Case, assignments: Sequence[str], out: str, plot: bool, debug: bool) -> int:
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


def _interrupted(case: Case, exc: KeyboardInterrupt, out: str, debug: bool, stop: StopSignal) -> int:
    """Report Ctrl-C or a stop signal: where the simulation stopped and what was written.

    Exit status 130 for Ctrl-C, ``128 + signal number`` for a stop signal (143 for SIGTERM).
    """
    how = "interrupted" if stop.signum is None else f"stopped by {stop.name}"
    if isinstance(exc, SimulationInterrupted):
        files = getattr(exc, "files", [])
        rows = exc.result.n_rows if exc.result is not None else 0
        if files:
            written = f"; wrote the {rows} recorded instants up to there (marked partial) to {files[0]}"
        else:
            written = "; nothing was written (no output directory, or nothing computed yet)"
        return _fail(f"{case.name}: {how} at t = {exc.time:.6g} s{written}", debug, stop.exit_status)
    return _fail(f"{case.name}: {stop.describe()} before the simulation started or after it ended; "
                 "files may be missing", debug, stop.exit_status)


def _fail(exc: BaseException | str, debug: bool, status: int) -> int:
    if debug and isinstance(exc, BaseException):
        traceback.print_exception(type(exc), exc, exc.__traceback__)
    message = " ".join(str(exc).split()) or type(exc).__name__
    print(f"error: {message}", file=sys.stderr)
    return status


# ----------------------------------------------------------------------------- discovery
def case_dirs(cases_dir: str | os.PathLike | None = None) -> list[Path]:
    """Directories searched for cases by name, in order (existing ones only).

    ``cases_dir`` (``--cases-dir``), then ``$EXUDYN_ATCM_CASES`` (``os.pathsep``-separated),
    then the ``cases/`` folder of the source checkout beside the package (only if it is this
    package's checkout), then the example cases installed with the package
    (``exudyn_atcm.example_cases``).  Not the current directory's ``cases/`` unless given.
    """
    candidates: list[Path] = []
    if cases_dir is not None:
        candidates.append(Path(cases_dir))
    env = os.environ.get(ENV_CASES, "")
    candidates.extend(Path(p) for p in env.split(os.pathsep) if p.strip())
    checkout = _checkout_cases_dir()
    if checkout is not None:
        candidates.append(checkout)
    installed = _installed_cases_dir()
    if installed is not None:
        candidates.append(installed)
    seen: list[Path] = []
    for path in candidates:
        resolved = path.resolve()
        if resolved.is_dir() and resolved not in seen:
            seen.append(resolved)
    return seen


def _checkout_cases_dir() -> Path | None:
    """``cases/`` beside the package if the package sits in its source checkout (not site-packages)."""
    root = Path(__file__).resolve().parents[2]
    try:
        setup = (root / "setup.cfg").read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    return root / "cases" if "name = exudyn-atcm" in setup else None


def _installed_cases_dir() -> Path | None:
    """Directory of the installed package ``exudyn_atcm.example_cases`` (``cases/`` shipped with the package)."""
    try:
        spec = importlib.util.find_spec("exudyn_atcm.example_cases")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    return Path(list(spec.submodule_search_locations)[0])


def list_cases(cases_dir: str | os.PathLike | None = None) -> list[Path]:
    """Case files found by name: ``*.py`` not starting with ``_``; the first of a name wins."""
    found: dict[str, Path] = {}
    for directory in case_dirs(cases_dir):
        for path in sorted(directory.glob("*.py")):
            if not path.name.startswith("_") and path.stem not in found:
                found[path.stem] = path
    return [found[name] for name in sorted(found)]


def find_case(spec: str | os.PathLike, cases_dir: str | os.PathLike | None = None) -> Path:
    """The file of a case given by path or by name.

    Raises
    ------
    CaseError
        If no such file or name exists; the message lists the cases found.
    """
    text = os.fspath(spec)
    path = Path(text)
    if text.endswith(".py") or os.sep in text or (os.altsep and os.altsep in text):
        if path.is_file():
            return path.resolve()
        raise CaseError(f"case file {text!r} does not exist")
    found = case_files(text, cases_dir)
    if found:
        if len(found) > 1:
            warnings.warn(
                f"case {text!r} is found in {len(found)} different files: using {found[0]} (the first in the search "
                f"order --cases-dir, ${ENV_CASES}, the package's cases); not using {', '.join(str(f) for f in found[1:])}",
                RuntimeWarning, stacklevel=3,
            )
        return found[0]
    stems = [p.stem for p in list_cases(cases_dir)]
    names = ", ".join(stems) or "none"
    dirs = ", ".join(str(d) for d in case_dirs(cases_dir)) or "none"
    raise CaseError(f"no case named {text!r}{closest(text, stems)}; available: {names} (searched {dirs})"
                    + _local_hint(text))


def _local_hint(name: str) -> str:
    """A note if ``./cases/<name>.py`` exists: the current directory is searched only when asked."""
    local = Path("cases") / f"{name}.py"
    if not local.is_file():
        return ""
    return (f"; {local} exists here, but the current directory is searched only when asked: "
            f"give --cases-dir cases or the path {local}")


def case_files(name: str, cases_dir: str | os.PathLike | None = None) -> list[Path]:
    """Every file that defines case ``name`` in the search order of :func:`case_dirs`, the one used first.

    Files with the same content (the checkout's case and its installed copy) count once.
    """
    files: list[Path] = []
    if name.startswith("_"):
        return files
    contents: list[bytes] = []
    for directory in case_dirs(cases_dir):
        path = directory / f"{name}.py"
        if not path.is_file():
            continue
        try:
            content = path.read_bytes()
        except OSError:
            content = b""
        if content not in contents:
            files.append(path)
            contents.append(content)
    return files


def load_case(spec: str | os.PathLike, cases_dir: str | os.PathLike | None = None) -> Case:
    """Import a case file (by path or name) and return its ``CASE``.

    A file that does not mention ``CASE`` and ``exudyn_atcm.casework.case`` is refused without being
    executed (a plain script may run a whole simulation when imported).

    Raises
    ------
    CaseError
        If the file is missing, fails to import, or defines no ``CASE``.
    """
    path = find_case(spec, cases_dir)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise CaseError(f"{path}: cannot be read: {exc}") from None
    if "CASE" not in text or "exudyn_atcm.casework.case" not in text:
        # not executed: a plain script might run a whole simulation on import
        raise CaseError(f"{path}: does not follow the case convention (no CASE = exudyn_atcm.casework.case.Case(...))")
    module_name = f"exudyn_atcm_case_{path.stem}"
    spec_ = importlib.util.spec_from_file_location(module_name, path)
    if spec_ is None or spec_.loader is None:  # pragma: no cover
        raise CaseError(f"{path}: cannot be imported")
    module = importlib.util.module_from_spec(spec_)
    try:
        spec_.loader.exec_module(module)
    except Exception as exc:  # noqa: BLE001
        message = " ".join(str(exc).split())
        raise CaseError(f"{path}: import failed: {type(exc).__name__}: {message}") from exc
    case = getattr(module, "CASE", None)
    if not isinstance(case, Case):
        raise CaseError(f"{path}: defines no CASE = exudyn_atcm.casework.case.Case(...)")
    case.source = path
    return case
