"""Exudyn system of the ``"ritz"`` cell: assumed modes of the rotation field (Rayleigh-Ritz).

The whole bender is one ``ObjectGenericODE2`` on one ``NodeGenericODE2`` with ``n`` coordinates
``q_i`` [rad], the amplitudes of the rotation shapes of :mod:`exudyn_atcm.theory.ritz_beam` (``n`` =
``act.n_cells``).  Its matrices are dense numpy arrays: the diagonal bending stiffness ``K``,
the damping ``beta K`` (stiffness-proportional, as in the other cells) and the mass matrix
``M(kappa)`` linearised about the quasi-static arc of the current free curvature.  The free
curvature loads only ``q_1`` (one ``LoadCoordinate``, ``EI kappa`` written in the pre-step hook,
the same torque per strain as the beam cell's tip torque).

The mass matrix follows the free curvature: :meth:`RitzModel.set_strain` writes ``M(kappa_g)``
whenever the free curvature moves to another point ``kappa_g`` of a grid of spacing
:data:`MASS_UPDATE_ANGLE` ``/ L`` (so ``|kappa - kappa_g| L <= 0.005 rad``), cached by grid point.
Exudyn keeps a constant mass matrix between steps unless
``timeIntegration.reuseConstantMassMatrix`` is off, which :meth:`RitzModel.adjust_settings`
does.  Eigenfrequencies use ``M`` at the exact free curvature of the static state
(:meth:`RitzModel.before_linearisation`).

Tip loads are refused: they would need the load's geometric stiffness, which the model leaves
out (see :mod:`exudyn_atcm.theory.ritz_beam`).
"""

from __future__ import annotations

import exudyn as exu
import numpy as np
from exudyn import itemInterface as ii

from ..theory import ritz_beam
from ..mechanism.actuator import TIP_LOAD_CELLS
from .actuator_model import BuiltModel

#: Grid spacing [rad] of ``kappa L`` at which the mass matrix is re-evaluated.  The first
#: bending frequency of the reference bender changes by 0.26 % between the straight state and
#: the state at 1500 V (``kappa L = 0.36 rad``); the largest offset, half a grid step
#: (0.005 rad), changes f1 there by 7.3e-5 (measured, n = 4).  On the paper's 0.5 s triangle the
#: tip angle differs by 8e-7 rad from a run on a 0.001 rad grid (and by 2e-4 rad from a run that
#: keeps the straight state's mass).
MASS_UPDATE_ANGLE = 0.01


