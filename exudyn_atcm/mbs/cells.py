"""The Exudyn realisation of each cell kind, registered by class (generic functions).

:func:`add_actuator_cells` builds a lone actuator's chain of a given kind;
:func:`add_mechanism_bender` adds a mechanism bender's cells.  Both dispatch on the class of the
:class:`~exudyn_atcm.cells.CellKind` (``functools.singledispatch``), so a subclass of a kind,
also one defined outside the package, is built like its parent; a new kind registers its
own builders::

    @add_actuator_cells.register
    def _(cell: MyCell, SC, mbs, actuator, stroke_path, tip_force): ...

The package's own realisations are registered by :mod:`~exudyn_atcm.mbs.actuator_chains` and
:mod:`~exudyn_atcm.mbs.builder`.
"""

from __future__ import annotations

from functools import singledispatch
from typing import Any

from ..cells import CellKind

__all__ = ["add_actuator_cells", "add_mechanism_bender"]


@singledispatch
def add_actuator_cells(cell: CellKind, SC: Any, mbs: Any, actuator: Any, stroke_path: str, tip_force: Any) -> Any:
    """Add a lone actuator made of ``cell`` to ``mbs``; returns its model handles (not assembled).

    Raises
    ------
    ValueError
        If no realisation is registered for the class of ``cell``.
    """
    raise ValueError(f"cell kind {cell.name!r} ({type(cell).__name__}) has no Exudyn realisation for a lone "
                     "actuator: register one with exudyn_atcm.mbs.cells.add_actuator_cells.register")


@singledispatch
def add_mechanism_bender(cell: CellKind, builder: Any, bender: Any) -> None:
    """Add the cells of a mechanism's ``bender`` (made of ``cell``) through the mechanism ``builder``.

    Raises
    ------
    ValueError
        If no realisation is registered for the class of ``cell``.
    """
    raise ValueError(f"cell kind {cell.name!r} ({type(cell).__name__}) has no Exudyn realisation in a mechanism: "
                     "register one with exudyn_atcm.mbs.cells.add_mechanism_bender.register")
