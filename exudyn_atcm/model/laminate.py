"""The two-layer laminate of a bender: stiffness, free curvature, mass and damping per unit length.

One formula set for every bender of the package: :class:`~exudyn_atcm.mechanism.actuator.BendingActuator`
and :class:`~exudyn_atcm.mechanism.Bender` both take their physics from :class:`Laminate`.

Coordinates of a cross-section: the passive layer's mid-plane is the reference line; the
active layer's mid-plane lies at the distance ``e = (h_passive + h_active)/2`` on the
active side.  Lamination theory (Timoshenko 1925) gives the bending stiffness and the free
curvature per unit free strain of the active layer.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .damping import RayleighDamping
from .materials import Layer

STIFFNESS_MODELS = ("composite", "paper")

_BETA1_L = 1.8751040687119611  # first root of 1 + cos x cosh x = 0


@dataclass(frozen=True)
class Laminate:
    """Cross-section of a bender: a passive layer and an optional active (MFC) layer.

    Parameters
    ----------
    width : float
        Width ``b`` of both layers [m].
    passive : Layer
        Passive layer (textile composite).
    active : Layer or None
        Active layer (MFC); ``None`` for a passive strip (a textile flexure).
    stiffness : {"composite", "paper"}
        ``"composite"``: the layers couple through ``a1 a2/(a1 + a2)`` (lamination theory);
        ``"paper"``: through ``a2 = E2 b h2`` as printed in the paper (its Eq. 4).
    damping : RayleighDamping or None, optional
        Material damping of the laminate (Rayleigh coefficients, the same for every bender
        of it however it is cut into parts); ``None`` (default): none given, a bender then
        uses its damping ratio at its own first mode (see :meth:`rayleigh_damping`).
    """

    width: float
    passive: Layer
    active: Layer | None
    stiffness: str = "composite"
    damping: RayleighDamping | None = None

    def __post_init__(self) -> None:
        if self.damping is not None and not isinstance(self.damping, RayleighDamping):
            raise ValueError(f"damping must be a RayleighDamping or None, got {self.damping!r}")

    @property
    def layer_offset(self) -> float:
        """Distance ``e`` between the layers' mid-planes [m] (0 without an active layer)."""
        if self.active is None:
            return 0.0
        return 0.5 * (self.passive.thickness + self.active.thickness)

    @property
    def axial_rigidity_effective(self) -> float:
        """Axial rigidity that couples the layers [N]: ``a1 a2/(a1+a2)`` (composite) or ``a2`` (paper)."""
        if self.active is None:
            return 0.0
        a1 = self.passive.axial_rigidity(self.width)
        a2 = self.active.axial_rigidity(self.width)
        if self.stiffness == "composite":
            return a1 * a2 / (a1 + a2)
        return a2

    @property
    def own_bending_stiffness(self) -> float:
        """``E1 I1 + E2 I2``: the layers' bending stiffness about their own mid-planes [N m²]."""
        own = self.passive.bending_stiffness(self.width)
        if self.active is not None:
            own = own + self.active.bending_stiffness(self.width)
        return own

    @property
    def bending_stiffness(self) -> float:
        """Bending stiffness ``EI = E1 I1 + E2 I2 + a_eff e²`` [N m²]."""
        if self.active is None:
            return self.passive.bending_stiffness(self.width)
        return (
            self.passive.bending_stiffness(self.width)
            + self.active.bending_stiffness(self.width)
            + self.axial_rigidity_effective * self.layer_offset**2
        )

    @property
    def curvature_per_strain(self) -> float:
        """Free curvature per unit free strain ``a_eff e / EI`` [1/m] (0 without an active layer)."""
        if self.active is None:
            return 0.0
        return self.axial_rigidity_effective * self.layer_offset / self.bending_stiffness

    @property
    def mass_per_length(self) -> float:
        """Mass per unit length ``b (rho1 h1 + rho2 h2)`` [kg/m]."""
        mass = self.passive.mass_per_length(self.width)
        if self.active is not None:
            mass = mass + self.active.mass_per_length(self.width)
        return mass

    @property
    def axial_rigidity(self) -> float:
        """Summed axial rigidity ``a1 + a2`` of the layers [N] (the beam cells' practically inextensible axis)."""
        a = self.passive.axial_rigidity(self.width)
        if self.active is not None:
            a = a + self.active.axial_rigidity(self.width)
        return a

    @property
    def rotary_inertia_per_length(self) -> float:
        """Rotary inertia per unit length about the passive layer's mid-plane [kg m].

        ``b (rho1 h1³/12 + rho2 (h2³/12 + h2 e²))``: each layer about its own mid-plane, the
        active layer shifted by ``e`` (the beam cells' cross-section inertia).
        """
        rho_i = self.passive.density * self.width * self.passive.thickness**3 / 12.0
        if self.active is not None:
            h2, e = self.active.thickness, self.layer_offset
            rho_i = rho_i + self.active.density * self.width * (h2**3 / 12.0 + h2 * e**2)
        return rho_i

    def first_frequency(self, length: float) -> float:
        """First bending frequency [Hz] of a clamped-free beam of this laminate and ``length`` [m]."""
        return _BETA1_L**2 / (2.0 * math.pi * length**2) * math.sqrt(self.bending_stiffness / self.mass_per_length)

    def stiffness_damping_factor(self, damping: float, length: float) -> float:
        """``beta = 2 zeta / omega_1`` [s] for the damping ratio ``damping`` of the cantilever's first mode.

        Every spring of stiffness ``k`` gets the damping ``beta k`` (stiffness-proportional damping).
        """
        return 2.0 * damping / (2.0 * math.pi * self.first_frequency(length))

    def rayleigh_damping(self, length: float, ratio: float | None = None) -> RayleighDamping:
        """Rayleigh coefficients of a bender of this laminate and ``length`` [m].

        The laminate's material damping :attr:`damping` when given (then ``length`` and
        ``ratio`` do not matter); otherwise stiffness-proportional damping with the damping
        ratio ``ratio`` [-] at the first clamped-free mode of ``length``:
        ``beta = 2 ratio / omega_1(length)`` (:meth:`stiffness_damping_factor`), ``alpha = 0``.
        """
        if self.damping is not None:
            return self.damping
        if ratio is None:
            raise ValueError("ratio must be a damping ratio >= 0 when the laminate has no material damping, got None")
        return RayleighDamping(0.0, self.stiffness_damping_factor(ratio, length))

    def rigid_cell(self, cell_length: float) -> tuple[float, float, float]:
        """One rigid cell of length ``cell_length`` [m]: mass [kg], centre-of-mass offset [m], inertia [kg m²].

        The offset is measured from the passive layer's mid-plane towards the active layer
        (``m2 e / m``); the inertia is about the centre of mass, both layers as thin strips.
        """
        m1 = self.passive.mass_per_length(self.width) * cell_length
        if self.active is None:
            return m1, 0.0, m1 * cell_length**2 / 12.0 + m1 * self.passive.thickness**2 / 12.0
        e = self.layer_offset
        h1, h2 = self.passive.thickness, self.active.thickness
        m2 = self.active.mass_per_length(self.width) * cell_length
        m = m1 + m2
        j_com = m * cell_length**2 / 12.0 + (m1 * h1**2 + m2 * h2**2) / 12.0 + m1 * m2 / m * e**2
        return m, m2 * e / m, j_com

    # ------------------------------------------------------------------ six-bar cell (paper Fig. 2)
    def layer_joint_stiffness(self, cell_length: float) -> tuple[float, float]:
        """Six-bar cell: torsion springs ``2 E1 I1 / L_c`` (passive) and ``2 E2 I2 / L_c`` (active) [N m/rad]."""
        if self.active is None:
            raise ValueError("the six-bar cell needs an active layer (active=None given)")
        return (2.0 * self.passive.bending_stiffness(self.width) / cell_length,
                2.0 * self.active.bending_stiffness(self.width) / cell_length)

    def axial_spring_stiffness(self, cell_length: float) -> float:
        """Six-bar cell: axial spring ``k1 = a_eff / L_c`` between A2 and A3 [N/m]."""
        return self.axial_rigidity_effective / cell_length

    def interface_length(self, cell_length: float) -> float:
        """Length ``s = min(h1 + h2, L_c/10)`` of laminate lumped into each six-bar interface [m]."""
        h = self.passive.thickness + (self.active.thickness if self.active is not None else 0.0)
        return min(h, 0.1 * cell_length)
