"""The compliant four-bar and the micro-gripper built directly in Exudyn, as an Exudyn user would.

No package layer: the benders are ``N`` ``ObjectBeamGeometricallyExact2D`` elements on
``NodeRigidBody2D`` nodes, the rest is written item by item.  From ``exudyn_atcm`` only the
hysteresis operator (``paper_strain_preisach``) and the parameter *numbers* are taken: the
case modules (``cases/compliant_four_bar.py``, ``cases/micro_gripper.py``) build their
mechanism description, and :func:`four_bar_numbers` / :func:`gripper_numbers` read plain floats
off it (geometry, laminate EI, EA, mass per length, rotary inertia, damping factor, the
flexures' PRBM spring and segment masses, link masses) so that both models are the same
mechanism.  The Exudyn system is built from those floats only.

Modelling choices (an expert's, stated):

* bender: clamped base node (three ``ObjectConnectorCoordinate`` to the ground), free
  curvature of the laminate as the end torque ``EI kappa(strain)`` on the tip node (one
  uniform segment: the base node's opposite torque goes into the clamp);
* a weld of a bender tip to a rigid part: the part's ``ObjectRigidBody2D`` sits *on the beam's
  tip node* (shared node, no weld constraint);
* the four-bar's flexure hinges are pseudo-rigid-body joints as in the case: an
  ``ObjectJointRevolute2D`` at the characteristic pivot plus an
  ``ObjectConnectorCoordinateSpringDamper`` between the two rotation coordinates
  (``K = EI/l``, damping ``beta K``); the flexures' rigid segments' masses are lumped into the
  parts they are welded to;
* hysteresis in the step: ``evaluate(u)`` (a trial from the committed memory) in ``PreStep``,
  ``commit(u)`` in ``PostStep`` (accepted steps only), one operator per bender; the voltage is
  a plain-float triangle (the same volts as ``Triangle(500, 1000, 0.5)``);
* record: an Exudyn ``SensorBody`` of the tracked point stored internally (``record="sensor"``,
  the default), or the tracked body's node coordinates copied in ``PostStep`` into a
  preallocated array (``record="array"``).  Measured on 2026-11-26 (shared 2-core machine,
  four-bar, 4 elements, 0.5 s, 8 interleaved runs each): the sensor 1.06 s/s best, the array
  1.20 s/s; both give the same path to the last bit;
* initial state: static equilibrium at ``U(0)`` (load factor ramp), then time integration with
  the package's dynamic settings (copied below), step 1e-4 s.
"""

from __future__ import annotations

import importlib.util
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import exudyn as exu
import numpy as np
from exudyn import itemInterface as ii

from exudyn_atcm.model.parameter_sets import paper_strain_preisach

CASES = Path(__file__).resolve().parents[1] / "cases"
PERIOD = 0.5  # s, triangle period
STEP = 1e-4  # s


def triangle(t: float) -> float:
    """The paper's triangle (-500 ... 1500 V, period 0.5 s) with plain float arithmetic [V]."""
    k = int(2.0 * t / PERIOD)
    return 500.0 + 1000.0 * (4.0 * t / PERIOD - 1.0 - 2.0 * k) * (-1.0 if k % 2 else 1.0)


# ----------------------------------------------------------------------------- numbers from the cases

