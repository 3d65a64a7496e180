"""Cell kinds: one object per discretisation of a bender, listed once.

Every place that accepts ``cell=`` resolves it here with :func:`cell_kind`: a name from
:data:`CELL_KINDS`, a :class:`CellKind` instance or a :class:`CellKind` subclass.  No other code
compares cell names; it asks the cell object (``cell.carries_tip_load``, ``cell.end_kind``,
``cell.mechanism_refusal()``, ...).  The Exudyn side of each kind is registered in
:mod:`exudyn_atcm.mbs.cells` by class, so a subclass defined outside the package is realised
like its parent.

May import: :mod:`exudyn_atcm.theory` and the top-level helpers (no Exudyn, no solving).
"""

from __future__ import annotations

from typing import Any

from ..suggestions import close_names
from .ancf import AncfCell
from .base import END_BODY, END_CHAIN, END_NODE, CellKind
from .beam import BeamCell
from .rigid import RigidCell
from .ritz import RitzCell
from .rod import RodCell
from .six_bar import SixBarCell

__all__ = ["CellKind", "RigidCell", "SixBarCell", "BeamCell", "AncfCell", "RitzCell", "RodCell", "CELL_KINDS", "cell_kind",
           "END_BODY", "END_CHAIN", "END_NODE"]

#: The package's cell kinds by name (the one place where kinds are listed).
CELL_KINDS: dict[str, CellKind] = {kind.name: kind for kind in
                                   (SixBarCell(), RigidCell(), BeamCell(), AncfCell(), RitzCell(), RodCell())}


def cell_kind(value: Any, parameter: str = "cell") -> CellKind:
    """The :class:`CellKind` for ``value``: a name (``"rigid"``), a kind, or a kind's class.

    Raises
    ------
    ValueError
        Naming ``parameter``, the value received and the known names.
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
    raise ValueError(f"{parameter} must be one of {tuple(CELL_KINDS)} or a CellKind, got {value!r}"
                     + (f" (did you mean {hint[0]!r}?)" if hint else ""))
