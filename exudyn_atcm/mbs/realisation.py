"""The realisation contract: what a cell kind's Exudyn realisation implements and the builder calls.

A cell kind (:class:`~exudyn_atcm.cells.CellKind`, the description) is realised in an Exudyn system
by a subclass of :class:`CellRealisation`, registered for the kind's class with
:func:`register_realisation`.  The builder (:mod:`~exudyn_atcm.mbs.builder`) makes one realisation
per bender and calls, in this order:

1. :attr:`CellRealisation.ends_on_group_body`, :attr:`CellRealisation.ends_are_nodes` (how the
   bender's ends join the rigid groups of :mod:`~exudyn_atcm.mbs.layout`);
2. :meth:`CellRealisation.end_masses` / :meth:`CellRealisation.interface_body_mass` (what an end
   puts on the body of its group);
3. :meth:`CellRealisation.add_cells` (bodies, nodes, elements, springs; the cells' keys, whose
   rotations are recorded as the ``cell_angle_j`` channels, through
   :meth:`~exudyn_atcm.mbs.build_context.BuildContext.set_cells`);
4. :meth:`CellRealisation.end_body_key` (an end that is a node of the bender) and
   :meth:`CellRealisation.end_spring` (an end that is a massless interface);
5. :meth:`CellRealisation.connect_end` for both ends;
6. :meth:`CellRealisation.strain_writer` and :meth:`CellRealisation.linearisation_hook`.

A realisation writes into the system only through the public methods of the
:class:`~exudyn_atcm.mbs.build_context.BuildContext` it is handed.  Its mass-damping ability and its
cost are the kind's (:attr:`~exudyn_atcm.cells.CellKind.realises_mass_damping`,
:meth:`~exudyn_atcm.cells.CellKind.estimate_step_cost`), read through the realisation.

Three end behaviours are written once and shared: :class:`HingedEnds` (rigid-cell chains: a
bender end is a massless interface joined to its end cell by an end spring),
:class:`~exudyn_atcm.mbs.node_chain.NodeEnds` (beam, ANCF, assumed-mode and rod benders: an end is a
node) and the six-bar chain's own (its ends are the bodies of the groups they join).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import ClassVar

import numpy as np

from .._checks import shown
from ..cells import CellKind
from ..mechanism.bender import Bender
from ..mechanism.points import MechanismError
from .model import Element, EndReadout

#: The build context's type (:class:`exudyn_atcm.mbs.build_context.BuildContext`, which imports this module),
#: for annotations only.
BuildContext = "exudyn_atcm.mbs.build_context.BuildContext"

__all__ = ["CellRealisation", "HingedEnds", "register_realisation", "realisation_for", "make_realisation",
           "registered_realisations", "EndMass"]

#: ``(mass [kg], inertia about its centre [kg m²], centre (global, reference pose) [m])``
EndMass = tuple[float, float, np.ndarray]

_REALISATIONS: dict[type, type[CellRealisation]] = {}


class CellRealisation(ABC):
    """The Exudyn realisation of one bender made of one cell kind (one instance per bender and build).

    Parameters
    ----------
    bender : Bender
        The bender this instance realises (``bender.cell`` is its kind).

    Attributes
    ----------
    ends_on_group_body : bool
        The chain ends on the bodies of the groups its ends belong to (the six-bar chain): the layout
        makes every such group a real body.
    ends_are_nodes : bool
        The bender's ends are nodes of its own (:meth:`end_body_key`): a group of bender ends only has
        that node as its body.
    """

    ends_on_group_body: ClassVar[bool] = False
    ends_are_nodes: ClassVar[bool] = False

    def __init__(self, bender: Bender) -> None:
        self.bender = bender
        self.cell: CellKind = bender.cell

    # ------------------------------------------------------------------ what the builder calls
    @abstractmethod
    def add_cells(self, ctx: BuildContext) -> None:
        """Add the bender's items through ``ctx`` and register its cells (:meth:`~BuildContext.set_cells`)."""

    @abstractmethod
    def connect_end(self, ctx: BuildContext, end: str) -> None:
        """Join ``end`` (``"base"`` or ``"tip"``) to the rest of the mechanism and register how its rotation
        is read (:meth:`~exudyn_atcm.mbs.build_context.BuildContext.set_end_readout`)."""

    def end_body_key(self, end: str) -> str | None:
        """The key of the body (node) that is this end, if the end is a node of the bender (else ``None``)."""
        return None

    def end_spring(self, ctx: BuildContext, end: str) -> tuple[Element, str, tuple[float, float]]:
        """The end spring of a massless end interface: element, end cell key, the end point in the cell's frame [m].

        Raises
        ------
        MechanismError
            If the kind's ends are no massless interfaces.
        """
        raise MechanismError(f"bender {self.bender.name!r}: the {self.cell.name} cell has no end springs (its "
                             f"{end} is no massless interface)")

    def interface_mass(self, end: str) -> EndMass:
        """The laminate over ``s = min(h1 + h2, L_c/10)`` at ``end``: mass [kg], inertia [kg m²], centre [m]."""
        bender = self.bender
        lam = bender.laminate
        lc = float(bender.cell_lengths[0 if end == "base" else -1])
        h = lam.passive.thickness + (lam.active.thickness if lam.active is not None else 0.0)
        s = lam.interface_length(lc)
        m = lam.mass_per_length * s
        return m, m * (s**2 + h**2) / 12.0, np.array(bender.points[end], dtype=float)

    def end_masses(self, end: str, carried: bool) -> list[EndMass]:
        """The masses ``end`` puts on its group's body; ``carried``: the group holds parts other than bender
        ends (a link), which then carry the end (no interface mass of its own by default)."""
        return [] if carried else [self.interface_mass(end)]

    def interface_body_mass(self, end: str) -> tuple[float, float, tuple[float, float]]:
        """Mass [kg], inertia [kg m²] and centre in the end frame [m] of an interface body of ``end`` alone."""
        m, j, _ = self.interface_mass(end)
        return m, j, (0.0, 0.0)

    def strain_writer(self) -> Callable[[np.ndarray], None] | None:
        """A function of the sources' strains that writes them into the realisation's own items before every
        attempted step (``None``: the actuation goes through the hinges' springs or the builder's torques)."""
        return None

    def linearisation_hook(self) -> Callable[[np.ndarray], None] | None:
        """A function of the strains called before an eigenvalue analysis (``None``: nothing to update)."""
        return None

    # ------------------------------------------------------------------ the kind's own figures
    @property
    def realises_mass_damping(self) -> bool:
        """Every mass of the realisation is a rigid body with its own mass damper (the kind's flag)."""
        return self.cell.realises_mass_damping

    def estimate_step_cost(self) -> float | None:
        """Measured wall time per accepted step [s] of this bender (the kind's cost model), or ``None``."""
        return self.cell.estimate_step_cost(self.bender.n_cells)


