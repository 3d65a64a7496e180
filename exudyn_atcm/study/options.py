"""Option objects of the studies: how runs are executed and stored, and how a search proceeds.

:func:`~exudyn_atcm.study.sweep`, :func:`~exudyn_atcm.study.run_study` and
:func:`~exudyn_atcm.study.optimize` take what a study *is* as keywords (the case, the grid or
bounds, the fixed values) and how it is *run* as one :class:`RunOptions`; :func:`optimize` takes
the settings of its search as one :class:`OptimizeOptions`::

    sweep(case, {"n_cells": [2, 4]}, run=RunOptions(workers=2, out="study"))
    optimize(case, "work", bounds, options=OptimizeOptions(maxiter=20), run=RunOptions(out="opt"))

The flat keywords of earlier releases (``sweep(..., workers=2, out="study")``) still work for one
release, with an :class:`~exudyn_atcm.AtcmDeprecationWarning`.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Callable

__all__ = ["RunOptions", "OptimizeOptions", "METHODS"]

#: Methods of :func:`~exudyn_atcm.study.optimize`.
METHODS = ("differential_evolution", "nelder-mead", "l-bfgs-b")


@dataclass(frozen=True)
class RunOptions:
    """Where a study's runs execute and where they are stored.

    Parameters
    ----------
    workers : int, optional
        Worker processes on this machine (default: one per core; 1 runs in this process).
    client : dask.distributed.Client, optional
        Send the runs to this Dask cluster instead (``LocalCluster`` or a real one).
    scheduler : str, optional
        Address of a Dask scheduler (``"tcp://HOST:8786"``); a client is connected for the study.
    out : str or os.PathLike, optional
        Directory for the study's table and JSON and, unless ``store`` is given, the run store ``runs/``.
    store : str or os.PathLike or RunStore, optional
        Run store directory (see :mod:`exudyn_atcm.study.store`).  Without ``out`` and ``store``,
        nothing is stored and nothing can be resumed.
    retry_failed : bool
        Sweeps: run again the points whose stored run failed (default: a failure is a result).
    progress : callable, optional
        Sweeps: ``progress(done, total, failed)`` after each finished run.
    use_pandas : bool, optional
        Sweeps, deprecated: ``True`` returns ``table.to_pandas()``, ``False`` ``table.to_numpy()``.
    """

    workers: int | None = None
    client: Any = None
    scheduler: str | None = None
    out: str | os.PathLike | None = None
    store: Any = None
    retry_failed: bool = False
    progress: Callable[[int, int, int], None] | None = None
    use_pandas: bool | None = None


@dataclass(frozen=True)
class OptimizeOptions:
    """The settings of :func:`~exudyn_atcm.study.optimize`'s search (its parameters of the same names).

    Parameters
    ----------
    seed : int or None
        Seed of differential evolution (default 0: reproducible, and resumable from the store).
    maxiter, popsize, tol : int, int, float
        Differential evolution: generations, population size factor, relative tolerance.
        Local methods: ``maxiter`` is multiplied by the number of variables.
    xatol, fatol : float
        Nelder-Mead stopping tolerances (normalised coordinates; relative objective).
    polish : bool
        After differential evolution, refine the best design with Nelder-Mead.
    max_evaluations : int, optional
        The most evaluations of the objective, polish included.
    penalty : float
        Weight of a constraint's relative violation (default 10).
    constraint_handling : {"penalty", "scipy"}
        How constraints are applied.
    rerun_best : bool
        Run the best design again in this process to return its full output.
    plot : bool
        Write the best run's plots (with ``RunOptions.out``).
    """

    seed: int | None = 0
    maxiter: int = 100
    popsize: int = 15
    tol: float = 1e-3
    xatol: float = 1e-4
    fatol: float = 1e-4
    polish: bool = True
    max_evaluations: int | None = None
    penalty: float = 10.0
    constraint_handling: str = "penalty"
    rerun_best: bool = True
    plot: bool = False
