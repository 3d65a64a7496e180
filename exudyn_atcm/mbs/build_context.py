"""The one public build context: what a cell's realisation and a connection's ``realise`` write through.

One :class:`BuildContext` exists per build of a mechanism into an Exudyn ``MainSystem``; the builder
(:mod:`~exudyn_atcm.mbs.builder`) makes it and hands it to every cell realisation
(:mod:`~exudyn_atcm.mbs.realisation`: bodies, cells, hinges with series springs, strain writers,
tolerances) and to every connection and load (:mod:`~exudyn_atcm.mechanism.connection`: markers at
points, items, pins, sliders, loads, recorded columns).  Extensions read the system, the mechanism
and the layout here and add their items with its methods; they never write the model's attributes.
Units are SI: positions [m], angles [rad], forces [N], torques [N m].
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from functools import partial
from typing import Any

import exudyn as exu
import numpy as np
from .._checks import shown
from .exudyn_items import ii

from ..errors import AtcmDeprecationWarning
from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..mechanism.connection import Readout
from ..mechanism.points import GROUND, MechanismError, PointRef
from . import loads
from .hooks import add_post_newton
from .items import NOVIS, add_body, local_point, position_marker, rigid_marker, rotation_marker
from .layout import Group, part_of
from .mass_damping import MassDampers
from .model import Body, Element, EndReadout, Hinge, MechanismModel
from .node_chain import weld_node
from .realisation import CellRealisation

__all__ = ["BuildContext"]


class BuildContext:
    """The public handle of one build, for cell realisations and connections alike (system, mechanism, layout).

    Its methods add bodies, cells, hinges, pins, sliders, markers, loads, items and recorded columns; units SI.

    Attributes
    ----------
    mbs : exudyn MainSystem
        The system being built (for items this context has no method for).
    mechanism : Mechanism
        The mechanism being built.
    model : MechanismModel
        The built model's handle (read it; write through the methods).
    package_solves : bool
        Only the package's runs solve this system (they apply the model's settings adjusters); False
        after :func:`~exudyn_atcm.add_to`, whose user may solve with any settings.
    ground_coordinate : int
        A fixed coordinate marker (Exudyn's ground for coordinate connectors).
    groups, group_of : dict
        The rigid groups by key and the group key of every part (:func:`~exudyn_atcm.mbs.layout.rigid_groups`).
    """

    def __init__(self, mbs, mechanism: Mechanism, model: MechanismModel, package_solves: bool) -> None:
        self.mbs = mbs
        self.mechanism = mechanism
        self.model = model
        self.package_solves = package_solves
        self.ground_coordinate: int = -1
        self.groups: dict[str, Group] = {}
        self.group_of: dict[str, str] = {}
        self.realisations: dict[str, CellRealisation] = {}
        self.clamped: set[str] = set()  # nodes clamped to the ground (no actuation torque)
        self.dampers: MassDampers | None = None

    # ------------------------------------------------------------------ reading
    @property
    def system(self) -> Any:
        """Deprecated name of :attr:`mbs` (the ``MainSystem`` being built)."""
        warnings.warn("BuildContext.system is deprecated; use BuildContext.mbs (the same MainSystem); the old name "
                      "goes away in the next release", AtcmDeprecationWarning, stacklevel=2)
        return self.mbs

    @property
    def stroke_path(self) -> str:
        """How the strains reach the system (:attr:`exudyn_atcm.cells.CellKind.stroke_paths`)."""
        return self.model.stroke_path

    def zeros(self) -> np.ndarray:
        """A zero vector over the drive sources (coefficients per unit strain of each source)."""
        return np.zeros(len(self.model.sources))

    def source(self, bender: Bender, segment: int) -> int | None:
        """The source index of segment ``segment`` of ``bender`` (``None``: the segment has no drive)."""
        if bender.segments[int(segment)].drive is None:
            return None
        return self.model.drive_source[bender.drive_name(int(segment))]

    def body(self, key: str) -> Body:
        """The body (or node) registered under ``key`` (a body key; for a point see :meth:`body_at`)."""
        if isinstance(key, PointRef):
            warnings.warn("BuildContext.body(point) is deprecated; use body_at(point).item (the Exudyn object "
                          "number); body(key) takes a body key", AtcmDeprecationWarning, stacklevel=2)
            return int(self.body_at(key).item)  # type: ignore[return-value]
        return self.model.bodies[key]

    def group(self, bender: Bender, end: str) -> Group:
        """The rigid group that ``end`` of ``bender`` belongs to."""
        return self.groups[self.group_of[f"{bender.name}#{end}"]]

    def group_body(self, bender: Bender, end: str) -> Body:
        """The body of the group that ``end`` of ``bender`` belongs to (a real body: six-bar chains)."""
        return self.model.bodies[self.group(bender, end).key]

    def realisation(self, bender_name: str) -> CellRealisation:
        """The realisation of the bender named ``bender_name``."""
        return self.realisations[bender_name]

    # ------------------------------------------------------------------ points (after the cells exist)
    def reference(self, point: PointRef) -> np.ndarray:
        """Position (x, y) [m] of ``point`` in the reference pose."""
        return self.mechanism.position(point)

    def anchor(self, point: PointRef) -> tuple[Body, np.ndarray]:
        """The body that carries ``point`` and the point's position [m] in that body's frame."""
        try:
            key, local = self.model.anchors[str(point)]
        except KeyError:
            raise MechanismError(f"no body carries the point {point}: it is not a point of the built mechanism "
                                 f"{self.mechanism.name!r}") from None
        return self.model.bodies[key], local

    def body_at(self, point: PointRef) -> Body:
        """The body that carries ``point`` (its ``item`` is the Exudyn object number; the ground on the ground)."""
        return self.anchor(point)[0]

    def is_fixed(self, point: PointRef) -> bool:
        """True if ``point`` sits on the ground (welded to it): loads there have no effect."""
        return self.body_at(point).node is None

    def position_marker(self, point: PointRef) -> int:
        """A new position marker at ``point`` on the body that carries it."""
        return position_marker(self.mbs, *self.anchor(point))

    def rigid_marker(self, point: PointRef) -> int:
        """A new rigid-body marker (position and orientation) at ``point`` on the body that carries it."""
        return rigid_marker(self.mbs, *self.anchor(point))

    def rotation_marker(self, point: PointRef) -> int:
        """The marker of the rotation [rad] from the reference pose of the body that carries ``point``
        (its ODE2 rotation coordinate; a fixed ground coordinate on the ground)."""
        return rotation_marker(self.mbs, self.body_at(point), self.ground_coordinate)

    def ground_marker(self, position: Any) -> int:
        """A new position marker on the ground at ``position`` (x, y) [m]."""
        return position_marker(self.mbs, self.model.bodies[GROUND], position)

    # ------------------------------------------------------------------ bodies and cells
    def add_body(self, key: str, position, angle: float, mass: float, inertia: float, com=(0.0, 0.0),
                 graphics: list | None = None, mass_damping: float = 0.0) -> Body:
        """Add and register a planar rigid body (node at ``position`` [m], reference ``angle`` [rad], centre of
        mass ``com`` [m] in its frame, ``inertia`` [kg m²] about it), damped by ``mass_damping`` [1/s] times its
        mass and inertia."""
        body = add_body(self.mbs, key, position, angle, mass, inertia, com, graphics or [])
        self.model.bodies[key] = body
        self.add_mass_damping(body, mass_damping, mass, inertia, com)
        return body

    def add_mass_damping(self, body: Body, alpha: float, mass: float, inertia: float, center) -> None:
        """Damp ``mass`` [kg] and ``inertia`` [kg m²] at ``center`` (body frame) of ``body`` by ``alpha`` [1/s]."""
        self.dampers.add(body, alpha, mass, inertia, center)

    def register_body(self, body: Body) -> Body:
        """Register a body or node made by the realisation itself under ``body.key``."""
        self.model.bodies[body.key] = body
        return body

    def set_cells(self, bender: Bender, keys: list[str]) -> None:
        """The bodies whose rotations are ``bender``'s cell angles (recorded as ``cell_angle_j``)."""
        self.model.cells[bender.name] = list(keys)

    def add_element_chain(self, bender: Bender, keys: list[str], items: list[int]) -> None:
        """Register a chain of beam elements between nodes ``keys``: the nodes as cells (a cell's angle is the
        mean of its nodes'), the elements (actuated by end torques or reference curvatures)."""
        self.set_cells(bender, keys)
        self.model.elements[bender.name] = list(items)
        self.model.beam_benders.add(bender.name)

    # ------------------------------------------------------------------ items
    def add_object(self, item: Any) -> int:
        """Add an Exudyn object (``exudyn.itemInterface``); its number."""
        return int(self.mbs.AddObject(item))

    def add_marker(self, item: Any) -> int:
        """Add an Exudyn marker; its number."""
        return int(self.mbs.AddMarker(item))

    # ------------------------------------------------------------------ joints and springs between bodies
    def revolute(self, a: Body, la, b: Body, lb) -> None:
        """A revolute joint between point ``la`` of ``a`` and ``lb`` of ``b`` (body frames) [m]."""
        self.add_object(ii.ObjectJointRevolute2D(markerNumbers=[position_marker(self.mbs, a, la),
                                                                position_marker(self.mbs, b, lb)],
                                                 visualization=NOVIS))

    def add_hinge(self, a: str, b: str, elements: list[Element], local_a=None, local_b=None, position=None) -> int:
        """A revolute joint between bodies ``a`` and ``b`` (at ``local_a``/``local_b`` in their frames, or at the
        global ``position``) carrying the series spring of ``elements``; returns the hinge's index.

        (``add_hinge(p, q, stiffness, damping, label)`` with points is the deprecated form of :meth:`add_pin`.)
        """
        if isinstance(a, PointRef):
            warnings.warn("BuildContext.add_hinge(point, point, stiffness, damping, label) is deprecated; use "
                          "add_pin with the same arguments", AtcmDeprecationWarning, stacklevel=2)
            self.add_pin(a, b, elements, local_a, local_b)  # type: ignore[arg-type]
            return len(self.model.hinges) - 1
        body_a, body_b = self.model.bodies[a], self.model.bodies[b]
        if position is not None:
            local_a, local_b = local_point(body_a, position), local_point(body_b, position)
        self.revolute(body_a, local_a, body_b, local_b)
        self.model.hinges.append(Hinge(a, b, elements))
        return len(self.model.hinges) - 1

    def hinge_at(self, a: str, b: str, elements: list[Element], position) -> int:
        """:meth:`add_hinge` at the global ``position`` [m]."""
        return self.add_hinge(a, b, elements, position=position)

    def add_spring(self, item: int, stiffness: Any, damping_parameter: str = "damping") -> None:
        """Register a spring-damper item (``stiffness`` and the name of its damping parameter) for the relaxation."""
        self.model.springs.append((item, stiffness, damping_parameter))

    def add_motor_offset(self, item: int, factor: float, source: int) -> None:
        """A coordinate constraint whose offset is ``factor`` times the strain of ``source``, written per step."""
        self.model.motor_offsets.append((item, factor, source))

    def weld_node(self, node: Body, body: Body) -> None:
        """Weld a bender's end ``node`` to ``body`` (its own weld if it has one; a clamp on the ground)."""
        if node.weld is not None:
            node.weld(self.mbs, body, self.ground_coordinate)
        else:
            weld_node(self.mbs, node, body, self.ground_coordinate)
        if body.node is None:
            self.clamped.add(node.key)

    def set_end_readout(self, bender: Bender, end: str, readout: EndReadout) -> None:
        """How the rotation of ``end`` of ``bender`` is read from the state."""
        self.model.ends[f"{bender.name}.{end}"] = readout

    def join_in_series(self, side_a: str, link: Element | None, side_b: str, position) -> None:
        """A hinge from ``side_a`` to ``side_b`` (body keys, or ``"bender#end"`` for massless end interfaces)
        through the interfaces' end springs and ``link`` (a pin's spring; ``None`` for a weld)."""
        els: list[Element] = []
        keys, nodes = [], []
        for i, (side, forward) in enumerate(((side_a, "tip"), (side_b, "base"))):
            if i == 1 and link is not None:
                els.append(link)
            if not self.is_virtual(side):
                keys.append(side)
                continue
            name, end = side.split("#")
            el, key, _ = self.realisations[name].end_spring(self, end)
            # an interface turns +theta from its cell at the A side's tip and the B side's base, -theta otherwise
            els.append(el if end == forward else Element(el.stiffness, el.damping, -el.theta, -el.moment))
            keys.append(key)
            nodes.append((f"{name}.{end}", len(els) if i == 0 else len(els) - 1))
        index = self.hinge_at(keys[0], keys[1], els, position)
        for name, node in nodes:
            self.model.ends[name] = EndReadout("hinge", hinge=index, node=node)

    def is_virtual(self, side: str) -> bool:
        """True if ``side`` is a bender-end part of a massless (virtual) group (not a body key)."""
        return side in self.group_of and self.groups[self.group_of[side]].kind == "virtual"

    # ------------------------------------------------------------------ joints, springs and loads at points
    def side(self, point: PointRef | None) -> str:
        """The group key of ``point``'s part (``None``: the ground), or the part if it is a massless bender end."""
        part = part_of(self.mechanism, point)
        g = self.groups[self.group_of[part]]
        return part if g.kind == "virtual" else g.key

    def _movable(self, label: str, side_a: str, side_b: str) -> None:
        """Refuse a joint between two points of one rigid group (welded together): it could not move."""
        if side_a == side_b:
            group = self.groups[self.group_of[side_a]] if side_a in self.group_of else self.groups[side_a]
            parts = ", ".join(sorted(p.replace("#", ".") for p in group.parts))
            raise MechanismError(f"{label} joins two points of one rigid group (welded together: {parts}); it cannot "
                                 "move. Remove the joint or one of the welds")

    def add_pin(self, p: PointRef, q: PointRef | None, stiffness: float, damping: float, label: str) -> None:
        """A revolute joint at ``p`` (= ``q``; ``None``: the ground) with a torsion spring [N m/rad] and
        damper [N m s/rad] in series with the bender ends' own springs; ``label`` names it in messages."""
        side_a, side_b = self.side(p), self.side(q)
        self._movable(label, side_a, side_b)
        pin = Element(stiffness, damping, self.zeros(), self.zeros())
        self.join_in_series(side_a, pin, side_b, self.reference(p))

    def add_slider(self, p: PointRef, q: PointRef | None, axis: tuple[float, float], stiffness: float,
                   damping: float, label: str) -> None:
        """A prismatic joint along ``axis`` (global, reference pose) with an axial spring [N/m] and damper [N s/m]."""
        a, b = self.side(p), self.side(q)
        self._movable(label, a, b)
        body_a, body_b = self.model.bodies[a], self.model.bodies[b]
        la = local_point(body_a, self.reference(p))
        lb = local_point(body_b, self.reference(p if q is None else q))
        ca, sa = math.cos(body_a.reference[2]), math.sin(body_a.reference[2])
        cb, sb = math.cos(body_b.reference[2]), math.sin(body_b.reference[2])
        ax, ay = axis
        axis_a = [ca * ax + sa * ay, -sa * ax + ca * ay, 0.0]
        normal_b = [cb * (-ay) + sb * ax, -sb * (-ay) + cb * ax, 0.0]
        ma, mb = rigid_marker(self.mbs, body_a, la), rigid_marker(self.mbs, body_b, lb)
        self.add_object(ii.ObjectJointPrismatic2D(markerNumbers=[ma, mb], axisMarker0=axis_a, normalMarker1=normal_b,
                                                  constrainRotation=True, visualization=NOVIS))
        if stiffness > 0.0 or damping > 0.0:
            # the sliding coordinate: relative translation along the axis (zero in the reference pose)
            coord = self.add_marker(ii.MarkerBodiesRelativeTranslationCoordinate(
                bodyNumbers=[body_a.item, body_b.item], localPosition0=[la[0], la[1], 0.0],
                localPosition1=[lb[0], lb[1], 0.0], axis0=axis_a))
            self.add_spring(self.add_object(ii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[self.ground_coordinate, coord], stiffness=stiffness, damping=damping,
                visualization=NOVIS)), stiffness)

    def add_force(self, point: PointRef, value: Any, *, follower: bool = False, name: str = "") -> None:
        """A point force [N] (pair or callable of time), dead or follower, written per step (warns on the ground)."""
        loads.add_force(self.mbs, self.model, point, value, follower, name)

    def add_torque(self, component: str, value: Any, *, name: str = "") -> None:
        """A torque [N m] (number or callable of time) on a rigid component's body, written per step."""
        loads.add_torque(self.mbs, self.model, component, value, name)

    def add_spring_damper(self, p: PointRef, q: PointRef, stiffness: float, damping: float,
                          rest_length: float | None, name: str) -> int:
        """A spring-damper [N/m], [N s/m] between two points (rest length [m], ``None``: their reference
        distance); its object number (its ``ForceLocal`` output is the tension)."""
        rest = loads.reference_distance(self.reference(p), self.reference(q)) if rest_length is None \
            else float(rest_length)
        markers = [self.position_marker(p), self.position_marker(q)]
        return loads.add_spring_damper(self.mbs, self.model, markers, stiffness, damping, rest, name)

    def add_contact(self, point: PointRef, position: Any, normal: Any, stiffness: float, damping: float,
                    name: str) -> int:
        """A one-sided contact of ``point`` with a ground wall through ``position`` [m] on the free side of
        ``normal``, stiffness [N/m], damping [N s/m]; its object number (``Force`` output)."""
        markers = [self.ground_marker(position), self.position_marker(point)]
        return loads.add_contact(self.mbs, self.model, markers, normal, stiffness, damping, name)

    def add_rotational_spring(self, p: PointRef, q: PointRef, torque: Callable[[float, float], float]) -> int:
        """A torsional connector between the bodies carrying ``p`` and ``q``: ``torque(angle, rate)``
        [N m] of their relative rotation [rad] from the reference pose and its rate [rad/s] acts on
        ``q``'s body as ``-torque`` and on ``p``'s as ``+torque`` (a spring resisting the rotation
        for a positive slope).  Its ``Force`` output is the torque; its object number."""
        m0, m1 = self.rotation_marker(p), self.rotation_marker(q)

        def user(mbs, t, item, u, v, k, d, offset):
            return float(torque(u, v))

        return self.add_object(ii.ObjectConnectorCoordinateSpringDamper(
            markerNumbers=[m0, m1], stiffness=0.0, damping=0.0, springForceUserFunction=user, visualization=NOVIS))

    # ------------------------------------------------------------------ read-outs
    def output(self, item: int, variable: str) -> Callable[[], Any]:
        """A function reading Exudyn object ``item``'s output ``variable`` (an
        ``exudyn.OutputVariableType`` name such as ``"Force"``) in the current state."""
        kind = getattr(exu.OutputVariableType, variable, None)
        if kind is None:
            raise ValueError(f"variable must be an exudyn.OutputVariableType name such as 'Force', got {shown(variable)}")
        return partial(self.mbs.GetObjectOutput, item, kind)

    def add_readout(self, readout: Readout, read: Callable[[], Any]) -> None:
        """Record ``read()`` (a float in ``readout.unit``) as the result column ``readout.column``."""
        if not isinstance(readout, Readout) or not callable(read):
            raise ValueError(f"add_readout takes a Readout and a callable, got {shown(readout)} and {read!r}")
        self.model.readouts.append((readout, read))

    def recorded(self) -> tuple[Readout, ...]:
        """The columns recorded so far (:meth:`add_readout`), in order."""
        return tuple(r for r, _ in self.model.readouts)

    # ------------------------------------------------------------------ per step and solver
    def add_strain_writer(self, writer: Callable[[np.ndarray], None]) -> None:
        """Call ``writer(strains)`` before every attempted step (and whenever the strains are set)."""
        self.model.strain_writers.append(writer)

    def add_linearisation_hook(self, hook: Callable[[np.ndarray], None]) -> None:
        """Call ``hook(strains)`` before an eigenvalue analysis."""
        self.model.linearisation_hooks.append(hook)

    def add_settings_adjuster(self, adjust: Callable[[Any], None]) -> None:
        """Let the package's runs change their solver settings with ``adjust(settings)``."""
        self.model.settings_adjusters.append(adjust)

    def mark_varying_mass(self, bender: Bender) -> None:
        """The bender's mass matrix changes from step to step: the package's runs let Exudyn re-read it."""
        self.model.varying_mass_benders.append(bender.name)

    def set_truncation_estimator(self, bender: Bender, estimate: Callable[[], float], *,
                                 deferred: tuple[Callable[[], Any], Callable[[list], Any]] | None = None) -> None:
        """``estimate()``: the tip error [m] of the bender's discretisation in a static state.

        ``deferred``: optionally ``(read, many)``, the same estimate in two parts for a static sweep:
        ``read()`` a cheap reading of the current state, ``many(readings)`` the errors [m] of many
        states at once (after the sweep)."""
        self.model.truncation_estimators[bender.name] = estimate
        if deferred is not None:
            self.model.truncation_deferred[bender.name] = deferred

    def add_post_newton(self, check: Callable[[Any, float], float]) -> None:
        """A check after every Newton solve (see :func:`~exudyn_atcm.mbs.hooks.add_post_newton`)."""
        add_post_newton(self.mbs, check)

    def require_static_absolute_tolerance(self, tolerance: float) -> None:
        """The static solves' absolute Newton tolerance is at most ``tolerance`` [SI]."""
        self.model.static_absolute_tolerance = min(tolerance, self.model.static_absolute_tolerance or math.inf)

    def set_static_relative_tolerance(self, tolerance: float) -> None:
        """The static solves' relative Newton tolerance."""
        self.model.static_relative_tolerance = tolerance

    def raise_newton_tolerance_floor(self, floor: float) -> None:
        """The smallest absolute Newton tolerance the model can reach is at least ``floor`` [SI]."""
        self.model.newton_tolerance_floor = max(self.model.newton_tolerance_floor, floor)
