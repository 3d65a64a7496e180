"""Design optimisation of the bending actuator: passive layer and cell count for the most work at 1500 V.

The actuator of the paper (MFC 0.3 mm / 30.336 GPa on a passive textile-composite layer,
28 mm wide, cells of 29 mm, clamped at the first interface) is bent by the linear piezo law
(Eq. 3, d33 = 460 pm/V, t_IDE = 0.5 mm) at 1500 V.  Its figure of merit is the *work*
W = delta_free F_b, the product of the free tip deflection and the blocked tip force (the
force that holds the tip at y = 0).  The design variables are the passive layer's thickness
h1 and modulus E1 (within a range: glass- to carbon-fibre textiles) and the number of cells
(the actuator's length); the first bending frequency must stay above a bound.

``mode = "optimise"`` (default) runs :func:`exudyn_atcm.study.optimize` (differential
evolution, population in parallel, polished by Nelder-Mead) over the design with this
same case in ``mode = "evaluate"`` as the inner run, which builds the multibody model
(rigid cells by default) and solves: the free static deflection, the blocked force (tip
held at y = 0 by a tip force, found by secant iteration), and the first eigenfrequency.

Closed-form cross-check (composite beam theory, Timoshenko 1925): with
kappa = a_s e eps / EI (a_s = a1 a2/(a1 + a2), e = (h1 + h2)/2), delta_free = kappa L²/2
and F_b = 1.5 EI kappa / L,

    W = 0.75 L (a_s e eps)² / EI = 2.25 L eps² E2 b h2 g(n, t),
    g(n, t) = n² t² (1 + t)² / [(1 + n t)(1 + 4nt + 6nt² + 4nt³ + n²t⁴)],

n = E1/E2, t = h1/h2.  d ln g/dt = 0 gives the quartic
n² t⁴ + (3n² - 2n) t³ - 3n t² - 5n t - 2 = 0 with one positive root t*(n) (t* = 2 for
n = 1; 1.1036 for carbon fibre at 70 GPa).  g(n, t*(n)) grows with n, so the stiffest
passive layer of the range is best, and W grows with the length L: the cell count goes to
its upper bound unless the frequency bound stops it.  When the frequency bound is not
active at the optimum (the default: at most 4 cells, f1 >= 20 Hz), the optimum thickness
ratio is t*(E1_max/E2); the case reports the optimiser's ratio against it (goal: within
1 %).  With more cells allowed the bound becomes active and sets the thickness instead
(with ``cells_max = 8``: 7 cells of the softest layer, 20 GPa, 1.3 mm thick, f1 at 20 Hz).

``kinematics``: ``"linear"`` (default) evaluates the model's small-deflection response
(solved at 1/1000 of the voltage and scaled: the work of linear beam theory, the standard
actuator figure of merit); ``"nonlinear"`` solves the geometrically nonlinear statics at the
full voltage: the large free deflection (kappa L of about 0.3 rad) lowers the work of thin
passive layers most and moves the optimum to thicker layers (about +2 % in t at 4 cells).
The optimise mode reports that nonlinear optimum as well (``check_nonlinear``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_atcm import BendingActuator, Layer, PiezoDrive, Result, eigenfrequencies, solve_static
from exudyn_atcm import theory
from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, RunContext
from exudyn_atcm.plots import axis_label, new_figure, save_figure

PARAMETERS = [
    Parameter("mode", "optimise", "-", "optimise the design, or evaluate one design", choices=("optimise", "evaluate")),
    Parameter("voltage", 1500.0, "V", "drive voltage"),
    Parameter("kinematics", "linear", "-", "small-deflection response scaled to the voltage, or nonlinear statics", choices=("linear", "nonlinear")),
    Parameter("cell", "rigid", "-", "cell model", choices=("rigid", "six-bar")),
    Parameter("passive_thickness", 0.2e-3, "m", "passive layer thickness h1 (evaluate mode)", exclusive_minimum=0.0),
    Parameter("passive_modulus", 70e9, "Pa", "passive layer Young's modulus E1 (evaluate mode)", exclusive_minimum=0.0),
    Parameter("n_cells", 3, "-", "number of cells (evaluate mode)", minimum=1),
    Parameter("passive_density", 1550.0, "kg/m^3", "passive layer density", exclusive_minimum=0.0),
    Parameter("active_thickness", 0.3e-3, "m", "active (MFC) layer thickness h2", exclusive_minimum=0.0),
    Parameter("active_modulus", 30.336e9, "Pa", "active layer Young's modulus E2", exclusive_minimum=0.0),
    Parameter("active_density", 5440.0, "kg/m^3", "active layer density", exclusive_minimum=0.0),
    Parameter("cell_length", 29e-3, "m", "cell length", exclusive_minimum=0.0),
    Parameter("width", 28e-3, "m", "width of both layers", exclusive_minimum=0.0),
    Parameter("thickness_min", 0.05e-3, "m", "optimise: smallest passive thickness", exclusive_minimum=0.0),
    Parameter("thickness_max", 1.5e-3, "m", "optimise: largest passive thickness", exclusive_minimum=0.0),
    Parameter("modulus_min", 20e9, "Pa", "optimise: smallest passive modulus", exclusive_minimum=0.0),
    Parameter("modulus_max", 70e9, "Pa", "optimise: largest passive modulus", exclusive_minimum=0.0),
    Parameter("cells_min", 2, "-", "optimise: fewest cells", minimum=1),
    Parameter("cells_max", 4, "-", "optimise: most cells", minimum=1),
    Parameter("f1_min", 20.0, "Hz", "lower bound of the first bending frequency", minimum=0.0),
    Parameter("maxiter", 30, "-", "optimise: generations of differential evolution", minimum=1),
    Parameter("popsize", 10, "-", "optimise: population size per design variable", minimum=1),
    Parameter("workers", 1, "-", "optimise: worker processes evaluating the population", minimum=1),
    Parameter("check_nonlinear", True, "-", "optimise: also find the thickness optimum with nonlinear kinematics"),
]

_LINEAR_SCALE = 1e-3  # linear kinematics: solve at 1/1000 of the voltage (tip rotation ~3e-4 rad), scale up


def _actuator(p: Parameters, voltage: float) -> BendingActuator:
    """The design at ``voltage`` [V]; the drive has no rating of its own (the user's voltage is checked
    against the MFC's rating once per run, in :func:`run`), so the internal solves, one of them at
    1/1000 of the voltage, never warn."""
    return BendingActuator(
        n_cells=p.n_cells, cell_length=p.cell_length, width=p.width,
        passive=Layer(p.passive_thickness, p.passive_modulus, p.passive_density),
        active=Layer(p.active_thickness, p.active_modulus, p.active_density),
        drive=PiezoDrive(voltage, rated_range=None), cell=p.cell,
    )


def _tip_y(actuator: BendingActuator, force: float) -> float:
    return float(solve_static(actuator, tip_force=(0.0, -force))["actuator.tip_y"][-1])


def _blocked_force(actuator: BendingActuator, free: float, compliance: float) -> tuple[float, int]:
    """Tip force that brings the tip back to y = 0 (secant iteration from the linear estimate)."""
    tol = 1e-10 * actuator.length
    f0, y0 = 0.0, free
    f1 = free / compliance
    y1 = _tip_y(actuator, f1)
    for iteration in range(1, 30):
        if abs(y1) <= tol:
            return f1, iteration
        f0, y0, f1 = f1, y1, f1 - y1 * (f1 - f0) / (y1 - y0)
        y1 = _tip_y(actuator, f1)
    raise RuntimeError(f"blocked force: secant iteration did not bring the tip to y = 0 (|y| = {abs(y1):.3g} m after 30 solves)")


def evaluate(p: Parameters) -> dict[str, tuple[float, str]]:
    """The key scalars of one design (see the module docstring)."""
    probe = _actuator(p, 0.0)
    unit_force = 1e-3 * probe.bending_stiffness / probe.length**2  # small: tip rotation ~1e-3 rad
    compliance = -_tip_y(probe, unit_force) / unit_force
    if p.kinematics == "linear":
        small = _actuator(p, _LINEAR_SCALE * p.voltage)
        free = float(solve_static(small)["actuator.tip_y"][-1]) / _LINEAR_SCALE
        force, solves = free / compliance, 0
    else:
        full = _actuator(p, p.voltage)
        free = float(solve_static(full)["actuator.tip_y"][-1])
        force, solves = _blocked_force(full, free, compliance)
    f1 = float(eigenfrequencies(probe, n=1)[0])
    e1, h1, e2, h2, b = p.passive_modulus, p.passive_thickness, p.active_modulus, p.active_thickness, p.width
    strain = probe.drive.linear_strain(p.voltage)
    return {
        "tip_deflection": (free, "m"),
        "blocked_force": (force, "N"),
        "work": (free * force, "J"),
        "first_frequency": (f1, "Hz"),
        "thickness_ratio": (h1 / h2, "-"),
        "modulus_ratio": (e1 / e2, "-"),
        "length": (probe.length, "m"),
        "work_beam_theory": (theory.actuator_work(e1, h1, e2, h2, b, strain, probe.length), "J"),
        "first_frequency_beam_theory": (theory.first_bending_frequency(theory.composite_bending_stiffness(e1, h1, e2, h2, b),
                                                                   theory.mass_per_length(p.passive_density, h1, p.active_density, h2, b), probe.length), "Hz"),
        "thickness_ratio_beam_theory": (theory.optimal_thickness_ratio(e1 / e2), "-"),
        "blocked_force_solves": (float(solves), "-"),
    }


def _fixed(p: Parameters, **changes) -> dict:
    names = ("voltage", "kinematics", "cell", "passive_density", "active_thickness", "active_modulus",
             "active_density", "cell_length", "width")
    return {"mode": "evaluate", **{n: p[n] for n in names}, **changes}


def optimise(p: Parameters, ctx: RunContext) -> CaseOutput:
    from exudyn_atcm.study import OptimizeOptions, RunOptions, optimize

    store = ctx.out_dir / "runs" if ctx.out_dir is not None else None
    bounds = {
        "passive_thickness": (p.thickness_min, p.thickness_max),
        "passive_modulus": (p.modulus_min, p.modulus_max),
        "n_cells": (p.cells_min, p.cells_max),
    }
    constraints = {"first_frequency": (p.f1_min, None)}
    best = optimize(CASE, "work", bounds, maximize=True, constraints=constraints, fixed=_fixed(p),
                    options=OptimizeOptions(maxiter=p.maxiter, popsize=p.popsize, rerun_best=False),
                    run=RunOptions(workers=p.workers, store=store))
    design = best.design
    n_ratio = design["passive_modulus"] / p.active_modulus
    t_opt = design["passive_thickness"] / p.active_thickness
    t_theory = theory.optimal_thickness_ratio(n_ratio)
    scalars = {
        "thickness_ratio_optimum": (t_opt, "-"),
        "thickness_ratio_beam_theory": (t_theory, "-"),
        "thickness_ratio_error": (t_opt / t_theory - 1.0, "-"),
        "passive_thickness_optimum": (design["passive_thickness"], "m"),
        "passive_modulus_optimum": (design["passive_modulus"], "Pa"),
        "n_cells_optimum": (float(design["n_cells"]), "-"),
        "work_optimum": (best.scalars["work"], "J"),
        "tip_deflection_optimum": (best.scalars["tip_deflection"], "m"),
        "blocked_force_optimum": (best.scalars["blocked_force"], "N"),
        "first_frequency_optimum": (best.scalars["first_frequency"], "Hz"),
        "frequency_bound_active": (float(best.scalars["first_frequency"] < p.f1_min * 1.001), "-"),
        "evaluations": (float(best.evaluations), "-"),
    }
    notes = {"optimiser": best.message, "runs executed": best.executed, "evaluation rate": best.describe_rate()}
    if p.check_nonlinear and p.kinematics == "linear":
        fixed = _fixed(p, kinematics="nonlinear", passive_modulus=design["passive_modulus"], n_cells=design["n_cells"])
        nonlinear = optimize(CASE, "work", {"passive_thickness": bounds["passive_thickness"]}, method="nelder-mead",
                             maximize=True, constraints=constraints, fixed=fixed,
                             x0={"passive_thickness": design["passive_thickness"]},
                             options=OptimizeOptions(rerun_best=False), run=RunOptions(workers=1, store=store))
        t_nl = nonlinear.design["passive_thickness"] / p.active_thickness
        scalars["thickness_ratio_optimum_nonlinear"] = (t_nl, "-")
        scalars["work_optimum_nonlinear"] = (nonlinear.scalars["work"], "J")
    history = best.history
    columns = {"evaluation": "-", "passive_thickness": "m", "passive_modulus": "Pa", "n_cells": "-", "work": "J",
               "violation": "-"}
    data = {name: np.asarray([row for row in _column(history, name)], dtype=float) for name in columns}
    result = Result(data, columns, parameters={"design variables": list(bounds), "constraints": {"first_frequency [Hz]": [p.f1_min, None]}})
    return CaseOutput(result, scalars, steps=int(best.evaluations), notes=notes)


def _column(table, name):
    from exudyn_atcm.study import column

    return column(table, name)


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    # the voltage the user gave, against the MFC's rating (and the kV check): once per run
    PiezoDrive(p.voltage).check_voltage_range(p.voltage, p.voltage, what=f"voltage={p.voltage:g} V", stacklevel=2)
    if p.mode == "optimise":
        if not (0.0 < p.thickness_min < p.thickness_max and 0.0 < p.modulus_min < p.modulus_max and 1 <= p.cells_min <= p.cells_max):
            raise ValueError("optimise: need 0 < thickness_min < thickness_max, 0 < modulus_min < modulus_max and "
                             f"1 <= cells_min <= cells_max, got {p.thickness_min}, {p.thickness_max}, {p.modulus_min}, "
                             f"{p.modulus_max}, {p.cells_min}, {p.cells_max}")
        return optimise(p, ctx)
    scalars = evaluate(p)
    row = {name: np.array([value]) for name, (value, _) in scalars.items()}
    result = Result(row, {name: unit for name, (_, unit) in scalars.items()})
    return CaseOutput(result, scalars, steps=1)


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    if p.mode != "optimise":
        return []
    r = output.result
    s = output.scalars
    fig, (ax,) = new_figure(1, height=3.8)
    same = (r["n_cells"] == s["n_cells_optimum"]) & np.isclose(r["passive_modulus"], s["passive_modulus_optimum"], rtol=0.02)
    ratio = r["passive_thickness"] / p.active_thickness
    ax.plot(ratio[~same], r["work"][~same] * 1e3, ".", color="0.7", markersize=3, label="other evaluations")
    ax.plot(ratio[same], r["work"][same] * 1e3, "o", markersize=3, label="evaluations at the optimum's E1 (±2 %) and cells")
    t = np.linspace(ratio.min(), ratio.max(), 300)
    e1 = s["passive_modulus_optimum"]
    n = int(s["n_cells_optimum"])
    strain = 460e-12 * p.voltage / 0.5e-3
    chain = 1.0 + 1.0 / (2.0 * n * n) if p.cell == "rigid" else 1.0
    work = [theory.actuator_work(e1, ti * p.active_thickness, p.active_modulus, p.active_thickness, p.width, strain, n * p.cell_length) / chain for ti in t]
    ax.plot(t, np.array(work) * 1e3, "-", label="beam theory (with the chain's compliance factor)")
    ax.axvline(s["thickness_ratio_beam_theory"], color="k", linestyle="--", linewidth=1.0, label="closed-form optimum t*")
    ax.plot([s["thickness_ratio_optimum"]], [s["work_optimum"] * 1e3], "*", markersize=12, label="optimiser")
    ax.set_xlabel(axis_label("thickness ratio h1/h2", "-"))
    ax.set_ylabel(axis_label("work δ_free·F_b", "mJ"))
    ax.set_title(f"Work at {p.voltage:g} V: {n} cells, E1 = {e1 / 1e9:.3g} GPa")
    ax.legend(loc="upper right", fontsize=7.5)
    return [save_figure(fig, out_dir / f"{output.case}_work.png")]


#: Cheap settings for the smoke test (3 iterations, no nonlinear check): they change no check the defaults pass.
SMOKE = {"maxiter": 3, "check_nonlinear": False}

CASE = Case("optimise_bender", __doc__, PARAMETERS, run, plot, smoke=SMOKE, table_order=12,
            summary="passive layer and cell count for the most actuator work (closed-form optimum)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
