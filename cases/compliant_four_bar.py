"""Compliant four-bar: an A-TCM bender as input crank, flexure hinges, coupler path with and without hysteresis.

A four-bar linkage whose input crank is a piezo bender (the paper's laminate: CFC 0.2 mm /
70 GPa under MFC 0.3 mm / 30.336 GPa, 28 mm wide) clamped to the ground, and whose three
other hinges are flexures (short CFC strips, Howell's small-length flexural pivot: the
pseudo-rigid-body model with gamma = 0.5, K = EI/l): crank tip - coupler (hinge_B), coupler -
rocker (hinge_C), rocker - ground (hinge_D).  The coupler is a triangular CFC plate carrying the
coupler point P.

The crank's MFC is driven through one voltage cycle -500 V -> 1500 V -> -500 V, solved
quasi-statically (each step continues from the previous state and hysteresis memory), twice:

* with hysteresis: the paper's continuous Preisach loop as free strain (Eqs. 8-10);
* without hysteresis: a linear voltage-to-strain law with the same end points (the same
  operator with both exponents 1: ascending and descending branch coincide).

Reference: the rigid four-bar through the flexures' characteristic pivots (B*, C*, D*).
For the simulated crank-tip pivot B* the rigid four-bar's loop closure (circle intersection,
:mod:`exudyn_atcm.theory.four_bar`) gives the rocker joint and the coupler point; the key scalar
``reference_error`` is the largest distance between simulated and reference coupler point,
relative to the coupler point's travel.  The hysteresis path error is the largest distance
between the two runs' coupler points at the same voltage; the loop width the largest distance
between the rising and the falling half-cycle at the same voltage.

A dynamic run over one period of the paper's triangle wave (Eq. 11), with the hysteresis
evaluated in the solver step, is checked against the same rigid four-bar at every recorded
instant (``reference_error_dynamic``: the coupler and rocker are rigid, the pivots pins, so
the loop closure holds in dynamics too); the GIF shows it.  Its time step is chosen for
``accuracy`` (default 1e-3 of the recorded positions' travel, :func:`exudyn_atcm.simulate` with
``accuracy=``; about 2.5e-4 s by default); ``--set step=1e-4`` fixes it instead.  The JSON's notes give
the step used and why (``step [s]``, ``step_choice``).

Outputs: the sweep (coupler point, pivots, voltages, strains, reference point) as CSV; plots
of the coupler path (both runs and the reference), coupler point over voltage, the mechanism
drawing, and a GIF of the moving mechanism.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from exudyn_atcm import Bender, Flexure, Layer, Link, Mechanism, PiezoDrive, Result, static_sweep
from exudyn_atcm.casework import (Case, CaseOutput, CellChoices, Parameter, Parameters, RunContext, case_dynamic_run,
                                  step_notes)
from exudyn_atcm.hysteresis import ContinuousPreisach
from exudyn_atcm.model import Triangle, paper_strain_preisach
from exudyn_atcm.plots import animate_mechanism, axis_label, new_figure, plot_mechanism, save_figure
from exudyn_atcm.solve import ACCURACY_RANGE
from exudyn_atcm.theory import RigidFourBar

#: Default ``accuracy`` [-] of the dynamic run (relative to the travel of the recorded positions); its check against
#: the rigid four-bar (the loop closure at every recorded instant) does not depend on the step.
DEFAULT_ACCURACY = 1e-3

PARAMETERS = [
    Parameter("n_cells", 8, "-", "cells of the crank bender", minimum=1),
    Parameter("cell", "rigid", "-", "cell model of the crank bender", choices=CellChoices(joins_anywhere=True, first=("rigid",))),
    Parameter("crank_length", 0.06, "m", "length of the crank bender", exclusive_minimum=0.0),
    Parameter("coupler_length", 0.05, "m", "distance of the coupler's hinges B* - C*", exclusive_minimum=0.0),
    Parameter("rocker_pivot_height", 0.02, "m", "height of the rocker's ground pivot D* above the crank's base", minimum=0.0),
    Parameter("coupler_point_x", 0.025, "m", "coupler point P from the coupler's hinge point B, along B -> C"),
    Parameter("coupler_point_y", 0.02, "m", "coupler point P from the coupler's hinge point B, normal to B -> C (up)"),
    Parameter("flexure_length", 4e-3, "m", "length of each flexure hinge", exclusive_minimum=0.0),
    Parameter("flexure_thickness", 0.1e-3, "m", "thickness of the flexure strips (CFC)", exclusive_minimum=0.0),
    Parameter("n_steps", 40, "-", "static steps per voltage cycle"),
    Parameter("exponents", "exact", "-", "continuous Preisach exponents", choices=("exact", "rounded")),
    Parameter("dynamic_period", 0.5, "s", "period of a dynamic run (triangle -500 ... 1500 V, one cycle); 0: none", minimum=0.0),
    Parameter("step", 0.0, "s", "time step of the dynamic run (0: chosen for accuracy)", minimum=0.0),
    Parameter("accuracy", DEFAULT_ACCURACY, "-", "largest error of the dynamic run's recorded positions relative to "
              "their travel, for which the step is chosen when step = 0", minimum=ACCURACY_RANGE[0],
              maximum=ACCURACY_RANGE[1]),
    Parameter("animation", True, "-", "also write a GIF of the moving mechanism"),
]

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)


def build_mechanism(p: Parameters, strain_law, voltage=0.0) -> Mechanism:
    """The compliant four-bar in its reference pose (crank straight, pointing up).

    ``strain_law``: the drive's voltage-to-strain operator; ``voltage``: its program [V]
    (a number or a callable of time; the static sweeps set the voltage themselves).
    """
    # --- user code: building the mechanism takes the 18 lines below (counted by user_code_lines and the tests: < 30;
    # with its 3 import lines and the 2 Layer lines at the top of this file, 23) ---
    L, b, lf, h, u, v = p.crank_length, p.coupler_length, p.flexure_length, p.rocker_pivot_height, p.coupler_point_x, p.coupler_point_y
    crank = Bender("crank", width=28e-3, passive=CFC, active=MFC, length=L, n_cells=p.n_cells,
                   drive=PiezoDrive(voltage, hysteresis=strain_law), angle=math.pi / 2, active_side="left", cell=p.cell)

    def flexure(name, base, tip):  # Howell's small-length flexural pivot: pivot mid-way, K = EI/l
        return Flexure(name, base=base, tip=tip, width=10e-3, layer=Layer(p.flexure_thickness, 70e9, 1550.0),
                       gamma=0.5, k_theta=2.0)

    hinge_b = flexure("hinge_B", (0.0, L), (0.0, L + lf))
    coupler = Link.from_outline("coupler", {"B": (0.0, L + lf), "C": (b, L + lf), "P": (u, L + lf + v)},
                                outline=[(0.0, L + lf), (b, L + lf), (u, L + lf + v)],
                                density=1550.0, thickness=1e-3)
    hinge_c = flexure("hinge_C", (b, L + lf), (b, L))
    rocker = Link("rocker", {"C": (b, L), "D": (b, h + lf)}, mass=1550.0 * 1e-3 * 5e-3 * (L - h - lf),
                  inertia=1550.0 * 1e-3 * 5e-3 * (L - h - lf) ** 3 / 12.0)
    hinge_d = flexure("hinge_D", (b, h + lf), (b, h))
    mech = Mechanism("compliant_four_bar").add(crank, hinge_b, coupler, hinge_c, rocker, hinge_d)
    mech.ground(crank.base).weld(crank.tip, hinge_b.base).weld(hinge_b.tip, coupler.point("B"))
    mech.weld(coupler.point("C"), hinge_c.base).weld(hinge_c.tip, rocker.point("C"))
    mech.weld(rocker.point("D"), hinge_d.base).ground(hinge_d.tip)
    # --- end of user code ---
    return mech


def strain_laws(exponents: str) -> dict[str, ContinuousPreisach]:
    """The hysteretic law (paper) and the linear law through the same end points."""
    paper = paper_strain_preisach(rounded=exponents == "rounded")
    linear = ContinuousPreisach(paper.u_min, paper.u_max, paper.y_min, paper.y_max, 1.0, 1.0)
    return {"hysteresis": paper, "linear": linear}


def voltage_cycle(n_steps: int) -> np.ndarray:
    """-500 V -> 1500 V -> -500 V in ``n_steps`` equal steps (first and last point -500 V)."""
    if n_steps < 4 or n_steps % 2:
        raise ValueError(f"n_steps must be an even integer >= 4, got {n_steps}")
    half = np.linspace(-500.0, 1500.0, n_steps // 2 + 1)
    return np.concatenate([half, half[-2::-1]])


def pivot(result: Result, mech: Mechanism, name: str) -> np.ndarray:
    """Position [m] of a PRBM flexure's pivot from its recorded base point and base-segment angle."""
    flex = mech.components[name]
    angle = result[f"{name}.base_angle"]
    base = np.stack([result[f"{name}.base_x"], result[f"{name}.base_y"]], axis=-1)
    return base + flex.segment_lengths[0] * np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def reference_four_bar(mech: Mechanism) -> RigidFourBar:
    """The rigid four-bar through the characteristic pivots of the reference pose."""
    return RigidFourBar.from_points(A=mech.components["crank"].base_position, B=mech.components["hinge_B"].pivot,
                                    C=mech.components["hinge_C"].pivot, D=mech.components["hinge_D"].pivot,
                                    P=mech.position("coupler.P"))


