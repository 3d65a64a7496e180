"""The handle of a mechanism built into an Exudyn system: bodies, hinges, drives, loads, read-outs.

Built by :mod:`exudyn_atcm.mbs.builder`.  The model writes the actuation (free strains of
the drives) and the loads into the system for each step, and turns recorded ODE2
coordinates into point positions and angles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from ..mechanism.assembly import Mechanism


@dataclass
class Body:
    """A body of the built model (``node is None`` for the ground).

    ``node_only``: a beam bender's node (:mod:`exudyn_atcm.mbs.chains.beam`); its markers are node
    markers at the node itself, and ``item`` is the number of a beam element attached to it.
    """

    key: str
    node: int | None
    item: int
    reference: np.ndarray          # x, y, angle of the node in the reference pose
    rot_marker: Any = None
    ode2: int = -1                 # first ODE2 index (set after Assemble)
    node_only: bool = False
    #: ANCF node (position and slope): orientation markers go on the element ``item`` at local x
    #: ``element_x`` [m], and the angle is the slope's
    slope_at: float | None = None
    #: pose rows (n, 3) from rows of ODE2 coordinates, for bodies whose pose is not their node's
    #: first three coordinates (assumed-modes benders)
    pose_function: Any = None
    #: ``weld(mbs, body, ground_coordinate)``: how this end node is welded to its group's ``body`` when not
    #: by :func:`~exudyn_atcm.mbs.node_chain.weld_node` (an ANCF base: position and slope clamped; an
    #: assumed-modes base: clamped by the modes themselves, nothing to add)
    weld: Any = None

    def pose_rows(self, q: np.ndarray) -> np.ndarray:
        """Pose ``(x, y, angle)`` rows [m, m, rad] from rows ``q`` of ODE2 coordinates (shape (n, nODE2))."""
        if self.node is None:
            return np.tile(self.reference, (q.shape[0], 1))
        if self.pose_function is not None:
            return self.pose_function(q)
        if self.slope_at is not None:
            c = q[:, self.ode2:self.ode2 + 4]
            a = self.reference[2]
            slope = np.arctan2(math.sin(a) + c[:, 3], math.cos(a) + c[:, 2])
            angle = a + np.remainder(slope - a + math.pi, 2.0 * math.pi) - math.pi
            return np.column_stack([self.reference[0] + c[:, 0], self.reference[1] + c[:, 1], angle])
        return self.reference + q[:, self.ode2:self.ode2 + 3]


@dataclass
class Element:
    """A compliance on a hinge: stiffness [N m/rad] (``inf``: rigid), damping, rest angle and moment per strain."""

    stiffness: float
    damping: float
    theta: np.ndarray              # rest angle per unit strain of each source [rad]
    moment: np.ndarray             # stiffness * theta, computed exactly where possible [N m]


@dataclass
class Hinge:
    """Revolute joint between bodies ``a`` and ``b`` with the series spring of its elements."""

    a: str
    b: str
    elements: list[Element]
    stiffness: float = 0.0
    moment: np.ndarray | None = None   # rest-angle moment per strain of each source (+ on b, - on a)
    spring_item: int = -1


@dataclass
class EndReadout:
    """How a bender end's interface rotation is obtained from the state."""

    kind: str                      # "body" | "free" | "hinge"
    body: str = ""                 # "body": the group body; "free": the end cell
    sign: float = 1.0              # "free": +1 tip, -1 base
    theta: np.ndarray | None = None
    hinge: int = -1                # "hinge": index into model.hinges
    node: int = 0                  # "hinge": the interface sits after this many elements


