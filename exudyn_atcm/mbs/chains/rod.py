"""The ``"rod"`` cell in the one builder: a geometrically exact rod in assumed modes, with a tip node.

Items per bender:

* the rod: one ``ObjectGenericODE2`` on a ``NodeGenericODE2`` with ``n`` coordinates ``q_i`` [rad]
  (the amplitudes of the rotation shapes of :mod:`exudyn_atcm.theory.rotation_rod`), its constant
  stiffness ``K`` and damping ``beta K``, its mass matrix ``M(q)`` (given to Exudyn through
  ``massMatrixUserFunction``, which returns the stored matrix: Exudyn then treats it as
  varying in every solver, the user's too) and the quadratic velocity vector as its
  ``forceVector``;
* the tip: a ``NodeRigidBody2D`` (no mass of its own) that joints, welds, loads and sensors
  attach to, tied to the rod by an ``ObjectConnectorCoordinateVector``: its three coordinates
  equal the tip pose ``base + R P(q)``, ``angle + q_1`` (``P``: the tip in the rod's frame);
* the actuation: ``LoadCoordinate`` ``EI kappa`` on ``q_1`` (as the ``ritz`` cell).

The nonlinear parts (``M``, the quadratic velocity vector and the tip pose) are evaluated by
compiled kernels (:mod:`exudyn_atcm.theory.rod_kernels`) and written into the items:

* before every attempted step (the model's strain writer, run in the pre-step hook), at the
  state predicted for the step's end, ``q + h q_dot``: the tip constraint becomes linear in
  the step, ``x1 q - q_tip = offset`` with ``x1 = R dP/dq`` at the prediction;
* after every Newton solve (Exudyn's ``PostNewton`` hook, static and dynamic solvers, also a
  user's own solve after :func:`~exudyn_atcm.add_to`): the tip's distance from the exact tip
  pose of the solved ``q`` is checked; above the tolerance the
  constraint is linearised at the solved state and Exudyn repeats the Newton solve
  (its "discontinuous iteration", up to ``discontinuous.maxIterations`` = 5 passes by default).
  So every accepted state satisfies the exact nonlinear tip constraint to :data:`TIP_TOLERANCE`
  times the length (:data:`STATIC_TIP_TOLERANCE` at rest).  With
  the prediction a dynamic step needs no second pass (measured on the compliant four-bar at
  steps 1e-4 ... 1e-3 s); a static load step converges quadratically in the passes;
* before an eigenvalue analysis: the constraint's geometric stiffness
  ``lambda . d^2 (R P)/dq^2`` (the tip force turning with the rod) is added to ``K`` (and
  compensated in the force vector, so the state stays an equilibrium); the next step's
  update writes ``K`` back.

The base is clamped by the modes (``theta(0) = 0``, at the base point): the cell refuses
other base connections (:meth:`exudyn_atcm.cells.RodCell.end_refusal`).
"""

from __future__ import annotations

import math

import exudyn as exu
import numpy as np
from exudyn import itemInterface as ii

from ...cells import RodCell
from ...mechanism.bender import Bender
from ...mechanism.points import MechanismError
from ...theory import ritz_beam, rotation_rod
from ..cells import add_mechanism_bender
from ..hooks import add_post_newton
from ..items import NOVIS
from ..model import Body
from ..node_chain import beam_node_key

__all__ = ["add_rod_bender", "TIP_TOLERANCE", "STATIC_TIP_TOLERANCE"]

#: Largest distance [in units of the rod's length] of the tip node from the exact tip pose of
#: the rod's coordinates that a solved state of a moving rod may keep (else the Newton solve is
#: repeated with the constraint linearised there).  On the compliant four-bar's 0.5 s triangle
#: (steps 1e-4 and 5e-4 s) 1e-7 ... 1e-10 gave the same path to 1e-3 of its error against 64 beam
#: elements; 1e-10 repeated 7 % of the steps at 5e-4 s, 1e-8 none.
TIP_TOLERANCE = 1e-8
#: The same for a rod at rest (static solves, eigenvalue analyses): the passes converge
#: quadratically, so round-off is reached in one or two more.
STATIC_TIP_TOLERANCE = 1e-13

_START = exu.ConfigurationType.StartOfStep


