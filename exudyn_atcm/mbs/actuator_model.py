"""The handles of a built :class:`~exudyn_atcm.mechanism.actuator.BendingActuator` system and its read-out.

:class:`BuiltModel` holds the ``SystemContainer`` and ``MainSystem`` built by
:func:`exudyn_atcm.mbs.actuator_chains.build`, the items through which the stroke enters each
solver step, and the ODE2 indices from which the tip pose and the cells' angles are read
(SI units: m, rad).  The beam, ANCF, assumed-modes and kinematic-tree cells subclass it
(:mod:`~exudyn_atcm.mbs.actuator_beam`, :mod:`~exudyn_atcm.mbs.actuator_ancf`,
:mod:`~exudyn_atcm.mbs.actuator_ritz`, :mod:`~exudyn_atcm.mbs.actuator_tree`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np


@dataclass
class BuiltModel:
    """Handles of a built system (internal)."""

    SC: Any
    mbs: Any
    cell: str
    n_cells: int
    cell_length: float
    # items whose offset carries the stroke; offset = factor * strain
    offset_items: list = field(default_factory=list)
    offset_factors: list = field(default_factory=list)
    offset_parameter: str = "offset"  # the items' parameter that carries factor * strain
    # rigid cell: tip angle = last angle + tip_rotation_per_strain * strain
    tip_rotation_per_strain: float = 0.0
    # ODE2 indices of (x, y, phi) of the tip node and phi of every cell body
    tip_indices: np.ndarray | None = None
    cell_angle_indices: np.ndarray | None = None
    tip_reference: tuple = (0.0, 0.0, 0.0)
    tip_local_x: float = 0.0  # tip point's local x in the tip node's frame
    tip_load: int = -1
    # strain as a function of the solver's t, used by the user-function path
    uf_strain: Any = None
    # (item, stiffness, damping parameter name) of every spring-damper and beam element, for
    # temporary damping changes (damping = factor * stiffness)
    springs: list = field(default_factory=list)
    # beam cell: the recorded angles are the n + 1 node rotations; a cell's angle is the mean
    # of its two nodes' rotations
    cell_angles_from_nodes: bool = False
    # smallest absolute Newton tolerance [N, N m] the model can reach (round-off of stiff
    # axial forces); the solves raise a tighter tolerance to it
    newton_tolerance_floor: float = 0.0
    # relative Newton tolerance of the static solves, if the default (1e-8 of the first
    # residual of a load step) stops too early for this model
    static_relative_tolerance: float | None = None
    # absolute Newton tolerance of the static solves [N, N m], if the default is too loose for
    # this model (a linear model solved to round-off)
    static_absolute_tolerance: float | None = None
    tip_force: tuple = (0.0, 0.0)

    # rigid cell, pre-step path: the rest angles' net effect, one torque on the last body
    torque_load: Any = None
    torque_per_strain: float = 0.0

    def set_strain(self, strain: float) -> None:
        """Write the stroke for free strain ``strain`` into the model (pre-step paths)."""
        mbs = self.mbs
        for item, factor in zip(self.offset_items, self.offset_factors):
            mbs.SetObjectParameter(item, self.offset_parameter, factor * strain)
        if self.torque_load is not None:
            mbs.SetLoadParameter(self.torque_load, "loadVector", [0.0, 0.0, self.torque_per_strain * strain])

    def adjust_settings(self, settings) -> None:
        """Model-specific changes to the dynamic solver settings (before the user's); none by default."""

    def before_linearisation(self, strain: float) -> None:
        """Prepare the eigenvalue analysis about the static state at ``strain``; nothing by default."""

    def scale_loads(self, factor: float) -> None:
        """Set the tip load to ``factor`` times the tip force (load ramps of the relaxation)."""
        fx, fy = self.tip_force
        self.mbs.SetLoadParameter(self.tip_load, "loadVector", [factor * fx, factor * fy, 0.0])

    def read_state(self, q: np.ndarray, strain: float) -> tuple:
        """Tip x, y, angle and per-cell angles from the ODE2 coordinates ``q`` (displacements)."""
        xt, yt, pt = q[self.tip_indices]
        x0, y0, p0 = self.tip_reference
        phi = p0 + pt
        x = x0 + xt + self.tip_local_x * math.cos(phi)
        y = y0 + yt + self.tip_local_x * math.sin(phi)
        angle = phi + self.tip_rotation_per_strain * strain
        angles = q[self.cell_angle_indices]
        if self.cell_angles_from_nodes:
            angles = 0.5 * (angles[:-1] + angles[1:])
        return x, y, angle, angles

    @property
    def record_indices(self) -> np.ndarray:
        """ODE2 indices recorded per step: tip node (x, y, phi), then each cell's angle."""
        return np.concatenate([self.tip_indices, self.cell_angle_indices])

    def states_from_records(self, records: np.ndarray, strains: np.ndarray) -> tuple:
        """Vectorised :meth:`read_state` over rows of ``q[record_indices]``."""
        x0, y0, p0 = self.tip_reference
        phi = p0 + records[:, 2]
        x = x0 + records[:, 0] + self.tip_local_x * np.cos(phi)
        y = y0 + records[:, 1] + self.tip_local_x * np.sin(phi)
        angle = phi + self.tip_rotation_per_strain * strains
        angles = records[:, 3:]
        if self.cell_angles_from_nodes:
            angles = 0.5 * (angles[:, :-1] + angles[:, 1:])
        return x, y, angle, angles

    def coordinates(self) -> np.ndarray:
        """Current ODE2 coordinates (a view, no copy)."""
        return self.mbs.systemData.GetODE2Coordinates(copy=False)

