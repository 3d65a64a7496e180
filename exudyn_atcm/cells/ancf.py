"""``cell="ancf"``: one ANCF cable element per cell (``ObjectANCFCable2D``)."""

from __future__ import annotations

from .base import CellKind

__all__ = ["AncfCell"]


class AncfCell(CellKind):
    """One cubic ANCF cable element (Bernoulli-Euler, node positions and slopes) per cell.

    Same laminate data and tip torque as the beam cell; higher-order accurate (f1 +0.05 % at
    2 elements).  In strongly bent states coarse meshes lock (f1 about 1500 V +4 % at 2
    elements): use >= 8 elements for large deflections.  Node rotations are the slope angles.
    """

    name = "ancf"
    summary = "one ANCF cable element per cell"
    limits = "coarse meshes lock in strongly bent states: use >= 8 elements for large deflections"

    def mechanism_refusal(self) -> str | None:
        return ("the ancf cell is built for the lone actuator only (its end slopes are not joined to rigid "
                "bodies); use cell='beam' (geometrically exact elements) in a mechanism")
