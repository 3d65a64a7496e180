"""The ``"ritz"`` cell in the one builder: assumed modes of a bender's rotation field (Rayleigh-Ritz).

The whole bender is one ``ObjectGenericODE2`` on one ``NodeGenericODE2`` with ``n`` coordinates
``q_i`` [rad], the amplitudes of the rotation shapes of :mod:`exudyn_atcm.theory.ritz_beam`
(``n`` = the bender's ``n_cells``).  Its matrices are dense: the diagonal bending stiffness
``K``, the damping ``beta K`` (stiffness-proportional, as in the other cells) and the mass
matrix ``M(kappa)`` linearised about the quasi-static arc of the current free curvature.  The
free curvature loads only ``q_1`` (one ``LoadCoordinate``, ``EI kappa`` written with the strains,
the same torque per strain as the beam cell's end torques).

The mass matrix follows the free curvature: it is rewritten whenever ``kappa L`` moves to
another point of a grid of spacing :data:`MASS_UPDATE_ANGLE` (so ``|kappa - kappa_g| L <= 0.005
rad``), cached by grid point.  Exudyn keeps a constant mass matrix between steps unless
``timeIntegration.reuseConstantMassMatrix`` is off, which the model's settings adjuster does
(with the dense linear solver for the small dense system).  Eigenfrequencies use ``M`` at the
exact free curvature of the static state.

The bender's base is clamped by the modes themselves (``theta(0) = 0``, position at the base
point); its tip is free and carries no load (the cell refuses other end connections and loads:
:meth:`exudyn_atcm.cells.RitzCell.end_refusal`).  The tip's pose and the segments' mean rotations
are read from the coordinates (:func:`~exudyn_atcm.theory.ritz_beam.tip_position`,
:func:`~exudyn_atcm.theory.ritz_beam.segment_rotation_matrix`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import exudyn as exu
import numpy as np
from ..exudyn_items import ii

from ...cells import RitzCell
from ...mechanism.bender import Bender
from ...mechanism.points import MechanismError
from ...theory import ritz_beam
from ..node_chain import NodeEnds, beam_node_key
from ..model import Body
from ..realisation import register_realisation

__all__ = ["RitzBender", "add_ritz_bender", "MASS_UPDATE_ANGLE"]

#: Grid spacing [rad] of ``kappa L`` at which the mass matrix is re-evaluated.  The first
#: bending frequency of the reference bender changes by 0.26 % between the straight state and
#: the state at 1500 V (``kappa L = 0.36 rad``); the largest offset, half a grid step
#: (0.005 rad), changes f1 there by 7.3e-5 (measured, n = 4).  On the paper's 0.5 s triangle the
#: tip angle differs by 8e-7 rad from a run on a 0.001 rad grid (and by 2e-4 rad from a run that
#: keeps the straight state's mass).
MASS_UPDATE_ANGLE = 0.01


def add_ritz_bender(ctx, bender: Bender) -> tuple[Callable | None, Callable]:
    """Add the assumed-modes model of ``bender`` through the build context ``ctx``; returns its strain writer
    (``None`` without a drive) and its linearisation hook."""
    if len(bender.segments) != 1:
        raise MechanismError(f"bender {bender.name!r}: the ritz cell models one uniform segment, got "
                             f"{len(bender.segments)} segments; use cell='beam' for segmented benders")
    mbs = ctx.mbs
    n, length = bender.n_cells, bender.length
    lam = bender.laminate
    ei, mu, rho_i = lam.bending_stiffness, lam.mass_per_length, lam.rotary_inertia_per_length
    K = ritz_beam.stiffness_matrix(n, length, ei)
    M0 = ritz_beam.mass_matrix(n, length, mu, rho_i, 0.0)
    node = mbs.AddNode(ii.NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                          initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    obj = mbs.AddObject(ii.ObjectGenericODE2(nodeNumbers=[node], massMatrix=M0, stiffnessMatrix=K,
                                             dampingMatrix=bender.stiffness_damping_factor * K))
    marker = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node, coordinate=0))
    load = mbs.AddLoad(ii.LoadCoordinate(markerNumber=marker, load=0.0))

    # free curvature per unit strain of each source [1/m], signed by the active side
    curvature = ctx.zeros()
    if bender.segments[0].drive is not None:
        curvature[ctx.source(bender, 0)] = bender.curvature_sign * lam.curvature_per_strain
    angle, base = bender.angle, np.array(bender.base_position, dtype=float)
    c, s = math.cos(angle), math.sin(angle)
    segments = ritz_beam.segment_rotation_matrix(n, n)

    base_key, tip_key = beam_node_key(bender, 0), beam_node_key(bender, n)
    reference_tip = np.array([*bender.points["tip"], angle], dtype=float)
    base_body = ctx.register_body(Body(base_key, node, obj, np.array([base[0], base[1], angle]), node_only=True))
    base_body.pose_function = lambda q, b=base_body: np.tile(b.reference, (q.shape[0], 1))
    base_body.weld = lambda mbs, body, ground_coordinate: None  # clamped by the modes themselves
    tip = Body(tip_key, node, obj, reference_tip, node_only=True)

    def tip_pose(q: np.ndarray) -> np.ndarray:
        modes = q[:, tip.ode2:tip.ode2 + n]
        x, y = ritz_beam.tip_position(modes, length)
        return np.column_stack([base[0] + c * x - s * y, base[1] + s * x + c * y, angle + modes[:, 0]])

    tip.pose_function = tip_pose
    ctx.register_body(tip)
    keys = []
    for j in range(n):
        key = f"{bender.name}/segment{j + 1}"
        seg = Body(key, node, obj, np.array([np.nan, np.nan, angle]), node_only=True)
        seg.pose_function = (lambda q, row=segments[j]:
                             np.column_stack([np.full(q.shape[0], np.nan), np.full(q.shape[0], np.nan),
                                              angle + q[:, tip.ode2:tip.ode2 + n] @ row]))
        ctx.register_body(seg)
        keys.append(key)
    ctx.set_cells(bender, keys)

    cache = {0: M0}
    state = {"grid": 0}

    source = int(np.flatnonzero(curvature)[0]) if np.any(curvature) else None  # the bender's one drive
    curvature_per_strain = float(curvature[source]) if source is not None else 0.0
    set_load = mbs.SetLoadParameter
    grids_per_curvature = length / MASS_UPDATE_ANGLE

    def write_strains(strains: np.ndarray) -> None:
        # the hot path of every attempted step: Python numbers only
        kappa = curvature_per_strain * strains.item(source)
        set_load(load, "load", ei * kappa)
        grid = round(kappa * grids_per_curvature)
        if grid != state["grid"]:
            matrix = cache.get(grid)
            if matrix is None:
                matrix = cache[grid] = ritz_beam.mass_matrix(n, length, mu, rho_i, grid * MASS_UPDATE_ANGLE / length)
            mbs.SetObjectParameter(obj, "massMatrix", matrix)
            state["grid"] = grid

    def linearise(strains: np.ndarray) -> None:
        kappa = float(curvature @ np.asarray(strains, dtype=float))
        mbs.SetObjectParameter(obj, "massMatrix", ritz_beam.mass_matrix(n, length, mu, rho_i, kappa))
        state["grid"] = None  # the next strains write a grid value again

    ctx.add_settings_adjuster(_ritz_settings)
    ctx.mark_varying_mass(bender)
    # the static problem is linear, K q = Q: Exudyn's Newton iteration (numerical Jacobian) stops
    # at the default tolerance ~1e-9 rad off; 1e-13 rad of generalised moment reaches round-off
    ctx.require_static_absolute_tolerance(1e-13 * ei / length)
    ctx.set_static_relative_tolerance(1e-14)
    # without a drive the load stays 0 and the mass matrix M(0)
    return (write_strains if source is not None else None), linearise


def _ritz_settings(settings) -> None:
    """Dense solver for the small dense system (the mass matrix is re-read each step: varying_mass_benders)."""
    settings.linearSolver.solverType = exu.LinearSolverType.EXUdense


@register_realisation(RitzCell)
class RitzBender(NodeEnds):
    """Assumed modes of the whole bender; the base clamped by the modes, the tip free."""

    def add_cells(self, ctx) -> None:
        self._writer, self._hook = add_ritz_bender(ctx, self.bender)

    def strain_writer(self) -> Callable | None:
        return self._writer

    def linearisation_hook(self) -> Callable | None:
        return self._hook
