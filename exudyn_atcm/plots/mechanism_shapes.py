"""Geometry of a mechanism's drawing at one recorded instant (no plotting here).

From a :class:`~exudyn_atcm.mechanism.Mechanism` and a :class:`~exudyn_atcm.Result` of it:
each bender's passive-layer polyline (from the recorded base point and the absolute cell
angles ``{bender}.cell_angle_{j}``; for beam cells these are the mean rotations of each
element's two nodes, the direction of its chord, so the polyline runs through the nodes to the
axis's strain, ~1e-7), its active-layer segments offset by the layer distance
``e`` to the MFC side with the drive of every cell, the links' polygons through their named
points, the pseudo-rigid-body flexures' two segments and pivot (from ``{flexure}.base_angle``),
and the springs' end points.  Displacements can be magnified; magnified bender rotations are
corrected along each chain so that its end meets the magnified tip displacement.
:mod:`exudyn_atcm.plots.mechanism` draws these shapes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._checks import shown
from ..mechanism.actuator import NAME, BendingActuator
from ..mechanism import Bender, Flexure, Link, Mechanism

__all__ = ["BenderShape", "MechanismShape", "mechanism_shape", "actuator_as_mechanism"]


# ----------------------------------------------------------------------------- geometry
@dataclass
class BenderShape:
    """Drawn geometry of one bender at one instant [m].

    Attributes
    ----------
    name : str
        Component name.
    passive : numpy.ndarray, shape (N + 1, 2)
        Joints of the passive layer's mid-plane, base first.
    active : numpy.ndarray or None, shape (N, 2, 2)
        Each cell's active-layer segment (start, end), offset to the MFC side.
    drives : list of str or None
        Drive name of every cell (``None`` for an unpowered cell).
    """

    name: str
    passive: np.ndarray
    active: np.ndarray | None
    drives: list


@dataclass
class MechanismShape:
    """Drawn geometry of a whole mechanism at one instant [m] (see :func:`mechanism_shape`)."""

    benders: list[BenderShape] = field(default_factory=list)
    links: dict[str, np.ndarray] = field(default_factory=dict)
    link_points: dict[str, dict[str, np.ndarray]] = field(default_factory=dict)
    flexures: dict[str, np.ndarray] = field(default_factory=dict)
    pivots: dict[str, np.ndarray] = field(default_factory=dict)
    springs: list[tuple[str, np.ndarray, np.ndarray]] = field(default_factory=list)

    def all_points(self) -> np.ndarray:
        """Every drawn vertex, shape (n, 2), for axis limits."""
        parts = [b.passive for b in self.benders]
        parts += [b.active.reshape(-1, 2) for b in self.benders if b.active is not None]
        parts += list(self.links.values()) + list(self.flexures.values())
        parts += [np.array([p, q]) for _, p, q in self.springs]
        return np.concatenate(parts) if parts else np.zeros((0, 2))


def result_column(result, name: str) -> np.ndarray:
    try:
        return result[name]
    except KeyError:
        raise ValueError(
            f"the result has no column {name!r} needed to draw the mechanism; was it computed for this mechanism?"
        ) from None


def point_at(result, mechanism: Mechanism, ref: str, row: int, scale: float) -> np.ndarray:
    """Position [m] of point ``ref`` (``"comp.point"``) at ``row`` of ``result``, displacements times ``scale``."""
    component, point = ref.split(".")
    x = result_column(result, f"{ref}_x")[row]
    y = result_column(result, f"{ref}_y")[row]
    x0, y0 = mechanism.components[component].points[point]
    return np.array([x0 + scale * (x - x0), y0 + scale * (y - y0)])


def _chain(base: np.ndarray, angles: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    steps = lengths[:, None] * np.stack([np.cos(angles), np.sin(angles)], axis=-1)
    return np.vstack([base, base + np.cumsum(steps, axis=0)])


def _bender_shape(bender: Bender, result, row: int, scale: float, offset_scale: float) -> BenderShape:
    lengths = bender.cell_lengths
    absolute = np.array([result_column(result, f"{bender.name}.cell_angle_{j + 1}")[row] for j in range(bender.n_cells)])
    angles = bender.angle + scale * (absolute - bender.angle)
    base = np.array(bender.base_position) + scale * (
        np.array([result_column(result, f"{bender.name}.base_{c}")[row] for c in "xy"]) - np.array(bender.base_position))
    passive = _chain(base, angles, lengths)
    if scale != 1.0:
        # magnified rotations do not add up to the magnified tip displacement: spread the
        # closure gap along the chain so that welded neighbours stay attached in the drawing
        ref_tip = np.array(bender.points["tip"])
        tip = ref_tip + scale * (np.array([result_column(result, f"{bender.name}.tip_{c}")[row] for c in "xy"]) - ref_tip)
        share = np.concatenate([[0.0], np.cumsum(lengths)]) / float(np.sum(lengths))
        passive = passive + share[:, None] * (tip - passive[-1])[None, :]
    active = None
    drives: list = [None] * bender.n_cells
    if bender.active is not None:
        e = bender.laminate.layer_offset * offset_scale
        # active layer on the right of base -> tip for active_side="right", on the left otherwise
        side = -1.0 if bender.active_side == "right" else 1.0
        normal = np.stack([-np.sin(angles), np.cos(angles)], axis=-1) * (side * e)
        active = np.stack([passive[:-1] + normal, passive[1:] + normal], axis=1)
        for j, k in enumerate(bender.cell_segments):
            if bender.segments[int(k)].drive is not None:
                drives[j] = bender.drive_name(int(k))
    return BenderShape(bender.name, passive, active, drives)


def order_around_centroid(points: np.ndarray) -> np.ndarray:
    if len(points) < 3:
        return points
    c = points.mean(axis=0)
    order = np.argsort(np.arctan2(points[:, 1] - c[1], points[:, 0] - c[0]))
    return points[order]


def mechanism_shape(
    mechanism: Mechanism, result, row: int, *, scale: float = 1.0, offset_scale: float = 1.0
) -> MechanismShape:
    """Geometry of every component at recorded ``row`` [m].

    Parameters
    ----------
    mechanism : Mechanism
        The description the result was computed for.
    result : Result
        A mechanism run (columns listed in the module docstring).
    row : int
        Recorded instant, ``0 <= row < result.n_rows`` (negative counts from the end).
    scale : float, optional
        Displacement magnification (1: true shape).
    offset_scale : float, optional
        Magnification of the layer offset ``e`` in the drawing.

    Raises
    ------
    ValueError
        For a row out of range or a result that lacks a needed column (named).
    """
    n = result.n_rows
    if isinstance(row, bool) or not isinstance(row, (int, np.integer)) or not -n <= row < n:
        raise ValueError(f"row must be an integer in [{-n}, {n - 1}] (the result has {n} rows), got {shown(row)}")
    row = int(row) % n
    shape = MechanismShape()
    for comp in mechanism.components.values():
        if isinstance(comp, Bender):
            shape.benders.append(_bender_shape(comp, result, row, scale, offset_scale))
        elif isinstance(comp, Link):
            pts = {p: point_at(result, mechanism, f"{comp.name}.{p}", row, scale) for p in comp.points}
            shape.link_points[comp.name] = pts
            shape.links[comp.name] = order_around_centroid(np.array(list(pts.values())))
        elif isinstance(comp, Flexure):
            if comp.model == "cells":
                bent = _bender_shape(comp.as_bender(), result, row, scale, offset_scale)
                shape.flexures[comp.name] = bent.passive
            else:
                base = point_at(result, mechanism, f"{comp.name}.base", row, scale)
                tip = point_at(result, mechanism, f"{comp.name}.tip", row, scale)
                angle = comp.angle + scale * (result_column(result, f"{comp.name}.base_angle")[row] - comp.angle)
                pivot = base + comp.segment_lengths[0] * np.array([math.cos(angle), math.sin(angle)])
                shape.flexures[comp.name] = np.array([base, pivot, tip])
                shape.pivots[comp.name] = pivot
    for spring in mechanism.springs:
        p = point_at(result, mechanism, str(spring.p), row, scale)
        q = point_at(result, mechanism, str(spring.q), row, scale)
        shape.springs.append((spring.name, p, q))
    return shape


def actuator_as_mechanism(actuator, result, name: str = "actuator"):
    """A :class:`~exudyn_atcm.BendingActuator` run as its one-bender mechanism, for drawing.

    Returns :meth:`actuator.as_mechanism() <exudyn_atcm.BendingActuator.as_mechanism>` (the one
    description every solve uses: the actuator's own cell kind, layers, cells and drive) and the run
    (its columns are that mechanism's: ``actuator.tip_x``, ``actuator.cell_angle_j``, ...), so that :func:`plot_mechanism` and
    :func:`animate_mechanism` draw both layers, the cell joints (labelled by the cell kind) and the
    motors of a cantilever actuator too.  Nothing is converted here.

    Parameters
    ----------
    actuator : BendingActuator
        The actuator the result was computed for.
    result : Result
        A run of it by :func:`~exudyn_atcm.simulate`, :func:`~exudyn_atcm.solve_static` or
        :func:`~exudyn_atcm.static_sweep` (a file written before 0.3.0 lacks the mechanism's columns:
        draw it with :func:`exudyn_atcm.plots.result.plot_shapes`; a file written from 0.3.0 on has them).
    name : str, optional
        Deprecated and ignored unless ``"actuator"``: the bender of an actuator is named ``"actuator"``.

    Raises
    ------
    ValueError
        For an ``actuator`` that is not a :class:`~exudyn_atcm.BendingActuator`, another ``name``, or a
        result without the mechanism's columns.
    """
    if not isinstance(actuator, BendingActuator):
        raise ValueError(f"actuator must be a BendingActuator, got {shown(actuator)}")
    if name != NAME:
        raise ValueError(f"name must be {NAME!r} (the bender of an actuator's one-bender mechanism), got {shown(name)}")
    drawn = result
    if f"{NAME}.base_x" not in drawn:
        raise ValueError(f"the result has no column {NAME + '.base_x'!r} of the actuator's one-bender mechanism "
                         "(a file written before 0.3.0?); draw it with exudyn_atcm.plots.result.plot_shapes")
    return actuator.as_mechanism(), drawn
