"""Where the description meets the layer that builds it (dependency inversion, no Exudyn here).

The description layer (:mod:`exudyn_atcm.mechanism`) never imports the Exudyn layer
(:mod:`exudyn_atcm.mbs`).  The two conveniences of the description that need a built model,
:meth:`Mechanism.degrees_of_freedom <exudyn_atcm.Mechanism.degrees_of_freedom>` and the check of
dependent joints in :meth:`Mechanism.check <exudyn_atcm.Mechanism.check>`, call the functions that
:mod:`exudyn_atcm.mbs` registers here when it is imported (``import exudyn_atcm`` imports it), so
the only import arrow runs from ``mbs`` to ``mechanism``.
"""

from __future__ import annotations

from typing import Any, Callable

__all__ = ["register_dof_counter", "count_degrees_of_freedom", "register_redundancy_check", "check_redundancy"]

_COUNTERS: list[Callable[[Any], Any]] = []
_REDUNDANCY_CHECKS: list[Callable[[Any], None]] = []


def register_dof_counter(counter: Callable[[Any], Any]) -> None:
    """Register ``counter(mechanism) -> DofReport`` (the Exudyn layer does this on import)."""
    if not callable(counter):
        raise ValueError(f"counter must be callable, got {counter!r}")
    _COUNTERS[:] = [counter]


def count_degrees_of_freedom(mechanism: Any) -> Any:
    """Degrees of freedom of ``mechanism`` from the registered counter.

    Raises
    ------
    RuntimeError
        If no counter is registered (only when :mod:`exudyn_atcm.mechanism` was imported without
        the package's Exudyn layer; ``import exudyn_atcm`` registers it).
    """
    if not _COUNTERS:
        raise RuntimeError("no degrees-of-freedom counter registered: import exudyn_atcm (its Exudyn layer, "
                           "exudyn_atcm.mbs, registers it)")
    return _COUNTERS[0](mechanism)


def register_redundancy_check(check: Callable[[Any], None]) -> None:
    """Register ``check(mechanism)``, raising ``MechanismError`` for dependent joints (the Exudyn layer does this)."""
    if not callable(check):
        raise ValueError(f"check must be callable, got {check!r}")
    _REDUNDANCY_CHECKS[:] = [check]


def check_redundancy(mechanism: Any) -> bool:
    """Refuse ``mechanism`` when its joints are dependent in the reference pose (the registered check).

    Returns ``False`` without checking when no check is registered: only when the description
    layer is used without the package's Exudyn layer (``import exudyn_atcm`` registers it, and
    every solve checks the model it builds in any case).
    """
    if not _REDUNDANCY_CHECKS:
        return False
    _REDUNDANCY_CHECKS[0](mechanism)
    return True
