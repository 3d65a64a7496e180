"""Where the description meets the layer that builds it (dependency inversion, no Exudyn here).

The description layer (:mod:`exudyn_atcm.mechanism`) never imports the Exudyn layer
(:mod:`exudyn_atcm.mbs`).  The two conveniences of the description that need a built model,
:meth:`Mechanism.degrees_of_freedom <exudyn_atcm.Mechanism.degrees_of_freedom>` and the check of
dependent joints in :meth:`Mechanism.check <exudyn_atcm.Mechanism.check>`, call the functions that
:mod:`exudyn_atcm.mbs` registers here when it is imported, so the only import arrow runs from
``mbs`` to ``mechanism``.  ``import exudyn_atcm`` loads its parts on first use (a fast start),
so the first call here that finds nothing registered imports the registering module,
:data:`PROVIDER`, by name (until 2026-11-30 :meth:`Mechanism.check <exudyn_atcm.Mechanism.check>`
then skipped the check of dependent joints silently, and ``degrees_of_freedom`` asked the user to
``import exudyn_atcm``, which they had done).
"""

from __future__ import annotations

import importlib
from typing import Any, Callable
from .._checks import shown

__all__ = ["register_dof_counter", "count_degrees_of_freedom", "register_redundancy_check", "check_redundancy", "PROVIDER"]

_COUNTERS: list[Callable[[Any], Any]] = []
_REDUNDANCY_CHECKS: list[Callable[[Any], None]] = []
#: The module whose import registers the functions (the package's Exudyn layer).
PROVIDER = "exudyn_atcm.mbs"


def _registered(functions: list, what: str) -> Callable | None:
    """The registered function of ``functions``, the :data:`PROVIDER` imported first if none is; ``None`` when the
    provider cannot be imported (the description layer used without Exudyn installed)."""
    if not functions:
        try:
            importlib.import_module(PROVIDER)
        except ImportError:
            return None
    if not functions:
        raise RuntimeError(f"no {what} registered: importing {PROVIDER} should have registered it")
    return functions[0]


def register_dof_counter(counter: Callable[[Any], Any]) -> None:
    """Register ``counter(mechanism) -> DofReport`` (the Exudyn layer does this on import)."""
    if not callable(counter):
        raise ValueError(f"counter must be callable, got {shown(counter)}")
    _COUNTERS[:] = [counter]


def count_degrees_of_freedom(mechanism: Any) -> Any:
    """Degrees of freedom of ``mechanism`` from the registered counter.

    Raises
    ------
    RuntimeError
        If :data:`PROVIDER` cannot be imported (Exudyn not installed) or registered no counter.
    """
    counter = _registered(_COUNTERS, "degrees-of-freedom counter")
    if counter is None:
        raise RuntimeError(f"degrees_of_freedom() needs the package's Exudyn layer, and {PROVIDER} cannot be imported "
                           "(is Exudyn installed?)")
    return counter(mechanism)


def register_redundancy_check(check: Callable[[Any], None]) -> None:
    """Register ``check(mechanism)``, raising ``MechanismError`` for dependent joints (the Exudyn layer does this)."""
    if not callable(check):
        raise ValueError(f"check must be callable, got {shown(check)}")
    _REDUNDANCY_CHECKS[:] = [check]


def check_redundancy(mechanism: Any) -> bool:
    """Refuse ``mechanism`` when its joints are dependent in the reference pose (the registered check).

    Returns whether it was checked: ``False`` only when :data:`PROVIDER` cannot be imported (the
    description layer used without Exudyn installed; every solve checks the model it builds).

    Raises
    ------
    MechanismError
        For dependent joints.
    RuntimeError
        If importing :data:`PROVIDER` registered no check.
    """
    check = _registered(_REDUNDANCY_CHECKS, "check of dependent joints")
    if check is None:
        return False
    check(mechanism)
    return True
