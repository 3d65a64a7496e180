"""The build context: what a cell's realisation (:mod:`~exudyn_atcm.mbs.realisation`) writes through.

One :class:`BuildContext` exists per build of a mechanism into an Exudyn ``MainSystem``; the builder
(:mod:`~exudyn_atcm.mbs.builder`) is one.  A realisation reads the system, the mechanism and the
layout from it and adds its items, cells, springs, hinges, strain writers and tolerances with its
methods; it never writes the builder's or the model's attributes itself.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from exudyn import itemInterface as ii

from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from .hooks import add_post_newton
from .items import NOVIS, add_body, local_point, position_marker
from .layout import Group
from .mass_damping import MassDampers
from .model import Body, Element, EndReadout, Hinge, MechanismModel
from .node_chain import weld_node
from .realisation import CellRealisation

__all__ = ["BuildContext"]


class BuildContext:
    """The public handle of one build (``mbs``, ``mechanism``, ``model`` and the layout, read-only by convention).

    Attributes
    ----------
    mbs : exudyn MainSystem
        The system being built.
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
        """The body (or node) registered under ``key``."""
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

    # ------------------------------------------------------------------ joints and springs
    def revolute(self, a: Body, la, b: Body, lb) -> None:
        """A revolute joint between point ``la`` of ``a`` and ``lb`` of ``b`` (body frames) [m]."""
        self.mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[position_marker(self.mbs, a, la),
                                                                   position_marker(self.mbs, b, lb)],
                                                    visualization=NOVIS))

    def add_hinge(self, a: str, b: str, elements: list[Element], local_a=None, local_b=None, position=None) -> int:
        """A revolute joint between bodies ``a`` and ``b`` (at ``local_a``/``local_b`` in their frames, or at the
        global ``position``) carrying the series spring of ``elements``; returns the hinge's index."""
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
        a_key, a_node = side_a, None
        if self.is_virtual(side_a):
            name, end = side_a.split("#")
            el, a_key, _ = self.realisations[name].end_spring(self, end)
            # tip on the A side: the interface turns +theta from the cell; base: -theta
            els.append(el if end == "tip" else _flipped(el))
            a_node = (f"{name}.{end}", 1)
        if link is not None:
            els.append(link)
        b_key, b_node = side_b, None
        if self.is_virtual(side_b):
            name, end = side_b.split("#")
            el, b_key, _ = self.realisations[name].end_spring(self, end)
            els.append(el if end == "base" else _flipped(el))
            b_node = (f"{name}.{end}", len(els) - 1)
        index = self.hinge_at(a_key, b_key, els, position)
        for node in (a_node, b_node):
            if node is not None:
                self.model.ends[node[0]] = EndReadout("hinge", hinge=index, node=node[1])

    def is_virtual(self, side: str) -> bool:
        """True if ``side`` is a bender-end part of a massless (virtual) group (not a body key)."""
        return side in self.group_of and self.groups[self.group_of[side]].kind == "virtual"

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

    def set_truncation_estimator(self, bender: Bender, estimate: Callable[[], float]) -> None:
        """``estimate()``: the tip error [m] of the bender's discretisation in a static state."""
        self.model.truncation_estimators[bender.name] = estimate

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


def _flipped(el: Element) -> Element:
    return Element(el.stiffness, el.damping, -el.theta, -el.moment)
