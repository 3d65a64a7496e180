"""Exudyn graphics of a mechanism's rigid parts (links, flexure segments)."""

from __future__ import annotations

import exudyn as exu
import numpy as np

from ..mechanism.assembly import Mechanism
from ..mechanism.flexure import Flexure
from ..mechanism.link import Link
from ..mechanism.points import GROUND

__all__ = ["part_graphics", "shift_graphics", "LINK_COLOR", "FLEXURE_COLOR"]

LINK_COLOR = [0.55, 0.55, 0.55, 1.0]
FLEXURE_COLOR = [0.85, 0.55, 0.15, 1.0]


def part_graphics(mech: Mechanism, part: str) -> list:
    """Exudyn graphics of a rigid part of ``mech`` (a link's outline, a flexure segment) in global coordinates."""
    if part == GROUND:
        return []
    name, _, end = part.partition("#")
    comp = mech.components[name]
    if isinstance(comp, Link):
        pts = list(comp.points.values())
        if len(pts) == 1:
            pts = [pts[0], comp.center_of_mass]
        loop = pts + ([pts[0]] if len(pts) > 2 else [])
        return [exu.graphics.Lines([[p[0], p[1], 0.0] for p in loop], color=LINK_COLOR)]
    if isinstance(comp, Flexure) and comp.model == "prbm":
        a = comp.base_position if end == "base" else comp.pivot
        b = comp.pivot if end == "base" else comp.tip_position
        return [exu.graphics.Lines([[a[0], a[1], 0.0], [b[0], b[1], 0.0]], color=FLEXURE_COLOR)]
    return []


def shift_graphics(gdata: dict, offset: np.ndarray) -> dict:
    """``gdata`` with its points moved by ``offset`` (x, y) [m]."""
    gd = dict(gdata)
    if "points" in gd:
        pts = np.array(gd["points"], dtype=float).reshape(-1, 3)
        pts[:, 0] += offset[0]
        pts[:, 1] += offset[1]
        gd["points"] = pts.ravel().tolist()
    return gd