class RitzModel(BuiltModel):
    """Handles of the assumed-modes model (internal)."""

    node_index: int = 0
    length: float = 0.0
    mass_items: tuple = ()  # (object, rotary inertia [kg m], mass per length [kg/m])
    _mass_grid: int | None = None
    _mass_cache: dict | None = None
    _load_item: int = -1
    _segments: np.ndarray | None = None

    # ------------------------------------------------------------------ stroke and mass
    def set_strain(self, strain: float) -> None:
        """Write the free curvature's load ``EI kappa`` and, if ``kappa`` moved a grid step, ``M``."""
        self.mbs.SetLoadParameter(self._load_item, "load", self.torque_per_strain * strain)
        grid = int(round(self.curvature_per_strain * strain * self.length / MASS_UPDATE_ANGLE))
        if grid != self._mass_grid:
            cached = self._mass_cache.get(grid)
            if cached is None:
                cached = self._mass(grid * MASS_UPDATE_ANGLE / self.length)
                self._mass_cache[grid] = cached
            self.mbs.SetObjectParameter(self.mass_items[0], "massMatrix", cached)
            self._mass_grid = grid

    def _mass(self, curvature: float) -> np.ndarray:
        _, rho_i, mu = self.mass_items
        return ritz_beam.mass_matrix(self.n_cells, self.length, mu, rho_i, curvature)

    def before_linearisation(self, strain: float) -> None:
        """Set ``M`` at the exact free curvature of ``strain`` (eigenfrequencies about a static state)."""
        self.mbs.SetObjectParameter(self.mass_items[0], "massMatrix",
                                    self._mass(self.curvature_per_strain * strain))
        self._mass_grid = None  # the next set_strain writes a grid value again

    def scale_loads(self, factor: float) -> None:
        """No tip load exists in this model (refused when building it)."""

    def adjust_settings(self, settings) -> None:
        """Let Exudyn re-read the mass matrix each step; dense solver for the small dense system."""
        settings.timeIntegration.reuseConstantMassMatrix = False
        settings.linearSolver.solverType = exu.LinearSolverType.EXUdense

    # ------------------------------------------------------------------ read-out
    @property
    def record_indices(self) -> np.ndarray:
        return self.node_index + np.arange(self.n_cells)

    def states_from_records(self, records: np.ndarray, strains: np.ndarray) -> tuple:
        q = np.asarray(records, dtype=float).reshape(-1, self.n_cells)
        x, y = ritz_beam.tip_position(q, self.length)
        # theta(L) = sum q_i phi_i(1) = q_1
        return x, y, q[:, 0].copy(), q @ self._segments.T

    def read_state(self, q: np.ndarray, strain: float) -> tuple:
        x, y, a, cells = self.states_from_records(np.asarray(q)[self.record_indices][None, :], None)
        return float(x[0]), float(y[0]), float(a[0]), cells[0]

    def finish_indices(self) -> None:
        self.node_index = self.mbs.GetNodeODE2Index(self._node)
        total = len(self.mbs.systemData.GetODE2Coordinates())
        if self.node_index != 0 or total != self.n_cells:  # the recorder reads them all
            raise RuntimeError(f"ritz model: expected the node's {self.n_cells} coordinates to be the system's "
                               f"only ODE2 coordinates, found {total} starting at {self.node_index}")
        self.tip_indices = self.record_indices


def build_ritz(SC, mbs, act, stroke_path, tip_force) -> RitzModel:
    """Add the assumed-modes actuator to ``mbs``; returns the model handles (not yet assembled)."""
    if stroke_path != "prestep":
        raise ValueError(f"stroke_path must be 'prestep' for the ritz cell (the free curvature is one generalised "
                         f"force written in the pre-step), got {stroke_path!r}")
    fx, fy = (float(v) for v in tip_force)
    if (fx, fy) != (0.0, 0.0):
        raise ValueError(
            f"tip_force must be (0, 0) for cell='ritz', got {tuple(tip_force)!r}: the assumed-modes model leaves "
            "out the geometric stiffness a tip load needs (it is exact for actuation alone); use one of the cells "
            f"{TIP_LOAD_CELLS} for tip loads")
    n = act.n_cells
    length = act.length
    EI = act.bending_stiffness
    K = ritz_beam.stiffness_matrix(n, length, EI)
    rho_i = act.laminate.rotary_inertia_per_length
    mu = act.mass_per_length
    M0 = ritz_beam.mass_matrix(n, length, mu, rho_i, 0.0)
    node = mbs.AddNode(ii.NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                          initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    obj = mbs.AddObject(ii.ObjectGenericODE2(nodeNumbers=[node], massMatrix=M0, stiffnessMatrix=K,
                                             dampingMatrix=act.stiffness_damping_factor * K))
    marker = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node, coordinate=0))
    load = mbs.AddLoad(ii.LoadCoordinate(markerNumber=marker, load=0.0))
    model = RitzModel(SC=SC, mbs=mbs, cell="ritz", n_cells=n, cell_length=act.cell_length)
    model.length = length
    model.mass_items = (obj, rho_i, mu)
    model._mass_grid = 0
    model._mass_cache = {0: M0}
    model._load_item = load
    model._node = node
    model._segments = ritz_beam.segment_rotation_matrix(n, n)
    model.torque_per_strain = EI * act.curvature_per_strain
    model.curvature_per_strain = act.curvature_per_strain
    model.tip_force = (0.0, 0.0)
    # the static problem is linear, K q = Q: Exudyn's Newton iteration (numerical Jacobian) stops
    # at the default tolerance ~1e-9 rad off; 1e-13 rad of generalised moment reaches round-off
    model.static_absolute_tolerance = 1e-13 * EI / length
    model.static_relative_tolerance = 1e-14
    return model