def add_rod_bender(builder, bender: Bender) -> None:
    """Add the rod model of ``bender`` (its tip node and the tie) through the mechanism ``builder``."""
    from ...theory import rod_kernels  # noqa: PLC0415 - numba is imported (and the kernels compiled) for rods only

    if len(bender.segments) != 1:
        raise MechanismError(f"bender {bender.name!r}: the rod cell models one uniform segment, got "
                             f"{len(bender.segments)} segments; use cell='beam' for segmented benders")
    mbs, model = builder.mbs, builder.model
    n, length = bender.n_cells, bender.length
    lam = bender.laminate
    ei, mu, rho_i = lam.bending_stiffness, lam.mass_per_length, lam.rotary_inertia_per_length
    shapes = rotation_rod.rod_shapes(n, length)
    phi, integration, weights, phi_tip = shapes.phi, shapes.integration, shapes.weights, shapes.phi_tip
    K = ritz_beam.stiffness_matrix(n, length, ei)
    angle, base = bender.angle, np.array(bender.base_position, dtype=float)
    c, s = math.cos(angle), math.sin(angle)
    zeros = np.zeros(n)
    mass0, force0, x1, offset = rod_kernels.step_matrices(zeros, zeros, phi, integration, weights, length, mu, rho_i,
                                                          phi_tip, base[0], base[1], c, s, angle)
    state = {"mass": mass0, "stiffened": False}

    def mass_matrix(mbs_, t, item, q, q_t):
        return state["mass"]

    node = mbs.AddNode(ii.NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                          initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    obj = mbs.AddObject(ii.ObjectGenericODE2(nodeNumbers=[node], massMatrix=mass0, stiffnessMatrix=K,
                                             dampingMatrix=bender.stiffness_damping_factor * K, forceVector=force0,
                                             massMatrixUserFunction=mass_matrix))
    load = mbs.AddLoad(ii.LoadCoordinate(markerNumber=mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node,
                                                                                             coordinate=0)), load=0.0))
    tip_reference = np.array([*bender.points["tip"], angle], dtype=float)
    tip_node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=tip_reference.tolist(), visualization=NOVIS))
    tie = mbs.AddObject(ii.ObjectConnectorCoordinateVector(
        markerNumbers=[mbs.AddMarker(ii.MarkerNodeCoordinates(nodeNumber=tip_node)),
                       mbs.AddMarker(ii.MarkerNodeCoordinates(nodeNumber=node))],
        scalingMarker0=np.eye(3), scalingMarker1=x1, offset=offset, visualization=NOVIS))

    base_key, tip_key = beam_node_key(bender, 0), beam_node_key(bender, n)
    base_body = Body(base_key, node, obj, np.array([base[0], base[1], angle]), node_only=True)
    base_body.pose_function = lambda q, b=base_body: np.tile(b.reference, (q.shape[0], 1))
    base_body.weld = lambda mbs_, body, ground_coordinate: None  # clamped by the modes themselves
    model.bodies[base_key] = base_body
    tip = Body(tip_key, tip_node, obj, tip_reference, node_only=True)
    model.bodies[tip_key] = tip
    segments = ritz_beam.segment_rotation_matrix(n, n)
    keys = []
    for j in range(n):
        key = f"{bender.name}/segment{j + 1}"
        seg = Body(key, node, obj, np.array([np.nan, np.nan, angle]), node_only=True)
        seg.pose_function = (lambda q, row=segments[j], body=seg:
                             np.column_stack([np.full(q.shape[0], np.nan), np.full(q.shape[0], np.nan),
                                              angle + q[:, body.ode2:body.ode2 + n] @ row]))
        model.bodies[key] = seg
        keys.append(key)
    model.cells[bender.name] = keys
    # ODE2 indices of the rod's and the tip's coordinates, read at first use (after Assemble; a user's
    # system after add_to is assembled later): nodes are numbered in the order they were added, so the
    # indices of these two stay valid when items are added after them and the system is assembled again
    ode2 = [-1, -1]

    def indices() -> list[int]:
        """[rod, tip] ODE2 indices; -1 before the system is assembled."""
        if ode2[0] < 0:
            ode2[:] = [mbs.GetNodeODE2Index(node), mbs.GetNodeODE2Index(tip_node)]
        return ode2
    sd = mbs.systemData
    set_parameter = mbs.SetObjectParameter
    get_output = mbs.GetObjectOutput
    get_q, get_v, get_time = sd.GetODE2Coordinates, sd.GetODE2Coordinates_t, sd.GetTime
    force_output = exu.OutputVariableType.Force
    parameters = np.array([length, mu, rho_i, base[0], base[1], c, s, angle])
    linearisation, tip_gap = rod_kernels.linearisation, rod_kernels.tip_gap

    out = (np.empty((n, n)), np.empty((n, n)), np.empty(n), np.empty((3, n)), np.empty(3))
    mass_out, tangent, force, x1_, offset_ = out
    no_multipliers = np.empty(0)

    def write(coordinates: np.ndarray, velocities: np.ndarray, h: float, stiffen: bool) -> None:
        """Linearise the rod at ``q + h q_dot``: mass matrix, quadratic velocity vector and tie; with ``stiffen``
        also the tie's geometric stiffness at its current force (static passes and eigenvalues: a dynamic step's
        prediction is close enough without it)."""
        lam_ = get_output(tie, force_output) if stiffen else no_multipliers
        linearisation(coordinates, velocities, indices()[0], h, lam_, K, phi, integration, weights, phi_tip,
                      parameters, *out)
        state["mass"] = mass_out  # Exudyn copies what the mass matrix function returns
        if stiffen or state["stiffened"]:
            set_parameter(obj, "stiffnessMatrix", tangent)
            state["stiffened"] = stiffen
        set_parameter(obj, "forceVector", force)
        set_parameter(tie, "scalingMarker1", x1_)
        set_parameter(tie, "offset", offset_)

    source = None
    curvature_per_strain = 0.0
    if bender.segments[0].drive is not None:
        source = model.drive_source[bender.drive_name(0)]
        curvature_per_strain = bender.curvature_sign * lam.curvature_per_strain
    set_load = mbs.SetLoadParameter

    def write_strains(strains: np.ndarray) -> None:
        """The actuation, and the rod linearised at the state predicted for the attempted step's end
        (``q + h q_dot`` from the step's start)."""
        if source is not None:
            set_load(load, "load", ei * curvature_per_strain * strains.item(source))
        start = indices()[0]
        if start < 0:  # not assembled yet: the first step's pre-step hook linearises
            return
        h = get_time() - get_time(_START)
        velocities = get_v(_START, False)
        dynamic = 0.0 < h < math.inf and any(velocities[start:start + n])
        write(get_q(_START, False), velocities, h if dynamic else 0.0, not dynamic)

    limit, static_limit = TIP_TOLERANCE * length, STATIC_TIP_TOLERANCE * length
    tip_reference_xy = np.ascontiguousarray(tip_reference[:2])

    def check_tip(mbs_, t) -> float:
        """Distance of the tip node from the exact tip pose over the tolerance; linearise there if above."""
        start, tip_start = indices()
        if start < 0:
            return 0.0
        coordinates, velocities = get_q(copy=False), get_v(copy=False)
        ratio = tip_gap(coordinates, velocities, start, tip_start, tip_reference_xy, phi, weights, phi_tip, parameters,
                        limit, static_limit)
        if ratio <= 1.0:
            return 0.0
        write(coordinates, velocities, 0.0, True)
        return ratio

    def linearise(strains: np.ndarray) -> None:
        """Eigenvalues: the tangent at the current (equilibrium) state, with the tie's geometric stiffness."""
        if indices()[0] < 0:
            return
        coordinates = get_q(copy=False)
        write(coordinates, np.zeros_like(coordinates), 0.0, True)

    model.strain_writers.append(write_strains)
    model.linearisation_hooks.append(linearise)
    add_post_newton(mbs, check_tip)
    # the rod's equations are moments of order EI/L per rad: Newton's default absolute
    # tolerance 1e-8 would leave ~1e-8 L / (EI/L) rad
    absolute = 1e-12 * ei / length
    model.static_absolute_tolerance = min(absolute, model.static_absolute_tolerance or math.inf)


@add_mechanism_bender.register
def _rod(cell: RodCell, builder, bender: Bender) -> None:
    add_rod_bender(builder, bender)
