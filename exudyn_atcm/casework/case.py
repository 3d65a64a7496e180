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
    DIR/<case>.partial.json only while a run is unfinished, or after one was interrupted: why

The convention, in full (see ``cases/paper_stroke_table.py`` for a short example)::

    \"\"\"One-line description shown by `exudyn-atcm list`.

    Longer explanation (what the case reproduces, which figure of the paper).
    \"\"\"
    from exudyn_atcm.casework import Case, CaseOutput, Parameter

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

Cases are found (:func:`~exudyn_atcm.casework.discovery.find_case`) by path, or by name in, in this order: the directory
given with ``--cases-dir``, the directories in the environment variable
``EXUDYN_ATCM_CASES`` (``os.pathsep``-separated), the ``cases/`` folder of the source
checkout beside the package, and the example cases installed with the package
(``exudyn_atcm.example_cases``, built from ``cases/``), so that ``exudyn-atcm list`` works
from any directory of any installation.  The current directory is searched only when asked
(``--cases-dir cases``, or a path such as ``cases/my_case.py``): running the command line
inside someone else's unpacked archive does not execute its files.  A name found in two
different files is taken from the first and a warning (:class:`~exudyn_atcm.errors.SetupWarning`) names both
(:func:`~exudyn_atcm.casework.discovery.case_files`).

A folder never mixes the files of two runs (:mod:`exudyn_atcm.casework.output_folder`): the
previous run's own files (those its JSON lists) are removed before the first new file is
written, the JSON comes before the plots, and a run that does not finish leaves the marker
``DIR/<case>.partial.json`` saying why; files the case did not write are never touched.

Ctrl-C during a run stops the simulation cleanly: what was computed so far is written (the
CSV and JSON marked ``partial``, with the marker), the message says ``interrupted at t = ... s``,
and the exit status is 130.  ``SIGTERM`` (``timeout``, batch schedulers, ``docker stop``) and ``SIGHUP`` are
handled the same way (:mod:`exudyn_atcm.casework.termination`): ``stopped by SIGTERM at t = ... s``,
exit status 143 (129 for ``SIGHUP``).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from ..io.atomic import make_directory, write_json
from ..io.progress import ProgressCallback, no_progress, reporting
from ..io.result import Result
from ..solve.run_checks import SimulationInterrupted
from .declarations import declared_benchmarks, declared_order, declared_smoke
from .output_folder import OutputFolder, describe_stop
from .outputs import CaseOutput, RunContext, versions
from .parameters import CaseError, Parameter, Parameters, closest
from .run_command import add_run_options, run_and_report
from .run_warnings import warnings_once

