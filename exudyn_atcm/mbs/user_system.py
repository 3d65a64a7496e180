"""Adding a mechanism or a lone bender to a user's own Exudyn ``MainSystem``.

The convention of ``exudyn.robotics`` and ``exudyn.beams``: :func:`add_to` adds the items to
``mbs`` and returns a handle with markers for the user's joints, the body numbers and
sensors.  The drives' hysteresis runs in the step through :class:`~exudyn_atcm.mbs.hooks.StepHooks`
(trial in ``PreStep``, commit and record in ``PostStep``, by the same
:class:`~exudyn_atcm.mbs.stepping.Stepping` as the package's own solves), so any solver the user calls
(``mbs.SolveDynamic``, ``exudyn.SolveStatic``...) takes the voltage programs into account.

An error a voltage program or controller raises in those hooks reaches the user through Exudyn,
which reports any exception of a user function as its own ``ModelError`` (a ``ValueError``): the
original exception is that error's ``__cause__``, unchanged, with notes naming the program, the
drive and the time (Exudyn's message quotes them too).  The package's own solves
(:func:`exudyn_atcm.simulate` ...) raise the original exception itself.
"""

from __future__ import annotations

import warnings
from typing import Any, Union

import exudyn as exu
import numpy as np
from .._checks import shown
from .exudyn_items import ii

from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..mechanism.build_cost import warn_if_large
from ..mechanism.points import MechanismError, PointRef, closest
from ..io.result import Result
from .builder import add_mechanism
from .hooks import add_post_step, add_pre_step
from .items import position_marker, rigid_marker
from .model import MechanismModel
from .tolerance_floor import ToleranceFloor
from .stepping import Stepping
from ..errors import SetupWarning

#: Key in ``mbs.variables``: the component names already added by :func:`add_to`.
ADDED_VARIABLE = "exudyn_atcm.added_components"


class MechanismHandle:
    """What :func:`exudyn_atcm.add_to` added: markers, bodies, sensors and the recorded run.

    Attributes
    ----------
    mechanism : Mechanism
        The mechanism added (a lone bender is wrapped in a one-component mechanism).
    model : MechanismModel
        The built items (internal details).
    sensors : dict of str to int
        Exudyn sensor numbers (``storeInternal=True``): ``"{comp}.{point}"`` -> position
        [m] of every named point, ``"{link}.angle"`` -> rotation [rad] of every link's body.
        Read them with ``mbs.GetSensorStoredData(number)`` after a run (their write period
        is ``simulationSettings.solution.sensors.writePeriod``).
    newton_tolerance_floor : float
        Smallest absolute Newton tolerance [N, N m] the added items can reach: the stiff axis of
        beam cells (``cell="beam"``) leaves a round-off residual of about ``eps (a1 + a2) L/L_c``;
        ``exudyn.SolveDynamic`` / ``SolveStatic`` with a smaller ``newton.absoluteTolerance`` get it raised to
        this value for the running solver, with a ``RuntimeWarning``
        (:class:`~exudyn_atcm.mbs.tolerance_floor.ToleranceFloor`); 0 without beam cells.
    """

    def __init__(self, mechanism: Mechanism, model: MechanismModel, stepping: Stepping) -> None:
        self.mechanism = mechanism
        self.model = model
        self.sensors: dict[str, int] = {}
        self.newton_tolerance_floor = float(model.newton_tolerance_floor)
        #: the drives' trial and commit and the record of every accepted step (as in :func:`exudyn_atcm.simulate`)
        self.stepping = stepping

    # ------------------------------------------------------------------ markers and bodies
    def _anchor(self, point: PointRef | str) -> tuple[Any, np.ndarray]:
        ref = self.mechanism.resolve(point)
        key, local = self.model.anchors[str(ref)]
        return self.model.bodies[key], local

    def marker(self, point: PointRef | str) -> int:
        """A new ``MarkerBodyRigid`` at ``point`` (for the user's joints: revolute, generic...).

        At a bender end that is joined to nothing inside the mechanism, this is the end's
        interface body; the marker's frame is the body's frame (global axes in the reference pose
        for links and interface bodies, the bender's axis for cells).  At the end of a beam bender
        (``cell="beam"``) joined to no link, it is a ``MarkerNodeRigid`` of the end node (the
        bender's axis).
        """
        body, local = self._anchor(point)
        return rigid_marker(self.model.mbs, body, local)

    def position_marker(self, point: PointRef | str) -> int:
        """A new ``MarkerBodyPosition`` at ``point`` (for springs, forces, position joints); a
        ``MarkerNodePosition`` at a beam bender's end node."""
        body, local = self._anchor(point)
        return position_marker(self.model.mbs, body, local)

    def body(self, component_or_point: PointRef | str) -> int:
        """Exudyn object number of the body that carries a point (``"comp.point"``) or a link (``"comp"``).

        At a beam bender's end node: the beam element attached to it.
        """
        name = str(component_or_point)
        if "." in name or isinstance(component_or_point, PointRef):
            return int(self._anchor(component_or_point)[0].item)
        key = self.model.group_of_component.get(name)
        if key is None:
            known = list(self.model.group_of_component)
            raise MechanismError(f"no rigid component {name!r}{closest(name, known)}; give a point "
                                 f"'component.point' or one of the links: {', '.join(known) or 'none'}")
        return int(self.model.bodies[key].item)

    # ------------------------------------------------------------------ recording
    def result(self) -> Result:
        """The accepted steps recorded by the package's post-step hook, with the columns of
        :func:`exudyn_atcm.simulate` for mechanisms (``result.info`` is empty of solver statistics).

        Recorded by the same :class:`~exudyn_atcm.mbs.stepping.Stepping` as :func:`exudyn_atcm.simulate`'s runs.
        """
        record = self.stepping.record
        if record is None or not record.accepted:
            raise ValueError("nothing recorded yet: solve the system (e.g. mbs.SolveDynamic) first; if you did, the "
                             "package's post-step hook did not run: a later mbs.SetPostStepUserFunction replaced it "
                             "(add your own functions with exudyn_atcm.mbs.add_post_step / add_pre_step instead)")
        self.model.resolve_indices()
        self.stepping.close()
        return self.stepping.result({"solver": "user (add_to)"})

    def clear(self) -> None:
        """Forget the recorded rows (e.g. before a second solve)."""
        self.stepping.record = None


