"""The connection context: what a connection's ``realise`` may use (no private model state).

The builder (:mod:`exudyn_atcm.mbs.builder`) makes one :class:`ConnectionContext` per build, after
the components' bodies exist, and calls ``connection.realise(context)`` for every connection of
the mechanism (:mod:`exudyn_atcm.mechanism.connection`).  A connection finds the bodies and
markers at its points here, adds its Exudyn items and declares the functions that read its
result columns; recording, measurements and feedback find them through the model.
"""

from __future__ import annotations

from functools import partial
from typing import Any, Callable

import exudyn as exu
import numpy as np
from exudyn import itemInterface as ii

from ..mechanism.connection import Readout
from ..mechanism.points import MechanismError, PointRef
from . import loads
from .items import NOVIS, position_marker, rigid_marker, rotation_marker
from .model import MechanismModel

__all__ = ["ConnectionContext", "realise_connections"]


class ConnectionContext:
    """Where a connection adds itself to an Exudyn system.

    Parameters
    ----------
    model : MechanismModel
        The model being built (its bodies exist; reached only through these methods).
    ground_coordinate : int
        Marker number of a fixed ground coordinate (for coordinate connectors against the ground).
    hinge, slider : callable
        The builder's realisations of a revolute and a prismatic joint (see :meth:`add_hinge`,
        :meth:`add_slider`).
    """

    def __init__(self, model: MechanismModel, ground_coordinate: int, hinge: Callable[..., None],
                 slider: Callable[..., None]) -> None:
        self._model = model
        self._ground_coordinate = ground_coordinate
        self._hinge = hinge
        self._slider = slider

    # ---------------------------------------------------------------- looking up
    @property
    def system(self) -> Any:
        """The Exudyn ``MainSystem`` being built (for items this context has no method for)."""
        return self._model.mbs

    @property
    def mechanism(self) -> Any:
        """The :class:`~exudyn_atcm.Mechanism` being built."""
        return self._model.mechanism

    def reference(self, point: PointRef) -> np.ndarray:
        """Position (x, y) [m] of ``point`` in the reference pose."""
        return self._model.mechanism.position(point)

    def _anchor(self, point: PointRef) -> tuple[Any, np.ndarray]:
        try:
            key, local = self._model.anchors[str(point)]
        except KeyError:
            raise MechanismError(f"no body carries the point {point}: it is not a point of the built mechanism "
                                 f"{self._model.mechanism.name!r}") from None
        return self._model.bodies[key], local

    def body(self, point: PointRef) -> int:
        """Exudyn object number of the body that carries ``point`` (the ground object on the ground)."""
        return int(self._anchor(point)[0].item)

    def is_fixed(self, point: PointRef) -> bool:
        """True if ``point`` sits on the ground (welded to it): loads there have no effect."""
        return self._anchor(point)[0].node is None

    def position_marker(self, point: PointRef) -> int:
        """A new position marker at ``point`` on the body that carries it."""
        body, local = self._anchor(point)
        return position_marker(self._model.mbs, body, local)

    def rigid_marker(self, point: PointRef) -> int:
        """A new rigid-body marker (position and orientation) at ``point`` on the body that carries it."""
        body, local = self._anchor(point)
        return rigid_marker(self._model.mbs, body, local)

    def rotation_marker(self, point: PointRef) -> int:
        """The marker of the rotation [rad] from the reference pose of the body that carries ``point``
        (its ODE2 rotation coordinate; a fixed ground coordinate on the ground)."""
        body, _ = self._anchor(point)
        return rotation_marker(self._model.mbs, body, self._ground_coordinate)

    def ground_marker(self, position: Any) -> int:
        """A new position marker on the ground at ``position`` (x, y) [m]."""
        return position_marker(self._model.mbs, self._model.bodies["ground"], position)

    # ---------------------------------------------------------------- adding items
    def add_object(self, item: Any) -> int:
        """Add an Exudyn object (``exudyn.itemInterface``); its number."""
        return int(self._model.mbs.AddObject(item))

    def add_marker(self, item: Any) -> int:
        """Add an Exudyn marker; its number."""
        return int(self._model.mbs.AddMarker(item))

    def add_force(self, point: PointRef, value: Any, *, follower: bool = False, name: str = "") -> None:
        """A point force [N] (pair or callable of time), dead or follower, written per step (warns on the ground)."""
        loads.add_force(self._model.mbs, self._model, point, value, follower, name)

    def add_torque(self, component: str, value: Any, *, name: str = "") -> None:
        """A torque [N m] (number or callable of time) on a rigid component's body, written per step."""
        loads.add_torque(self._model.mbs, self._model, component, value, name)

    def add_spring_damper(self, p: PointRef, q: PointRef, stiffness: float, damping: float,
                          rest_length: float | None, name: str) -> int:
        """A spring-damper [N/m], [N s/m] between two points (rest length [m], ``None``: their reference
        distance); its object number (its ``ForceLocal`` output is the tension)."""
        rest = loads.reference_distance(self.reference(p), self.reference(q)) if rest_length is None \
            else float(rest_length)
        return loads.add_spring_damper(self._model.mbs, self._model, p, q, stiffness, damping, rest, name)

    def add_contact(self, point: PointRef, position: Any, normal: Any, stiffness: float, damping: float,
                    name: str) -> int:
        """A one-sided contact of ``point`` with a ground wall; its object number (``Force`` output)."""
        return loads.add_contact(self._model.mbs, self._model, point, position, normal, stiffness, damping, name)

    def add_rotational_spring(self, p: PointRef, q: PointRef, torque: Callable[[float, float], float]) -> int:
        """A torsional connector between the bodies carrying ``p`` and ``q``: ``torque(angle, rate)``
        [N m] of their relative rotation [rad] from the reference pose and its rate [rad/s] acts on
        ``q``'s body as ``-torque`` and on ``p``'s as ``+torque`` (a spring resisting the rotation
        for a positive slope).  Its ``Force`` output is the torque; its object number."""
        m0, m1 = self.rotation_marker(p), self.rotation_marker(q)

        def user(mbs, t, item, u, v, k, d, offset):
            return float(torque(u, v))

        return self.add_object(ii.ObjectConnectorCoordinateSpringDamper(
            markerNumbers=[m0, m1], stiffness=0.0, damping=0.0, springForceUserFunction=user,
            visualization=NOVIS))

    def add_hinge(self, p: PointRef, q: PointRef | None, stiffness: float, damping: float, label: str) -> None:
        """A revolute joint at ``p`` (= ``q``; ``None``: the ground) with a torsion spring [N m/rad] and
        damper [N m s/rad] in series with the bender ends' own springs (a pin)."""
        self._hinge(p, q, stiffness, damping, label)

    def add_slider(self, p: PointRef, q: PointRef | None, axis: tuple[float, float], stiffness: float,
                   damping: float, label: str) -> None:
        """A prismatic joint along ``axis`` (global, reference pose) with an axial spring [N/m] and damper [N s/m]."""
        self._slider(p, q, axis, stiffness, damping, label)

    # ---------------------------------------------------------------- read-outs
    def output(self, item: int, variable: str) -> Callable[[], Any]:
        """A function reading Exudyn object ``item``'s output ``variable`` (an
        ``exudyn.OutputVariableType`` name such as ``"Force"``) in the current state."""
        kind = getattr(exu.OutputVariableType, variable, None)
        if kind is None:
            raise ValueError(f"variable must be an exudyn.OutputVariableType name such as 'Force', got {variable!r}")
        return partial(self._model.mbs.GetObjectOutput, item, kind)

    def add_readout(self, readout: Readout, read: Callable[[], Any]) -> None:
        """Record ``read()`` (a float in ``readout.unit``) as the result column ``readout.column``."""
        if not isinstance(readout, Readout) or not callable(read):
            raise ValueError(f"add_readout takes a Readout and a callable, got {readout!r} and {read!r}")
        self._model.readouts.append((readout, read))


def realise_connections(context: ConnectionContext, connections: Any, labelled: Callable[[str], Any]) -> None:
    """``connection.realise(context)`` for each of ``connections``, its items labelled with its
    description (for the messages on dependent joints), and check that it recorded the columns its
    ``readouts()`` declare.

    Raises
    ------
    MechanismError
        If a connection recorded other columns than it declares.
    """
    readouts = context._model.readouts
    for connection in connections:
        before = len(readouts)
        with labelled(connection.describe()):
            connection.realise(context)
        recorded = [r for r, _ in readouts[before:]]
        if recorded != list(connection.readouts()):
            raise MechanismError(f"{connection.describe()}: realise() recorded the columns {recorded} but readouts() "
                                 f"declares {list(connection.readouts())}; call context.add_readout once per "
                                 "declared Readout")
