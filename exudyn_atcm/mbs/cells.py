"""The Exudyn realisation of each cell kind, registered by class (a generic function).

:func:`add_mechanism_bender` adds a bender's cells to the system the builder
(:mod:`~exudyn_atcm.mbs.builder`) is making, for a mechanism and for a lone actuator alike
(the actuator is built as a one-bender mechanism).  It dispatches on the class of the
:class:`~exudyn_atcm.cells.CellKind` (``functools.singledispatch``), so a subclass of a kind,
also one defined outside the package, is built like its parent; a new kind registers its own
realisation::

    @add_mechanism_bender.register
    def _(cell: MyCell, builder, bender): ...

The package's realisations are in :mod:`~exudyn_atcm.mbs.rigid_chain`,
:mod:`~exudyn_atcm.mbs.six_bar`, :mod:`~exudyn_atcm.mbs.beam_chain`,
:mod:`~exudyn_atcm.mbs.ancf_chain` and :mod:`~exudyn_atcm.mbs.ritz_bender`.
"""

from __future__ import annotations

from functools import singledispatch
from typing import Any

from ..cells import CellKind

__all__ = ["add_mechanism_bender"]


@singledispatch
def add_mechanism_bender(cell: CellKind, builder: Any, bender: Any) -> None:
    """Add the cells of a mechanism's ``bender`` (made of ``cell``) through the mechanism ``builder``.

    Raises
    ------
    ValueError
        If no realisation is registered for the class of ``cell``.
    """
    raise ValueError(f"cell kind {cell.name!r} ({type(cell).__name__}) has no Exudyn realisation: register one"
                     " with exudyn_atcm.mbs.cells.add_mechanism_bender.register")