def check_geometry(p: Parameters) -> None:
    """Refuse dimensions that leave no room for the rocker (it spans from D* up to the coupler)."""
    if not 0.0 <= p.rocker_pivot_height < p.crank_length - p.flexure_length:
        raise ValueError(
            f"rocker_pivot_height must be in [0, crank_length - flexure_length) = [0, "
            f"{p.crank_length - p.flexure_length:.6g}) m so that the rocker has a length, got {p.rocker_pivot_height!r}")


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    check_geometry(p)
    voltages = voltage_cycle(p.n_steps)
    results, meches = {}, {}
    for label, law in strain_laws(p.exponents).items():
        meches[label] = mech = build_mechanism(p, law)
        results[label] = static_sweep(mech, voltages)
        ctx.progress(len(results), 2)
    mech, res = meches["hysteresis"], results["hysteresis"]
    four_bar = reference_four_bar(mech)
    points = {}
    for label, r in results.items():
        points[label] = np.stack([r["coupler.P_x"], r["coupler.P_y"]], axis=-1)
    b_star = pivot(res, mech, "hinge_B")
    p_ref = four_bar.coupler_point_from_crank_tip(b_star)
    c_ref = four_bar.rocker_joint(b_star)
    p_sim, p_lin = points["hysteresis"], points["linear"]
    travel = float(np.max(np.linalg.norm(p_sim - p_sim[0], axis=1)))
    ref_err = float(np.max(np.linalg.norm(p_sim - p_ref, axis=1)))
    c_err = float(np.max(np.linalg.norm(pivot(res, mech, "hinge_C") - c_ref, axis=1)))
    lin_err = float(np.max(np.linalg.norm(
        p_lin - four_bar.coupler_point_from_crank_tip(pivot(results["linear"], meches["linear"], "hinge_B")), axis=1)))
    n_half = p.n_steps // 2
    rising, falling = p_sim[: n_half + 1], p_sim[n_half:][::-1]
    hyst_path = np.linalg.norm(p_sim - p_lin, axis=1)
    series = {"voltage": voltages}
    units = {"voltage": "V"}
    for label, r in results.items():
        series[f"{label}.strain"] = r["crank.strain"]
        series[f"{label}.P_x"], series[f"{label}.P_y"] = points[label][:, 0], points[label][:, 1]
        units.update({f"{label}.strain": "-", f"{label}.P_x": "m", f"{label}.P_y": "m"})
    series.update({"hysteresis.B_star_x": b_star[:, 0], "hysteresis.B_star_y": b_star[:, 1],
                   "reference.P_x": p_ref[:, 0], "reference.P_y": p_ref[:, 1], "path_error": hyst_path})
    units.update({k: "m" for k in series if k not in units})
    table = Result(series, units, parameters=mech.parameters())
    scalars = {
        "reference_error": (ref_err / travel, "-"),
        "reference_error_abs": (ref_err, "m"),
        "rocker_joint_error_abs": (c_err, "m"),
        "reference_error_linear": (lin_err / travel, "-"),
        "coupler_travel": (travel, "m"),
        "hysteresis_path_error_max": (float(hyst_path.max()), "m"),
        "hysteresis_path_error_rel": (float(hyst_path.max()) / travel, "-"),
        "loop_width_max": (float(np.max(np.linalg.norm(rising - falling, axis=1))), "m"),
        "loop_width_linear": (float(np.max(np.linalg.norm(p_lin[: n_half + 1] - p_lin[n_half:][::-1], axis=1))), "m"),
        "strain_max": (float(res["crank.strain"].max()), "-"),
    }
    tables = {"sweep_hysteresis": res}
    if p.dynamic_period > 0.0:
        # the same mechanism in time: the paper's triangle wave, hysteresis in the solver step
        dyn_mech = build_mechanism(p, strain_laws(p.exponents)["hysteresis"], Triangle(500.0, 1000.0, p.dynamic_period))
        dyn = case_dynamic_run(dyn_mech, p.dynamic_period, step=p.step, accuracy=p.accuracy,
                               default_accuracy=DEFAULT_ACCURACY, progress=ctx.progress)
        p_dyn = np.stack([dyn["coupler.P_x"], dyn["coupler.P_y"]], axis=-1)
        dyn_ref = four_bar.coupler_point_from_crank_tip(pivot(dyn, dyn_mech, "hinge_B"))
        scalars["reference_error_dynamic"] = (float(np.max(np.linalg.norm(p_dyn - dyn_ref, axis=1))) / travel, "-")
        scalars["dynamic_travel"] = (float(np.max(np.linalg.norm(p_dyn - p_dyn[0], axis=1))), "m")
        scalars["dynamic_rejected_steps"] = (float(dyn.info.get("rejected_steps", 0)), "-")
        tables["dynamic"] = dyn
    notes = {"reference": "rigid four-bar through the PRBM pivots B*, C*, D* (circle intersection) "
                          "for the simulated crank-tip pivot B*; error relative to the coupler point's travel",
             "user_code_lines": user_code_lines(),
             "degrees_of_freedom": mech.degrees_of_freedom().dof}
    if p.dynamic_period > 0.0:
        notes.update(step_notes(dyn))
    return CaseOutput(table, scalars, steps=len(voltages), tables=tables, notes=notes)


