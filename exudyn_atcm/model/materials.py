"""Layer materials of the bending actuator."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

from .._checks import positive_float
from ..physical_bounds import check_physical
from ..errors import InputRangeWarning

#: Plausible ranges (SI) of a layer's values; outside them a ``RuntimeWarning`` suggests a unit
#: mistake.  Thickness: textile and piezo layers are 10 µm ... 10 mm thick (0.2 means
#: 0.2 m, not 0.2 mm).  Young's modulus: 1e5 Pa (soft elastomers) ... 1.2e12 Pa (diamond);
#: 70 means 70 Pa, not 70 GPa.  Density: 10 kg/m³ (foams) ... 23000 kg/m³ (osmium); 1.55 is
#: g/cm³, not kg/m³.
PLAUSIBLE_RANGES = {
    "thickness": (1e-5, 1e-2, "m", "a thickness in mm or µm passed as metres"),
    "youngs_modulus": (1e5, 1.2e12, "Pa", "a modulus in GPa or MPa passed as Pa"),
    "density": (10.0, 23000.0, "kg/m³", "a density in g/cm³ passed as kg/m³"),
}


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
        If a value is not a finite positive number (the message names the parameter), or
        cannot be physical (:data:`~exudyn_atcm.physical_bounds.PHYSICAL_LIMITS`: a modulus
        above 1e13 Pa, a density above 1e5 kg/m³, a thickness below 1e-10 m).

    Warns
    -----
    RuntimeWarning
        If a value lies outside :data:`PLAUSIBLE_RANGES` (likely a unit mistake).

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
        for name in ("thickness", "youngs_modulus", "density"):
            check_physical(name, getattr(self, name), "Layer")
        for name, (low, high, unit, mistake) in PLAUSIBLE_RANGES.items():
            value = getattr(self, name)
            if not low <= value <= high:
                warnings.warn(
                    f"Layer {name} = {value!r} {unit} is outside the plausible range {low:g} ... {high:g} {unit} "
                    f"for a laminate layer; is it {mistake}? All values are SI units",
                    InputRangeWarning,
                    stacklevel=4,
                )

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
