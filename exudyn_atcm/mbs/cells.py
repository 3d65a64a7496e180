"""The Exudyn realisation of each cell kind, registered by class (a generic function).

:func:`add_mechanism_bender` adds a bender's cells to the system the builder
(:mod:`~exudyn_atcm.mbs.builder`) is making, for a mechanism and for a lone actuator alike
(the actuator is built as a one-bender mechanism).  It dispatches on the class of the
:class:`~exudyn_atcm.cells.CellKind` (``functools.singledispatch``), so a subclass of a kind,
also one defined outside the package, is built like its parent; a new kind registers its own
realisation::

    @add_mechanism_bender.register
    def _(cell: MyCell, builder, bender): ...

The package's realisations are in :mod:`~exudyn_atcm.mbs.chains.rigid`,
:mod:`~exudyn_atcm.mbs.chains.six_bar`, :mod:`~exudyn_atcm.mbs.chains.beam`,
:mod:`~exudyn_atcm.mbs.chains.ancf`, :mod:`~exudyn_atcm.mbs.chains.ritz` and
:mod:`~exudyn_atcm.mbs.chains.rod`.
"""

from __future__ import annotations

import warnings
from functools import singledispatch
from typing import Any, Callable

from ..cells import CellKind
from ..errors import AtcmDeprecationWarning

__all__ = ["add_mechanism_bender", "add_actuator_cells"]


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


class _RetiredActuatorRealisations:
    """``add_actuator_cells`` of earlier releases, kept for one release: the lone actuator has no builder of
    its own any more (it is built as a one-bender mechanism through :func:`add_mechanism_bender`).
    Registering with it warns and registers nothing; calling it raises."""

    def register(self, cls: Any, func: Callable | None = None) -> Any:
        warnings.warn("exudyn_atcm.mbs.cells.add_actuator_cells is retired and this registration has no effect: the "
                      "lone actuator is built as a one-bender mechanism, so register the kind's realisation once with "
                      "exudyn_atcm.mbs.cells.add_mechanism_bender.register", AtcmDeprecationWarning, stacklevel=2)
        if func is None and isinstance(cls, type):
            return lambda f: f
        return cls if func is None else func

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        raise ValueError("exudyn_atcm.mbs.cells.add_actuator_cells is retired: the lone actuator is built as a "
                         "one-bender mechanism (exudyn_atcm.mbs.builder.build of "
                         "exudyn_atcm.solve.as_mechanism.actuator_mechanism(actuator))")


#: Retired (one release): see :class:`_RetiredActuatorRealisations`.
add_actuator_cells = _RetiredActuatorRealisations()
