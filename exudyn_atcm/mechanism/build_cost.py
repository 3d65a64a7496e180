"""What building a mechanism's Exudyn model costs, and the announcement of a model too large to build quietly.

A model is built before its first step, and for many cells the build is the dear part: 1e5 rigid
cells took about 20 s and 1.2 GB before the first step of a 1 ms run (issue 29, finding 9), and
a static solve or an eigenvalue analysis of a few thousand cells takes minutes.  The estimates
here are made from the description alone, before anything is built, so that such a run is
announced (:class:`~exudyn_atcm.errors.RunCostWarning`) before the expensive part starts:

* :func:`build_estimate` -- wall time [s] and memory [bytes] of building a mechanism, from each
  cell kind's measured :attr:`~exudyn_atcm.cells.CellKind.build_cost`
  (``benchmarks/bench_build_cost.py``);
* :func:`warn_if_large` -- the announcement of a static solve, a static sweep, an eigenvalue
  analysis or an :func:`~exudyn_atcm.add_to` whose build and solves are predicted to take more
  than :data:`~exudyn_atcm.solve.run_checks.LONG_RUN_SECONDS` or whose model needs more than
  :data:`LARGE_MODEL_BYTES`.  A time integration adds the build to its own estimate
  (:func:`~exudyn_atcm.solve.run_checks.warn_if_long`).

A cell count above :data:`~exudyn_atcm.physical_bounds.MAX_CELLS` is refused where it is given
(:class:`~exudyn_atcm.Bender`, :class:`~exudyn_atcm.BendingActuator`, :class:`~exudyn_atcm.Flexure`).
The module lives below the Exudyn layer, so that :func:`~exudyn_atcm.add_to` announces too.
"""

from __future__ import annotations

import warnings

from ..cells import CellKind, RigidCell
from ..errors import RunCostWarning
from ..io.progress import format_duration
from .assembly import Mechanism
from .bender import Bender
from .flexure import Flexure

__all__ = ["LARGE_MODEL_BYTES", "STATIC_CELLS_MEASURED", "STATIC_SOLVE_STEPS", "EIGEN_SECONDS_PER_COORDINATE3", "build_estimate", "build_detail",
           "step_estimate", "coordinates_at_least", "eigen_estimate", "warn_if_large", "warn_if_eigen_long"]

#: A model whose build is predicted to need more memory than this [bytes] is announced whatever its time:
#: about 60,000 rigid cells (8.1 kB each); the models of the package's cases need less than 10 MB.  A study
#: runs one model per worker process, so a few such models fill the memory of a common machine.
LARGE_MODEL_BYTES = 0.5e9

#: A static solve (or sweep) of more cells than this is announced whatever its estimate: beyond it the
#: static solver was measured to fall back to dynamic relaxation or to fail (2026-11-28, 500 V on a
#: 30 mm bender: 1e4 rigid cells took 69 s by relaxation; 1000 beam elements failed, 2000 took more
#: than 150 s; 2000 six-bar cells more than 150 s), which no step count predicts.
STATIC_CELLS_MEASURED = 2000

#: A static equilibrium is counted as this many time steps of the same model.  Measured
#: (2026-11-28, 500 V on a 30 mm bender): 250 ... 2000 rigid and six-bar cells converged within the
#: cost of 1 to 4 steps beyond the build; 10 leaves a margin.  An equilibrium the static solver
#: cannot reach falls back to dynamic relaxation, about 600 steps, which this does not predict
#: (1e4 rigid cells: 69 s).
STATIC_SOLVE_STEPS = 10

#: Wall time of an eigenvalue analysis per cube of the model's coordinates [s]: the tangent
#: stiffness by differences and a dense eigenproblem (:mod:`exudyn_atcm.mbs.eigen`).  Measured
#: (2026-11-28): 5.9 s at 2400 coordinates (800 rigid cells), 34 s at 3000 (200 six-bar cells);
#: the larger constant is used.
EIGEN_SECONDS_PER_COORDINATE3 = 1.3e-9


def _parts(mech: Mechanism) -> list[tuple[CellKind, int]]:
    """(cell kind, count) of every bender segment; a flexure's cells and every link as rigid cells (two per
    pseudo-rigid-body flexure)."""
    rigid = RigidCell()
    parts: list[tuple[CellKind, int]] = []
    for comp in mech.components.values():
        if isinstance(comp, Bender):
            comp.n_cells  # noqa: B018 - refused while the count is left to the package
            parts += [(comp.cell, seg.n_cells) for seg in comp.segments]
        elif isinstance(comp, Flexure):
            parts.append((rigid, comp.n_cells if comp.model == "cells" else 2))
        else:
            parts.append((rigid, 1))
    return parts


def build_estimate(mech: Mechanism) -> tuple[float, float]:
    """Predicted wall time [s] and memory [bytes] of building ``mech``'s Exudyn model.

    Every bender segment by its cell kind's :attr:`~exudyn_atcm.cells.CellKind.build_cost` (a kind
    without one counts nothing), a flexure's cells and every link as rigid cells.
    """
    seconds, memory = 0.0, 0.0
    for kind, n in _parts(mech):
        estimate = kind.estimate_build(n)
        if estimate is not None:
            seconds += estimate[0]
            memory += estimate[1]
    return seconds, memory


