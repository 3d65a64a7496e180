"""Layer materials of the bending actuator."""

from __future__ import annotations

from dataclasses import dataclass

from ._checks import positive_float


@dataclass(frozen=True)
class Layer:
    """One homogeneous layer of the laminate (the passive CFC or the active MFC layer).

    Parameters
    ----------
    thickness : float
        Layer thickness ``h`` [m], > 0.
    youngs_modulus : float
        Young's modulus along the actuator axis ``E`` [Pa], > 0.
    density : float
        Mass density ``rho`` [kg/m³], > 0.

    Raises
    ------
    ValueError
        If a value is not a finite positive number (the message names the parameter).

    Examples
    --------
    >>> cfc = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
    """

    thickness: float
    youngs_modulus: float
    density: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "thickness", positive_float("thickness", self.thickness))
        object.__setattr__(self, "youngs_modulus", positive_float("youngs_modulus", self.youngs_modulus))
        object.__setattr__(self, "density", positive_float("density", self.density))

    def second_moment(self, width: float) -> float:
        """Second moment of area ``b h³/12`` of the layer cross-section [m⁴] (Eq. 6)."""
        return width * self.thickness**3 / 12.0

    def axial_rigidity(self, width: float) -> float:
        """Axial rigidity ``E b h`` [N]."""
        return self.youngs_modulus * width * self.thickness

    def bending_stiffness(self, width: float) -> float:
        """Own bending stiffness ``E I`` about the layer's mid-plane [N m²]."""
        return self.youngs_modulus * self.second_moment(width)

    def mass_per_length(self, width: float) -> float:
        """Mass per unit length ``rho b h`` [kg/m]."""
        return self.density * width * self.thickness
