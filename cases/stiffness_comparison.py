"""The paper's stiffness calibration against the composite-consistent one, and beam theory.

The same actuator (the paper's actuator by default: 3 cells of 29 mm, 28 mm wide, CFC 0.2 mm
/ 70 GPa under MFC 0.3 mm / 30.336 GPa) is built twice: with ``stiffness="composite"``
(reproduces lamination theory's bending stiffness EI and free curvature exactly) and with
``stiffness="paper"`` (Eqs. 4-5 as printed, with the text's doubling).  For both it computes

* the static tip position over a voltage ramp 0 ... U (linear piezo law, Eq. 3) against the
  circular arc of beam theory (free curvature, Timoshenko's bimetal formula);
* the tip compliance under a small tip force against ``L³/(3 EI)`` times the chain factor
  of the cell model (derived on the theory page of the documentation): ``1 + 1/(2N²)`` for
  rigid cells, ``1 + (3/(4 rho_s) - 1/4)/N²`` for six-bar cells, ``1 - 1/(4N²)`` for linear
  beam elements (``cell="beam"``) and 1 for cubic ANCF cable elements (``cell="ancf"``);
* the first bending eigenfrequency against the Euler-Bernoulli ``f1``;
* the large deflection under a tip force ``F = alpha EI/L²`` perpendicular to the undeformed
  axis (composite calibration, no voltage, a chain of ``elastica_cells`` rigid cells of the
  same total length), against the elastica (Bisshopp & Drucker 1945).

The CSV holds the voltage ramp (one row per voltage, tip positions of both calibrations and
of the arc).  The key scalars compare model and theory; lamination theory predicts the paper's
calibration about 1.49x too stiff with a 1.11x too large free curvature for this actuator.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_atcm import BendingActuator, Layer, PiezoDrive, Result, eigenfrequencies, solve_static
from exudyn_atcm import theory
from exudyn_atcm.casework import Case, CaseOutput, CellChoices, Parameter, Parameters, RunContext
from exudyn_atcm.plots import Curve, plot_loops

PARAMETERS = [
    Parameter("n_cells", 3, "-", "number of cells", minimum=1),
    Parameter("cell", "rigid", "-", "cell model (beam, ancf: Exudyn's 2-D beam elements, one per cell; "
              "not ritz, which refuses the tip force of the compliance run)", choices=CellChoices(carries_tip_load=True)),
    Parameter("cell_length", 29e-3, "m", "length of one cell L_j", exclusive_minimum=0.0),
    Parameter("width", 28e-3, "m", "width b of both layers", exclusive_minimum=0.0),
    Parameter("h1", 0.2e-3, "m", "passive (CFC) layer thickness", exclusive_minimum=0.0),
    Parameter("E1", 70e9, "Pa", "passive layer Young's modulus", exclusive_minimum=0.0),
    Parameter("rho1", 1550.0, "kg/m^3", "passive layer density", exclusive_minimum=0.0),
    Parameter("h2", 0.3e-3, "m", "active (MFC) layer thickness", exclusive_minimum=0.0),
    Parameter("E2", 30.336e9, "Pa", "active layer Young's modulus", exclusive_minimum=0.0),
    Parameter("rho2", 5440.0, "kg/m^3", "active layer density", exclusive_minimum=0.0),
    Parameter("voltage", 1500.0, "V", "highest voltage of the ramp"),
    Parameter("n_voltages", 6, "-", "voltages in the ramp 0 ... voltage", minimum=2),
    Parameter("tip_force", 0.01, "N", "small tip force (perpendicular to the axis) for the compliance"),
    Parameter("elastica_alpha", 2.0, "-", "load parameter F L^2/EI of the large-deflection run (composite)"),
    Parameter("elastica_cells", 24, "-", "rigid cells of the large-deflection run (a coarse chain is far from the elastica)", minimum=1),
]

MODELS = ("composite", "paper")


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    # the voltage the user gave, against the MFC's rating (and the kV check): once per run, quoted as given;
    # the solves of the ramp's voltages below are not checked again (each would warn about its own voltage)
    PiezoDrive(p.voltage).check_voltage_range(min(0.0, p.voltage), max(0.0, p.voltage),
                                              what=f"voltage={p.voltage:g} V (the ramp 0 ... {p.voltage:g} V)", stacklevel=2)
    passive = Layer(p.h1, p.E1, p.rho1)
    active = Layer(p.h2, p.E2, p.rho2)
    length = p.n_cells * p.cell_length
    voltages = np.linspace(0.0, p.voltage, p.n_voltages)

    ei = {
        "composite": theory.composite_bending_stiffness(p.E1, p.h1, p.E2, p.h2, p.width),
        "paper": theory.paper_bending_stiffness(p.E1, p.h1, p.E2, p.h2, p.width),
    }
    curvature_fn = {"composite": theory.free_curvature, "paper": theory.paper_free_curvature}
    mu = theory.mass_per_length(p.rho1, p.h1, p.rho2, p.h2, p.width)

    series: dict[str, np.ndarray] = {"voltage": voltages}
    units = {"voltage": "V"}
    scalars: dict[str, tuple[float, str]] = {}
    steps = 0
    for model in MODELS:
        tip_x, tip_y, angle, arc_x, arc_y = [], [], [], [], []
        for k, u in enumerate(voltages):
            act = BendingActuator(p.n_cells, p.cell_length, p.width, passive, active, PiezoDrive(float(u), rated_range=None), cell=p.cell,
                                   stiffness=model)
            r = solve_static(act)
            steps += 1
            tip_x.append(r["actuator.tip_x"][0])
            tip_y.append(r["actuator.tip_y"][0])
            angle.append(r["actuator.tip_angle"][0])
            kappa = curvature_fn[model](p.E1, p.h1, p.E2, p.h2, p.width, theory.piezo_strain(float(u)))
            ax, ay = theory.arc_point(kappa, length)
            arc_x.append(float(ax))
            arc_y.append(float(ay))
            ctx.progress(k + 1 + (p.n_voltages if model == "paper" else 0), 2 * p.n_voltages)
        for name, values in (("tip_x", tip_x), ("tip_y", tip_y), ("tip_angle", angle), ("arc_tip_x", arc_x), ("arc_tip_y", arc_y)):
            series[f"{name}_{model}"] = np.asarray(values)
            units[f"{name}_{model}"] = "rad" if name == "tip_angle" else "m"

        kappa = curvature_fn[model](p.E1, p.h1, p.E2, p.h2, p.width, theory.piezo_strain(p.voltage))
        unloaded = BendingActuator(p.n_cells, p.cell_length, p.width, passive, active, PiezoDrive(0.0), cell=p.cell, stiffness=model)
        loaded = solve_static(unloaded, voltage=0.0, tip_force=(0.0, p.tip_force))
        compliance = float(loaded["actuator.tip_y"][0]) / p.tip_force
        factor = {
            "rigid": lambda: theory.rigid_chain_compliance_factor(p.n_cells),
            "six-bar": lambda: theory.six_bar_chain_compliance_factor(p.n_cells, unloaded.spring_share),
            "beam": lambda: theory.beam_element_compliance_factor(p.n_cells),
            "ancf": lambda: 1.0,  # cubic elements: the cantilever's cubic deflection exactly
        }[p.cell]()
        f1 = float(eigenfrequencies(unloaded, n=1)[0])
        steps += 2
        scalars.update(
            {
                f"EI_theory_{model}": (ei[model], "N m^2"),
                f"curvature_theory_{model}": (kappa, "1/m"),
                f"tip_angle_{model}": (angle[-1], "rad"),
                f"tip_angle_theory_{model}": (kappa * length, "rad"),
                f"tip_y_{model}": (tip_y[-1], "m"),
                f"arc_tip_y_{model}": (arc_y[-1], "m"),
                f"compliance_{model}": (compliance, "m/N"),
                f"compliance_theory_{model}": (theory.tip_compliance(ei[model], length), "m/N"),
                f"compliance_chain_theory_{model}": (theory.tip_compliance(ei[model], length) * factor, "m/N"),
                f"f1_{model}": (f1, "Hz"),
                f"f1_theory_{model}": (theory.first_bending_frequency(ei[model], mu, length), "Hz"),
            }
        )
    elastica_force = p.elastica_alpha * ei["composite"] / length**2
    unloaded = BendingActuator(
        p.elastica_cells, length / p.elastica_cells, p.width, passive, active, PiezoDrive(0.0), cell="rigid"
    )
    bent = solve_static(unloaded, voltage=0.0, tip_force=(0.0, elastica_force))
    steps += 1
    scalars["elastica_force"] = (elastica_force, "N")
    scalars["elastica_y_over_L"] = (float(bent["actuator.tip_y"][0]) / length, "-")
    scalars["elastica_1_minus_x_over_L"] = (1.0 - float(bent["actuator.tip_x"][0]) / length, "-")
    scalars["EI_ratio_paper_to_composite"] = (ei["paper"] / ei["composite"], "-")
    scalars["curvature_ratio_paper_to_composite"] = (
        scalars["curvature_theory_paper"][0] / scalars["curvature_theory_composite"][0],
        "-",
    )
    scalars["tip_y_ratio_paper_to_composite"] = (scalars["tip_y_paper"][0] / scalars["tip_y_composite"][0], "-")
    result = Result(series, units, parameters={"length [m]": length})
    return CaseOutput(result, scalars, steps=steps, notes={"steps": "static solves plus eigenvalue analyses"})


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    curves = []
    for model, style in (("composite", {}), ("paper", {"linestyle": "--"})):
        curves.append(Curve(r["voltage"], r[f"tip_y_{model}"], f"{model} stiffness, {p.cell} cells", {"marker": "o", **style}))
        curves.append(Curve(r["voltage"], r[f"arc_tip_y_{model}"], f"{model}: circular arc (beam theory)", {"color": "0.4", **style}))
    path = out_dir / f"{output.case}_tip.png"
    plot_loops(
        curves,
        path=path,
        y_name="tip deflection y",
        title="Static tip deflection: paper vs composite stiffness",
    )
    return [path]


#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "stiffness_ref_a",
        "quick": True,
        "base": "voltage",
        "parameters": {"n_cells": 3, "cell": "rigid", "cell_length": 0.029, "n_voltages": 6, "tip_force": 0.01},
        "channels": {
            "tip_y_composite": {"rms": 1e-9, "max": 1e-9},
            "tip_x_composite": {"rms": 1e-9, "max": 1e-9},
            "tip_y_paper": {"rms": 1e-9, "max": 1e-9}
        },
        "scalars": [
            {"scalar": "EI_theory_composite", "analytic": 1.28699e-2, "rel": 1e-5, "source": "docs/theory.rst, the paper's actuator: EI = 1.28699e-2 N m²"},
            {"scalar": "curvature_theory_composite", "analytic": 4.13984, "rel": 1e-5, "source": "docs/theory.rst, the paper's actuator: κ = 4.13984 1/m"},
            {"name": "tip_angle_composite (static curvature, = κL)", "scalar": "tip_angle_composite", "analytic": 0.36016608, "rel": 1e-5, "source": "docs/theory.rst, reference actuator: κ L = 4.13984 · 0.087, exact for every N"},
            {"scalar": "arc_tip_y_composite", "analytic": 15.499e-3, "abs": 1e-6, "source": "docs/theory.rst, the paper's actuator: arc tip y = 15.499 mm"},
            {"scalar": "compliance_theory_composite", "analytic": 17.055e-3, "rel": 1e-4, "source": "docs/theory.rst, the paper's actuator: 17.055 mm/N"},
            {"name": "compliance_composite (tip compliance, 3 rigid cells)", "scalar": "compliance_composite", "analytic": 18.0025e-3, "rel": 2e-4, "source": "docs/theory.rst, reference actuator: 17.055 mm/N · (1 + 1/(2·3²))"},
            {"scalar": "f1_theory_composite", "analytic": 35.97, "abs": 0.005, "source": "docs/theory.rst, the paper's actuator: f1 = 35.97 Hz"},
            {"scalar": "EI_ratio_paper_to_composite", "analytic": 1.49, "abs": 0.005, "source": "docs/theory.rst, stiffness calibration: printed model 1.49x too stiff"},
            {"scalar": "curvature_ratio_paper_to_composite", "analytic": 1.11, "abs": 0.005, "source": "docs/theory.rst, stiffness calibration: free curvature 1.11x too large"},
            {"scalar": "tip_y_composite", "rel": 1e-6},
            {"scalar": "tip_y_paper", "rel": 1e-6},
            {"scalar": "compliance_paper", "rel": 1e-6},
            {"scalar": "f1_composite", "rel": 1e-6},
            {"scalar": "f1_paper", "rel": 1e-6}
        ]
    },
    {
        "id": "convergence_48_rigid_cells",
        "quick": True,
        "base": "voltage",
        "parameters": {"n_cells": 48, "cell": "rigid", "cell_length": 0.0018125, "n_voltages": 2, "tip_force": 0.01, "elastica_alpha": 2.0, "elastica_cells": 48},
        "scalars": [
            {"name": "f1_composite (eigenfrequency, 48 cells)", "scalar": "f1_composite", "analytic": 35.97, "abs": 0.02, "source": "docs/theory.rst, the paper's actuator: f1 = 35.97 Hz (continuum; 48 cells within 0.02 Hz)"},
            {"name": "compliance_composite (48 rigid cells)", "scalar": "compliance_composite", "analytic": 17.0587e-3, "rel": 2e-4, "source": "docs/theory.rst, reference actuator: 17.055 mm/N · (1 + 1/(2·48²))"},
            {"name": "elastica y/L (alpha = 2)", "scalar": "elastica_y_over_L", "analytic": 0.49346, "abs": 5e-4, "source": "docs/theory.rst, reference actuator (Bisshopp & Drucker 1945)"},
            {"name": "elastica 1-x/L (alpha = 2)", "scalar": "elastica_1_minus_x_over_L", "analytic": 0.16064, "abs": 5e-4, "source": "docs/theory.rst, reference actuator (Bisshopp & Drucker 1945)"},
            {"scalar": "f1_composite", "rel": 1e-6},
            {"scalar": "elastica_y_over_L", "rel": 1e-6}
        ]
    },
]

CASE = Case("stiffness_comparison", __doc__, PARAMETERS, run, plot, benchmarks=BENCHMARKS, table_order=5,
            summary="the paper's calibration against lamination theory (beam theory, elastica)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
