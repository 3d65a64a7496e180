"""A static sweep's points after the first, continued in one static solve, every point checked for stability.

:func:`continue_sweep` runs the points through :func:`~exudyn_atcm.mbs.sweep_solve.solve_points`
(one Exudyn static solve whose load steps are the points) and keeps a point only when its
equilibrium is shown stable:

* where Exudyn's Jacobian is the tangent (:attr:`StabilityProbe.use_jacobian
  <exudyn_atcm.mbs.stability.StabilityProbe.use_jacobian>`: rod and beam cells, links on revolute
  joints), by the cheap proof from the running solver's Jacobian inside the solve
  (:meth:`~exudyn_atcm.mbs.stability.StabilityProbe.proved_in_solve`); where that proof fails the
  solve stops, the point gets the full check, and a new solve continues after it;
* elsewhere (rigid and six-bar cells), by the full check of every point's state after the solve.

A point whose continuation fails (Exudyn's Newton iteration, even after its adaptive halving) or
ends on an unstable equilibrium is solved as its own equilibrium from the last kept point (as a
point-by-point sweep solves it: :func:`~exudyn_atcm.solve.mechanism_static.equilibrium`, with its
relaxation fallback), with a note; the continuation resumes after it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..mbs import solver_runs as runs
from ..mbs.model import MechanismModel
from ..mbs.blas_threads import one_blas_thread
from ..mbs.stability import Stability, StabilityProbe
from ..mbs.stepping import Stepping
from ..mbs.sweep_solve import set_state, solve_points, system_state
from ..mechanism.assembly import Mechanism
from .mechanism_static import equilibrium

__all__ = ["SweepPoint", "continue_sweep"]


@dataclass
class SweepPoint:
    """One solved point of a sweep: its index, record row, truncation readings
    (:meth:`~exudyn_atcm.mbs.model.MechanismModel.truncation_readings`), stability and method."""

    index: int
    row: np.ndarray
    truncation: dict
    stability: Stability | None
    method: str = "static"
    state: list = field(default_factory=list)


def continue_sweep(mech: Mechanism, model: MechanismModel, volts: np.ndarray, strains: np.ndarray,
                   probe: StabilityProbe, stepping: Stepping, where: Callable[[int], str],
                   keep: Callable[[SweepPoint], None]) -> list[str]:
    """Solve points ``1, ..., len(strains) - 1`` of a sweep whose point 0 is the model's current equilibrium.

    ``volts`` and ``strains``: every point's source values [V] and strains [-] (rows);
    ``where(k)``: point ``k`` described for messages; ``keep(point)``: called for every point in
    order, once it is solved and checked (its :attr:`SweepPoint.row` is what
    :meth:`Stepping.record_state <exudyn_atcm.mbs.stepping.Stepping.record_state>` would record).
    Returns the notes of the points solved as their own equilibria (``"k: why; solved as its own
    equilibrium (method)"``).
    """
    n = len(strains)
    in_solve = probe.use_jacobian
    notes: list[str] = []
    first = 1
    last_state = system_state(model)
    while first < n:
        pending: list[SweepPoint] = []

        def on_point(k: int, solver, state: list) -> bool:
            proved = in_solve and probe.proved_in_solve(solver, state[0], state[3])
            pending.append(SweepPoint(k, stepping.state_row(float(k), volts[k], strains[k]), model.truncation_readings(),
                                      probe.last if proved else None, state=state))
            return proved or not in_solve  # where the proof in the solve missed: stop, check it outside

        start = first
        with one_blas_thread():  # once for all the points' proofs (each proof's own use then only reads the counts)
            solved = solve_points(model, strains, first, on_point, connector_derivative=in_solve)
        why = ""
        if solved.failure is not None:
            why = f"the continuation step failed at load factor {solved.failure.time:.3g} ({solved.failure})"
        for point in pending:
            if point.stability is None:  # not proved in the solve: the full check on its state
                set_state(model, point.state, strains[point.index])
                point.stability = probe.check()
            if point.stability.state == "unstable":
                why = "the continuation step ended on an unstable equilibrium"
                break
            keep(point)
            first, last_state = point.index + 1, point.state
        if first >= n:
            break
        if not why and first == start:  # no point reached and no failure reported: never loop on it
            why = "the continuation reached no point"
        if not why:  # stopped where the proof missed, and that point was stable after all: continue after it
            set_state(model, last_state, strains[first - 1])
            runs.set_current_as_initial(model, zero_velocity=True)
            continue
        # point `first` failed or is unstable: its own equilibrium from the last kept point, as a per-point sweep
        set_state(model, last_state, strains[first - 1])
        runs.set_current_as_initial(model, zero_velocity=True)
        method = equilibrium(mech, model, strains[first - 1], strains[first], False, None, where(first), probe)
        notes.append(f"{first}: {why}; solved as its own equilibrium ({method})")
        runs.set_current_as_initial(model, zero_velocity=True)
        last_state = system_state(model)
        keep(SweepPoint(first, stepping.state_row(float(first), volts[first], strains[first]),
                        model.truncation_readings(), probe.last, method, last_state))
        first += 1
    return notes
