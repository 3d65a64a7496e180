"""Bender with a rigid lever: the extension's end follows tip + a (cos theta, sin theta) exactly.

The paper's bending actuator (three cells' length, 87 mm; CFC 0.2 mm / 70 GPa under MFC
0.3 mm / 30.336 GPa, 28 mm wide) carries a rigid lever of length ``a`` welded to its tip along
the tip tangent (an amplifying extension, as in bender-driven grippers and positioners).  The
MFC is driven by the paper's triangle wave (Eq. 11, -500 ... 1500 V) through the paper's
continuous Preisach loop as free strain, evaluated in the solver step.  The time step is chosen
for ``accuracy`` (default 1e-3 of the recorded positions' travel, :func:`exudyn_atcm.simulate`
with ``accuracy=``; about 5e-4 s by default); ``--set step=1e-4`` fixes it instead (the
regression benchmark does).  The JSON's notes give the step used and why (``step [s]``,
``step_choice``).

References:

* dynamics (``lever_error``): the weld keeps the lever along the tip tangent, so its end is
  exactly ``tip + a (cos theta, sin theta)`` with the recorded tip position and absolute tip
  angle ``theta``, at every recorded instant (relative to the lever end's travel);
* statics (``static_error_arc``): without load, the bender takes its free shape, a circular
  arc of curvature ``kappa`` (Timoshenko's bimetal formula from the recorded free strain), so
  the lever's end is at ``(sin kappa L, 1 - cos kappa L)/kappa + a (cos kappa L, sin kappa L)``;
  a chain of rigid cells has its joints on the inscribed polygon of the arc, which shifts the
  tip by a relative ``(kappa L_c)²/24`` (``static_error_chain_polygon`` compares with the
  polygon itself).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_atcm import Bender, Layer, Link, Mechanism, PiezoDrive, Result, static_sweep
from exudyn_atcm import theory
from exudyn_atcm.casework import (Case, CaseOutput, Parameter, Parameters, RunContext, case_dynamic_run,
                                  step_notes)
from exudyn_atcm.model import Triangle, paper_strain_preisach
from exudyn_atcm.plots import animate_mechanism, axis_label, new_figure, plot_mechanism, save_figure
from exudyn_atcm.solve import ACCURACY_RANGE

#: Default ``accuracy`` [-] of the dynamic run (relative to the travel of the recorded positions); the checks
#: against the references (the lever's kinematics, the statics) do not depend on the step.
DEFAULT_ACCURACY = 1e-3

PARAMETERS = [
    Parameter("n_cells", 6, "-", "rigid cells of the bender", minimum=1),
    Parameter("length", 0.087, "m", "bender length L", exclusive_minimum=0.0),
    Parameter("lever", 0.03, "m", "lever length a", exclusive_minimum=0.0),
    Parameter("lever_mass", 1e-3, "kg", "lever mass (a slender bar)", exclusive_minimum=0.0),
    Parameter("period", 0.5, "s", "period of the triangle voltage", exclusive_minimum=0.0),
    Parameter("cycles", 1, "-", "voltage periods simulated", minimum=1),
    Parameter("step", 0.0, "s", "time step (0: chosen for accuracy)", minimum=0.0),
    Parameter("accuracy", DEFAULT_ACCURACY, "-", "largest error of the recorded positions relative to their travel, "
              "for which the step is chosen when step = 0", minimum=ACCURACY_RANGE[0], maximum=ACCURACY_RANGE[1]),
    Parameter("record_every", 1e-3, "s", "recording interval [s] (0: every step); the solution and the scalars (from every "
              "accepted step) are the same, the files smaller (an interval coarser than the program is warned about)", minimum=0.0),
    Parameter("static_voltages", (0.0, 500.0, 1000.0, 1500.0), "V", "voltages of the static check (rising)"),
    Parameter("animation", True, "-", "also write a GIF of the moving bender and lever"),
]

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
WIDTH = 28e-3


def build_mechanism(p: Parameters) -> Mechanism:
    """The bender along +x with the lever welded to its tip."""
    drive = PiezoDrive(Triangle(500.0, 1000.0, p.period), hysteresis=paper_strain_preisach())
    bender = Bender("bender", width=WIDTH, passive=CFC, active=MFC, length=p.length, n_cells=p.n_cells, drive=drive,
                    cell="rigid")
    lever = Link("lever", {"root": (p.length, 0.0), "end": (p.length + p.lever, 0.0)},
                 mass=p.lever_mass, inertia=p.lever_mass * p.lever**2 / 12.0)
    return Mechanism("bender_with_lever").add(bender, lever).ground(bender.base).weld(bender.tip, lever.point("root"))




def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    a, L = p.lever, p.length
    mech = build_mechanism(p)
    result = case_dynamic_run(mech, p.cycles * p.period, step=p.step, accuracy=p.accuracy,
                              default_accuracy=DEFAULT_ACCURACY, record_every=p.record_every, progress=ctx.progress)
    every = result.every_step  # every accepted step: the scalars do not depend on record_every
    end = np.stack([every["lever.end_x"], every["lever.end_y"]], axis=-1)
    ref = np.stack(theory.rigid_extension_point(every["bender.tip_x"], every["bender.tip_y"],
                                            every["bender.tip_angle"], a), axis=-1)
    travel = float(np.max(np.linalg.norm(end - end[0], axis=1)))
    scalars = {
        "lever_error": (float(np.max(np.linalg.norm(end - ref, axis=1))) / travel, "-"),
        "lever_error_abs": (float(np.max(np.linalg.norm(end - ref, axis=1))), "m"),
        "lever_end_travel": (travel, "m"),
        "lever_end_y_max": (float(end[:, 1].max()), "m"),
        "lever_end_y_min": (float(end[:, 1].min()), "m"),
    }
    # statics: the free shape (arc) plus the lever
    static = static_sweep(build_mechanism(p), list(p.static_voltages))
    kappa = theory.free_curvature(CFC.youngs_modulus, CFC.thickness, MFC.youngs_modulus, MFC.thickness, WIDTH,
                              static["bender.strain"])
    arc = np.array([theory.arc_point(float(k), L) for k in kappa])
    arc_end = np.stack(theory.rigid_extension_point(arc[:, 0], arc[:, 1], kappa * L, a), axis=-1)
    poly = np.array([[x[-1], y[-1]] for x, y in (theory.chain_polygon(float(k), L, p.n_cells) for k in kappa)])
    poly_end = np.stack(theory.rigid_extension_point(poly[:, 0], poly[:, 1], kappa * L, a), axis=-1)
    static_end = np.stack([static["lever.end_x"], static["lever.end_y"]], axis=-1)
    static_travel = float(np.max(np.linalg.norm(static_end - np.array([L + a, 0.0]), axis=1)))
    scalars["static_error_arc"] = (float(np.max(np.linalg.norm(static_end - arc_end, axis=1))) / static_travel, "-")
    scalars["static_error_chain_polygon"] = (
        float(np.max(np.linalg.norm(static_end - poly_end, axis=1))) / static_travel, "-")
    scalars["static_tip_angle_error"] = (float(np.max(np.abs(static["bender.tip_angle"] - kappa * L))), "rad")
    table = Result({"voltage": static["bender.voltage"], "strain": static["bender.strain"], "kappa": kappa,
                    "lever.end_x": static_end[:, 0], "lever.end_y": static_end[:, 1],
                    "arc_reference_x": arc_end[:, 0], "arc_reference_y": arc_end[:, 1]},
                   {"voltage": "V", "strain": "-", "kappa": "1/m", "lever.end_x": "m", "lever.end_y": "m",
                    "arc_reference_x": "m", "arc_reference_y": "m"})
    notes = {"rejected_steps": int(result.info.get("rejected_steps", 0)), **step_notes(result),
             "reference": "lever end = tip + a (cos theta, sin theta) in dynamics; arc + lever in statics"}
    return CaseOutput(result, scalars, steps=int(result.info.get("accepted_steps", result.n_rows)),
                      tables={"static": table}, notes=notes)


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    files = []
    fig, axes = new_figure(2, 1, width=6.4, height=6.0, sharex=True)
    axes[0].plot(r["time"], r["bender.voltage"])
    axes[0].set_ylabel(axis_label("voltage U", "V"))
    axes[1].plot(r["time"], r["bender.tip_y"] * 1e3, label="bender tip")
    axes[1].plot(r["time"], r["lever.end_y"] * 1e3, label=f"lever end (a = {p.lever * 1e3:g} mm)")
    ref = theory.rigid_extension_point(r["bender.tip_x"], r["bender.tip_y"], r["bender.tip_angle"], p.lever)
    axes[1].plot(r["time"], np.asarray(ref[1]) * 1e3, "k:", lw=1, label="tip + a (cos θ, sin θ)")
    axes[1].set_ylabel(axis_label("y", "mm"))
    axes[1].set_xlabel(axis_label("time t", "s"))
    axes[1].legend(fontsize=8)
    files.append(save_figure(fig, out_dir / f"{output.case}_time_series.png"))
    fig, (ax,) = new_figure(1, 1, width=6.4, height=4.5)
    ax.plot(r["bender.voltage"], r["lever.end_y"] * 1e3, label="lever end")
    ax.plot(r["bender.voltage"], r["bender.tip_y"] * 1e3, label="bender tip")
    ax.set_xlabel(axis_label("voltage U", "V"))
    ax.set_ylabel(axis_label("y", "mm"))
    ax.legend(fontsize=8)
    files.append(save_figure(fig, out_dir / f"{output.case}_loop.png"))
    mech = build_mechanism(p)
    peak = int(np.argmax(r["lever.end_y"]))
    files.append(out_dir / f"{output.case}_mechanism.png")
    plot_mechanism(mech, r, path=files[-1], row=peak,
                   trace=["lever.end"], title="bender with lever at its largest deflection")
    if p.animation:
        files.append(animate_mechanism(mech, r, out_dir / f"{output.case}_animation.gif", frames=40,
                                       trace=["lever.end", "bender.tip"]))
    return files


#: Cheap settings for the smoke test (no GIF): they change no check the defaults pass.
SMOKE = {"animation": False}

#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "bender_with_lever",
        "quick": True,
        "parameters": {"animation": False, "step": 1e-4},
        "scalars": [
            {"name": "lever_error (/ travel)", "scalar": "lever_error", "analytic": 0.0, "abs": 1e-12, "source": "welded rigid lever: end = tip + a (cos theta, sin theta) at every recorded instant"},
            {"name": "static_error_chain_polygon (/ travel)", "scalar": "static_error_chain_polygon", "analytic": 0.0, "abs": 1e-9, "source": "the stress-free rigid-cell polygon plus the rigid lever; static solver tolerance"},
            {"name": "static_error_arc (/ travel)", "scalar": "static_error_arc", "analytic": 0.0, "abs": 1e-3, "source": "constant-curvature arc plus the lever (pure bending, Timoshenko 1925); discretisation error of 6 cells"},
            {"name": "static_tip_angle_error", "scalar": "static_tip_angle_error", "analytic": 0.0, "abs": 1e-12, "source": "tip angle = kappa L, exact for every number of rigid cells"},
            {"scalar": "lever_end_y_max", "rel": 1e-6},
            {"scalar": "lever_end_y_min", "rel": 1e-6}
        ]
    },
]

CASE = Case("bender_with_lever", __doc__, PARAMETERS, run, plot, smoke=SMOKE, benchmarks=BENCHMARKS, table_order=9,
            summary="a rigid extension welded to a bender tip (lever kinematics)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
