"""The README's materials and four-bar, shared by ``bench_accuracy.py``, ``bench_rebuild.py`` and
``bench_static_sweep.py`` (each varies the crank's cells and its drive)."""

from __future__ import annotations

import math
from typing import Any

import exudyn_atcm as atcm

#: The README's layers: CFC under MFC (thickness [m], Young's modulus [Pa], density [kg/m^3]).
CFC = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)


def readme_four_bar(program: Any, *, n_cells: int = 6, cell: str | None = None) -> atcm.Mechanism:
    """The README's four-bar, its crank driven by ``program`` (a voltage program or a constant [V]) with
    ``n_cells`` cells of kind ``cell`` (``None``: the package default)."""
    kind = {} if cell is None else {"cell": cell}
    crank = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=n_cells,
                        drive=atcm.PiezoDrive(program), angle=math.pi / 2, **kind)
    coupler = atcm.Link("coupler", {"A": (0.0, 0.03), "B": (0.04, 0.03), "P": (0.02, 0.05)}, mass=1e-4, inertia=1e-8)
    rocker = atcm.Link("rocker", {"B": (0.04, 0.03), "O": (0.04, 0.0)}, mass=1e-4, inertia=1e-8)
    m = atcm.Mechanism("four_bar").add(crank, coupler, rocker)
    m.ground(crank.base)
    m.pin(crank.tip, coupler.point("A"))
    m.pin("coupler.B", "rocker.B")
    m.ground("rocker.O", joint="pin")
    return m
