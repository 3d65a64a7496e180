"""The mechanism realisation of ``cell="rigid"``: one rigid body per cell, revolute joints with torsion springs.

Registered for :class:`~exudyn_atcm.cells.RigidCell` (and its subclasses) with
:func:`~exudyn_atcm.mbs.realisation.register_realisation`; its ends are massless interfaces joined by
the end springs ``2 EI/L_c`` (:class:`~exudyn_atcm.mbs.realisation.HingedEnds`).
"""

from __future__ import annotations

import exudyn as exu
import numpy as np

from ...cells import RigidCell
from ...mechanism.bender import Bender
from ..model import Element
from ..realisation import HingedEnds, register_realisation

__all__ = ["RigidChain", "add_rigid_chain"]

CELL_COLOR = [0.2, 0.45, 0.8, 1.0]


@register_realisation(RigidCell)
class RigidChain(HingedEnds):
    """One rigid body per cell (both layers' mass), joined by revolute joints with torsion springs ``EI/L_c``."""

    def add_cells(self, ctx) -> None:
        bender = self.bender
        lam = bender.laminate
        ei, c, side = lam.bending_stiffness, lam.curvature_per_strain, bender.curvature_sign
        beta = bender.stiffness_damping_factor
        lengths = bender.cell_lengths
        seg_of = bender.cell_segments
        d = bender.direction
        x0 = np.array(bender.base_position)
        thick = lam.passive.thickness + (lam.active.thickness if lam.active is not None else 0.0)
        keys, s = [], 0.0
        for j, lc in enumerate(lengths):
            s += lc
            m, com_offset, j_com = lam.rigid_cell(lc)
            # active layer on the right of base->tip = local -y
            com = (-0.5 * lc, -side * com_offset)
            gfx = [exu.graphics.Brick(centerPoint=[-0.5 * lc, -side * 0.5 * (thick - lam.passive.thickness), 0.0],
                                      size=[lc, thick, 0.2 * lc], color=CELL_COLOR)]
            key = f"{bender.name}/cell{j + 1}"
            ctx.add_body(key, x0 + s * d, bender.angle, m, j_com, com, gfx, mass_damping=bender.mass_damping_factor)
            keys.append(key)
        ctx.set_cells(bender, keys)

        def theta(j: int) -> np.ndarray:
            """Free rotation of half cell j per unit strain of each source [rad]."""
            out = ctx.zeros()
            source = ctx.source(bender, seg_of[j])
            if source is not None:
                out[source] = 0.5 * side * c * lengths[j]
            return out

        def moment_full(j: int) -> np.ndarray:
            """EI kappa per unit strain: the rest moment of a joint standing for two halves of one drive."""
            out = ctx.zeros()
            source = ctx.source(bender, seg_of[j])
            if source is not None:
                out[source] = side * ei * c
            return out

        self.rotations = (theta, moment_full, ei, beta, lengths)
        self.keys = keys
        # inner joints
        for j in range(len(lengths) - 1):
            k = 2.0 * ei / (lengths[j] + lengths[j + 1])
            if seg_of[j] == seg_of[j + 1]:
                k = ei / lengths[j] if lengths[j] == lengths[j + 1] else k
                moment = moment_full(j)
            else:
                moment = k * (theta(j) + theta(j + 1))
            el = Element(k, beta * k, theta(j) + theta(j + 1), moment)
            ctx.add_hinge(keys[j], keys[j + 1], [el], (0.0, 0.0), (-lengths[j + 1], 0.0))

    def end_spring(self, ctx, end: str) -> tuple[Element, str, tuple[float, float]]:
        """The end spring ``2 EI/L_c`` of half the end cell, with its free rotation."""
        theta, moment_full, ei, beta, lengths = self.rotations
        j = 0 if end == "base" else len(lengths) - 1
        k = 2.0 * ei / lengths[j]
        el = Element(k, beta * k, theta(j), moment_full(j))
        local = (-lengths[j], 0.0) if end == "base" else (0.0, 0.0)
        return el, self.keys[j], local


def add_rigid_chain(ctx, bender: Bender) -> RigidChain:
    """Add the rigid cells of ``bender`` through the build context ``ctx``; returns the realisation
    (whose :meth:`~RigidChain.end_spring` gives the end springs)."""
    realisation = RigidChain(bender)
    realisation.add_cells(ctx)
    return realisation
