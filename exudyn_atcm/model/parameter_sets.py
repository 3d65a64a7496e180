"""Parameter sets from the literature, each with its citation.

All values in SI units.  The paper's hysteresis loop is given as the stroke of a 29 mm cell
(-4 µm ... 40 µm over -500 ... 1500 V); :func:`paper_strain_preisach` gives the same loop as
free strain (stroke / cell length), which serves cells of any length.
"""

from __future__ import annotations

from ..hysteresis.continuous import ContinuousPreisach

PAPER_CITATION = (
    "D. Margineanu, E.-C. Lovasz, N. Modler: Multibody System Simulation of Hysteresis Effect by "
    "Micro Textile-Reinforced Compliant Mechanisms with Piezo-electric Actuators."
)

#: The paper's loop data (Sect. 3, Fig. 6): voltages [V] and strokes [m] of a 29 mm cell.
PAPER_LOOP = {
    "cell_length [m]": 29e-3,
    "u_min [V]": -500.0,
    "u_max [V]": 1500.0,
    "x_min [m]": -4e-6,
    "x_max [m]": 40e-6,
    "u_m [V]": 500.0,
    "x_m1 [m]": 12e-6,
    "x_m2 [m]": 28e-6,
    "r1 (rounded)": 1.5,
    "r2 (rounded)": 2.0,
}

#: Piezo constant [m/V] and electrode spacing [m] used in the paper (Eq. 3).
PAPER_D33 = 460e-12
PAPER_ELECTRODE_SPACING = 0.5e-3


def paper_stroke_preisach(rounded: bool = False) -> ContinuousPreisach:
    """The paper's continuous Preisach model as the stroke [m] of a 29 mm cell.

    Its ``output_quantity`` is ``"stroke"``: a :class:`~exudyn_atcm.model.drive.PiezoDrive` refuses
    it (the drive needs strain; use :func:`paper_strain_preisach`).

    Parameters
    ----------
    rounded : bool, optional
        ``True`` for the paper's rounded exponents ``r1 = 1.5``, ``r2 = 2``; ``False`` (default)
        for the exact exponents through the precision points (corrected Eq. 10:
        ``r1 = 1.459432``, ``r2 = 1.874469``).
    """
    d = PAPER_LOOP
    if rounded:
        operator = ContinuousPreisach(
            d["u_min [V]"], d["u_max [V]"], d["x_min [m]"], d["x_max [m]"], d["r1 (rounded)"], d["r2 (rounded)"]
        )
    else:
        operator = ContinuousPreisach.from_points(
            d["u_min [V]"], d["u_max [V]"], d["x_min [m]"], d["x_max [m]"], d["u_m [V]"], d["x_m1 [m]"], d["x_m2 [m]"]
        )
    return operator.with_output_quantity("stroke")


def paper_strain_preisach(rounded: bool = False) -> ContinuousPreisach:
    """The paper's continuous Preisach model as free strain [-] (stroke / 29 mm).

    Same exponents as :func:`paper_stroke_preisach`; output range about
    ``-1.3793e-4 ... 1.3793e-3``; ``output_quantity`` is ``"strain"``.
    """
    stroke = paper_stroke_preisach(rounded)
    length = PAPER_LOOP["cell_length [m]"]
    return ContinuousPreisach(
        stroke.u_min, stroke.u_max, stroke.y_min / length, stroke.y_max / length, stroke.r1, stroke.r2
    ).with_output_quantity("strain")
