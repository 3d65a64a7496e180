"""``cell="rigid"``: one rigid body per cell with a torsion spring at each joint."""

from __future__ import annotations

from .base import END_BODY, CellKind

__all__ = ["RigidCell"]


class RigidCell(CellKind):
    """One rigid body per cell on the passive layer's mid-plane, carrying the mass of both layers.

    A torsion spring at each joint whose rest angle follows the stroke gives the laminate's
    bending stiffness and free curvature, without the six-bar cell's shear mode.  Works in
    mechanisms and for passive strips.  Tip compliance factor ``1 + 1/(2 N^2)`` for ``N`` cells
    (:func:`exudyn_atcm.theory.beam.rigid_chain_compliance_factor`).
    """

    name = "rigid"
    summary = "one rigid body per cell, torsion springs at the joints"
    end_kind = END_BODY
    # bench_run_cost.py: 20, 28 and 192 µs per step at 3, 10 and 40 cells (fit, rounded up)
    realises_mass_damping = True
    cost_per_step = (20e-6, 1e-6, 0.12e-6)
    limits = ("the chain's tip compliance is 1 + 1/(2 N^2) times the beam's (N cells); a cell turning by more "
              "than 0.5 rad against its neighbour is warned about as a coarse discretisation")