@dataclass
class LoadRecord:
    """A force or torque load whose value may change per step."""

    load: int
    kind: str                      # "force" | "torque"
    value: Any                     # tuple / float or callable of t
    follower: bool = False
    rotation: float = 0.0          # follower: reference angle of the carrying body
    free_end: EndReadout | None = None  # follower on a free interface: turns with the interface
    name: str = ""

    def at(self, t: float) -> tuple[float, ...]:
        """The load's value at time ``t`` [s]: ``(Fx, Fy)`` [N] or ``(T,)`` [N m], checked finite."""
        value = self.value(t) if callable(self.value) else self.value
        try:
            out = (float(value),) if self.kind == "torque" else (float(value[0]), float(value[1]))
            if len(out) == 2 and len(value) != 2:
                raise TypeError
        except (TypeError, ValueError, IndexError):
            out = None
        if out is None or not all(math.isfinite(v) for v in out):
            what = "a finite torque [N m]" if self.kind == "torque" else "a pair (Fx, Fy) of finite forces [N]"
            raise ValueError(f"{self.kind} {self.name!r} gave {value!r} at t = {t!r} s; it must give {what}")
        return out


@dataclass
class MechanismModel:
    """Handles of a mechanism inside an Exudyn system (internal; see :func:`exudyn_atcm.add_to`)."""

    mechanism: Mechanism
    mbs: Any
    SC: Any = None
    bodies: dict[str, Body] = field(default_factory=dict)
    anchors: dict[str, tuple[str, np.ndarray]] = field(default_factory=dict)
    hinges: list[Hinge] = field(default_factory=list)
    sources: list[Any] = field(default_factory=list)          # unique PiezoDrive objects
    drive_source: dict[str, int] = field(default_factory=dict)  # drive name -> source index
    torque_loads: list[tuple[int, np.ndarray]] = field(default_factory=list)
    motor_offsets: list[tuple[int, float, int]] = field(default_factory=list)  # six-bar: (item, L_c, source)
    loads: list[LoadRecord] = field(default_factory=list)
    spring_items: dict[str, int] = field(default_factory=dict)  # spring/stop name -> Exudyn object
    # the connections' recorded columns and their readers (BuildContext.add_readout), in column order
    readouts: list[tuple[Any, Callable[[], Any]]] = field(default_factory=list)
    ends: dict[str, EndReadout] = field(default_factory=dict)   # "bender.base"/"bender.tip"
    cells: dict[str, list[str]] = field(default_factory=dict)   # bender -> its cell body keys
    # beam benders: cells[name] holds the N + 1 node keys; a cell's angle is the mean of its nodes'
    beam_benders: set[str] = field(default_factory=set)
    # (item, stiffness, damping parameter name) of every spring-damper, for the relaxation
    springs: list[tuple[int, float, str]] = field(default_factory=list)
    # smallest absolute Newton tolerance the model can reach; None: no static relative tolerance
    # override (the attributes the shared solver runs of mbs.solver_runs read)
    newton_tolerance_floor: float = 0.0
    static_relative_tolerance: float | None = None
    static_absolute_tolerance: float | None = None
    group_of_component: dict[str, str] = field(default_factory=dict)  # link / prbm segment -> body key
    # state of the actuation path (see set_path / set_strain)
    strains: np.ndarray | None = None
    path_from: np.ndarray | None = None
    path_to: np.ndarray | None = None
    ramp_loads: bool = True
    load_factor: float = 1.0
    time: float = 0.0
    # how the stroke reaches the system (see exudyn_atcm.cells.CellKind.stroke_paths)
    stroke_path: str = "prestep"
    # start equilibria solved on this build, by their strains: (state, stability, note) for the runs that start there
    # (:func:`exudyn_atcm.solve.mechanism_static.start_equilibrium`)
    start_equilibria: dict = field(default_factory=dict)
    # "offsets": (item, parameter, coefficient per source) written as coefficient @ strains
    offset_items: list = field(default_factory=list)
    # "user_function": the strains [-] per source at the solver's time t (default: the strains last set)
    uf_strains: Any = None
    # beam and ANCF benders: their elements, base first
    elements: dict[str, list[int]] = field(default_factory=dict)
    # cells whose actuation is not a torque or an offset (assumed modes): called with the strains
    strain_writers: list = field(default_factory=list)
    # called with the strains before a linearisation about the current state
    linearisation_hooks: list = field(default_factory=list)
    # cells' changes to the dynamic solver settings (before the user's)
    settings_adjusters: list = field(default_factory=list)
    # benders whose mass matrix the package rewrites during a run: Exudyn must re-read it every step
    # (adjust_settings sets reuseConstantMassMatrix = False, check_settings refuses True)
    varying_mass_benders: list[str] = field(default_factory=list)
    # assumed-mode benders: name -> estimate() of the tip error [m] at the current static state from the left-out modes
    truncation_estimators: dict = field(default_factory=dict)
    # name -> (read() -> a reading of the current state, many(readings) -> errors [m]): the same estimate deferred
    truncation_deferred: dict = field(default_factory=dict)
    # Exudyn object number -> the joint it realises, for messages ("pin(a.tip, b.base)", "the cells of bender 'b'")
    constraint_labels: dict[int, str] = field(default_factory=dict)
    _writer: tuple | None = None               # (item counts, strain writer) of strain_writer()
    _written_factor: float | None = None       # load factor at which every load was last written
    _connectors: tuple | None = None           # (spring count, connector_reader()) of connector_forces()

    # ------------------------------------------------------------------ actuation and loads
    def set_strains(self, strains: np.ndarray) -> None:
        """Write the free strains of every source [-] into the actuation torques (and follower loads)."""
        if strains.__class__ is not np.ndarray or strains.dtype != float:  # the run's own array passes as it is
            strains = np.asarray(strains, dtype=float)
        self.strains = strains
        self.strain_writer()(strains)

    def strain_writer(self) -> Callable[[np.ndarray], None]:
        """The callable that writes a strain vector [-] (one per source) into the system.

        It does only what this model needs (actuation torques, six-bar motor offsets, offset
        items, the cells' own writers, follower loads); a run calls it in every attempted step
        with its own array, after ``model.strains`` was set to that array (:meth:`set_strains`
        does both).  Rebuilt when items were added since.
        """
        key = (len(self.torque_loads), len(self.motor_offsets), len(self.offset_items), len(self.strain_writers),
               len(self.loads))
        if self._writer is None or self._writer[0] != key:
            self._writer = (key, self._make_strain_writer())
        return self._writer[1]

    def _make_strain_writer(self) -> Callable[[np.ndarray], None]:
        # the hot path of every attempted step: Python numbers and bound methods, no numpy products
        mbs = self.mbs
        actions: list[Callable[[np.ndarray], None]] = []
        if self.torque_loads:
            plan = [(load, [(k, float(c)) for k, c in enumerate(coef) if c != 0.0]) for load, coef in self.torque_loads]
            set_load = mbs.SetLoadParameter

            def torques(strains: np.ndarray) -> None:
                values = strains.tolist()
                for load, terms in plan:
                    torque = 0.0
                    for k, c in terms:
                        torque += c * values[k]
                    set_load(load, "loadVector", [0.0, 0.0, torque])
            actions.append(torques)
        if self.motor_offsets:
            motors = list(self.motor_offsets)

            def motor_offsets(strains: np.ndarray) -> None:
                for item, factor, source in motors:
                    mbs.SetObjectParameter(item, "offset", factor * strains.item(source))
            actions.append(motor_offsets)
        if self.offset_items:
            items = list(self.offset_items)

            def offsets(strains: np.ndarray) -> None:
                for item, parameter, coefficient in items:
                    mbs.SetObjectParameter(item, parameter, float(coefficient @ strains))
            actions.append(offsets)
        actions.extend(self.strain_writers)
        if self.loads:
            actions.append(lambda strains: self._write_loads(varying_only=True))
        if len(actions) == 1:
            return actions[0]

        def write_all(strains: np.ndarray) -> None:
            for action in actions:
                action(strains)
        return write_all

    def strains_at(self, t: float) -> np.ndarray:
        """Strains [-] per source for the user functions of the ``"user_function"`` stroke path at time ``t`` [s]."""
        if self.uf_strains is not None:
            return self.uf_strains(t)
        return self.strains if self.strains is not None else np.zeros(len(self.sources))

    def adjust_settings(self, settings: Any) -> None:
        """The cells' changes to the dynamic solver settings (before the user's)."""
        if self.varying_mass_benders:
            settings.timeIntegration.reuseConstantMassMatrix = False
        for adjust in self.settings_adjusters:
            adjust(settings)

    def check_settings(self, settings: Any) -> None:
        """Refuse dynamic settings (after the user's) that would freeze a mass matrix the package rewrites."""
        if self.varying_mass_benders and settings.timeIntegration.reuseConstantMassMatrix:
            raise ValueError(
                "settings: timeIntegration.reuseConstantMassMatrix = True would keep the mass matrix of bender(s) "
                f"{self.varying_mass_benders} at its first value (their cells rewrite it every step, so the "
                "dynamics would be wrong); leave it False")

    def truncation_errors(self) -> dict[str, float]:
        """Estimated tip-position error [m] of every assumed-mode bender from the modes it leaves out (current state)."""
        return {name: estimate() for name, estimate in self.truncation_estimators.items()}

    def truncation_readings(self) -> dict:
        """What :meth:`largest_truncation_errors` needs of the current state: per bender its deferred reading
        (cheap: a few coordinates and forces), or its error [m] where the estimate is not deferred."""
        deferred = self.truncation_deferred
        return {name: deferred[name][0]() if name in deferred else estimate()
                for name, estimate in self.truncation_estimators.items()}

    def largest_truncation_errors(self, readings: list[dict]) -> dict[str, float]:
        """The largest :meth:`truncation_errors` [m] over states given by their :meth:`truncation_readings`
        (a deferred estimate evaluated once for all of them)."""
        out = {}
        for name in self.truncation_estimators:
            values = [r[name] for r in readings if name in r]
            if values:
                errors = self.truncation_deferred[name][1](values) if name in self.truncation_deferred else values
                out[name] = float(np.max(errors))
        return out

    def before_linearisation(self) -> None:
        """Prepare an eigenvalue analysis about the current state (the cells' hooks, with the current strains)."""
        strains = self.strains if self.strains is not None else np.zeros(len(self.sources))
        for hook in self.linearisation_hooks:
            hook(strains)

    def set_path(self, start: np.ndarray, end: np.ndarray, ramp_loads: bool) -> None:
        """Static path: strains go from ``start`` to ``end`` with the path parameter; loads ramp if asked."""
        self.path_from = np.asarray(start, dtype=float)
        self.path_to = np.asarray(end, dtype=float)
        self.ramp_loads = ramp_loads

    def set_strain(self, f: float) -> None:
        """Path parameter ``f`` in [0, 1] (the static solver's load factor): strains and, if ramped, loads."""
        if self.ramp_loads:
            self.load_factor = f
        # at the path's end its end itself (a continuation's every whole step; the same to round-off)
        self.set_strains(self.path_to if f == 1.0 else self.path_from + f * (self.path_to - self.path_from))

    def scale_loads(self, factor: float) -> None:
        """Scale every external force and torque by ``factor`` (relaxation ramps; kept at 1 on a sweep's later steps)."""
        self.load_factor = factor if self.ramp_loads else 1.0
        self._write_loads()

    def set_time(self, t: float) -> None:
        """Time [s] at which callable loads are evaluated."""
        self.time = t
        self._write_loads()

    def _write_loads(self, varying_only: bool = False) -> None:
        """Write every load at the current time, strains and load factor.

        ``varying_only``: skip the constant loads (a fixed value, not a follower of a free
        end) when they were last written at the current load factor (the per-step call).
        """
        f = self.load_factor
        skip_constant = varying_only and self._written_factor == f
        self._written_factor = f
        for rec in self.loads:
            if skip_constant and not callable(rec.value) and rec.free_end is None:
                continue
            value = rec.at(self.time)
            if rec.kind == "torque":
                self.mbs.SetLoadParameter(rec.load, "loadVector", [0.0, 0.0, f * value[0]])
                continue
            fx, fy = value[0] * f, value[1] * f
            if rec.follower:
                angle = -rec.rotation
                if rec.free_end is not None and self.strains is not None:
                    angle += rec.free_end.sign * float(rec.free_end.theta @ self.strains)
                c, s = math.cos(angle), math.sin(angle)
                fx, fy = c * fx - s * fy, s * fx + c * fy
            self.mbs.SetLoadParameter(rec.load, "loadVector", [fx, fy, 0.0])

    # ------------------------------------------------------------------ state read-out
    def coordinates(self) -> np.ndarray:
        """Current ODE2 coordinates (a view)."""
        return self.mbs.systemData.GetODE2Coordinates(copy=False)

    def poses(self, q: np.ndarray, keys: Any = None) -> dict[str, np.ndarray]:
        """Pose (x, y, angle) of every body (or of the bodies ``keys``) for rows of ODE2 coordinates ``q``
        (shape (n, nODE2))."""
        q = np.atleast_2d(q)
        bodies = self.bodies.items() if keys is None else ((key, self.bodies[key]) for key in keys)
        done: dict[int, np.ndarray] = {}  # a body under two keys (a bender's end) is computed once
        out = {}
        for key, body in bodies:
            pose = done.get(id(body))
            if pose is None:
                pose = done[id(body)] = body.pose_rows(q)
            out[key] = pose
        return out

    def point_positions(self, poses: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Position (x, y) rows of every component point (``"comp.point"``)."""
        out = {}
        for name, (key, local) in self.anchors.items():
            pose = poses[key]
            c, s = np.cos(pose[:, 2]), np.sin(pose[:, 2])
            out[name] = np.column_stack([pose[:, 0] + c * local[0] - s * local[1],
                                         pose[:, 1] + s * local[0] + c * local[1]])
        return out

    def rotation(self, poses: dict[str, np.ndarray], key: str) -> np.ndarray:
        """Rotation of body ``key`` from its reference pose [rad]."""
        return poses[key][:, 2] - self.bodies[key].reference[2]

    def end_rotation(self, poses: dict[str, np.ndarray], strains: np.ndarray, end: str) -> np.ndarray:
        """Rotation [rad] of a bender end's interface from the reference pose (quasi-static for virtual ends)."""
        r = self.ends[end]
        strains = np.atleast_2d(strains)
        if r.kind == "body":
            return self.rotation(poses, r.body)
        if r.kind == "free":
            return self.rotation(poses, r.body) + r.sign * (strains @ r.theta)
        hinge = self.hinges[r.hinge]
        ra, rb = self.rotation(poses, hinge.a), self.rotation(poses, hinge.b)
        thetas = [strains @ e.theta for e in hinge.elements]
        if hinge.stiffness == 0.0:
            # no moment: the interface follows its own end cell
            zero = next(i for i, e in enumerate(hinge.elements) if e.stiffness == 0.0)
            if r.node <= zero:
                return ra + sum(thetas[:r.node], 0.0)
            return rb - sum(thetas[r.node:], 0.0)
        moment = hinge.stiffness * (rb - ra - sum(thetas, 0.0))
        out = ra
        for e, th in zip(hinge.elements[:r.node], thetas[:r.node]):
            out = out + th + (moment / e.stiffness if math.isfinite(e.stiffness) else 0.0)
        return out

    # ------------------------------------------------------------------ connectors
    def connector_names(self) -> list[str]:
        """The connections' recorded columns (without unit), in the order of :meth:`connector_forces`."""
        return [r.column for r, _ in self.readouts]

    def connector_units(self) -> list[str]:
        """The units of :meth:`connector_names`."""
        return [r.unit for r, _ in self.readouts]

    def connector_forces(self) -> list[float]:
        """Every connection's recorded value now (springs' tension [N], stops' compression [N], ...)."""
        if self._connectors is None or self._connectors[0] != len(self.readouts):
            self._connectors = (len(self.readouts), self.connector_reader())
        return self._connectors[1]()

    def connector_reader(self) -> Callable[[], list[float]]:
        """A function giving :meth:`connector_forces`, its plan made once (a run calls it every step)."""
        readers = [read for _, read in self.readouts]

        def read() -> list[float]:
            return [float(r()) for r in readers]

        return read

    def resolve_indices(self) -> None:
        """Read the bodies' ODE2 indices (after ``mbs.Assemble()``)."""
        for body in self.bodies.values():
            if body.node is not None:
                body.ode2 = self.mbs.GetNodeODE2Index(body.node)