__all__ = ["Case", "RunFunction", "PlotFunction", "add_run_options", "run_and_report"]  # the last two: .run_command


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
    smoke : mapping, optional
        The cheap parameter values a smoke test runs the case with (``None``: the defaults).
    benchmarks : sequence of mapping, optional
        The case's regression benchmarks, each a ``suite.json`` entry without ``"case"``.
    summary : str, optional
        The case's row in the case tables: what it shows (and its reference).
    table_order : float, optional
        The row's position in the case tables (``None``: after the ordered rows, by name).  The
        four declarations are described in :mod:`exudyn_atcm.casework.declarations`.

    Raises
    ------
    ValueError
        For a bad name, duplicate parameters, or a smoke setting, benchmark or order the case refuses.
    """

    def __init__(
        self,
        name: str,
        description: str | None,
        parameters: Sequence[Parameter],
        run: RunFunction,
        plot: PlotFunction | None = None,
        *,
        smoke: Mapping[str, Any] | None = None,
        benchmarks: Sequence[Mapping[str, Any]] | None = None,
        summary: str | None = None,
        table_order: float | None = None,
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
        self.smoke: dict[str, Any] = declared_smoke(name, smoke, self.resolve)
        self.benchmarks: tuple[dict[str, Any], ...] = declared_benchmarks(name, benchmarks, self.resolve)
        self.summary: str = " ".join((summary or self.description).split())
        self.table_order: float = declared_order(name, table_order)
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
            For a malformed assignment, an unknown name, a name given twice (``--set period=1 --set
            period=3`` would otherwise silently use one of them) or a value of the wrong type; the
            message lists the valid parameters.
        """
        values: dict[str, Any] = {}
        texts: dict[str, str] = {}
        declared = {p.name: p for p in self.parameters}
        for text in assignments:
            name, sep, value = text.partition("=")
            name = name.strip()
            if not sep or not name:
                raise CaseError(f"--set expects NAME=VALUE, got {text!r}; valid parameters of {self.name}: {self.parameter_list()}")
            if name not in declared:
                raise CaseError(f"unknown parameter {name!r} for case {self.name}{closest(name, list(declared))}; "
                                f"valid parameters: {self.parameter_list()}")
            if name in texts:
                raise CaseError(f"case {self.name}: parameter {name!r} is given twice (--set {texts[name]} and "
                                f"--set {text}); give each parameter once")
            texts[name] = text
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

        Warns
        -----
        AtcmWarning
            Each distinct warning of the run (same category and text) is shown once, however
            often the case's solves issue it (:func:`~exudyn_atcm.casework.run_warnings.warnings_once`).
        """
        params = self.resolve(values)
        directory = Path(out_dir) if out_dir is not None else None
        folder = None
        if directory is not None:
            make_directory(directory)
            folder = OutputFolder(directory, self.name)
        ctx = RunContext(self.name, directory, bool(plot and directory is not None), progress or no_progress, folder)
        start = time.perf_counter()
        with reporting(ctx.progress), warnings_once():  # each distinct warning once per run
            try:
                output = self._run(params, ctx)
            except SimulationInterrupted as exc:
                self._write_partial(exc, params, folder, time.perf_counter() - start)
                raise
            except BaseException as exc:  # files the run wrote itself (ctx.output_file) stay marked unfinished
                if folder is not None:
                    folder.abandon(describe_stop(exc, "running"))
                raise
            wall = time.perf_counter() - start
            if not isinstance(output, CaseOutput):
                error = CaseError(f"case {self.name}: run() must return a CaseOutput, got {type(output).__name__}")
                if folder is not None:
                    folder.abandon(describe_stop(error, "running"))
                raise error
            output.case = self.name
            output.parameters = params
            output.wall_time = wall
            if folder is not None:
                self._write(output, params, folder, ctx.plot)
        return output

    def _write_partial(self, exc: SimulationInterrupted, params: Parameters, folder: OutputFolder | None, wall: float) -> None:
        """Write what an interrupted run computed (CSV and JSON, marked partial); ``exc.files`` lists them."""
        exc.files = []
        if folder is None:
            return
        if exc.result is None:
            folder.abandon(f"interrupted at t = {exc.time:.6g} s before anything was recorded")
            return
        notes = {"partial": True, "interrupted_at [s]": exc.time}
        if "interrupted_in" in exc.result.info:  # a run of simulate(accuracy=)'s choice: which one (the probe's is not the run)
            notes["interrupted_in"] = exc.result.info["interrupted_in"]
        partial = CaseOutput(exc.result, notes=notes)
        partial.case = self.name
        partial.parameters = params
        partial.wall_time = wall
        self._write(partial, params, folder, plot=False, unfinished=f"interrupted at t = {exc.time:.6g} s")
        exc.files = list(partial.files)

    def _write(self, output: CaseOutput, params: Parameters, folder: OutputFolder, plot: bool,
               unfinished: str | None = None) -> None:
        """Write the run's files so that the folder never mixes two runs (see :mod:`.output_folder`).

        The previous run's files go first, then the JSON (the run's description, ``complete``
        false), the CSV and tables, the plots (drawn apart, moved in together) and the JSON again
        (``complete`` true unless ``unfinished``, which keeps the marker with that reason).
        """
        directory = folder.directory
        vers = versions()
        metadata = {"case": self.name, **params.with_units()}
        info = {
            **output.result.info,
            "exudyn_version": vers["exudyn"],
            "wall_time [s]": round(output.wall_time, 6),
            "steps": output.steps,
        }
        path = directory / f"{self.name}.csv"
        tables = {directory / f"{self.name}_{name}.csv": table for name, table in output.tables.items()}
        json_path = directory / f"{self.name}.json"
        written_by_run = [directory / name for name in folder.files]  # ctx.output_file(...) during the run
        files = [path, *tables, *(p for p in written_by_run if p not in tables and p != path)]
        step = "writing the CSV files"
        try:
            folder.add(json_path.name, *(p.name for p in files))
            self._write_json(output, folder, files + [json_path], complete=False)
            Result(output.result, output.result.units, parameters={**metadata, **output.result.parameters}, info=info).to_csv(path)
            for tpath, table in tables.items():
                Result(table, table.units, parameters={**metadata, **table.parameters},
                       info={"exudyn_version": vers["exudyn"], **table.info}).to_csv(tpath)
            if plot and self._plot is not None:
                step = "drawing the plots"
                start = time.perf_counter()
                written = self._plot(output, params, folder.plot_stage()) or []
                output.plot_time = time.perf_counter() - start
                files.extend(folder.take_plots(written))
            step = "writing the JSON file"
            output.files = files + [json_path]
            self._write_json(output, folder, output.files, complete=unfinished is None)
        except BaseException as exc:
            output.files = [p for p in files + [json_path] if p.exists()]
            folder.abandon(describe_stop(exc, step) + ("" if unfinished is None else f" ({unfinished})"))
            raise
        if unfinished is None:
            folder.finish()
        else:
            folder.abandon(unfinished)

    def _write_json(self, output: CaseOutput, folder: OutputFolder, files: Sequence[Path], complete: bool) -> None:
        """``<case>.json``: the run's description; ``files`` as names in the folder (paths elsewhere in full)."""
        names = [p.name if p.parent == folder.directory else str(p) for p in files]
        folder.add(*(n for n in names if "/" not in n))
        write_json(folder.directory / f"{self.name}.json", {"description": self.description, "source": str(self.source or ""),
                                                             **output.to_dict(), "files": names, "complete": complete})

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