def step_estimate(mech: Mechanism) -> float:
    """Predicted wall time [s] of one time step of ``mech``: every segment by its kind's measured
    :attr:`~exudyn_atcm.cells.CellKind.cost_per_step` (kinds without one count nothing)."""
    return sum(kind.estimate_step_cost(n) or 0.0 for kind, n in _parts(mech))


def build_detail(seconds: float, memory: float) -> str:
    """``"building the Exudyn model: about 20 s and 810 MB"`` for messages."""
    return f"building the Exudyn model: about {format_duration(seconds, rough=True)} and {memory / 1e6:.3g} MB"


def eigen_estimate(n_coordinates: int) -> float:
    """Predicted wall time [s] of an eigenvalue analysis of a model of ``n_coordinates`` coordinates."""
    return EIGEN_SECONDS_PER_COORDINATE3 * float(n_coordinates) ** 3


def coordinates_at_least(mech: Mechanism) -> int:
    """A lower bound of the model's coordinates before it is built: 3 per cell of a chain (a planar rigid body
    or a beam node; six-bar cells have about 15), 1 per mode, 3 per link."""
    return sum((3 * n if kind.chain_of_cells else n) for kind, n in _parts(mech))


def warn_if_large(mech: Mechanism, what: str, *, equilibria: int = 0, eigen: bool = False, limit: float = 60.0,
                  quiet: bool = False, stacklevel: int = 4) -> bool:
    """Announce (:class:`~exudyn_atcm.errors.RunCostWarning`) a build and solve predicted to take long.

    Parameters
    ----------
    mech : Mechanism
        What is about to be built.
    what : str
        What is done with it, for the message (``"solve_static"``, ``"add_to"``).
    equilibria : int, optional
        Static equilibria solved after the build (:data:`STATIC_SOLVE_STEPS` time steps each).
    eigen : bool, optional
        An eigenvalue analysis follows (:func:`eigen_estimate` of :func:`coordinates_at_least`).
    limit : float, optional
        Announce above this many seconds (default 60, :data:`~exudyn_atcm.solve.run_checks.LONG_RUN_SECONDS`).
    quiet : bool, optional
        Do not announce (a run of several solves announced as a whole,
        :func:`~exudyn_atcm.solve.long_runs.is_announced`).
    stacklevel : int, optional
        Passed to ``warnings.warn``.

    Returns
    -------
    bool
        Whether it was announced.
    """
    seconds, memory = build_estimate(mech)
    solve_seconds = equilibria * STATIC_SOLVE_STEPS * step_estimate(mech)
    eigen_seconds = eigen_estimate(coordinates_at_least(mech)) if eigen else 0.0
    total = seconds + solve_seconds + eigen_seconds
    cells = sum(n for _, n in _parts(mech))
    unmeasured = equilibria > 0 and cells > STATIC_CELLS_MEASURED
    if (total > limit or memory > LARGE_MODEL_BYTES or unmeasured) and not quiet:
        statics = ""
        if equilibria:
            statics = (f"; {equilibria} static equilibri{'um' if equilibria == 1 else 'a'}: about "
                       f"{format_duration(solve_seconds, rough=True)}"
                       + (f" if the static solver converges, which above {STATIC_CELLS_MEASURED} cells was measured to "
                          "take minutes by dynamic relaxation or to fail" if unmeasured else ""))
        if eigen:
            statics += (f"; the eigenvalue analysis of at least {coordinates_at_least(mech)} coordinates: at least "
                        f"{format_duration(eigen_seconds, rough=True)}")
        warnings.warn(
            f"{what} of {mech.name!r} ({cells} cells and bodies) is predicted to take about "
            f"{format_duration(total, rough=True)}{' or more' if unmeasured else ''} ({build_detail(seconds, memory)}"
            f"{statics}), measured per cell kind. Fewer cells change the answer little (chains of cells converge at "
            "second order in their number, modes exponentially): halve the count and compare; Ctrl-C stops it",
            RunCostWarning, stacklevel=stacklevel)
        return True
    return False


def warn_if_eigen_long(n_coordinates: int, what: str, *, limit: float = 60.0, quiet: bool = False,
                       stacklevel: int = 4) -> bool:
    """Announce an eigenvalue analysis of ``n_coordinates`` coordinates predicted (:func:`eigen_estimate`) to
    take more than ``limit`` [s]; ``what`` names the system in the message."""
    seconds = eigen_estimate(n_coordinates)
    memory = 8.0 * 4 * float(n_coordinates) ** 2  # a few dense matrices of the coordinates
    if (seconds > limit or memory > LARGE_MODEL_BYTES) and not quiet:
        warnings.warn(
            f"eigenfrequencies of {what} ({n_coordinates} coordinates) are predicted to take about "
            f"{format_duration(seconds, rough=True)} and {memory / 1e6:.3g} MB (a dense eigenproblem of the coordinates, "
            "measured); fewer cells give the lowest frequencies almost as well (they converge at second order in "
            "the cells); Ctrl-C stops it", RunCostWarning, stacklevel=stacklevel)
        return True
    return False
