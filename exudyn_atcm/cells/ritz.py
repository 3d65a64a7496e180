"""``cell="ritz"``: assumed modes of the whole bender's rotation field (Rayleigh-Ritz)."""

from __future__ import annotations

import math
from typing import Any

from ..theory import ritz_beam
from .base import END_NODE, CellKind, cantilever_refusal

__all__ = ["RitzCell"]


class RitzCell(CellKind):
    """The bender as ``n`` assumed modes of its rotation field (:mod:`exudyn_atcm.theory.ritz_beam`).

    ``n_cells`` is the number of modes; ``cell_angle_j`` is the mean rotation of the ``j``-th of
    ``n`` equal segments of one continuous field (not cells of a chain).  The static shape under
    actuation is the exact arc for any ``n``; the dynamics are linearised about the quasi-static
    arc of the current free curvature.  Tip loads are refused (the model leaves out a load's
    geometric stiffness).
    """

    name = "ritz"
    space_order = math.inf  # n assumed modes: the same errors as the rod's at equal n (bench_rod_vs_ritz.py)
    stroke_paths = ("prestep",)
    summary = "assumed modes of the rotation field (one dense system)"
    carries_tip_load = False
    chain_of_cells = False
    end_kind = END_NODE
    # bench_run_cost.py of 2026-11-26 (0.5 s, best of 2): 13, 24, 33 and 57 µs per step at 3, 10, 20 and 40
    # modes; the fit a + b n
    cost_per_step = (10e-6, 1.2e-6, 0.0)
    # bench_build_cost.py of 2026-11-28 (best of 2, fresh process each): 0.003, 0.015 and 0.31 s and 2.7, 4.0 and
    # 64.5 MB at 8, 32 and 128 modes (dense in the modes); the fit n (a + b n) s, n (m + k n) bytes
    build_cost = (1.9e-4, 1.3e-5, 9.1e4, 2.2e3)
    limits = ("dynamics linearised about the quasi-static arc (a warning above 0.05 rad of dynamic tip "
              "rotation); no tip loads; in a mechanism a cantilever only (base welded to the ground, tip free)")

    def check_run(self, result: Any, actuator: Any, stacklevel: int = 2) -> None:
        """Warn when the dynamic tip rotation leaves the quasi-static arc by more than 0.05 rad."""
        ritz_beam.warn_large_dynamic_rotation(result["tip_angle"], result["strain"],
                                              actuator.laminate.curvature_per_strain,
                                              actuator.length, stacklevel=stacklevel + 1)

    def tip_load_refusal(self) -> str | None:
        return ("the ritz cell refuses tip loads (the model leaves out a load's geometric stiffness); "
                "use cell='beam' or cell='ancf' for them")

    def add_to_refusal(self) -> str | None:
        return ("the ritz cell needs solver settings of its own (the mass matrix re-read every step, the dense "
                "linear solver), which a user's own solver run would not set: its dynamics would be quietly wrong; "
                "use cell='ancf' or cell='beam' with add_to")

    def end_refusal(self, end: str, connection: str) -> str | None:
        """A cantilever only: the base welded to the ground, the tip free."""
        return cantilever_refusal(self.name, end, connection,
                                  "the modes are clamped at the base and the model has no end connections")