class HingedEnds(CellRealisation):
    """Ends that are massless interfaces joined to the end cells by an end spring (rigid-cell chains).

    A subclass adds its cells (:meth:`add_cells`) and says what its end spring is (:meth:`end_spring`);
    this class joins the ends: to a group's body by a hinge, as a free end (read from the end cell and
    the spring's free rotation), or two ends welded together as one hinge through both end springs.
    """

    @abstractmethod
    def end_spring(self, ctx: BuildContext, end: str) -> tuple[Element, str, tuple[float, float]]:
        """The end spring: element, end cell key, the end point in the cell's frame [m]."""

    def connect_end(self, ctx: BuildContext, end: str) -> None:
        bender = self.bender
        part = f"{bender.name}#{end}"
        group = ctx.group(bender, end)
        el, cell, _ = self.end_spring(ctx, end)
        if group.kind != "virtual":
            a, b = (cell, group.key) if end == "tip" else (group.key, cell)
            ctx.hinge_at(a, b, [el], bender.points[end])
            ctx.set_end_readout(bender, end, EndReadout("body", body=group.key))
        elif not group.joints and len(group.interfaces) == 1:
            sign = 1.0 if end == "tip" else -1.0
            ctx.set_end_readout(bender, end, EndReadout("free", body=cell, sign=sign, theta=el.theta))
        elif not group.joints and part == group.interfaces[0]:
            # two ends welded together: one hinge from the first end cell to the second
            ctx.join_in_series(group.interfaces[0], None, group.interfaces[1], bender.points[end])


def register_realisation(kind: type[CellKind]) -> Callable[[type[CellRealisation]], type[CellRealisation]]:
    """Class decorator: register a :class:`CellRealisation` subclass for the cell kind class ``kind``.

    A subclass of ``kind`` without a registration of its own is realised the same way.

    Raises
    ------
    TypeError
        If ``kind`` is no :class:`~exudyn_atcm.cells.CellKind` subclass or the decorated class no
        :class:`CellRealisation` subclass.
    """
    if not (isinstance(kind, type) and issubclass(kind, CellKind)):
        raise TypeError(f"register_realisation: kind must be a CellKind subclass, got {shown(kind)}")

    def decorate(realisation: type[CellRealisation]) -> type[CellRealisation]:
        if not (isinstance(realisation, type) and issubclass(realisation, CellRealisation)):
            raise TypeError(f"register_realisation({kind.__name__}): the decorated class must subclass "
                            f"CellRealisation, got {shown(realisation)}")
        _REALISATIONS[kind] = realisation
        return realisation
    return decorate


def realisation_for(cell: CellKind | type[CellKind]) -> type[CellRealisation]:
    """The realisation class registered for ``cell``'s class or its nearest registered parent.

    Raises
    ------
    ValueError
        If none is registered, saying how to register one.
    """
    cls = cell if isinstance(cell, type) else type(cell)
    for klass in cls.__mro__:
        if klass in _REALISATIONS:
            return _REALISATIONS[klass]
    name = getattr(cell, "name", cls.__name__)
    raise ValueError(f"cell kind {name!r} ({cls.__name__}) has no Exudyn realisation: register one with "
                     "exudyn_atcm.mbs.realisation.register_realisation (a CellRealisation subclass)")


def make_realisation(bender: Bender) -> CellRealisation:
    """The realisation of ``bender``: an instance of the class registered for its cell kind."""
    return realisation_for(bender.cell)(bender)


def registered_realisations() -> dict[type, type[CellRealisation]]:
    """A copy of the registry: kind class -> realisation class."""
    return dict(_REALISATIONS)

