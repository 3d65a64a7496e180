"""Parallel guide: two S-shaped A-TCM benders welded to a rigid coupler, a translational stage.

Two identical benders of the paper's laminate (CFC 0.2 mm / 70 GPa under MFC 0.3 mm /
30.336 GPa) are clamped one above the other and welded to one rigid coupler.  Each bender is
made of two segments of equal length with their own drives; the segments are driven with
opposite voltages (+U on the base half, -U on the tip half, linear piezo law d33 U / t_IDE),
so each bender takes the free curvature +kappa over its first half and -kappa over its second:
an S.  The voltage runs 0 -> +U_max -> -U_max -> 0 (within the MFC's -500 ... 1500 V rating),
solved quasi-statically.

Reference (:func:`exudyn_atcm.theory.beam_mechanisms.s_blade_end`): the S's free curvature integrates to
zero, so the free shape ends with zero rotation and both blades' free end poses are the same
translation: the coupler fits them without any force, for any deflection.  The coupler then
translates by exactly ``(2 sin(kappa L/2)/kappa - L, 2 (1 - cos(kappa L/2))/kappa)`` and does not
rotate; the small-deflection value of the translation across the blades is ``kappa L²/4``.
Key scalars: the translation error against the exact value (``translation_error``) and
against ``kappa L²/4`` (``translation_error_small_deflection``, of order ``(kappa L)²/48``),
both relative to the largest translation, and the largest coupler rotation.  A rigid-cell
chain reproduces the S up to the polygon factor ``1 + (kappa L_c)²/24`` on the end position
(cell length ``L_c``): on the axial coordinate ``x ~ L`` that is ``L (kappa L_c)²/24``, a few
1e-5 of the translation at the defaults; ``translation_error_chain_polygon`` compares with the
polygon itself.  With ``cell="beam"`` the beam elements' nodes lie on the same polygon (each
element's chord has length ``L_c`` at its mean node rotation), so the same two references hold.
With ``cell="rod"`` each segment's modes represent its arc exactly: the exact reference holds
to the Newton tolerance with one mode per segment (``n_cells = 1``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_atcm import Bender, Layer, Link, Mechanism, PiezoDrive, Result, Segment, static_sweep
from exudyn_atcm import theory
from exudyn_atcm.casework import Case, CaseOutput, CellChoices, Parameter, Parameters, RunContext
from exudyn_atcm.plots import animate_mechanism, axis_label, new_figure, plot_mechanism, save_figure

PARAMETERS = [
    Parameter("n_cells", 8, "-", "cells per segment (two segments per bender)", minimum=1),
    Parameter("cell", "rigid", "-", "cell model of the benders", choices=CellChoices(joins_anywhere=True, first=("rigid",))),
    Parameter("length", 0.06, "m", "bender length L (two segments of L/2)", exclusive_minimum=0.0),
    Parameter("width", 10e-3, "m", "bender width", exclusive_minimum=0.0),
    Parameter("spacing", 0.02, "m", "distance between the two benders", exclusive_minimum=0.0),
    Parameter("voltage", 500.0, "V", "largest voltage magnitude U_max (one segment +U, the other -U)"),
    Parameter("n_steps", 24, "-", "static steps of the cycle 0 -> +U -> -U -> 0 (multiple of 4)"),
    Parameter("animation", True, "-", "also write a GIF of the moving stage"),
    Parameter("animation_scale", 5.0, "-", "displacement magnification of the drawings", exclusive_minimum=0.0),
]

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
DRIVES = ("lower.1", "lower.2", "upper.1", "upper.2")


def build_mechanism(p: Parameters) -> Mechanism:
    """The stage in its reference pose (benders straight along x)."""
    L, h = p.length, p.spacing
    mech = Mechanism("parallel_guide")
    for name, y in (("lower", 0.0), ("upper", h)):
        # no rating of their own: the voltage the user gave is checked once per run, in run()
        segments = [Segment(L / 2, p.n_cells, PiezoDrive(0.0, rated_range=None)),
                    Segment(L / 2, p.n_cells, PiezoDrive(0.0, rated_range=None))]
        mech.add(Bender(name, width=p.width, passive=CFC, active=MFC, segments=segments, base=(0.0, y),
                          cell=p.cell))
        mech.ground(f"{name}.base")
    coupler = Link("coupler", {"A": (L, 0.0), "B": (L, h), "P": (L + 0.01, h / 2)}, mass=2e-3, inertia=2e-3 * h * h / 12)
    mech.add(coupler).weld("lower.tip", coupler.point("A")).weld("upper.tip", coupler.point("B"))
    return mech


def voltage_program(u_max: float, n_steps: int) -> np.ndarray:
    """0 -> +u_max -> -u_max -> 0 in ``n_steps`` equal steps."""
    if n_steps < 4 or n_steps % 4:
        raise ValueError(f"n_steps must be a multiple of 4, >= 4, got {n_steps}")
    quarter = n_steps // 4
    return np.concatenate([np.linspace(0, u_max, quarter + 1), np.linspace(u_max, -u_max, 2 * quarter + 1)[1:],
                           np.linspace(-u_max, 0, quarter + 1)[1:]])


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    L = p.length
    volts = voltage_program(p.voltage, p.n_steps)
    # the voltage the user gave, against the MFC's rating (and the kV check): once per run, not once per drive
    PiezoDrive(p.voltage).check_voltage_range(-abs(p.voltage), abs(p.voltage), stacklevel=2,
                                              what=f"voltage={p.voltage:g} V (the segments at +U and -U)")
    mech = build_mechanism(p)
    result = static_sweep(mech, {"lower.1": volts, "lower.2": -volts, "upper.1": volts, "upper.2": -volts})
    ctx.progress(1, 1)
    strain = result["lower.1.strain"]
    kappa = theory.free_curvature(CFC.youngs_modulus, CFC.thickness, MFC.youngs_modulus, MFC.thickness, p.width, strain)
    ends = np.array([theory.s_blade_end(float(k), L) for k in kappa])
    ref = ends - np.array([L, 0.0])
    # the rigid-cell chain: joints on the arcs' inscribed polygons, end scaled by (k Lc/2)/sin(k Lc/2)
    half_cell = 0.5 * kappa * L / (2 * p.n_cells)
    polygon = np.where(half_cell == 0.0, 1.0, half_cell / np.sin(np.where(half_cell == 0.0, 1.0, half_cell)))
    ref_chain = ends * polygon[:, None] - np.array([L, 0.0])
    p0 = np.array(mech.position("coupler.P"))
    sim = np.stack([result["coupler.P_x"], result["coupler.P_y"]], axis=-1) - p0
    small = theory.s_blade_deflection_linear(kappa, L)
    biggest = float(np.max(np.linalg.norm(ref, axis=1)))
    scalars = {
        "translation_error": (float(np.max(np.linalg.norm(sim - ref, axis=1))) / biggest, "-"),
        "translation_error_chain_polygon": (float(np.max(np.linalg.norm(sim - ref_chain, axis=1))) / biggest, "-"),
        "translation_error_small_deflection": (float(np.max(np.abs(sim[:, 1] - small))) / biggest, "-"),
        "rotation_max": (float(np.max(np.abs(result["coupler.angle"]))), "rad"),
        "translation_y_max": (float(sim[:, 1].max()), "m"),
        "translation_y_reference_max": (float(ref[:, 1].max()), "m"),
        "translation_y_small_deflection_max": (float(small.max()), "m"),
        "strain_antisymmetry_error": (float(np.max(np.abs(result["lower.2.strain"] + strain))), "-"),
        "upper_lower_tip_difference": (float(np.max(np.hypot(
            result["upper.tip_x"] - result["lower.tip_x"], result["upper.tip_y"] - result["lower.tip_y"] - p.spacing))),
            "m"),
    }
    table = Result({"voltage": volts, "kappa": kappa, "translation_x": sim[:, 0], "translation_y": sim[:, 1],
                    "reference_x": ref[:, 0], "reference_y": ref[:, 1], "small_deflection_y": small,
                    "rotation": result["coupler.angle"]},
                   {"voltage": "V", "kappa": "1/m", "translation_x": "m", "translation_y": "m", "reference_x": "m",
                    "reference_y": "m", "small_deflection_y": "m", "rotation": "rad"},
                   parameters=mech.parameters())
    notes = {"reference": "exact S-blade end 2 sin(kL/2)/k, 2 (1 - cos(kL/2))/k with zero rotation; "
                          "small deflection kL^2/4",
             "drives": "segment 1 of each bender at +U, segment 2 at -U (linear piezo law)"}
    return CaseOutput(table, scalars, steps=len(volts), tables={"sweep": result}, notes=notes)


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    files = []
    fig, axes = new_figure(2, 1, width=6.4, height=6.0, sharex=True)
    axes[0].plot(r["voltage"], r["translation_y"] * 1e6, "o", ms=3, label="simulated")
    order = np.argsort(r["voltage"])
    axes[0].plot(r["voltage"][order], r["reference_y"][order] * 1e6, "-", label="exact S-blade 2(1 - cos(kL/2))/k")
    axes[0].plot(r["voltage"][order], r["small_deflection_y"][order] * 1e6, "--", label="small deflection kL²/4")
    axes[0].set_ylabel(axis_label("coupler translation y", "µm"))
    axes[0].legend(fontsize=8)
    axes[1].plot(r["voltage"], r["rotation"] * 1e6, "o", ms=3)
    axes[1].set_ylabel(axis_label("coupler rotation", "µrad"))
    axes[1].set_xlabel(axis_label("voltage U of the base segments (tip segments -U)", "V"))
    files.append(save_figure(fig, out_dir / f"{output.case}_translation.png"))
    mech = build_mechanism(p)
    sweep = output.tables["sweep"]
    peak = int(np.argmax(sweep["coupler.P_y"]))
    files.append(out_dir / f"{output.case}_mechanism.png")
    plot_mechanism(mech, sweep, path=files[-1], row=peak,
                   scale=p.animation_scale, title="parallel guide at +U")
    if p.animation:
        files.append(animate_mechanism(mech, sweep, out_dir / f"{output.case}_animation.gif",
                                       frames=min(sweep.n_rows, 41), scale=p.animation_scale, trace=["coupler.P"]))
    return files


#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "parallel_guide",
        "quick": True,
        "parameters": {"animation": False},
        "scalars": [
            {"name": "translation_error (/ travel)", "scalar": "translation_error", "analytic": 0.0, "abs": 1e-4, "source": "S-shaped bender of two opposite constant-curvature arcs: pure translation (large-deflection closed form); 8 cells per segment"},
            {"name": "translation_error_chain_polygon (/ travel)", "scalar": "translation_error_chain_polygon", "analytic": 0.0, "abs": 1e-9, "source": "the stress-free rigid-cell polygon of the two segments; static solver tolerance"},
            {"name": "rotation_max (stage rotation)", "scalar": "rotation_max", "analytic": 0.0, "abs": 1e-12, "source": "antisymmetric curvature: the stage translates without rotating"},
            {"scalar": "translation_y_max", "rel": 1e-6}
        ]
    },
]

CASE = Case("parallel_guide", __doc__, PARAMETERS, run, plot, benchmarks=BENCHMARKS, table_order=8,
            summary="two S-shaped two-segment benders and a coupler: a translational stage (guided S-blade)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