def user_code_lines() -> int:
    """Non-blank, non-comment lines of user code in :func:`build_mechanism` (between the markers)."""
    text = Path(__file__).read_text(encoding="utf-8").splitlines()
    start = next(k for k, line in enumerate(text) if "--- user code:" in line)
    end = next(k for k, line in enumerate(text) if "--- end of user code" in line)
    return sum(1 for line in text[start + 1:end] if line.strip() and not line.strip().startswith("#"))


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    files = []
    fig, (ax,) = new_figure(1, 1, width=6.4, height=4.8)
    for label, style in (("hysteresis", "-"), ("linear", "--")):
        ax.plot(r[f"{label}.P_x"] * 1e3, r[f"{label}.P_y"] * 1e3, style, marker=".", ms=3,
                label=f"coupler point P, {label}")
    ax.plot(r["reference.P_x"] * 1e3, r["reference.P_y"] * 1e3, "x", ms=4, color="k",
            label="rigid four-bar for the simulated B*")
    ax.set_xlabel(axis_label("x", "mm"))
    ax.set_ylabel(axis_label("y", "mm"))
    ax.set_title(f"coupler path over -500 -> 1500 -> -500 V\n(rigid four-bar reference: error "
                 f"{output.scalars['reference_error']:.1e} of the travel)")
    ax.legend(fontsize=8)
    files.append(save_figure(fig, out_dir / f"{output.case}_coupler_path.png"))
    fig, axes = new_figure(2, 1, width=6.4, height=6.0, sharex=True)
    for label in ("hysteresis", "linear"):
        axes[0].plot(r["voltage"], (r[f"{label}.P_x"] - r[f"{label}.P_x"][0]) * 1e3, label=f"{label}")
        axes[1].plot(r["voltage"], r["path_error"] * 1e6 if label == "hysteresis" else np.nan * r["voltage"])
    axes[0].set_ylabel(axis_label("coupler point x - x(-500 V)", "mm"))
    axes[0].legend(fontsize=8)
    axes[1].set_ylabel(axis_label("|P_hysteresis - P_linear|", "µm"))
    axes[1].set_xlabel(axis_label("voltage U", "V"))
    files.append(save_figure(fig, out_dir / f"{output.case}_coupler_vs_voltage.png"))
    mech = build_mechanism(p, strain_laws(p.exponents)["hysteresis"])
    sweep = output.tables["sweep_hysteresis"]
    peak = int(np.argmax(sweep["crank.strain"]))
    files.append(out_dir / f"{output.case}_mechanism.png")
    plot_mechanism(mech, sweep, path=files[-1], row=peak,
                   trace=["coupler.P"], title="compliant four-bar at 1500 V")
    if p.animation:
        moving = output.tables.get("dynamic", sweep)
        files.append(animate_mechanism(mech, moving, out_dir / f"{output.case}_animation.gif",
                                       frames=min(moving.n_rows, 41), trace=["coupler.P"]))
    return files


