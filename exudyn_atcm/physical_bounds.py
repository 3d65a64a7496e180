"""Values no material or model can have: refused before a run, with the reason.

The package warns about *implausible* values (a thickness in mm passed as metres: see
:data:`exudyn_atcm.model.materials.PLAUSIBLE_RANGES`) and runs them.  Values beyond the limits
here are not a unit slip but impossible: no known material comes within a factor of several,
and running them only overflows deep inside the solver (a ``d33`` of 1e300 m/V ends as an
``OverflowError`` in the strain) or computes for minutes (a hysteresis model with a million
relays).  They are refused with a ``ValueError`` that names the value, the limit and why.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["PHYSICAL_LIMITS", "MAX_OPERATOR_ELEMENTS", "MAX_CELLS", "MFC_P1_RATED_RANGE", "KV_SUSPECT_FRACTION", "PLAUSIBLE_STRAIN",
           "DAMPING_RATIO_SUSPECT", "check_physical", "check_element_count", "check_cell_count"]

#: Rated operating voltage of the MFC P1 type [V] (d33 mode, -500 ... +1500 V; Smart Material
#: Corp. data sheet; the paper drives its MFC over exactly this range).
MFC_P1_RATED_RANGE = (-500.0, 1500.0)

#: A voltage program whose peak ``|U|`` stays below this fraction of the largest magnitude of
#: the rated range (3 V for the MFC P1's -500 ... +1500 V) is most likely written in kV: a
#: program in kV peaks at 1/1000 of its meaning, at most 1.5 V within the MFC's rating.
#: The threshold leaves a factor 2 above that and a factor 5 below the smallest deliberate
#: small-signal program of the package (a 1 % triangle, -5 ... 15 V); at 3 V the MFC's free
#: strain is about 3e-6, 0.2 % of its full stroke.
KV_SUSPECT_FRACTION = 2e-3

#: Free strains [-] above this magnitude are implausible for a piezo layer (MFC P1 reaches
#: about 1.4e-3 at 1500 V, piezo ceramics about 2e-3): most likely a unit mistake.
PLAUSIBLE_STRAIN = 1e-2

#: A modal damping ratio (the ``damping=`` of a bender, an actuator or a flexure) at or above this
#: is most likely a percentage written as a number (``damping=5`` for 5 %, ``damping=1`` for 1 %):
#: a ratio of 1 is critical damping, at which the bender no longer vibrates at its first mode.
#: Fibre-composite laminates have about 0.005 ... 0.05 (0.5 ... 5 %; the package's default is
#: 0.02), and even the most dissipative viscoelastic layers stay below about 0.5 (loss factor 1).
#: A ratio below 1 cannot be told from a percentage (0.5 may be 50 % or a mistyped 0.5 %), so it
#: is not warned about.
DAMPING_RATIO_SUSPECT = 1.0


#: name -> (lowest, highest, unit, why): values outside ``[lowest, highest]`` cannot be physical.
PHYSICAL_LIMITS: dict[str, tuple[float, float, str, str]] = {
    "d33": (0.0, 1e-7, "m/V",
            "the largest piezoelectric coefficients measured (relaxor single crystals such as PMN-PT) are "
            "below 5e-9 m/V; the MFC P1 has 4.6e-10 m/V"),
    "electrode_spacing": (1e-7, math.inf, "m",
                          "interdigitated electrodes are at least micrometres apart (the MFC: 0.5e-3 m); "
                          "below 1e-7 m the field d33 U / spacing has no material to act in"),
    "youngs_modulus": (0.0, 1e13, "Pa", "the stiffest material, diamond, has about 1.2e12 Pa"),
    "density": (0.0, 1e5, "kg/m^3", "the densest element, osmium, has about 22600 kg/m^3"),
    "thickness": (1e-10, math.inf, "m", "a layer cannot be thinner than one atomic layer (about 1e-10 m)"),
}

#: Largest number of relays or plays of a hysteresis model built or identified by the package:
#: more levels than a 16-bit measurement resolves over its range (65 536) cannot be identified
#: from any record (the paper's model has 6 relays), and each element costs time in every step.
MAX_OPERATOR_ELEMENTS = 100_000

#: Largest number of cells (modes for the ``ritz`` and ``rod`` cells) of one bender, actuator or
#: flexure.  The chains of cells converge at second order, so 1e5 cells leave a discretisation
#: error of about 1e-10 of the length, below what Exudyn's Newton tolerance resolves: more cells
#: cannot change an answer.  They only cost: building the Exudyn model takes 30 ... 600 µs and
#: about 10 kB per cell (measured; 1e5 rigid cells: about 20 s and 1.2 GB before the first step),
#: and a static solve of a few thousand cells already takes minutes.  Counts below the bound are
#: announced by the run-time estimate when they take long
#: (:mod:`exudyn_atcm.mechanism.build_cost`).
MAX_CELLS = 100_000


def check_physical(name: str, value: float, owner: str) -> float:
    """``value`` if it lies within :data:`PHYSICAL_LIMITS` ``[name]``, else a ``ValueError`` saying why not.

    Parameters
    ----------
    name : str
        Key of :data:`PHYSICAL_LIMITS` (also the parameter's name in the message).
    value : float
        The value, already checked to be a finite number.
    owner : str
        What it belongs to (``"PiezoDrive"``, ``"Layer"``), for the message.

    Raises
    ------
    ValueError
        Naming the owner, the parameter, the value, the allowed range and the reason.
    """
    low, high, unit, why = PHYSICAL_LIMITS[name]
    if low <= value <= high:
        return value
    allowed = f"<= {high:g} {unit}" if value > high else f">= {low:g} {unit}"
    raise ValueError(f"{owner}: {name} = {value!r} {unit} cannot be physical ({why}); it must be {allowed}. "
                     "All values are SI units")


def check_element_count(name: str, value: Any, what: str) -> Any:
    """``value`` if it is at most :data:`MAX_OPERATOR_ELEMENTS`, else a ``ValueError`` saying why.

    Parameters
    ----------
    name : str
        The parameter (``"n"``, ``"n_relays"``), for the message.
    value : int
        The count (its type and lower bound are checked by the caller).
    what : str
        ``"relays"`` or ``"plays"``.

    Raises
    ------
    ValueError
        If ``value`` exceeds :data:`MAX_OPERATOR_ELEMENTS`.
    """
    if isinstance(value, (int, float)) and not isinstance(value, bool) and value > MAX_OPERATOR_ELEMENTS:
        raise ValueError(
            f"{name} = {value!r} {what} is more than {MAX_OPERATOR_ELEMENTS} {what}, which no record can identify "
            f"(a 16-bit measurement resolves 65536 levels; the paper's model has 6 relays) and which would compute "
            f"for minutes per run; use at most {MAX_OPERATOR_ELEMENTS} (tens to hundreds are typical)"
        )
    return value


def check_cell_count(name: str, value: Any, owner: str) -> Any:
    """``value`` if it is at most :data:`MAX_CELLS`, else a ``ValueError`` saying why.

    Parameters
    ----------
    name : str
        The parameter (``"n_cells"``), for the message.
    value : int
        The count (its type and lower bound are checked by the caller).
    owner : str
        What it belongs to (``"bender 'b'"``, ``"BendingActuator"``), for the message.

    Raises
    ------
    ValueError
        If ``value`` exceeds :data:`MAX_CELLS`.
    """
    if isinstance(value, (int, float)) and not isinstance(value, bool) and value > MAX_CELLS:
        raise ValueError(
            f"{owner}: {name} = {value!r} is more than {MAX_CELLS} cells, which cannot change any answer (the "
            f"discretisation error at {MAX_CELLS} cells, about 1e-10 of the length, is below the solver's tolerance) "
            f"and would take minutes and gigabytes to build (about 10 kB and up to 0.6 ms per cell) before the first "
            f"step; use at most {MAX_CELLS} (tens to hundreds of cells are typical; modes of the ritz and rod "
            "cells: a few to tens)"
        )
    return value