def add_to(mbs, mechanism_or_bender: Union[Mechanism, Bender], *, clamp_base: bool = True) -> MechanismHandle:
    """Add a mechanism or a lone bender to an existing Exudyn ``MainSystem``.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The user's system (not yet assembled, or to be assembled again).
    mechanism_or_bender : Mechanism or Bender
        What to add.  A mechanism's own ground connections are kept; it need not be grounded
        (the user's joints may hold it).
    clamp_base : bool, optional
        A lone bender only: weld its base to the ground (default) or leave it free.

    Returns
    -------
    MechanismHandle
        Markers at any named point (:meth:`~MechanismHandle.marker`), bodies, sensors,
        and :meth:`~MechanismHandle.result` after a solve.

    Notes
    -----
    Bender ends joined to nothing inside the mechanism get small interface bodies (the
    laminate over ``min(h1 + h2, L_c/10)``), so a user's joint there is exact.  Every drive's
    hysteresis operator is reset here; its trial runs in ``PreStep`` and its commit in
    ``PostStep`` through :class:`~exudyn_atcm.mbs.hooks.StepHooks` (add your own step
    functions with :func:`~exudyn_atcm.mbs.add_pre_step` / :func:`~exudyn_atcm.mbs.add_post_step`).
    The system starts from the undeformed reference pose (no static pre-solve): a drive whose
    strain at ``t = 0`` is not zero applies it at once in the first step, and the bender rings
    (start the programs where the strain is 0, or solve statically first).  A program starting at
    0 V can have a strain there through its hysteresis (the paper's strain operator: 6.3e-5 at 0 V
    from its reset state): a :class:`~exudyn_atcm.SetupWarning` says so.
    """
    if isinstance(mechanism_or_bender, Bender):
        bender = mechanism_or_bender
        mechanism = Mechanism(bender.name).add(bender)
        if clamp_base:
            mechanism.ground(bender.base)
    elif isinstance(mechanism_or_bender, Mechanism):
        mechanism = mechanism_or_bender
    else:
        raise ValueError(f"add_to takes a Mechanism or a Bender, got {shown(mechanism_or_bender)}")
    if not isinstance(clamp_base, bool):
        raise ValueError(f"clamp_base must be True or False, got {shown(clamp_base)}")
    if not isinstance(mbs, exu.MainSystem):
        raise ValueError(f"mbs must be an exudyn MainSystem (SC.AddSystem()), got {type(mbs).__name__}")
    mechanism.check(grounded=False)
    # a second add_to of the same component names would give two handles the same sensor and
    # column names (and, for one Bender object, two copies at the same place)
    added = mbs.variables.setdefault(ADDED_VARIABLE, [])
    names = set(mechanism.components)
    clash = sorted(names & set(added))
    if clash:
        raise MechanismError(
            f"add_to: component(s) {clash} are already in this MainSystem (added by an earlier add_to); "
            "give the second copy other names (e.g. Bender('b2', ...)), or add both in one Mechanism")
    warn_if_large(mechanism, "add_to", stacklevel=3)  # before the build: for many cells it is the dear part
    model = add_mechanism(mbs, mechanism, free_end_bodies=True)
    n = len(model.sources)
    model.path_from, model.path_to = np.zeros(n), np.zeros(n)
    model.ramp_loads, model.load_factor = False, 1.0

    # Exudyn keeps one pre-/post-step function per system: a later mbs.SetPreStepUserFunction or
    # SetPostStepUserFunction silently replaces the package's hooks (no actuation, or a hysteresis
    # memory never committed).  Count the calls of each and warn once when one of them stops.
    calls = {"pre_since_post": 0, "post_without_pre": 0, "warned": False}
    labels = [f"drive {', '.join(repr(n) for n, j in model.drive_source.items() if j == k)} added by exudyn_atcm.add_to"
              for k in range(n)]

    def note(hook: str, t: float, label: str) -> str:
        return (f"({label}, in its {hook}-step hook at t = {t:.9g} s; Exudyn reports this as its ModelError, whose "
                "__cause__ is this exception)")

    # the same trial, commit and record as the package's own runs; a fresh view of the coordinates in each
    # step, since the user may assemble the system again between solves
    stepping = Stepping(model, labels=labels, note=note, system=f"mechanism {mechanism.name!r} added by add_to",
                        fixed_view=False)
    handle = MechanismHandle(mechanism, model, stepping)
    _warn_strained_start(stepping, labels)

    def _hooks_replaced(which: str, t: float) -> None:
        if not calls["warned"]:
            calls["warned"] = True
            warnings.warn(
                f"add_to: the package's {which}-step hook is not running (noticed at t = {t:g} s): "
                f"mbs.Set{which.capitalize()}StepUserFunction was probably called after add_to and replaced it, so "
                f"{'the benders are not actuated' if which == 'pre' else 'the hysteresis memory is never committed'}. "
                "Add your own functions with exudyn_atcm.mbs.add_pre_step(mbs, f) / add_post_step(mbs, f) instead",
                SetupWarning, stacklevel=2)

    def pre_step(mbs_, t: float) -> bool:
        calls["pre_since_post"] += 1
        if calls["pre_since_post"] > 50:  # a few repeats are step rejections; 50 without a post step is not
            _hooks_replaced("post", t)
        stepping.pre_step(t)
        return True

    def post_step(mbs_, t: float) -> bool:
        if calls["pre_since_post"] == 0 and t > 0.0:
            calls["post_without_pre"] += 1
            if calls["post_without_pre"] > 1:  # the first post step (t = 0 initial state) may come alone
                _hooks_replaced("pre", t)
        calls["pre_since_post"] = 0
        stepping.post_step(t)
        return True

    if handle.newton_tolerance_floor > 0.0:  # beam cells: raise a user's solve's tolerance to what they reach
        add_pre_step(mbs, ToleranceFloor(handle.newton_tolerance_floor))
    add_pre_step(mbs, pre_step)
    add_post_step(mbs, post_step)
    added.extend(sorted(names))
    model.strains = np.zeros(n)
    for name, (key, local) in model.anchors.items():
        body = model.bodies[key]
        if body.node is None:
            continue
        if body.node_only:  # a beam bender's end node
            handle.sensors[name] = mbs.AddSensor(ii.SensorNode(
                nodeNumber=body.node, outputVariableType=exu.OutputVariableType.Position, storeInternal=True))
            continue
        handle.sensors[name] = mbs.AddSensor(ii.SensorBody(
            bodyNumber=body.item, localPosition=[float(local[0]), float(local[1]), 0.0],
            outputVariableType=exu.OutputVariableType.Position, storeInternal=True))
    for comp, key in model.group_of_component.items():
        body = model.bodies[key]
        if "#" in comp or body.node is None:
            continue
        handle.sensors[f"{comp}.angle"] = mbs.AddSensor(ii.SensorNode(
            nodeNumber=body.node, outputVariableType=exu.OutputVariableType.Rotation, storeInternal=True))
    return handle


def _warn_strained_start(stepping: Stepping, labels: list[str]) -> None:
    """A :class:`~exudyn_atcm.SetupWarning` for every drive whose program starts at 0 V but whose strain there is not
    zero (its hysteresis operator's reset state): :func:`add_to` builds the system undeformed, so the first step
    applies that strain at once, although the program seems to start at rest."""
    for label, source in zip(labels, stepping.sources):
        try:
            volts = float(source.drive.voltage_at(0.0))
            strain = float(source.trial(0.0))
        except Exception:  # noqa: BLE001 - a program that fails at t = 0 is reported by the run itself
            continue
        if volts == 0.0 and strain != 0.0:
            warnings.warn(f"add_to: the system starts undeformed, but the {label} has the strain {strain:.3g} at 0 V "
                          "(t = 0: its hysteresis operator's reset state), so the first step applies it at once and "
                          "the bender rings about its equilibrium although the program starts at 0 V. Start the "
                          "program where the strain is 0, or use exudyn_atcm.simulate, which starts from the static "
                          "equilibrium at t = 0", SetupWarning, stacklevel=3)
