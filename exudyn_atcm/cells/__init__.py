"""Cell kinds: one object per discretisation of a bender, in one open registry by name.

Every place that accepts ``cell=`` resolves it here with :func:`cell_kind`: a name registered in
:data:`CELL_KINDS` (the package's kinds, and those of users registered with
:func:`register_cell_kind`), a :class:`CellKind` instance or a :class:`CellKind` subclass.  No
other code compares cell names; it asks the cell object (``cell.carries_tip_load``,
``cell.mechanism_refusal()``, ...), and lists of names are read from the registry when used
(:func:`cell_kind_names`).  The Exudyn side of each kind is registered by class in
:mod:`exudyn_atcm.mbs.realisation`, so a subclass defined outside the package is realised like
its parent unless it registers a realisation of its own.

May import: :mod:`exudyn_atcm.theory` and the top-level helpers (no Exudyn, no solving).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .._checks import shown
from ..suggestions import close_names
from .ancf import AncfCell
from .base import CELL_KINDS, END_BODY, END_CHAIN, END_NODE, CellKind
from .beam import BeamCell
from .rigid import RigidCell
from .ritz import RitzCell
from .rod import RodCell
from .six_bar import SixBarCell

__all__ = ["CellKind", "RigidCell", "SixBarCell", "BeamCell", "AncfCell", "RitzCell", "RodCell", "CELL_KINDS", "cell_kind",
           "register_cell_kind", "cell_kind_names", "END_BODY", "END_CHAIN", "END_NODE"]

#: The cell kinds by name: the package's, then those registered with :func:`register_cell_kind` (the one
#: place where kinds are listed; read it when used, never copy it at import).
CELL_KINDS.update({kind.name: kind for kind in (SixBarCell(), RigidCell(), BeamCell(), AncfCell(), RitzCell(), RodCell())})


def register_cell_kind(kind: CellKind | type[CellKind], *, replace: bool = False) -> CellKind:
    """Make the cell kind ``kind`` usable by its name everywhere ``cell=`` is accepted.

    After ``register_cell_kind(MyCell)``, ``Bender(..., cell="my-cell")``, a case's ``cell`` parameter,
    ``--set cell=my-cell``, sweeps over ``cell``, drawings and run-cost estimates accept the name.  Its
    Exudyn realisation is registered separately in the Exudyn layer
    (:func:`exudyn_atcm.mbs.realisation.register_realisation`).

    Parameters
    ----------
    kind : CellKind or CellKind subclass
        The kind (a class is instantiated without arguments).  Its ``name`` must be a non-empty string.
    replace : bool
        Allow replacing a registered kind of the same name by a kind of another class (the package's
        own kinds are never replaced).

    Returns
    -------
    CellKind
        The registered instance.

    Raises
    ------
    ValueError
        If ``kind`` is no cell kind, its name is empty, or the name is taken by another kind (a package
        kind, or another class without ``replace=True``).
    """
    if not (isinstance(kind, CellKind) or (isinstance(kind, type) and issubclass(kind, CellKind))):
        raise ValueError(f"kind must be a CellKind instance or subclass, got {shown(kind)}")
    kind = cell_kind(kind, "kind")
    taken = CELL_KINDS.get(kind.name)
    if taken is not None and type(taken) is not type(kind):
        if type(taken) in _PACKAGE_KINDS or not replace:
            raise ValueError(f"kind: the name {kind.name!r} is taken by {type(taken).__name__}; give "
                             f"{type(kind).__name__} another name" + ("" if type(taken) in _PACKAGE_KINDS
                                                                       else " or pass replace=True"))
    CELL_KINDS[kind.name] = kind
    return kind


_PACKAGE_KINDS = frozenset(type(kind) for kind in CELL_KINDS.values())


def cell_kind_names(where: Callable[[CellKind], bool] | None = None) -> tuple[str, ...]:
    """The names of the registered cell kinds (``where(kind)`` true, if given), read now."""
    return tuple(name for name, kind in CELL_KINDS.items() if where is None or where(kind))


def cell_kind(value: Any, parameter: str = "cell") -> CellKind:
    """The :class:`CellKind` for ``value``: a registered name (``"rigid"``), a kind, or a kind's class.

    Raises
    ------
    ValueError
        Naming ``parameter``, the value received and the registered names.
    """
    if isinstance(value, type) and issubclass(value, CellKind):
        value = value()
    if isinstance(value, CellKind):
        if not isinstance(value.name, str) or not value.name:
            raise ValueError(f"{parameter}: a CellKind needs a non-empty name, got {value.name!r} "
                             f"on {type(value).__name__}")
        return value
    if isinstance(value, str) and value in CELL_KINDS:
        return CELL_KINDS[value]
    hint = close_names(value, CELL_KINDS, ignore_case=True) if isinstance(value, str) else []
    # the registered names, read now (kinds registered with register_cell_kind included)
    raise ValueError(f"{parameter} must be one of {tuple(CELL_KINDS)} or a CellKind, got {shown(value)}"
                     + (f" (did you mean {hint[0]!r}?)" if hint else "")
                     + "; register a kind of your own by name with exudyn_atcm.register_cell_kind")
