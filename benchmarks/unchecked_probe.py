"""A stability probe that checks nothing, for benchmarks that split a static sweep's cost.

``unchecked_probe(mech, model)`` stands in for
:func:`exudyn_atcm.solve.static_stability.stability_probe`: every state is reported stable without
looking, inside the solve (:meth:`proved_in_solve`) and after it (:meth:`check`).  Its
``use_jacobian`` is the real probe's (``SolverJacobian(model.mbs).exact``): it decides whether the
continuation solves with the connectors' analytic derivative in the Newton Jacobian
(:func:`exudyn_atcm.mbs.sweep_solve.solve_points`), so the solver does the same work with the
stand-in as with the real probe.  Finding that flag reads the system's items once (about 0.1 to
0.4 ms a sweep, counted on the unchecked side).
"""

from __future__ import annotations

from exudyn_atcm.mbs.solver_jacobian import SolverJacobian
from exudyn_atcm.mbs.stability import Stability

__all__ = ["UncheckedProbe", "unchecked_probe"]


class UncheckedProbe:
    """Reports every state stable without looking (see the module docstring)."""

    last = Stability("stable")

    def __init__(self, use_jacobian: bool) -> None:
        self.use_jacobian = use_jacobian

    def check(self) -> Stability:
        return self.last

    def proved_in_solve(self, solver, q=None, multipliers=None) -> bool:
        return True


def unchecked_probe(mech, model) -> UncheckedProbe:
    """The stand-in for ``stability_probe(mech, model)``, solving as the real probe makes the sweep solve."""
    return UncheckedProbe(SolverJacobian(model.mbs).exact)
