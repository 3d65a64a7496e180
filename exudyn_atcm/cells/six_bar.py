"""``cell="six-bar"``: the paper's cell (Fig. 2) with a prescribed-stroke motor in the active layer."""

from __future__ import annotations

from .base import END_CHAIN, CellKind

__all__ = ["SixBarCell"]


class SixBarCell(CellKind):
    """The paper's six-bar cell: interface elements, the passive bar, the active layer as three bodies.

    Four revolute joints with torsion spring-dampers, the prismatic motor A1-A2 (prescribed
    stroke) and the prismatic joint A2-A3 carrying the axial spring ``k1``.  Models both
    layers, so a passive strip cannot be made of it.  Its shear mode makes dynamic tip
    deflections differ from the rigid chain's by 18 / 4.6 / 1.3 % at 5 / 10 / 20 cells.
    """

    name = "six-bar"
    summary = "the paper's six-bar cell (two layers, prescribed-stroke motor)"
    needs_active_layer = True
    end_kind = END_CHAIN
    # bench_run_cost.py of 2026-11-26 (0.5 s, best of 2): 306, 863, 1554 and 3478 µs per step at 3, 10, 20 and
    # 40 cells; the fit a + b n + c n^2
    cost_per_step = (140e-6, 61e-6, 0.55e-6)
    # bench_build_cost.py of 2026-11-28 (best of 2, fresh process each): 821, 1118 and 694 µs and 32, 30 and 30 kB
    # per cell at 200, 800 and 3200 cells; the fit n (a + b n) s, n (m + k n) bytes
    build_cost = (8.2e-4, 0.0, 3.1e4, 0.0)
    realises_mass_damping = True
    limits = ("about 10x the rigid chain's cost per step; the shear mode lowers the dynamic stiffness at few "
              "cells; a passive strip (no active layer) cannot be made of it")
