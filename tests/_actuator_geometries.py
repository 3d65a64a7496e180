"""Geometries shared by the actuator tests: the paper's actuator (docs/theory.rst) and two others."""

from __future__ import annotations

from dataclasses import dataclass

from exudyn_atcm.mechanism.actuator import BendingActuator
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.materials import Layer


@dataclass(frozen=True)
class Geometry:
    name: str
    n_cells: int
    cell_length: float
    width: float
    h1: float
    E1: float
    rho1: float
    h2: float
    E2: float
    rho2: float

    @property
    def length(self) -> float:
        return self.n_cells * self.cell_length

    def actuator(self, drive, n_cells=None, **kwargs) -> BendingActuator:
        n = self.n_cells if n_cells is None else n_cells
        return BendingActuator(
            n, self.length / n, self.width,
            Layer(self.h1, self.E1, self.rho1), Layer(self.h2, self.E2, self.rho2),
            drive if isinstance(drive, PiezoDrive) else PiezoDrive(drive), **{"cell": "six-bar", **kwargs},
        )


# the paper's actuator of docs/theory.rst: 3 x 29 mm, CFC 0.2 mm on MFC 0.3 mm
REF_A = Geometry("paper actuator", 3, 29e-3, 28e-3, 0.2e-3, 70e9, 1550.0, 0.3e-3, 30.336e9, 5440.0)
# thick CFC on MFC, narrow strip (spring share rho_s ~ 0.5)
GEO_B = Geometry("GEO-B", 4, 20e-3, 10e-3, 0.5e-3, 70e9, 1550.0, 0.3e-3, 30.336e9, 5440.0)
# thin steel on a soft active layer (the MFC's transverse modulus), 5 x 12 mm
GEO_C = Geometry("GEO-C", 5, 12e-3, 14e-3, 0.1e-3, 200e9, 7850.0, 0.2e-3, 15.857e9, 5440.0)

GEOMETRIES = (REF_A, GEO_B, GEO_C)
