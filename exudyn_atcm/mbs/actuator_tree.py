"""Exudyn system of the ``"rigid"`` cell in minimal coordinates (``ObjectKinematicTree``).

The chain of rigid cells of :func:`exudyn_atcm.mbs.actuator_chains.build_rigid` is a serial chain:
its ``N`` joint angles describe it completely.  Here it is one ``ObjectKinematicTree`` with a
revolute joint per cell (joint 0 at the clamp), the cells' masses and inertias about their
mass centres, and the torsion springs as the tree's joint P(D) control: joint torque
``k_j (theta0_j - q_j) - beta k_j q_j'`` with ``k_0 = 2 EI/L_c``, ``k_j = EI/L_c`` inside.  The
rest angles ``theta0`` (half a cell's free rotation at the clamp, a full one inside) follow the
strain and are written into ``jointPositionOffsetVector`` in the pre-step hook (one call per
step).  No joint constraints, no Lagrange multipliers: ``N`` unknowns instead of ``3N + 2N``.

The tip (the last cell's end) is found by forward kinematics from the recorded joint angles.
"""

from __future__ import annotations

import exudyn as exu
import numpy as np
from exudyn import itemInterface as ii

from .actuator_model import BuiltModel


class TreeModel(BuiltModel):
    """Handles of the minimal-coordinate rigid chain (internal)."""

    tree: int = -1
    joint_indices: np.ndarray | None = None
    rest_angle_factors: np.ndarray | None = None

    def set_strain(self, strain: float) -> None:
        self.mbs.SetObjectParameter(self.tree, "jointPositionOffsetVector", self.rest_angle_factors * strain)

    def _chain(self, angles: np.ndarray) -> tuple:
        phi = np.cumsum(angles, axis=-1)
        x = self.cell_length * np.sum(np.cos(phi), axis=-1)
        y = self.cell_length * np.sum(np.sin(phi), axis=-1)
        return x, y, phi

    def read_state(self, q: np.ndarray, strain: float) -> tuple:
        x, y, phi = self._chain(np.asarray(q)[self.joint_indices])
        return float(x), float(y), float(phi[-1] + self.tip_rotation_per_strain * strain), phi

    @property
    def record_indices(self) -> np.ndarray:
        return self.joint_indices

    def states_from_records(self, records: np.ndarray, strains: np.ndarray) -> tuple:
        x, y, phi = self._chain(records)
        return x, y, phi[:, -1] + self.tip_rotation_per_strain * strains, phi

    def finish_indices(self) -> None:
        start = self.mbs.GetNodeODE2Index(self._tree_node)
        self.joint_indices = start + np.arange(self.n_cells)
        self.tip_indices = self.joint_indices[-1:]


def build_tree(SC, mbs, act, stroke_path) -> TreeModel:
    """Add the rigid-cell actuator as one kinematic tree to ``mbs`` (not yet assembled)."""
    if stroke_path not in ("prestep", "offsets"):
        raise ValueError(f"stroke_path must be 'prestep' or 'offsets' for the kinematic tree, got {stroke_path!r}")
    n, lc, e = act.n_cells, act.cell_length, act.layer_offset
    beta = act.stiffness_damping_factor
    w = act.width
    h1, h2 = act.passive.thickness, act.active.thickness
    m1 = act.passive.mass_per_length(w) * lc
    m2 = act.active.mass_per_length(w) * lc
    m = m1 + m2
    y_com = -m2 * e / m
    j_com = m * lc**2 / 12.0 + (m1 * h1**2 + m2 * h2**2) / 12.0 + m1 * m2 / m * e**2
    k = np.full(n, act.joint_stiffness_inside)
    k[0] = act.joint_stiffness_end
    rot_per_strain = act.curvature_per_strain * lc
    factors = np.full(n, rot_per_strain)
    factors[0] = 0.5 * rot_per_strain

    model = TreeModel(SC=SC, mbs=mbs, cell="rigid", n_cells=n, cell_length=lc)
    node = mbs.AddNode(ii.NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                          initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    eye = np.eye(3)
    inertia = np.diag([j_com, j_com, j_com])
    model.tree = mbs.AddObject(ii.ObjectKinematicTree(
        nodeNumber=node, jointTypes=[exu.JointType.RevoluteZ] * n, linkParents=list(range(-1, n - 1)),
        jointTransformations=exu.Matrix3DList([eye] * n),
        jointOffsets=exu.Vector3DList([[0.0, 0.0, 0.0]] + [[lc, 0.0, 0.0]] * (n - 1)),
        linkInertiasCOM=exu.Matrix3DList([inertia] * n),
        linkCOMs=exu.Vector3DList([[0.5 * lc, y_com, 0.0]] * n),
        linkMasses=[m] * n, baseOffset=[0.0, 0.0, 0.0], gravity=[0.0, 0.0, 0.0],
        jointPControlVector=list(k), jointDControlVector=list(beta * k),
        jointPositionOffsetVector=[0.0] * n, jointVelocityOffsetVector=[0.0] * n,
        visualization=ii.VObjectKinematicTree(show=False)))
    model.springs.append((model.tree, k, "jointDControlVector"))
    model.rest_angle_factors = factors
    # the static Newton iteration stopped at 1e-8 of its first residual left ~5e-8 rad
    model.static_relative_tolerance = 1e-10
    model._tree_node = node
    model._tip_marker = mbs.AddMarker(ii.MarkerKinematicTreeRigid(objectNumber=model.tree, linkNumber=n - 1,
                                                                  localPosition=[lc, 0.0, 0.0]))
    model.tip_local_x = 0.0
    model.tip_rotation_per_strain = 0.5 * rot_per_strain
    return model
