"""Newton's absolute tolerance of a user's own solve raised to what the added beam cells can reach.

Beam cells (``cell="beam"``) leave a round-off residual on their stiff axis of about
``eps (a1 + a2) L/L_c`` (:attr:`~exudyn_atcm.mbs.user_system.MechanismHandle.newton_tolerance_floor`).
Exudyn's default absolute Newton tolerance (1e-10) lies below it for a bender of more than a few
cells, and a user who solves a system built with :func:`exudyn_atcm.add_to` with the defaults
got Exudyn's generic ``DYNAMIC SOLVER FAILED`` / ``SolveDynamic terminated``.

:class:`ToleranceFloor` is a pre-step function that :func:`~exudyn_atcm.add_to` registers first
when the added items have a floor.  ``exudyn.SolveDynamic`` and ``exudyn.SolveStatic`` (with their
default ``storeSolver=True``, also through ``mbs.SolveDynamic`` / ``mbs.SolveStatic``) store the
solver object in ``mbs.sys["dynamicSolver"]`` / ``mbs.sys["staticSolver"]`` before they start;
the running solver reads its Newton settings from that object's ``newton`` (a copy of the
settings' ``newton`` made at the start: raising the tolerance in ``mbs.sys["simulationSettings"]``
has no effect on the running solve, measured with Exudyn 1.13).  On the first step of each new
solve the function raises ``solver.newton.absoluteTolerance`` to the floor when it is below, and
warns once per handle with both values.  The user's settings object is left unchanged.

When no solver is stored (``storeSolver=False``) the running solver cannot be reached; the
function then warns once that the tolerance could not be checked, naming the floor (a solve with
``storeSolver=False`` after an earlier stored one cannot be told from that one and goes unchecked).
"""

from __future__ import annotations

import warnings
from typing import Any

from .._checks import shown
from ..errors import SetupWarning

__all__ = ["SOLVER_KEYS", "ToleranceFloor"]

#: Keys of ``mbs.sys`` under which Exudyn's solve functions store their solver object.
SOLVER_KEYS = ("dynamicSolver", "staticSolver")


class ToleranceFloor:
    """Pre-step function ``f(mbs, t)``: raise the running solver's Newton absolute tolerance to ``floor``.

    Parameters
    ----------
    floor : float
        Smallest absolute Newton tolerance [N, N m] the added items can reach (``> 0``).

    Attributes
    ----------
    raised : list of tuple
        ``(solver key, tolerance found, floor)`` for every solve whose tolerance was raised.
    """

    def __init__(self, floor: float) -> None:
        floor = float(floor)
        if not floor > 0.0:
            raise ValueError(f"floor must be a positive tolerance [N], got {shown(floor)}")
        self.floor = floor
        self.raised: list[tuple[str, float, float]] = []
        self._seen: dict[str, Any] = {}
        self._warned = False
        self._unreachable_warned = False

    def __call__(self, mbs: Any, t: float) -> bool:
        found = False
        for key in SOLVER_KEYS:
            solver = mbs.sys.get(key)
            if solver is None:
                continue
            found = True
            if self._seen.get(key) is solver:
                continue
            self._seen[key] = solver  # a new solve: each Solve* call makes a new solver object
            self._raise(key, solver)
        if not found and not self._unreachable_warned:
            self._unreachable_warned = True
            warnings.warn(
                f"add_to: the running solver is not stored in mbs.sys (storeSolver=False?), so its Newton "
                f"absolute tolerance cannot be checked against the floor {self.floor:.3g} of the beam cells "
                "(handle.newton_tolerance_floor); set simulationSettings.timeIntegration.newton.absoluteTolerance "
                "(and staticSolver.newton.absoluteTolerance) to at least that, or Newton may fail to converge",
                SetupWarning, stacklevel=2)
        return True

    def _raise(self, key: str, solver: Any) -> None:
        newton = getattr(solver, "newton", None)
        tolerance = getattr(newton, "absoluteTolerance", None)
        if tolerance is None or tolerance >= self.floor:
            return
        newton.absoluteTolerance = self.floor
        self.raised.append((key, float(tolerance), self.floor))
        if not self._warned:
            self._warned = True
            which = "timeIntegration" if key == "dynamicSolver" else "staticSolver"
            warnings.warn(
                f"add_to: Newton's absolute tolerance {tolerance:.3g} of this solve is below {self.floor:.3g}, the "
                f"smallest residual the beam cells can reach (handle.newton_tolerance_floor); raised to "
                f"{self.floor:.3g} for the running solver (your settings object is unchanged). Set "
                f"simulationSettings.{which}.newton.absoluteTolerance = handle.newton_tolerance_floor to silence this",
                SetupWarning, stacklevel=2)
