"""A planar mechanism: components, connections, loads, and the checks that it can be built."""

from __future__ import annotations

import math
import dataclasses
from typing import Any, Union

import numpy as np

from .._checks import finite_float, shown
from .bender import Bender
from .connection import Connection
from .joints import Joint, JointBase, Pin, Slider, Weld, joint_label
from .loads import Force, Spring, Stop, Torque
from .flexure import Flexure
from .link import Link
from .assembly_checks import check_assembly, check_connected, check_drives
from .realisation import check_redundancy, count_degrees_of_freedom
from .points import GROUND, MechanismError, PointRef, check_name, closest

Component = Union[Bender, Link, Flexure]
PointLike = Union[PointRef, str]

#: Joined points may be apart by this much relative to the mechanism's size in the reference pose.
ASSEMBLY_TOLERANCE = 1e-9


def _nonneg(name: str, value: Any) -> float:
    number = finite_float(name, value)
    if number < 0.0:
        raise MechanismError(f"{name} must be >= 0, got {shown(value)}")
    return number


def _vector(name: str, value: Any) -> tuple[float, float]:
    try:
        x, y = value
    except (TypeError, ValueError):
        raise MechanismError(f"{name} must be a pair of finite numbers, got {shown(value)}") from None
    return finite_float(f"{name}[0]", x), finite_float(f"{name}[1]", y)