#: Cheap settings for the smoke test (no GIF): they change no check the defaults pass.
SMOKE = {"animation": False}

#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "four_bar",
        "quick": True,
        "parameters": {"animation": False},
        "scalars": [
            {"name": "reference_error (coupler point vs rigid four-bar, / travel)", "scalar": "reference_error", "analytic": 0.0, "abs": 1e-6, "source": "closed-form four-bar position analysis (circle intersection) from the crank bender's simulated tip; static solver tolerance"},
            {"name": "reference_error_linear (/ travel)", "scalar": "reference_error_linear", "analytic": 0.0, "abs": 1e-6, "source": "closed-form four-bar position analysis, linear drive"},
            {"name": "reference_error_dynamic (/ travel)", "scalar": "reference_error_dynamic", "analytic": 0.0, "abs": 1e-6, "source": "closed-form four-bar position analysis at every recorded instant of the dynamic run"},
            {"name": "rocker_joint_error_abs", "scalar": "rocker_joint_error_abs", "analytic": 0.0, "abs": 1e-8, "source": "rigid rocker: |C - D| = rocker length; static solver tolerance 1e-8 m"},
            {"name": "loop_width_linear (no hysteresis, no loop)", "scalar": "loop_width_linear", "analytic": 0.0, "abs": 1e-8, "source": "a linear drive traces the same path up and down"},
            {"scalar": "coupler_travel", "rel": 1e-6},
            {"scalar": "loop_width_max", "rel": 1e-6},
            {"scalar": "hysteresis_path_error_max", "rel": 1e-6}
        ]
    },
]

CASE = Case("compliant_four_bar", __doc__, PARAMETERS, run, plot, smoke=SMOKE, benchmarks=BENCHMARKS, table_order=6,
            summary="a bender as input crank, flexure hinges; the coupler path with and without hysteresis (rigid four-bar kinematics)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
