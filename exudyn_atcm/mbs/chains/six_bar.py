"""The paper's six-bar cell (its Fig. 2) inside a mechanism: a chain between two end bodies.

Per cell ``j`` (for a lone actuator as for any bender): the passive bar,
the active layer as three bodies A1-A2-A3, revolute joints with torsion springs
``2 E_i I_i / L_c`` to the interfaces on both layers, the prismatic motor A1-A2 (its offset
is the stroke ``strain * L_c``, written per step) and the prismatic joint A2-A3 with the axial
spring ``k1``.  Inner interfaces are bodies of the chain; the two end interfaces are the
bodies of their rigid groups (the ground, a link, or an interface body of their own), so
joints at the ends act on real interface bodies.

Masses: each interface carries the laminate over ``s = min(h1 + h2, L_c/10)``, half from
each neighbouring cell; an end interface carries its half (:func:`six_bar_end_mass`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import exudyn as exu
import numpy as np
from ..exudyn_items import ii

from ...cells import SixBarCell
from ...mechanism.bender import Bender
from ..items import NOVIS, add_body, local_point, position_marker, rotation_marker
from ..model import Body, EndReadout, MechanismModel
from ..realisation import CellRealisation, EndMass, register_realisation

__all__ = ["SixBarChain", "add_six_bar_chain", "six_bar_end_mass"]


PASSIVE_COLOR = [0.2, 0.45, 0.8, 1.0]
ACTIVE_COLOR = [0.85, 0.3, 0.2, 1.0]


def six_bar_end_mass(bender: Bender, end: str) -> tuple[float, float, np.ndarray, float]:
    """Half an interface of the end cell: mass [kg], inertia about its centre [kg m²], centre [m]
    (global, reference pose) and the centre's offset from the passive layer towards the active one [m]."""
    lam = bender.laminate
    lc = float(bender.cell_lengths[0 if end == "base" else -1])
    m_if, j_if = _interface(bender, lc)
    e = lam.layer_offset
    normal = np.array([-math.sin(bender.angle), math.cos(bender.angle)])
    center = np.array(bender.points[end]) - bender.curvature_sign * 0.5 * e * normal
    return 0.5 * m_if, 0.5 * j_if, center, 0.5 * e


def _interface(bender: Bender, lc: float) -> tuple[float, float]:
    lam = bender.laminate
    s = lam.interface_length(lc)
    m_if = lam.mass_per_length * s
    h = lam.passive.thickness + lam.active.thickness
    return m_if, m_if * (s**2 + (lam.layer_offset + 0.5 * h) ** 2) / 12.0