class Mechanism:
    """A planar mechanism of benders, links and flexures, described in its assembled reference pose.

    Parameters
    ----------
    name : str, optional
        Name of the mechanism (default ``"mechanism"``).

    Notes
    -----
    Build it with :meth:`add`, connect points with :meth:`weld`, :meth:`pin`, :meth:`slider`
    and :meth:`ground`, load it with :meth:`force`, :meth:`torque`, :meth:`spring` and
    :meth:`stop`, or add any object of the connection protocol
    (:mod:`exudyn_atcm.mechanism.connection`) with :meth:`add_connection`; all are kept in
    one list, :attr:`connections`.  Points are :class:`PointRef` objects (``bender.tip``, ``link.point("P")``)
    or strings ``"component.point"``.  Names are resolved when a connection is made (the
    components must have been added); :meth:`check` runs the whole-mechanism checks, and
    every solve runs it first.  All errors are :class:`MechanismError` (a ``ValueError``)
    naming the parts involved.

    Examples
    --------
    >>> from exudyn_atcm import Layer
    >>> strip = Bender("strip", width=5e-3, passive=Layer(0.2e-3, 70e9, 1550), length=0.03, n_cells=4)
    >>> mech = Mechanism().add(strip)
    >>> mech.ground(strip.base).force(strip.tip, (0.0, 1e-3)).check()
    """

    def __init__(self, name: str = "mechanism") -> None:
        self.name = check_name("Mechanism name", name)
        self.components: dict[str, Component] = {}
        #: every joint and load, in the order added (the one list the build, the recording, the
        #: parameters and the drawings iterate)
        self.connections: list[Connection] = []
        #: drive name -> result column its controller observes (see :meth:`feedback`)
        self.measurements: dict[str, str] = {}

    # ------------------------------------------------------------------ building
    def add(self, *components: Component) -> "Mechanism":
        """Add components (:class:`Bender`, :class:`Link`, :class:`Flexure`); returns the mechanism."""
        for comp in components:
            if not isinstance(comp, (Bender, Link, Flexure)):
                raise MechanismError(f"components must be Bender, Link or Flexure objects, got {shown(comp)}")
            if comp.name == GROUND:
                raise MechanismError(f"the component name {GROUND!r} is reserved for the ground; rename {comp!r}")
            if comp.name in self.components:
                raise MechanismError(
                    f"duplicate component name {comp.name!r}: {self.components[comp.name]!r} and {comp!r}; "
                    "every component needs its own name")
            if comp.name in self._load_names():
                raise MechanismError(f"component name {comp.name!r} is already the name of a spring or stop")
            self.components[comp.name] = comp
        return self

    def resolve(self, point: PointLike) -> PointRef:
        """The :class:`PointRef` of ``point``, checked against the added components."""
        ref = PointRef.parse(point)
        comp = self.components.get(ref.component)
        if comp is None:
            known = list(self.components)
            raise MechanismError(
                f"unknown component {ref.component!r} in point {str(ref)!r}{closest(ref.component, known)} "
                f"(components: {', '.join(known) if known else 'none added yet'}; add it first with mechanism.add)")
        return comp.point(ref.point)

    def position(self, point: PointLike) -> np.ndarray:
        """Position of ``point`` in the reference pose [m]."""
        ref = self.resolve(point)
        return np.array(self.components[ref.component].points[ref.point], dtype=float)

    def add_connection(self, connection: Connection) -> "Mechanism":
        """Add a joint or load of the connection protocol (:mod:`exudyn_atcm.mechanism.connection`).

        Refused (:class:`MechanismError`) unless it implements the protocol, its name is new among
        the components and connections, and its points and components exist in this mechanism.
        """
        missing = [m for m in ("points", "components", "parameters", "describe", "readouts", "realise", "draw")
                   if not callable(getattr(connection, m, None))]
        if missing or not isinstance(getattr(connection, "name", None), str):
            raise MechanismError(f"add_connection: {connection!r} does not implement the connection protocol "
                                 f"(missing: {', '.join(missing) or 'a str name'}); derive it from ConnectionBase")
        if connection.holds:  # a joint: its own checks, named joint_k unless named
            if not isinstance(connection, JointBase):
                raise MechanismError(f"add_connection: {connection!r} has holds=True, which is for joints: subclasses "
                                     "of JointBase (points p and q) that the rigid groups and the ground check use")
            connection = self._checked_joint(connection)
        check_name("connection name", connection.name)
        if connection.name in self._load_names() or connection.name in self.components:
            raise MechanismError(f"duplicate name {connection.name!r}: loads, springs, stops and components "
                                 "need distinct names")
        what = connection.describe()
        for ref in connection.points():
            if not isinstance(ref, PointRef):
                raise MechanismError(f"{what}: points() must give PointRef objects, got {shown(ref)}")
            try:
                self.resolve(ref)
            except MechanismError as exc:
                raise MechanismError(f"{what}: {exc}") from None
        for cname in connection.components():
            if cname not in self.components:
                raise MechanismError(f"{what}: unknown component {cname!r}{closest(str(cname), self.components)} "
                                     f"(components: {', '.join(self.components) or 'none added yet'})")
        self.connections.append(connection)
        return self

    def _joint(self, joint: Joint) -> "Mechanism":
        return self.add_connection(joint)

    def _checked_joint(self, joint: JointBase) -> JointBase:
        if joint.q is not None and joint.p.component == joint.q.component:
            raise MechanismError(
                f"{joint_label(joint)} connects component {joint.p.component!r} to itself; "
                "connections join two different components (or a component and the ground)")
        key = frozenset((str(joint.p), GROUND if joint.q is None else str(joint.q)))
        for other in self.joints:
            okey = frozenset((str(other.p), GROUND if other.q is None else str(other.q)))
            if okey == key:
                how = "twice" if type(other) is type(joint) else "in conflicting ways"
                raise MechanismError(
                    f"{joint_label(joint)}: the points {' and '.join(sorted(key))} are already joined by "
                    f"{joint_label(other)}; a pair of points can be joined once only (joined {how})")
        return joint if joint.name else dataclasses.replace(joint, name=f"joint_{len(self.joints) + 1}")

    def _other(self, q: PointLike | None) -> PointRef | None:
        return None if q is None else self.resolve(q)

    def weld(self, p: PointLike, q: PointLike) -> "Mechanism":
        """Rigid connection of ``p`` and ``q``: positions and relative angle fixed."""
        return self._joint(Weld(self.resolve(p), self.resolve(q)))

    def pin(self, p: PointLike, q: PointLike, *, stiffness: float = 0.0, damping: float = 0.0) -> "Mechanism":
        """Revolute joint at ``p`` = ``q`` with an optional torsion spring [N m/rad] and damper [N m s/rad]."""
        return self._joint(Pin(self.resolve(p), self.resolve(q), _nonneg("stiffness", stiffness),
                               _nonneg("damping", damping)))

    def slider(self, p: PointLike, q: PointLike, *, axis: tuple[float, float] = (1.0, 0.0), stiffness: float = 0.0,
               damping: float = 0.0) -> "Mechanism":
        """Prismatic joint: ``q`` slides along ``axis`` (global, reference pose) relative to ``p``'s body.

        Optional axial spring [N/m] and damper [N s/m] on the sliding coordinate (zero in the
        reference pose).
        """
        return self._joint(Slider(self.resolve(p), self.resolve(q), self._axis(axis),
                                  _nonneg("stiffness", stiffness), _nonneg("damping", damping)))

    def ground(self, p: PointLike, joint: str = "weld", *, stiffness: float = 0.0, damping: float = 0.0,
               axis: tuple[float, float] | None = None) -> "Mechanism":
        """Connect ``p`` to the ground by ``joint`` = ``"weld"``, ``"pin"`` or ``"slider"`` (along ``axis``)."""
        ref = self.resolve(p)
        if joint == "weld":
            if stiffness or damping or axis is not None:
                raise MechanismError(f"ground({ref}, joint='weld') takes no stiffness, damping or axis")
            return self._joint(Weld(ref, None))
        if joint == "pin":
            if axis is not None:
                raise MechanismError(f"ground({ref}, joint='pin') takes no axis")
            return self._joint(Pin(ref, None, _nonneg("stiffness", stiffness), _nonneg("damping", damping)))
        if joint == "slider":
            return self._joint(Slider(ref, None, self._axis((1.0, 0.0) if axis is None else axis),
                                      _nonneg("stiffness", stiffness), _nonneg("damping", damping)))
        raise MechanismError(f"joint must be 'weld', 'pin' or 'slider', got {shown(joint)}")

    @staticmethod
    def _axis(axis: Any) -> tuple[float, float]:
        ax, ay = _vector("axis", axis)
        norm = math.hypot(ax, ay)
        if norm == 0.0:
            raise MechanismError(f"axis must be a non-zero direction (x, y), got {shown(axis)}")
        return ax / norm, ay / norm

    # ------------------------------------------------------------------ loads
    def _load_names(self) -> set[str]:
        return {c.name for c in self.connections}

    def _load_name(self, name: str | None, prefix: str, count: int) -> str:
        if name is None:
            name = f"{prefix}_{count + 1}"
        name = check_name(f"{prefix} name", name)
        if name in self._load_names() or name in self.components:
            raise MechanismError(f"duplicate name {name!r}: loads, springs, stops and components need distinct names")
        return name

    def force(self, p: PointLike, force: Any, *, follower: bool = False, name: str | None = None) -> "Mechanism":
        """Point force at ``p``: ``(Fx, Fy)`` [N] or a callable ``t -> (Fx, Fy)``.

        Dead (fixed global direction) by default; ``follower=True``: given in the reference
        pose, it turns with the body that carries ``p``.
        """
        ref = self.resolve(p)
        if not callable(force):
            force = _vector("force", force)
        if not isinstance(follower, bool):
            raise MechanismError(f"follower must be True or False, got {shown(follower)}")
        return self.add_connection(Force(ref, force, follower, self._load_name(name, "force", len(self.forces))))

    def torque(self, component: str | Link, torque: Any, *, name: str | None = None) -> "Mechanism":
        """Torque [N m] (number or callable of t) on a link, counter-clockwise positive."""
        cname = component.name if isinstance(component, (Bender, Link, Flexure)) else component
        comp = self.components.get(cname)
        if comp is None:
            raise MechanismError(f"torque: unknown component {cname!r}{closest(str(cname), self.components)}")
        if not isinstance(comp, Link):
            raise MechanismError(
                f"torque: {cname!r} is a {type(comp).__name__}; torques act on links (weld a Link to the "
                "bender or flexure end and load the link)")
        if not callable(torque):
            torque = finite_float("torque", torque)
        return self.add_connection(Torque(cname, torque, self._load_name(name, "torque", len(self.torques))))

    def spring(self, p: PointLike, q: PointLike, stiffness: float, *, damping: float = 0.0,
               rest_length: float | None = None, name: str | None = None) -> "Mechanism":
        """Linear spring-damper [N/m], [N s/m] between two points (e.g. a grasped object).

        ``rest_length`` [m] defaults to the points' distance in the reference pose; its
        force (tension positive) is recorded as ``{name}.force [N]``.
        """
        pr, qr = self.resolve(p), self.resolve(q)
        if pr == qr:
            raise MechanismError(f"spring between {pr} and itself")
        k = finite_float("stiffness", stiffness)
        if k <= 0.0:
            raise MechanismError(f"spring stiffness must be > 0 N/m, got {shown(stiffness)}")
        if rest_length is not None:
            rest_length = _nonneg("rest_length", rest_length)
        distance = float(np.linalg.norm(self.position(pr) - self.position(qr)))
        if distance == 0.0:
            raise MechanismError(
                f"spring {pr}-{qr}: the points coincide in the reference pose, so the spring has no direction; "
                "attach it between points that are apart")
        return self.add_connection(Spring(pr, qr, k, _nonneg("damping", damping), rest_length,
                                          self._load_name(name, "spring", len(self.springs))))

    def stop(self, p: PointLike, *, position: tuple[float, float], normal: tuple[float, float], stiffness: float,
             damping: float = 0.0, name: str | None = None) -> "Mechanism":
        """One-sided contact of ``p`` with a wall through ``position`` [m] whose free side is ``normal``.

        The force ``stiffness * pen`` [N] (plus ``damping`` times the approach speed) acts on
        ``p`` along ``normal`` while the penetration ``pen = -(x_p - position) . normal > 0``.
        """
        ref = self.resolve(p)
        nx, ny = _vector("normal", normal)
        norm = math.hypot(nx, ny)
        if norm == 0.0:
            raise MechanismError(f"stop normal must be a non-zero direction, got {shown(normal)}")
        k = finite_float("stiffness", stiffness)
        if k <= 0.0:
            raise MechanismError(f"stop stiffness must be > 0 N/m, got {shown(stiffness)}")
        return self.add_connection(Stop(ref, _vector("position", position), (nx / norm, ny / norm), k,
                                        _nonneg("damping", damping), self._load_name(name, "stop", len(self.stops))))

    def feedback(self, drive: str, measurement: str) -> "Mechanism":
        """Declare what the controller of ``drive`` observes: a result column of the mechanism.

        A drive whose voltage is a controller (:mod:`exudyn_atcm.model.control`) needs one; after
        every accepted step of :func:`exudyn_atcm.simulate` the controller's
        ``observe(t, value)`` receives the column's value in SI units.

        Parameters
        ----------
        drive : str
            A drive name (see :class:`Bender`: the bender's name, or ``"name.k"`` per segment).
        measurement : str
            A result column name, without or with its unit: a point's coordinate
            (``"crank.tip_y"`` [m]), an angle (``"lever.angle"``, ``"crank.tip_angle"`` [rad]) or a
            spring or stop force (``"object.force"`` [N]).  Checked when the run starts.
        """
        if drive not in self.drives:
            raise MechanismError(f"feedback: unknown drive {drive!r}{closest(str(drive), self.drives)} "
                                 f"(drives: {', '.join(self.drives) or 'none'})")
        if not isinstance(measurement, str) or not measurement:
            raise MechanismError(f"feedback: measurement must be a result column name such as 'crank.tip_y', "
                                 f"got {shown(measurement)}")
        self.measurements[drive] = measurement
        return self

    # ------------------------------------------------------------------ queries
    def _of_type(self, kind: type) -> tuple:
        return tuple(c for c in self.connections if isinstance(c, kind))

    # read-only views of :attr:`connections` (tuples: add through the methods or add_connection)
    @property
    def joints(self) -> tuple[Joint, ...]:
        """The connections that hold parts together (weld, pin, slider), in order."""
        return tuple(c for c in self.connections if c.holds)

    @property
    def forces(self) -> tuple[Force, ...]:
        """The point forces (:meth:`force`)."""
        return self._of_type(Force)

    @property
    def torques(self) -> tuple[Torque, ...]:
        """The torques (:meth:`torque`)."""
        return self._of_type(Torque)

    @property
    def springs(self) -> tuple[Spring, ...]:
        """The springs between points (:meth:`spring`)."""
        return self._of_type(Spring)

    @property
    def stops(self) -> tuple[Stop, ...]:
        """The one-sided stops (:meth:`stop`)."""
        return self._of_type(Stop)

    @property
    def benders(self) -> list[Bender]:
        """Benders, and flexures of the ``"cells"`` model as passive benders, in insertion order."""
        out = []
        for comp in self.components.values():
            if isinstance(comp, Bender):
                out.append(comp)
            elif isinstance(comp, Flexure) and comp.model == "cells":
                out.append(comp.as_bender())
        return out

    @property
    def drives(self) -> dict[str, Any]:
        """Every drive by name (see :class:`Bender`)."""
        out: dict[str, Any] = {}
        for comp in self.components.values():
            if isinstance(comp, Bender):
                out.update(comp.drives)
        return out

    @property
    def size(self) -> float:
        """Extent of the mechanism in the reference pose [m] (largest span of its points)."""
        pts = np.array([p for c in self.components.values() for p in c.points.values()], dtype=float)
        if pts.size == 0:
            return 0.0
        return float(max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1]),
                         max((c.length for c in self.components.values() if not isinstance(c, Link)), default=0.0)))

    def parameters(self) -> dict[str, Any]:
        """A flat description of the mechanism, parameters with units."""
        out: dict[str, Any] = {"mechanism": self.name}
        for comp in self.components.values():
            out.update(comp.parameters())
        for connection in self.connections:
            out.update(connection.parameters())
        return out

    def degrees_of_freedom(self):
        """Degrees of freedom of the built multibody model (Exudyn's ``ComputeSystemDegreeOfFreedom``).

        Every rigid cell of a bender is a body, so a bender of ``N`` cells contributes
        compliant degrees of freedom; a mechanism of rigid links alone gives its Gruebler count.

        Returns
        -------
        exudyn_atcm.mbs.DofReport
            ``dof``, ``coordinates``, ``constraints`` and ``redundant`` (dependent constraints,
            e.g. of an over-constrained loop).
        """
        return count_degrees_of_freedom(self)

    # ------------------------------------------------------------------ checks
    def check(self, *, grounded: bool = True, redundancy: bool = True) -> None:
        """Check the whole mechanism; raises :class:`MechanismError` naming the parts.

        Checks: at least one component; a connection to the ground; every component
        connected to the ground through joints; every joint's points coincide in the
        reference pose (slider: ``q`` on the axis line through ``p``) within
        ``1e-9`` times the mechanism's size; drives do not share one hysteresis operator;
        no dependent joints (the rank of the built model's constraint Jacobian in the reference
        pose, for every cell kind, :mod:`exudyn_atcm.mbs.redundancy`): refused naming them, as
        joints that repeat what others fix (three pins pairwise at one point) or a chain of
        cells that cannot stretch held straight between two points at its length (a rigid, six-bar
        or rod bender welded to the ground at both ends; beam elements stretch).
        :meth:`degrees_of_freedom` counts them without refusing.  (This check needs the Exudyn
        layer that ``import exudyn_atcm`` loads.)

        Parameters
        ----------
        grounded : bool, optional
            ``False`` leaves out the ground and redundancy checks (for :func:`exudyn_atcm.add_to`).
        redundancy : bool, optional
            ``False`` leaves out the redundancy check (each solve makes it on the model it builds).
        """
        if not self.components:
            raise MechanismError(f"mechanism {self.name!r} has no components; add benders, links or flexures")
        for bender in self.benders:  # a discretisation left to the package: chosen by an accuracy run only
            bender.n_cells  # noqa: B018 - raises, naming the bender and what to do
            bender.cell  # noqa: B018
        if not grounded:
            check_assembly(self, ASSEMBLY_TOLERANCE)
            check_drives(self)
            return
        if not any(j.q is None for j in self.joints):
            raise MechanismError(
                f"mechanism {self.name!r} has no ground connection; connect at least one point to the ground "
                f"with mechanism.ground(point) (components: {', '.join(self.components)})")
        check_connected(self)
        check_assembly(self, ASSEMBLY_TOLERANCE)
        check_drives(self)
        if redundancy:
            check_redundancy(self)

    def __repr__(self) -> str:
        return (f"Mechanism({self.name!r}: {len(self.components)} components, {len(self.joints)} joints, "
                f"{len(self.connections) - len(self.joints)} loads and other connections)")


__all__ = ["Mechanism", "MechanismError", "ASSEMBLY_TOLERANCE"]
