"""The damping of a laminate part (bender, actuator, flexure strip), from its ``damping`` argument.

A part made of the laminate gets Rayleigh damping: the material's coefficients when
``damping`` is a :class:`~exudyn_atcm.RayleighDamping` (independent of how the part was cut), or
``beta = 2 zeta / omega_1`` of the part itself as a cantilever for a damping ratio ``zeta``
(``alpha = 0``).  :class:`MaterialDamped` gives every such part the same three properties.
"""

from __future__ import annotations

from ..model.damping import RayleighDamping

__all__ = ["MaterialDamped"]


class MaterialDamped:
    """Mixin of the laminate parts: needs ``laminate``, ``length`` [m] and ``damping`` (ratio or RayleighDamping)."""

    @property
    def rayleigh_damping(self) -> RayleighDamping:
        """The part's Rayleigh coefficients: the material damping given, or ``beta = 2 zeta / omega_1``
        of the part as a cantilever (``alpha = 0``) for a damping ratio ``zeta``."""
        ratio = None if isinstance(self.damping, RayleighDamping) else self.damping
        return self.laminate.rayleigh_damping(self.length, ratio)

    @property
    def stiffness_damping_factor(self) -> float:
        """``beta`` [s]: every spring or element of stiffness ``k`` gets the damping ``beta k``."""
        return self.rayleigh_damping.beta

    @property
    def mass_damping_factor(self) -> float:
        """``alpha`` [1/s]: every mass ``m`` gets the damping force ``-alpha m v`` (0 for a damping ratio)."""
        return self.rayleigh_damping.alpha
