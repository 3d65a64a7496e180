"""The damping of a laminate part (bender, actuator, flexure strip), from its ``damping`` argument.

A part made of the laminate gets Rayleigh damping: the material's coefficients when
``damping`` is a :class:`~exudyn_atcm.RayleighDamping` (independent of how the part was cut), or
``beta = 2 zeta / omega_1`` of the part itself as a cantilever for a damping ratio ``zeta``
(``alpha = 0``).  :class:`MaterialDamped` gives every such part the same three properties.
"""

from __future__ import annotations

from typing import Any, Callable

from ..model.damping import RayleighDamping

__all__ = ["MaterialDamped"]


class MaterialDamped:
    """Mixin of the laminate parts: needs ``laminate``, ``length`` [m] and ``damping`` (ratio or RayleighDamping)."""

    def _cached(self, name: str, key: tuple, make: Callable[[], Any]) -> Any:
        """``make()``, kept while ``key`` (the inputs it depends on) is unchanged: a build asks for a part's
        laminate and damping a few dozen times (0.5 ms of a 7 ms synthesis evaluation, each time checking the
        layers' plausibility again), and a part's attributes may still be changed between builds."""
        cache = self.__dict__.setdefault("_derived", {})
        hit = cache.get(name)
        if hit is not None and hit[0] == key:
            return hit[1]
        value = make()
        cache[name] = (key, value)
        return value

    @property
    def rayleigh_damping(self) -> RayleighDamping:
        """The part's Rayleigh coefficients: the material damping given, or ``beta = 2 zeta / omega_1``
        of the part as a cantilever (``alpha = 0``) for a damping ratio ``zeta``."""
        ratio = None if isinstance(self.damping, RayleighDamping) else self.damping
        laminate, length = self.laminate, self.length
        return self._cached("rayleigh_damping", (laminate, length, ratio),
                            lambda: laminate.rayleigh_damping(length, ratio))

    @property
    def stiffness_damping_factor(self) -> float:
        """``beta`` [s]: every spring or element of stiffness ``k`` gets the damping ``beta k``."""
        return self.rayleigh_damping.beta

    @property
    def mass_damping_factor(self) -> float:
        """``alpha`` [1/s]: every mass ``m`` gets the damping force ``-alpha m v`` (0 for a damping ratio)."""
        return self.rayleigh_damping.alpha
