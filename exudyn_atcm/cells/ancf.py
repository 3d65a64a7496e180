"""``cell="ancf"``: one ANCF cable element per cell (``ObjectANCFCable2D``)."""

from __future__ import annotations

from .base import END_NODE, CellKind, cantilever_refusal

__all__ = ["AncfCell"]


class AncfCell(CellKind):
    """One cubic ANCF cable element (Bernoulli-Euler, node positions and slopes) per cell.

    Same laminate data and tip torque as the beam cell; higher-order accurate (f1 +0.05 % at
    2 elements).  In strongly bent states coarse meshes lock (f1 about 1500 V +4 % at 2
    elements): use >= 8 elements for large deflections.  Node rotations are the slope angles.
    """

    name = "ancf"
    stroke_paths = ("prestep", "offsets")
    summary = "one ANCF cable element per cell"
    end_kind = END_NODE
    # bench_run_cost.py of 2026-11-26 (0.5 s, best of 2): 60, 110, 185 and 288 µs per step at 3, 10, 20 and 40
    # elements; the fit a + b n
    cost_per_step = (49e-6, 6.1e-6, 0.0)
    # bench_build_cost.py of 2026-11-28 (best of 2, fresh process each): 87, 66 and 48 µs and 6.7, 3.7 and 3.1 kB
    # per element at 200, 800 and 3200 elements; the fit n (a + b n) s, n (m + k n) bytes
    build_cost = (5.9e-5, 0.0, 3.8e3, 0.0)
    limits = ("coarse meshes lock in strongly bent states: use >= 8 elements for large deflections; in a mechanism "
              "a cantilever only (base welded to the ground, tip free)")

    def end_refusal(self, end: str, connection: str) -> str | None:
        """A cantilever only: the base welded to the ground, the tip free."""
        return cantilever_refusal(self.name, end, connection, "its end slopes are not joined to rigid bodies")