def _case(name: str):
    spec = importlib.util.spec_from_file_location(name, CASES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@dataclass
class BenderNumbers:
    base: tuple[float, float]
    angle: float  # rad
    length: float  # m
    ei: float  # N m^2
    ea: float  # N
    mu: float  # kg/m
    rho_i: float  # kg m
    beta: float  # s
    torque_per_strain: float  # N m (signed: the bender's curvature sign)


@dataclass
class Part:
    """A rigid part: mass [kg], inertia about its centre of mass [kg m^2], centre [m]."""

    mass: float
    inertia: float
    com: np.ndarray


@dataclass
class Numbers:
    benders: dict[str, BenderNumbers]
    parts: dict[str, Part]  # rigid groups
    points: dict[str, tuple[float, float]] = field(default_factory=dict)
    hinges: list = field(default_factory=list)  # (part a, part b | None, pivot, K, damping)
    springs: list = field(default_factory=list)  # (point a, point b, k, d, rest length)
    tracked: tuple[str, str] = ("", "")  # (part, point)


def _bender(b) -> BenderNumbers:
    if len(b.segments) != 1:
        raise ValueError(f"bender {b.name!r}: the hand-built model takes one uniform segment, got {len(b.segments)}")
    lam = b.laminate
    return BenderNumbers(tuple(b.base_position), float(b.angle), float(b.length), lam.bending_stiffness,
                         lam.axial_rigidity, lam.mass_per_length, lam.rotary_inertia_per_length,
                         float(b.stiffness_damping_factor),
                         float(b.curvature_sign * lam.bending_stiffness * lam.curvature_per_strain))


def _lump(pieces) -> Part:
    m = sum(p[0] for p in pieces)
    com = sum(p[0] * np.asarray(p[2], dtype=float) for p in pieces) / m
    j = sum(p[1] + p[0] * float((np.asarray(p[2]) - com) @ (np.asarray(p[2]) - com)) for p in pieces)
    return Part(m, j, com)


def four_bar_numbers() -> Numbers:
    """The case's four-bar (default parameters) as plain floats."""
    module = _case("compliant_four_bar")
    p = module.CASE.resolve({"cell": "beam"})
    mech = module.build_mechanism(p, paper_strain_preisach())
    c = mech.components
    hb, hc, hd, coupler, rocker = c["hinge_B"], c["hinge_C"], c["hinge_D"], c["coupler"], c["rocker"]
    link = lambda k: (k.mass, k.inertia, k.center_of_mass)  # noqa: E731
    parts = {"crank_tip": _lump([hb.segment_masses()[0]]),
             "coupler": _lump([hb.segment_masses()[1], link(coupler), hc.segment_masses()[0]]),
             "rocker": _lump([hc.segment_masses()[1], link(rocker), hd.segment_masses()[0]])}
    hinges = [(a, b, h.pivot, h.torsion_stiffness, h.stiffness_damping_factor * h.torsion_stiffness)
              for a, b, h in (("crank_tip", "coupler", hb), ("coupler", "rocker", hc), ("rocker", None, hd))]
    return Numbers({"crank": _bender(c["crank"])}, parts, {"coupler.P": coupler.points["P"]}, hinges,
                   tracked=("coupler", "coupler.P"))


def gripper_numbers() -> Numbers:
    """The case's micro-gripper (default parameters, object spring k) as plain floats."""
    module = _case("micro_gripper")
    p = module.CASE.resolve({})
    mech = module.build_mechanism(p, p.object_stiffness)
    c = mech.components
    benders = {n: _bender(c[n]) for n in ("upper", "lower")}
    parts = {f"{n}_tip": _lump([(c[f"{n}_jaw"].mass, c[f"{n}_jaw"].inertia, c[f"{n}_jaw"].center_of_mass)])
             for n in ("upper", "lower")}
    points = {f"{n}_jaw.jaw": c[f"{n}_jaw"].points["jaw"] for n in ("upper", "lower")}
    springs = [(str(s.p), str(s.q), s.stiffness, s.damping,
                math.dist(mech.position(s.p), mech.position(s.q)) if s.rest_length is None else s.rest_length)
               for s in mech.springs]
    return Numbers(benders, parts, points, springs=springs, tracked=("lower_tip", "lower_jaw.jaw"))


# ----------------------------------------------------------------------------- the Exudyn system

class HandBuilt:
    """One hand-built Exudyn system of ``numbers`` with ``n`` GE beam elements per bender."""

    def __init__(self, numbers: Numbers, n: int, record: str = "sensor") -> None:
        self.numbers, self.n, self.record = numbers, n, record
        self.SC = exu.SystemContainer()
        mbs = self.mbs = self.SC.AddSystem()
        ground = mbs.AddObject(ii.ObjectGround())
        gnode = mbs.AddNode(ii.NodePointGround())
        self.gcoord = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=gnode, coordinate=0))
        self.frames = {}  # part -> (node, body item, reference pose x, y, angle)
        self.drives = []  # (operator, load, torque per strain)
        floor = 0.0
        for name, b in numbers.benders.items():
            lc = b.length / n
            d = np.array([math.cos(b.angle), math.sin(b.angle)])
            nodes = [mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[*(np.array(b.base) + j * lc * d), b.angle]))
                     for j in range(n + 1)]
            for k in range(3):  # clamp
                mk = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=k))
                mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[self.gcoord, mk]))
            for j in range(n):
                mbs.AddObject(ii.ObjectBeamGeometricallyExact2D(
                    nodeNumbers=[nodes[j], nodes[j + 1]], length=lc, massPerLength=b.mu, crossSectionInertia=b.rho_i,
                    bendingStiffness=b.ei, axialStiffness=b.ea, shearStiffness=b.ea, bendingDamping=b.beta * b.ei,
                    axialDamping=b.beta * b.ea, shearDamping=b.beta * b.ea))
            tip = np.array(b.base) + b.length * d
            part = numbers.parts[f"{name}_tip"]  # the rigid part welded to the tip, on the tip node
            c, s = math.cos(b.angle), math.sin(b.angle)
            r = part.com - tip
            com_local = [c * r[0] + s * r[1], -s * r[0] + c * r[1]]
            body = mbs.AddObject(ii.ObjectRigidBody2D(nodeNumber=nodes[-1], mass=part.mass,
                                                      inertia=part.inertia + part.mass * (r @ r),
                                                      centerOfMass=com_local))
            self.frames[f"{name}_tip"] = (nodes[-1], body, (tip[0], tip[1], b.angle))
            load = mbs.AddLoad(ii.LoadTorqueVector(markerNumber=mbs.AddMarker(ii.MarkerNodeRigid(nodeNumber=nodes[-1])),
                                                   loadVector=[0.0, 0.0, 0.0]))
            self.drives.append((paper_strain_preisach(), load, b.torque_per_strain))
            # round-off floor of the stiff axis's forces (as the package's beam cell): eps EA/lc L, x10
            floor = max(floor, 10.0 * np.finfo(float).eps * b.ea / lc * b.length)
        self.tolerance = max(1e-8, floor)
        for key, part in numbers.parts.items():  # the other rigid parts: node at the centre of mass, angle 0
            if key in self.frames:
                continue
            node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[part.com[0], part.com[1], 0.0]))
            body = mbs.AddObject(ii.ObjectRigidBody2D(nodeNumber=node, mass=part.mass, inertia=part.inertia))
            self.frames[key] = (node, body, (part.com[0], part.com[1], 0.0))
        self.ground = ground
        for a, b, pivot, k, damping in numbers.hinges:
            ma = self._position_marker(a, pivot)
            mb = self._position_marker(b, pivot)
            mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[ma, mb]))
            mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(markerNumbers=[self._rotation(a), self._rotation(b)],
                                                                   stiffness=k, damping=damping))
        for pa, pb, k, damping, rest in numbers.springs:
            ma = self._position_marker(pa.split(".")[0].replace("_jaw", "_tip"), numbers.points[pa])
            mb = self._position_marker(pb.split(".")[0].replace("_jaw", "_tip"), numbers.points[pb])
            mbs.AddObject(ii.ObjectConnectorSpringDamper(markerNumbers=[ma, mb], referenceLength=rest, stiffness=k,
                                                         damping=damping))
        part, point = numbers.tracked
        self.tracked_node, body, pose = self.frames[part]
        self.tracked_local = self._local(pose, numbers.points[point])
        self.tracked_reference = pose
        if record == "sensor":
            self.sensor = mbs.AddSensor(ii.SensorBody(bodyNumber=body, localPosition=[*self.tracked_local, 0.0],
                                                      outputVariableType=exu.OutputVariableType.Position,
                                                      storeInternal=True, writeToFile=False))
        elif record != "array":
            raise ValueError(f"record must be 'array' or 'sensor', got {record!r}")
        mbs.Assemble()
        self.i_tracked = mbs.GetNodeODE2Index(self.tracked_node)

    @staticmethod
    def _local(pose, point) -> list[float]:
        x, y, a = pose
        dx, dy = point[0] - x, point[1] - y
        c, s = math.cos(a), math.sin(a)
        return [c * dx + s * dy, -s * dx + c * dy]

    def _position_marker(self, part: str | None, point) -> int:
        if part is None:
            return self.mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=self.ground, localPosition=[*point, 0.0]))
        _, body, pose = self.frames[part]
        return self.mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=body, localPosition=[*self._local(pose, point), 0.0]))

    def _rotation(self, part: str | None) -> int:
        if part is None:
            return self.gcoord
        return self.mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=self.frames[part][0], coordinate=2))

    # ------------------------------------------------------------------------- solving

    def _static_settings(self, load_steps: int):
        # the package's static settings (exudyn_atcm/mbs/solver_settings.py: base_settings, static_settings)
        s = exu.SimulationSettings()
        s.linearSolver.solverType = exu.LinearSolverType.EigenSparse
        s.solution.file.write = False
        s.solution.sensors.writePeriod = 1e30
        s.timeIntegration.verboseMode = 0
        s.staticSolver.verboseMode = 0
        s.parallel.numberOfThreads = 1
        st = s.staticSolver
        st.numberOfLoadSteps = load_steps
        st.loadStepDuration = 1.0
        st.adaptiveStep = True
        st.minimumStepSize = 1e-3
        st.newton.maxIterations = 25
        st.newton.useModifiedNewton = False
        st.newton.numericalDifferentiation.jacobianConnectorDerivative = False
        st.useLoadFactor = True
        st.newton.absoluteTolerance = self.tolerance
        st.newton.relativeTolerance = 1e-10  # as the package's beam cell
        return s

    def _dynamic_settings(self, t_end: float, step: float):
        # the package's dynamic settings, copied (exudyn_atcm/mbs/solver_settings.py: dynamic_settings)
        s = exu.SimulationSettings()
        s.linearSolver.solverType = exu.LinearSolverType.EigenSparse
        s.solution.file.write = False
        s.solution.sensors.writePeriod = 1e30 if self.record == "array" else step
        s.timeIntegration.verboseMode = 0
        s.parallel.numberOfThreads = 1
        ti = s.timeIntegration
        ti.endTime = t_end
        ti.numberOfSteps = max(1, int(math.ceil(t_end / step - 1e-9)))
        ti.minimumStepSize = step * 1e-4
        ti.adaptiveStep = True
        ti.generalizedAlpha.spectralRadius = 0.8
        ti.newton.useModifiedNewton = True
        ti.newton.modifiedNewtonContractivity = 0.2
        ti.newton.numericalDifferentiation.jacobianConnectorDerivative = False
        ti.newton.absoluteTolerance = self.tolerance
        return s

    def simulate(self, t_end: float, step: float = STEP) -> tuple[np.ndarray, np.ndarray]:
        """Times [s] and tracked point positions [m] (rows x, y) of the accepted steps (t = 0 first)."""
        mbs = self.mbs
        drives = self.drives
        for op, _, _ in drives:
            op.reset()
        u0 = triangle(0.0)
        rot = 0.0
        for op, load, c in drives:
            strain = op.evaluate(u0)
            mbs.SetLoadParameter(load, "loadVector", [0.0, 0.0, c * strain])
            rot = max(rot, abs(c * strain) * max(b.length / b.ei for b in self.numbers.benders.values()))
        exu.config.printToConsole = False
        try:
            mbs.SolveStatic(self._static_settings(int(min(400, max(4, math.ceil(rot / 0.05))))))
            state = mbs.systemData.GetSystemState()
            mbs.systemData.SetSystemState(systemStateList=state, configuration=exu.ConfigurationType.Initial)
            n0 = len(mbs.systemData.GetODE2Coordinates())
            for setter in (mbs.systemData.SetODE2Coordinates_t, mbs.systemData.SetODE2Coordinates_tt):
                setter(np.zeros(n0), configuration=exu.ConfigurationType.Initial)
            n_steps = int(math.ceil(t_end / step - 1e-9))
            buf = {"t": np.empty(n_steps + 2), "q": np.empty((n_steps + 2, 3)), "k": 0}
            i0 = self.i_tracked
            record = self.record == "array"
            set_load = mbs.SetLoadParameter

            def pre(mbs_, t):
                u = triangle(t)
                for op, load, c in drives:
                    set_load(load, "loadVector", [0.0, 0.0, c * op.evaluate(u)])
                return True

            def post(mbs_, t):
                u = triangle(t)
                for op, _, _ in drives:
                    op.commit(u)
                if record:
                    k = buf["k"]
                    if k == len(buf["t"]):  # more accepted steps than planned (step reductions): grow
                        buf["t"] = np.concatenate([buf["t"], np.empty(k)])
                        buf["q"] = np.concatenate([buf["q"], np.empty((k, 3))])
                    buf["t"][k] = t
                    buf["q"][k] = mbs_.systemData.GetODE2Coordinates(copy=False)[i0:i0 + 3]
                    buf["k"] = k + 1
                return True

            mbs.SetPreStepUserFunction(pre)
            mbs.SetPostStepUserFunction(post)
            mbs.SolveDynamic(self._dynamic_settings(t_end, step), showHints=False)
        finally:
            exu.config.printToConsole = True
        if not record:
            data = mbs.GetSensorStoredData(self.sensor)
            return data[:, 0], data[:, 1:3]
        k = buf["k"]
        times, q = buf["t"][:k], buf["q"][:k]
        x0, y0, a0 = self.tracked_reference
        a = a0 + q[:, 2]
        lx, ly = self.tracked_local
        return times, np.column_stack([x0 + q[:, 0] + np.cos(a) * lx - np.sin(a) * ly,
                                       y0 + q[:, 1] + np.sin(a) * lx + np.cos(a) * ly])


NUMBERS = {"four_bar": four_bar_numbers, "gripper": gripper_numbers}


def run(mechanism: str, n: int, t_end: float, step: float = STEP, record: str = "sensor") -> tuple[float, np.ndarray,
                                                                                                  np.ndarray]:
    """Wall time [s] (build, initial equilibrium, integration), times [s] and tracked path [m] of one run."""
    numbers = NUMBERS[mechanism]()  # reading the case is not timed (a user's script has the numbers)
    start = time.perf_counter()
    system = HandBuilt(numbers, n, record)
    times, path = system.simulate(t_end, step)
    return time.perf_counter() - start, times, path
