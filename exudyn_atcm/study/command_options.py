"""The options of the ``exudyn-atcm sweep`` and ``optimize`` commands (argparse only).

Kept apart from :mod:`exudyn_atcm.study.command`, which runs the commands, so that the command line builds its
parser (and answers ``--help``) without importing numpy, Exudyn or the study engines.
"""

from __future__ import annotations

import argparse

from .options import METHODS

__all__ = ["add_sweep_parser", "add_optimize_parser", "add_run_options"]


def add_run_options(parser: argparse.ArgumentParser, out_default: str, scheduler_note: str = "") -> None:
    """The options shared by ``sweep`` and ``optimize``: --set, --workers, --scheduler, --out, --store."""
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE", help="fix a parameter for every run (repeatable)")
    parser.add_argument("--workers", type=int, default=None, metavar="N", help="worker processes (default: one per core; 1 = in this process)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS", help=f"Dask scheduler, e.g. tcp://HOST:8786{scheduler_note}")
    parser.add_argument("--out", default=out_default, metavar="DIR", help=f"output directory (default: ./{out_default})")
    parser.add_argument("--store", default=None, metavar="DIR", help="run store (default: DIR/runs of --out)")


def add_sweep_parser(sub: argparse._SubParsersAction, parents: list[argparse.ArgumentParser]) -> argparse.ArgumentParser:
    """Add the ``sweep`` subcommand to ``sub``; returns its parser."""
    sweep = sub.add_parser(
        "sweep",
        help="run a case over a grid or samples of its parameters (parallel, resumable)",
        parents=parents,
        description="Run CASE over a full grid (--grid) or Latin-hypercube samples (--samples) of its "
        "parameters; writes DIR/<case>_sweep.csv, a JSON summary, plots, and stores every finished "
        "run in DIR/runs so that running the same command again resumes.",
    )
    sweep.add_argument("case", metavar="CASE", help="case name (see `list`) or path to a case file")
    sweep.add_argument("--grid", action="append", default=[], metavar="SPEC",
                       help="NAME=START:STOP:N (N values), NAME=START:STOP (integers; a range with --samples) or NAME=A,B,C (repeatable)")
    sweep.add_argument("--samples", type=int, default=None, metavar="N",
                       help="draw N points in the START:STOP ranges of --grid (crossed with the lists)")
    sweep.add_argument("--sampling", choices=("lhs", "random"), default="lhs", help="sampler of --samples (default: lhs)")
    sweep.add_argument("--seed", type=int, default=0, help="seed of the sampler (default 0)")
    add_run_options(sweep, "out/sweep", scheduler_note=" (needs the [distributed] extra)")
    sweep.add_argument("--retry-failed", action="store_true", help="run again the points whose stored run failed")
    sweep.add_argument("--no-plot", action="store_true", help="do not write the plots")
    return sweep


def add_optimize_parser(sub: argparse._SubParsersAction, parents: list[argparse.ArgumentParser]) -> argparse.ArgumentParser:
    """Add the ``optimize`` subcommand to ``sub``; returns its parser."""
    opt = sub.add_parser(
        "optimize",
        help="find the parameters of a case that minimise or maximise a key scalar (scipy.optimize)",
        parents=parents,
        description="Optimise CASE over the parameters given with --bound; every evaluation is a stored run "
        "(DIR/runs), so running the same command again replays them and continues.  Writes the history "
        "(DIR/<case>_optimize_history.csv), a JSON summary and the best design's full run (DIR/best).",
    )
    opt.add_argument("case", metavar="CASE", help="case name (see `list`) or path to a case file")
    opt.add_argument("--objective", required=True, metavar="NAME", help="key scalar to minimise (or maximise)")
    opt.add_argument("--maximize", action="store_true", help="maximise the objective")
    opt.add_argument("--bound", action="append", default=[], metavar="NAME=LOW:HIGH", help="a design variable and its range (repeatable)")
    opt.add_argument("--constraint", action="append", default=[], metavar="NAME>=VALUE",
                     help="limit on a key scalar, NAME>=VALUE or NAME<=VALUE (repeatable; quote it in the shell)")
    opt.add_argument("--method", choices=METHODS, default="differential_evolution", help="optimiser (default: differential_evolution)")
    opt.add_argument("--maxiter", type=int, default=100, metavar="N", help="generations (differential evolution; default 100)")
    opt.add_argument("--popsize", type=int, default=15, metavar="N", help="population size per variable (default 15)")
    opt.add_argument("--seed", type=int, default=0, help="seed of differential evolution (default 0)")
    opt.add_argument("--max-evaluations", type=int, default=None, metavar="N",
                     help="stop after N evaluations of the objective, polish included (default: the method's own bound, "
                          "announced before the start)")
    add_run_options(opt, "out/optimize")
    opt.add_argument("--no-plot", action="store_true", help="do not write the best run's plots")
    return opt