def add_six_bar_chain(ctx, bender: Bender, base: Body, tip: Body,
                      damp: Callable[[Body, float, float, tuple[float, float]], None] | None = None) -> list:
    """Add the cells of ``bender`` between the end bodies ``base`` and ``tip`` through the build context
    ``ctx`` (:class:`~exudyn_atcm.mbs.build_context.BuildContext`); returns the passive bars' keys.

    Registers the motors (:meth:`~exudyn_atcm.mbs.build_context.BuildContext.add_motor_offset`) and the
    spring-dampers (:meth:`~exudyn_atcm.mbs.build_context.BuildContext.add_spring`).
    ``damp(body, mass, inertia, center)``, if given, is called for every body the chain adds
    (mass [kg], inertia about the centre [kg m²], centre in the body frame [m]): the
    mass-proportional damping of :mod:`exudyn_atcm.mbs.mass_damping`.
    """
    if damp is None:
        def damp(body, mass, inertia, center):
            return None
    mbs, model, ground_coordinate = ctx.mbs, ctx.model, ctx.ground_coordinate
    lam = bender.laminate
    side = bender.curvature_sign
    e = lam.layer_offset
    w = bender.width
    h1, h2 = lam.passive.thickness, lam.active.thickness
    beta = bender.stiffness_damping_factor
    angle = bender.angle
    d = bender.direction
    n_hat = np.array([-math.sin(angle), math.cos(angle)])
    x_base = np.array(bender.base_position, dtype=float)
    lengths = bender.cell_lengths
    segment = bender.cell_segments
    upper = (0.0, -side * e)  # the active layer's point of an interface, in the bender's frame

    def hinge(positions, rotations, k):
        mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=list(positions), visualization=NOVIS))
        item = mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
            markerNumbers=list(rotations), stiffness=k, damping=beta * k, visualization=NOVIS))
        ctx.add_spring(item, k)

    def ends(body: Body, point: np.ndarray):
        """Markers of an end interface: lower (passive) and upper (active) points, rotation."""
        low = position_marker(mbs, body, local_point(body, point))
        up = position_marker(mbs, body, local_point(body, point - side * e * n_hat))
        return low, up, rotation_marker(mbs, body, ground_coordinate)

    prev_lower, prev_upper, prev_rot = ends(base, x_base)
    bars, s_pos = [], 0.0
    for j, lc in enumerate(lengths):
        x0 = x_base + s_pos * d
        s_pos += lc
        k_p, k_a = lam.layer_joint_stiffness(lc)
        k1 = lam.axial_spring_stiffness(lc)
        keep = 1.0 - lam.interface_length(lc) / lc
        m1 = lam.passive.mass_per_length(w) * lc * keep
        key = f"{bender.name}/cell{j + 1}"
        bar = add_body(mbs, key, x0 + 0.5 * lc * d, angle, m1, m1 * (lc**2 + h1**2) / 12.0, (0.0, 0.0),
                       [exu.graphics.Brick(size=[lc, h1, 0.2 * lc], color=PASSIVE_COLOR)])
        ctx.register_body(bar)
        damp(bar, m1, m1 * (lc**2 + h1**2) / 12.0, (0.0, 0.0))
        bars.append(key)
        ma = lam.active.mass_per_length(w) * lc * keep / 3.0
        la = lc / 3.0
        act = []
        for k in range(3):
            pos = x0 + (k + 0.5) * la * d - side * e * n_hat
            body = add_body(mbs, f"{key}/A{k + 1}", pos, angle, ma, ma * (la**2 + h2**2) / 12.0, (0.0, 0.0),
                            [exu.graphics.Brick(size=[la, h2, 0.2 * lc], color=ACTIVE_COLOR)])
            damp(body, ma, ma * (la**2 + h2**2) / 12.0, (0.0, 0.0))
            act.append(body)
        if j < len(lengths) - 1:
            # an inner interface: half the lumped laminate of each neighbouring cell
            m_a, j_a = _interface(bender, lc)
            m_b, j_b = _interface(bender, float(lengths[j + 1]))
            nxt = add_body(mbs, f"{bender.name}/interface{j + 1}", x0 + lc * d, angle, 0.5 * (m_a + m_b),
                           0.5 * (j_a + j_b), (0.0, -side * 0.5 * e), [])
            ctx.register_body(nxt)
            damp(nxt, 0.5 * (m_a + m_b), 0.5 * (j_a + j_b), (0.0, -side * 0.5 * e))
            lower, upper_m, rot = (position_marker(mbs, nxt, (0.0, 0.0)), position_marker(mbs, nxt, upper),
                                   rotation_marker(mbs, nxt, ground_coordinate))
        else:
            lower, upper_m, rot = ends(tip, x0 + lc * d)
        bar_rot = rotation_marker(mbs, bar, ground_coordinate)
        hinge((prev_lower, position_marker(mbs, bar, (-0.5 * lc, 0.0))), (prev_rot, bar_rot), k_p)
        hinge((position_marker(mbs, bar, (0.5 * lc, 0.0)), lower), (bar_rot, rot), k_p)
        hinge((prev_upper, position_marker(mbs, act[0], (-0.5 * la, 0.0))),
              (prev_rot, rotation_marker(mbs, act[0], ground_coordinate)), k_a)
        hinge((position_marker(mbs, act[2], (0.5 * la, 0.0)), upper_m),
              (rotation_marker(mbs, act[2], ground_coordinate), rot), k_a)
        for left, right in ((0, 1), (1, 2)):
            m0 = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=act[left].item, localPosition=[0.5 * la, 0.0, 0.0]))
            m1_ = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=act[right].item, localPosition=[-0.5 * la, 0.0, 0.0]))
            mbs.AddObject(ii.ObjectJointPrismatic2D(markerNumbers=[m0, m1_], axisMarker0=[1.0, 0.0, 0.0],
                                                    normalMarker1=[0.0, 1.0, 0.0], constrainRotation=True,
                                                    visualization=NOVIS))
        m_motor, m_spring = (mbs.AddMarker(ii.MarkerBodiesRelativeTranslationCoordinate(
            bodyNumbers=[act[a].item, act[b].item], localPosition0=[0.5 * la, 0.0, 0.0],
            localPosition1=[-0.5 * la, 0.0, 0.0], axis0=[1.0, 0.0, 0.0])) for a, b in ((0, 1), (1, 2)))
        drive = bender.segments[segment[j]].drive
        source = model.drive_source[bender.drive_name(int(segment[j]))] if drive is not None else None
        if source is not None and model.stroke_path == "user_function":
            mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[ground_coordinate, m_motor],
                                                       offsetUserFunction=_motor_offset(model, float(lc), source),
                                                       visualization=NOVIS))
        else:
            motor = mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[ground_coordinate, m_motor],
                                                               offset=0.0, visualization=NOVIS))
            if source is not None:
                ctx.add_motor_offset(motor, float(lc), source)
        spring = mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
            markerNumbers=[ground_coordinate, m_spring], stiffness=k1, damping=beta * k1, visualization=NOVIS))
        ctx.add_spring(spring, k1)
        prev_lower, prev_upper, prev_rot = lower, upper_m, rot
    return bars


def _motor_offset(model: MechanismModel, factor: float, source: int) -> Callable:
    """The motor's offset user function: the stroke ``factor * strain`` of ``source`` at the solver's ``t``."""
    def offset(mbs_, t, item_number, offset_):
        return factor * float(model.strains_at(t)[source])
    return offset


@register_realisation(SixBarCell)
class SixBarChain(CellRealisation):
    """A six-bar chain between the bodies of the groups its two ends belong to (real interface bodies)."""

    ends_on_group_body = True

    def add_cells(self, ctx) -> None:
        bender = self.bender
        ends = [ctx.group_body(bender, end) for end in ("base", "tip")]
        alpha = bender.mass_damping_factor
        ctx.set_cells(bender, add_six_bar_chain(
            ctx, bender, *ends,
            damp=lambda body, mass, inertia, center: ctx.add_mass_damping(body, alpha, mass, inertia, center)))

    def connect_end(self, ctx, end: str) -> None:
        """The chain ends on the group's body itself: nothing to join, the end turns with that body."""
        ctx.set_end_readout(self.bender, end, EndReadout("body", body=ctx.group(self.bender, end).key))

    def end_masses(self, end: str, carried: bool) -> list[EndMass]:
        """Half the end interface, on the group's body wherever it sits."""
        m, j, center, _ = six_bar_end_mass(self.bender, end)
        return [(m, j, center)]

    def interface_body_mass(self, end: str) -> tuple[float, float, tuple[float, float]]:
        m, j, _, offset = six_bar_end_mass(self.bender, end)
        return m, j, (0.0, -self.bender.curvature_sign * offset)
