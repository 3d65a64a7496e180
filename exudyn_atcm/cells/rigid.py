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
    # bench_run_cost.py of 2026-11-26 (0.5 s, best of 2): 33, 70, 132 and 196 µs per step at 3, 10, 20 and 40
    # cells; the fit a + b n
    cost_per_step = (28e-6, 4.4e-6, 0.0)
    # bench_build_cost.py of 2026-11-28 (best of 2, fresh process each): 146, 209 and 150 µs and 10.9, 7.6 and 7.3
    # kB per cell at 200, 800 and 3200 cells; the fit n (a + b n) s, n (m + k n) bytes
    build_cost = (1.6e-4, 0.0, 8.1e3, 0.0)
    realises_mass_damping = True
    # the torque-actuated chain is nearly linear in its rotations: with the absolute tolerance 1e-8
    # Newton stopped after its first step at small voltages, missing ~19 % of the second-order
    # shortening of a 60 mm 16-cell bender at 20 V (tests/test_solver_tolerances.py); a tolerance
    # relative to the step's first residual scales with the deformation (converges in 1-3 steps
    # from 20 V to 1500 V and 3 to 40 cells, and in the four-bar and the gripper)
    static_tolerances = (1e-14, 1e-10)
    limits = ("the chain's tip compliance is 1 + 1/(2 N^2) times the beam's (N cells); a cell turning by more "
              "than 0.5 rad against its neighbour is warned about as a coarse discretisation")
