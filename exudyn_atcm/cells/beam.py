"""``cell="beam"``: one geometrically exact beam element per cell (``ObjectBeamGeometricallyExact2D``)."""

from __future__ import annotations

from .base import END_NODE, CellKind

__all__ = ["BeamCell"]


class BeamCell(CellKind):
    """One geometrically exact (Simo-Reissner) beam element per cell on the passive layer's mid-plane.

    The laminate's ``EI``, mass and rotary inertia, a practically inextensible, shear-rigid
    axis; the free curvature enters as end torques ``EI kappa``.  Exact under actuation alone
    at any element count; tip compliance factor ``1 - 1/(4 N^2)``, f1 from above.
    ``cell_angle_j`` is the mean of the element's two node rotations.
    """

    name = "beam"
    stroke_paths = ("prestep", "offsets")
    summary = "one geometrically exact beam element per cell"
    end_kind = END_NODE
    joint_label = "beam nodes"
    # bench_run_cost.py of 2026-11-26 (0.5 s, best of 2): 36, 79, 95 and 139 µs per step at 3, 10, 20 and 40
    # elements; the fit a + b n
    cost_per_step = (40e-6, 2.6e-6, 0.0)
    # bench_build_cost.py of 2026-11-28 (best of 2, fresh process each): 41, 36 and 36 µs and 8.8, 3.3 and 3.0 kB
    # per element at 200, 800 and 3200 elements; the fit n (a + b n) s, n (m + k n) bytes
    build_cost = (3.7e-5, 0.0, 3.4e3, 0.0)
    limits = ("Newton's absolute tolerance must be at least the model's floor (MechanismHandle."
              "newton_tolerance_floor) in a user's own solve")
