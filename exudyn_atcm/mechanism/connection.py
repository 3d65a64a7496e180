"""The one protocol of a mechanism's connections and loads (joints, forces, springs, stops, ...).

Every connection or load of a :class:`~exudyn_atcm.Mechanism` is an object with

* ``name`` (str): unique among the mechanism's components and connections; part of its columns;
* ``points()``: the :class:`~exudyn_atcm.mechanism.PointRef` points it uses (checked against the
  mechanism's components when it is added, and against the cells' tip-load refusals when built);
  ``components()``: the components it acts on (its points', or e.g. a torque's component);
* ``parameters()``: its entries of :meth:`Mechanism.parameters <exudyn_atcm.Mechanism.parameters>`
  (keys with units);
* ``describe()``: how messages name it (e.g. ``"pin(crank.base, ground)"``);
* ``readouts()``: the result columns it records, each a :class:`Readout` (column and unit);
* ``realise(context)``: adds its items to the Exudyn system through the public build context
  (:class:`exudyn_atcm.mbs.build_context.BuildContext`: markers at points, items, loads, read-outs);
* ``draw(canvas)``: draws it on a mechanism drawing (:class:`exudyn_atcm.plots.canvas.MechanismCanvas`);
* the class attributes ``holds`` (True for a joint that holds parts together: weld, pin, slider,
  subclasses of :class:`~exudyn_atcm.mechanism.joints.JointBase` that the rigid groups and the
  ground check use; they are realised with the bodies, before the hinges' springs) and ``loads_points`` (True when
  it loads its points, so that a cell kind that refuses tip loads refuses it).

:class:`ConnectionBase` gives the defaults; a new kind is one file: a subclass with ``points``,
``realise`` (and, as needed, ``readouts``, ``parameters``, ``draw``), added with
:meth:`Mechanism.add_connection <exudyn_atcm.Mechanism.add_connection>`.  This module imports
neither Exudyn nor the plots: the context and the canvas are handed in.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Protocol, runtime_checkable

from .points import PointRef

__all__ = ["Readout", "Connection", "ConnectionBase"]


@dataclass(frozen=True)
class Readout:
    """A result column recorded by a connection: ``column`` (without unit) and its SI ``unit``.

    Examples
    --------
    >>> Readout("object.force", "N")
    Readout(column='object.force', unit='N')
    """

    column: str
    unit: str


@runtime_checkable
class Connection(Protocol):
    """What :class:`~exudyn_atcm.Mechanism` asks of a connection or load (see the module text)."""

    name: str
    holds: ClassVar[bool]
    loads_points: ClassVar[bool]

    def points(self) -> tuple[PointRef, ...]:
        """The points it uses."""

    def components(self) -> tuple[str, ...]:
        """The components it acts on (those of its points, or a torque's component)."""

    def parameters(self) -> dict[str, Any]:
        """Its entries of the mechanism's parameters (keys with units)."""

    def describe(self) -> str:
        """How messages name it."""

    def readouts(self) -> tuple[Readout, ...]:
        """The result columns it records."""

    def realise(self, context: Any) -> None:
        """Add its items through the build context."""

    def draw(self, canvas: Any) -> None:
        """Draw it on a mechanism drawing."""


class ConnectionBase:
    """Defaults of the :class:`Connection` protocol: not a joint, loads its points, no columns,
    parameters ``{name: describe()}``, drawn as nothing.  Subclasses set ``name`` and define
    :meth:`points` and :meth:`realise`."""

    name: str = ""
    holds: ClassVar[bool] = False
    loads_points: ClassVar[bool] = True

    def points(self) -> tuple[PointRef, ...]:
        """The points it uses (none by default)."""
        return ()

    def components(self) -> tuple[str, ...]:
        """The components of its points, each once, in order."""
        return tuple(dict.fromkeys(p.component for p in self.points()))

    def describe(self) -> str:
        """``"Kind 'name'"``."""
        return f"{type(self).__name__} {self.name!r}"

    def parameters(self) -> dict[str, Any]:
        """``{name: describe()}``."""
        return {self.name: self.describe()}

    def readouts(self) -> tuple[Readout, ...]:
        """No recorded columns."""
        return ()

    def realise(self, context: Any) -> None:
        """Add nothing (override)."""

    def draw(self, canvas: Any) -> None:
        """Draw nothing (override)."""
