"""The ``"rod"`` cell in the one builder: a geometrically exact rod in assumed modes, between two nodes.

Items per bender (coordinates ``z = (X, Y, Phi, q)``, :mod:`exudyn_atcm.theory.rod_kernels`):

* the base: a ``NodeRigidBody2D`` at the base point, ``(X, Y, Phi)``; the rod's frame.  It is an
  ordinary node: welded to the ground (three coordinate constraints), to a link or to another
  bender's tip, pinned with a torsion spring, on a slider;
* the rod: one ``ObjectGenericODE2`` on the base node and a ``NodeGenericODE2`` with the ``n``
  mode amplitudes ``q_i`` [rad] (the rotation shapes of :mod:`exudyn_atcm.theory.rotation_rod`,
  relative to the base's rotation ``Phi``), its constant stiffness ``K`` and damping
  ``beta K`` on the modes, its mass matrix ``M(z)`` and the quadratic velocity vector as its
  ``forceVector``.  ``M(z)`` changes from step to step: the package's own runs write it as the
  item's ``massMatrix`` and let Exudyn re-read it (``reuseConstantMassMatrix = False``); in a
  user's system (:func:`~exudyn_atcm.add_to`) it is returned by a ``massMatrixUserFunction``,
  so that Exudyn treats it as varying in any solver with any settings;
* the tip: a ``NodeRigidBody2D`` (no mass of its own) that joints, welds, loads and sensors
  attach to, tied to the rod by an ``ObjectConnectorCoordinateVector`` (on the tip node's and
  the rod object's coordinates): its pose equals the exact tip pose ``P(z)``, ``Phi + q_1``;
* the actuation: ``LoadCoordinate`` ``EI kappa`` on ``q_1`` (as the ``ritz`` cell); a bender
  of segments has each segment's modes on its own length (:class:`~exudyn_atcm.theory.rotation_rod.RodShapes`)
  and one such load per driven segment, on that segment's first mode.  In a time step of a moving rod
  the same moments are added to the rod's force vector instead (written anyway every step) and the
  loads are held at zero: one Exudyn item write less per step (static solves, which scale loads by
  the load factor, and eigenvalue analyses use the loads).

The nonlinear parts (``M``, the quadratic velocity vector and the tip pose) are evaluated by
compiled kernels and written into the items (in a time step one compiled call per hook,
:func:`~exudyn_atcm.theory.rod_kernels.predicted_items` and
:func:`~exudyn_atcm.theory.rod_kernels.solved_check`, on the rod's constants packed once):

* before every attempted step (the model's strain writer, run in the pre-step hook), at the
  state predicted for the step's end to second order, ``z + h z_dot + h^2/2 z_ddot`` with the
  rates ``z_dot + h z_ddot``: the tip constraint becomes linear in the step,
  ``x1 z - q_tip = offset`` with ``x1 = dP/dz`` at the prediction;
* after every Newton solve (Exudyn's ``PostNewton`` hook, static and dynamic solvers, also a
  user's own solve after :func:`~exudyn_atcm.add_to`): the tip's distance from the exact tip
  pose of the solved ``z`` is checked, and in a time step also how far the solution would move
  if the mass matrix, the quadratic velocity vector and the tie's Jacobian were evaluated at the
  solved state instead of the prediction (:func:`~exudyn_atcm.theory.rod_kernels.step_check`,
  :data:`INERTIA_TOLERANCE`).  Above the tolerances the items are evaluated at the solved state
  (at rest: the constraint with the geometric stiffness ``-lambda . d^2 P/dz^2`` of the tie's
  current reaction) and Exudyn repeats the Newton solve (its "discontinuous iteration", up to
  ``discontinuous.maxIterations`` = 5 passes by default).  So every accepted state satisfies
  the exact nonlinear tip constraint to :data:`TIP_TOLERANCE` times the length
  (:data:`STATIC_TIP_TOLERANCE` at rest), and a time step is generalized-alpha applied to the
  rod's exact equations of motion: second order, and energy-stable without damping, at any
  rotation (``tests/test_rod_dynamics.py``; frozen at the step's start, as before issue 29, the
  integration was first order once the tip turned more than about 0.5 rad and the undamped energy
  grew).  Small motions rarely need a second pass (the compliant four-bar and the gripper: one
  pass per step); a 1.7 rad swing needs about three (its highest mode is not resolved by the step,
  so its prediction is poor).  A static load step converges quadratically in the passes;
* before an eigenvalue analysis: the tangent at the static state with that geometric
  stiffness (compensated in the force vector, so the state stays an equilibrium); the next
  step's update writes ``K`` back.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import exudyn as exu
import numpy as np
from ..exudyn_items import ii

from ...cells import RodCell
from ...mechanism.bender import Bender
from ...theory import rotation_rod
from ..items import NOVIS
from ..model import Body
from ..node_chain import NodeEnds, beam_node_key
from ..realisation import register_realisation

__all__ = ["RodBender", "add_rod_bender", "TIP_TOLERANCE", "STATIC_TIP_TOLERANCE", "INERTIA_TOLERANCE"]

#: Largest distance [in units of the rod's length] of the tip node from the exact tip pose of
#: the rod's coordinates that a solved state of a moving rod may keep (else the Newton solve is
#: repeated with the constraint linearised there).  On the compliant four-bar's 0.5 s triangle
#: (steps 1e-4 and 5e-4 s) 1e-7 ... 1e-10 gave the same path to 1e-3 of its error against 64 beam
#: elements; 1e-10 repeated 7 % of the steps at 5e-4 s, 1e-8 none.
TIP_TOLERANCE = 1e-8
#: The same for a rod at rest (static solves, eigenvalue analyses): the passes converge
#: quadratically, so round-off is reached in one or two more.
STATIC_TIP_TOLERANCE = 1e-13
#: Largest change [rad] of a rotation coordinate that evaluating the inertia (mass matrix, quadratic
#: velocity vector) and the tie at a solved dynamic step's own state, instead of at the state predicted
#: for it, may make before the step's Newton solve is repeated with them.
INERTIA_TOLERANCE = 1e-7
#: Coordinate change per acceleration change in the generalized-alpha Newton iteration, in units of the
#: step squared: ``beta (1 - alpha_f) / (1 - alpha_m)``, 0.26 at the package's spectral radius 0.8
#: (0.25 for the trapezoidal rule); an estimate, it scales the inconsistency into a coordinate change.
NEWTON_POSITION_FACTOR = 0.25

_START = exu.ConfigurationType.StartOfStep


def add_rod_bender(ctx, bender: Bender) -> tuple[Callable, Callable]:
    """Add the rod model of ``bender`` (its base and tip nodes and the tie) through the build context ``ctx``;
    returns its strain writer and its linearisation hook."""
    from ...theory import rod_kernels  # noqa: PLC0415 - numba is imported (and the kernels compiled) for rods only

    mbs, model = ctx.mbs, ctx.model
    n, length = bender.n_cells, bender.length
    size = 3 + n  # X, Y, Phi of the base node, then the modes
    lam = bender.laminate
    ei, mu, rho_i = lam.bending_stiffness, lam.mass_per_length, lam.rotary_inertia_per_length
    # each segment's modes on its own length (its free curvature, its drive); one segment: the plain rod
    shapes = rotation_rod.rod_shapes(n, length, tuple(seg.n_cells for seg in bender.segments),
                                     tuple(seg.length for seg in bender.segments))
    phi_hat, integration, weights, phi_hat_tip = shapes.phi_hat, shapes.integration, shapes.weights, shapes.phi_hat_tip
    K = np.zeros((size, size))
    K[3:, 3:] = shapes.stiffness_matrix(ei)
    angle = bender.angle
    base_reference = np.array([*bender.base_position, angle], dtype=float)
    z0 = np.concatenate([base_reference, np.zeros(n)])
    mass0, force0, x1, offset = rod_kernels.rod_matrices(z0, np.zeros(size), phi_hat, integration, weights, length,
                                                         mu, rho_i, phi_hat_tip)
    # "at": the inputs of the last linearisation at a state itself with the tie's stiffness (the items' values
    # then follow from them alone), None once anything else is written: see linearise
    state = {"mass": mass0, "stiffened": False, "h": 0.0, "at": None}
    # the mass matrix changes every step: in the package's own runs it is written as the item's
    # parameter and the runs let Exudyn re-read it (``reuseConstantMassMatrix = False``, from
    # BuildContext.mark_varying_mass); in a user's system (add_to), whose settings the package does not
    # control, a mass matrix user function makes Exudyn treat it as varying in any solver (about
    # 10 us per call, several calls per step: a third of the rod four-bar's step)
    by_parameter = ctx.package_solves
    varying_mass = {} if by_parameter else {"massMatrixUserFunction": lambda mbs_, t, item, q, q_t: state["mass"]}

    base_node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=base_reference.tolist(), visualization=NOVIS))
    node = mbs.AddNode(ii.NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                          initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    obj = mbs.AddObject(ii.ObjectGenericODE2(nodeNumbers=[base_node, node], massMatrix=mass0, stiffnessMatrix=K,
                                             dampingMatrix=bender.stiffness_damping_factor * K, forceVector=force0,
                                             **varying_mass))
    # the actuation: EI kappa_j on the first mode of every driven segment j
    actuation, actuated_modes = [], []
    for j, (seg, first) in enumerate(zip(bender.segments, shapes.first_modes)):
        if seg.drive is not None:
            marker = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node, coordinate=first))
            actuation.append((mbs.AddLoad(ii.LoadCoordinate(markerNumber=marker, load=0.0)),
                              ctx.source(bender, j)))
            actuated_modes.append(first)
    tip_reference = np.array([*bender.points["tip"], angle], dtype=float)
    tip_node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=tip_reference.tolist(), visualization=NOVIS))
    tie = mbs.AddObject(ii.ObjectConnectorCoordinateVector(
        markerNumbers=[mbs.AddMarker(ii.MarkerNodeCoordinates(nodeNumber=tip_node)),
                       mbs.AddMarker(ii.MarkerObjectODE2Coordinates(objectNumber=obj))],
        scalingMarker0=np.eye(3), scalingMarker1=x1, offset=offset, visualization=NOVIS))

    base = Body(beam_node_key(bender, 0), base_node, obj, base_reference.copy(), node_only=True)
    tip = Body(beam_node_key(bender, n), tip_node, obj, tip_reference, node_only=True)
    ctx.register_body(base)
    ctx.register_body(tip)
    cells = shapes.cell_rotations()
    keys = []
    for j in range(n):
        key = f"{bender.name}/segment{j + 1}"
        seg = Body(key, node, obj, np.array([np.nan, np.nan, angle]), node_only=True)
        seg.pose_function = (lambda q, row=cells[j], body=seg:
                             np.column_stack([np.full(q.shape[0], np.nan), np.full(q.shape[0], np.nan),
                                              angle + q[:, base.ode2 + 2] + q[:, body.ode2:body.ode2 + n] @ row]))
        ctx.register_body(seg)
        keys.append(key)
    ctx.set_cells(bender, keys)
    # ODE2 indices of the base's, the modes' and the tip's coordinates, read at first use (after Assemble;
    # a user's system after add_to is assembled later): nodes are numbered in the order they were added, so
    # these stay valid when items are added after them and the system is assembled again
    ode2 = [-1, -1, -1, -1]
    # the per-step work in one compiled call per hook (rod_kernels.predicted_items, solved_check): the constants
    # packed once, the items' arrays views of one buffer; in a time step the actuation is in the force vector
    limit, static_limit = TIP_TOLERANCE * length, STATIC_TIP_TOLERANCE * length
    tip_reference_xy = np.ascontiguousarray(tip_reference[:2])
    # the largest change of a coordinate that evaluating the inertia and the tie at a solved step's own state
    # may make before the step is solved again with them: X, Y [m], then the rotations [rad]
    limits = np.array([limit, limit] + [INERTIA_TOLERANCE] * (size - 2))
    moment_per_strain = ei * bender.curvature_sign * lam.curvature_per_strain
    ints, consts, packed = rod_kernels.pack_rod(base_reference, tip_reference_xy, [length, mu, rho_i], limits, limit,
                                                K, phi_hat, integration, weights, phi_hat_tip,
                                                [(3 + first, source) for (_, source), first in zip(actuation, actuated_modes)],
                                                moment_per_strain)
    out = rod_kernels.unpack_out(packed, size)
    mass_out, force, x1_, offset_, tangent = out
    out = (mass_out, tangent, force, x1_, offset_)  # the order of linearisation's outputs

    def indices() -> list[int]:
        """[base, modes, tip] ODE2 indices and the tie's first algebraic (multiplier) index; -1 before the system
        is assembled."""
        if ode2[0] < 0 and mbs.GetNodeODE2Index(base_node) >= 0:
            ode2[:] = [mbs.GetNodeODE2Index(base_node), mbs.GetNodeODE2Index(node), mbs.GetNodeODE2Index(tip_node),
                       int(sd.GetObjectLTGAE(tie)[0])]
            ints[:4] = ode2
        return ode2

    sd = mbs.systemData
    set_parameter = mbs.SetObjectParameter
    get_q, get_v, get_time = sd.GetODE2Coordinates, sd.GetODE2Coordinates_t, sd.GetTime
    parameters = np.array([length, mu, rho_i])
    linearisation, tip_gap = rod_kernels.linearisation, rod_kernels.tip_gap

    no_multipliers = no_accelerations = np.empty(0)
    get_a, get_ae = sd.GetODE2Coordinates_tt, sd.GetAECoordinates

    def publish(stiffen: bool) -> None:
        """Hand the rod's items in ``out`` to Exudyn (with ``stiffen``: the tangent with the tie's geometric
        stiffness; else ``K``, written back only if the tangent was written before)."""
        state["at"] = None
        if by_parameter:
            set_parameter(obj, "massMatrix", mass_out)
        else:
            state["mass"] = mass_out  # Exudyn copies what the mass matrix function returns
        if stiffen or state["stiffened"]:
            set_parameter(obj, "stiffnessMatrix", tangent if stiffen else K)
            state["stiffened"] = stiffen
        set_parameter(obj, "forceVector", force)
        set_parameter(tie, "scalingMarker1", x1_)
        set_parameter(tie, "offset", offset_)

    def write(coordinates: np.ndarray, velocities: np.ndarray, accelerations: np.ndarray, h: float,
              stiffen: bool) -> None:
        """Linearise the rod at the state predicted a step ``h`` ahead (``h = 0``: at the state itself): mass
        matrix, quadratic velocity vector and tie; with ``stiffen`` also the tie's geometric stiffness at its
        current force (static passes and eigenvalues; a dynamic step is checked by ``check_tip`` instead)."""
        base_start, rod_start, _, tie_ae = indices()
        # the tie's force: its algebraic coordinates (Exudyn's Force output of the item, to the bit, measured in
        # tests/test_mechanism_rod.py; reading the output inside a solve costs about 10 us, the slice 1 us)
        lam_ = get_ae(current, False)[tie_ae:tie_ae + 3].copy() if stiffen else no_multipliers
        linearisation(coordinates, velocities, accelerations, base_start, rod_start, base_reference, h, lam_, K,
                      phi_hat, integration, weights, phi_hat_tip, parameters, *out)
        publish(stiffen)
        if stiffen and h == 0.0 and not accelerations.shape[0]:
            state["at"] = linearised_at(coordinates, velocities, lam_)

    set_load = mbs.SetLoadParameter
    predicted_items, solved_check = rod_kernels.predicted_items, rod_kernels.solved_check
    current = exu.ConfigurationType.Current
    # the actuation EI kappa: the loads' values (static solves: scaled by the load factor; eigenvalues), or in a
    # time step of a moving rod folded into the force vector, the loads then held at zero
    loads = {"active": True, "strains": no_accelerations}

    def activate_loads(strains: np.ndarray) -> None:
        loads["active"] = True
        for load, source in actuation:
            set_load(load, "load", moment_per_strain * strains.item(source))

    def write_strains(strains: np.ndarray) -> None:
        """The actuation, and the rod linearised at the state predicted for the attempted step's end
        (``z + h z_dot + h^2/2 z_ddot`` and ``z_dot + h z_ddot`` from the step's start); at rest (a static
        load step) at the current state: the step's start, or where a continuation's predictor put the
        iteration's start (:func:`~exudyn_atcm.mbs.sweep_solve.solve_points`)."""
        loads["strains"] = strains
        base_start = ode2[0] if ode2[0] >= 0 else indices()[0]
        if base_start < 0:  # not assembled yet: the first step's pre-step hook linearises
            activate_loads(strains)
            return
        h = get_time() - get_time(_START)
        velocities = get_v(_START, False)
        # a time step of a rod in motion, or starting to move: one compiled call (a static solver's load steps
        # have neither rates nor a finite step)
        if predicted_items(get_q(_START, False), velocities, get_a(_START, False), h, strains, ints, consts, packed):
            if loads["active"]:
                loads["active"] = False
                for load, _ in actuation:
                    set_load(load, "load", 0.0)
            state["h"] = h
            publish(False)
            return
        activate_loads(strains)
        state["h"] = 0.0
        write(get_q(current, False), velocities, no_accelerations, 0.0, True)

    def check_tip(mbs_, t) -> float:
        """After a Newton solve: the tip node's distance from the exact tip pose, and in a time step the change
        that the inertia and the tie evaluated at the solved state would make, over their tolerances; above 1,
        the rod is linearised at the solved state and Exudyn repeats the Newton solve."""
        if ode2[0] < 0 and indices()[0] < 0:
            return 0.0
        h = state["h"]
        if h > 0.0:  # a time step, solved with the items evaluated at the state predicted for it
            ratio = solved_check(get_q(current, False), get_v(current, False), get_a(current, False),
                                 get_ae(current, False), loads["strains"], NEWTON_POSITION_FACTOR * h * h, ints,
                                 consts, packed)
            if ratio <= 1.0:
                return 0.0
            publish(False)  # solved_check evaluated the items at the solved state
            return ratio
        base_start, rod_start, tip_start, _ = ode2
        coordinates, velocities = get_q(current, False), get_v(current, False)
        ratio = tip_gap(coordinates, velocities, base_start, rod_start, tip_start, base_reference, tip_reference_xy,
                        phi_hat, weights, phi_hat_tip, length, limit, static_limit)
        if ratio <= 1.0:
            return 0.0
        write(coordinates, velocities, no_accelerations, 0.0, True)
        return ratio

    at_rest = bytes(8 * size)  # the rates of a state at rest: size zeros (+0.0) as bytes
    rest = [np.zeros(0)]  # zero rates of every ODE2 coordinate (the kernel reads them; never written)

    def linearised_at(coordinates: np.ndarray, velocities: np.ndarray | None, multipliers: np.ndarray) -> bytes:
        """Everything a linearisation at a state itself reads that can change, as bytes (compared bit for bit): the
        rod's coordinates and rates (base node and modes; ``None``: at rest) and the tie's multipliers (its force)."""
        b, r = ode2[0], ode2[1]
        rates = at_rest if velocities is None else velocities[b:b + 3].tobytes() + velocities[r:r + n].tobytes()
        return b"".join((coordinates[b:b + 3].tobytes(), coordinates[r:r + n].tobytes(), rates, multipliers.tobytes()))

    def linearise(strains: np.ndarray) -> None:
        """Eigenvalues: the tangent at the current (equilibrium) state, with the tie's geometric stiffness.

        Nothing is written when the items already hold the linearisation at exactly this state (the
        same coordinates, zero rates and tie multipliers, bit for bit, and nothing written since):
        a static solve's last Newton pass often leaves them so (the README four-bar's crank, whose tie
        carries no force, at every point of a sweep), and its stability proof then reads them as
        they are."""
        if indices()[0] < 0:
            return
        if not loads["active"]:  # after a time step: the actuation back from the force vector into the loads
            activate_loads(loads["strains"])
        coordinates = get_q(current, False)
        state["h"] = 0.0
        a = ode2[3]
        if state["at"] is not None and state["at"] == linearised_at(coordinates, None, get_ae(current, False)[a:a + 3]):
            return
        if rest[0].shape != coordinates.shape:  # the rates of a state at rest (the system's size, read once)
            rest[0] = np.zeros_like(coordinates)
        write(coordinates, rest[0], no_accelerations, 0.0, True)

    estimate = rotation_rod.truncation_estimator(shapes, ei)
    followers: list[int] = []  # the follower forces on the tip node (Exudyn load indices), found at first use
    found = [False]

    def follower_force(angle: float) -> np.ndarray:
        """The part [N] of the tip's force that turns with the tip (follower forces on the tip node), global."""
        if not found[0]:
            found[0] = True
            for rec in model.loads:
                if rec.kind == "force" and rec.follower:
                    marker = mbs.GetMarker(mbs.GetLoad(rec.load)["markerNumber"])
                    if int(marker.get("nodeNumber", -1)) == int(tip_node):
                        followers.append(rec.load)
        out = np.zeros(2)
        c, s_ = math.cos(angle), math.sin(angle)
        for load in followers:
            fx, fy = mbs.GetLoadParameter(load, "loadVector")[:2]  # in the tip node's frame
            out += (c * fx - s_ * fy, s_ * fx + c * fy)
        return out

    def reading() -> tuple | None:
        """What the estimate needs of the current (static) state: base angle, amplitudes, tip and follower forces."""
        base_start, rod_start, tip_start, tie_ae = indices()
        if base_start < 0:
            return None
        coordinates = get_q(copy=False)
        force = get_ae(current, False)[tie_ae:tie_ae + 2].copy()  # the tie's force on the tip node: dead and follower loads
        return (base_reference[2] + coordinates[base_start + 2], coordinates[rod_start:rod_start + n].copy(), force,
                follower_force(tip_reference[2] + coordinates[tip_start + 2]))

    def truncation() -> float:
        """The tip error [m] that the left-out modes would make, from the tie's force (static states)."""
        state = reading()
        return 0.0 if state is None else estimate(*state)

    def many(readings: list) -> np.ndarray:
        """:func:`truncation` of many states from their readings (one stacked evaluation)."""
        states = [r for r in readings if r is not None]
        if not states:
            return np.zeros(1)
        angles, q, forces, followers = (np.array(part) for part in zip(*states))
        return estimate.many(angles, q, forces, followers)

    ctx.set_truncation_estimator(bender, truncation, deferred=(reading, many))
    if by_parameter:
        ctx.mark_varying_mass(bender)  # the runs let Exudyn re-read it every step
    ctx.add_spring(obj, K, "dampingMatrix")  # the relaxation damps the modes at its factor times K
    ctx.add_post_newton(check_tip)
    # the rod's equations are moments of order EI/L per rad: Newton's default absolute
    # tolerance 1e-8 would leave ~1e-8 L / (EI/L) rad
    ctx.require_static_absolute_tolerance(1e-12 * ei / length)
    return write_strains, linearise


@register_realisation(RodCell)
class RodBender(NodeEnds):
    """The geometrically exact rod in assumed modes between a base node and a tip node."""

    def add_cells(self, ctx) -> None:
        self._writer, self._hook = add_rod_bender(ctx, self.bender)

    def strain_writer(self) -> Callable | None:
        return self._writer

    def linearisation_hook(self) -> Callable | None:
        return self._hook
