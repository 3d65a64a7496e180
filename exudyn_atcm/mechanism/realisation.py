"""Where the description meets the layer that builds it (dependency inversion, no Exudyn here).

The description layer (:mod:`exudyn_atcm.mechanism`) never imports the Exudyn layer
(:mod:`exudyn_atcm.mbs`).  The one convenience of the description that needs a built model,
:meth:`Mechanism.degrees_of_freedom <exudyn_atcm.Mechanism.degrees_of_freedom>`, calls the
counter that :mod:`exudyn_atcm.mbs` registers here when it is imported (``import exudyn_atcm``
imports it), so the only import arrow runs from ``mbs`` to ``mechanism``.
"""

from __future__ import annotations

from typing import Any, Callable

__all__ = ["register_dof_counter", "count_degrees_of_freedom"]

_COUNTERS: list[Callable[[Any], Any]] = []


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
