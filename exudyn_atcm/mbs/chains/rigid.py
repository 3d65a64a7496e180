"""The mechanism realisation of ``cell="rigid"``: one rigid body per cell, revolute joints with torsion springs.

Registered for :class:`~exudyn_atcm.cells.RigidCell` (and its subclasses) in
:func:`~exudyn_atcm.mbs.cells.add_mechanism_bender`.
"""

from __future__ import annotations

import exudyn as exu
import numpy as np

from ...cells import RigidCell
from ...mechanism.bender import Bender
from ..cells import add_mechanism_bender
from ..items import add_body
from ..model import Element, Hinge

__all__ = ["add_rigid_chain"]

CELL_COLOR = [0.2, 0.45, 0.8, 1.0]


def add_rigid_chain(builder, bender: Bender) -> None:
    """Add the rigid cells of ``bender`` and the joints between them through the mechanism ``builder``.

    The end springs (to the bodies the bender joins) are added by the builder from
    ``builder.cell_rotations[bender.name]``.
    """
    mbs, model = builder.mbs, builder.model
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
        model.bodies[key] = add_body(mbs, key, x0 + s * d, bender.angle, m, j_com, com, gfx)
        builder.dampers.add(model.bodies[key], bender.mass_damping_factor, m, j_com, com)
        keys.append(key)
    model.cells[bender.name] = keys

    def theta(j: int) -> np.ndarray:
        """Free rotation of half cell j per unit strain of each source [rad]."""
        out = builder.zeros()
        drive = bender.segments[seg_of[j]].drive
        if drive is not None:
            out[model.drive_source[bender.drive_name(int(seg_of[j]))]] = 0.5 * side * c * lengths[j]
        return out

    def moment_full(j: int) -> np.ndarray:
        """EI kappa per unit strain: the rest moment of a joint standing for two halves of one drive."""
        out = builder.zeros()
        drive = bender.segments[seg_of[j]].drive
        if drive is not None:
            out[model.drive_source[bender.drive_name(int(seg_of[j]))]] = side * ei * c
        return out

    builder.cell_rotations[bender.name] = (theta, moment_full, ei, beta, lengths)
    # inner joints
    for j in range(len(lengths) - 1):
        k = 2.0 * ei / (lengths[j] + lengths[j + 1])
        if seg_of[j] == seg_of[j + 1]:
            k = ei / lengths[j] if lengths[j] == lengths[j + 1] else k
            moment = moment_full(j)
        else:
            moment = k * (theta(j) + theta(j + 1))
        el = Element(k, beta * k, theta(j) + theta(j + 1), moment)
        left = model.bodies[keys[j]]
        right = model.bodies[keys[j + 1]]
        builder.revolute(left, (0.0, 0.0), right, (-lengths[j + 1], 0.0))
        model.hinges.append(Hinge(keys[j], keys[j + 1], [el]))



@add_mechanism_bender.register
def _rigid(cell: RigidCell, builder, bender: Bender) -> None:
    add_rigid_chain(builder, bender)
