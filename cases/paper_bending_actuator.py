"""Fig. 12: the paper's bending actuator driven through its Preisach loop, hysteresis in the solver step.

The paper's actuator (Margineanu, Lovasz, Modler; Figs. 11, 12): three cells of 29 mm, CFC
0.2 mm / 70 GPa on MFC 0.3 mm / 30.336 GPa, 28 mm wide, the first interface clamped.  The MFC
is driven by the paper's triangle wave (Eq. 11, U_med = 500 V, U_amp = 1000 V, -500 ... 1500 V)
through the paper's continuous Preisach loop as free strain (Eqs. 8-10; exact exponents by
default), evaluated inside each solver step and committed on accepted steps.  Everything else
is the package default: six-bar cell, composite stiffness, 2 % damping.  The time step is
chosen for ``accuracy`` (default 1e-3: the largest error of the recorded positions relative to
their travel, :func:`exudyn_atcm.simulate` with ``accuracy=``; about 5e-4 s by default, checked
by a probe run at twice the step); ``--set step=1e-4`` fixes it instead (the regression benchmark
does).  The JSON's notes give the step used and the line saying why (``step [s]``,
``step_choice``).  Every step is computed; one per millisecond is recorded (``record_every``;
0 records every step), which keeps the CSV at about 0.2 MB per simulated second.

Outputs: the time series (time, voltage, strain, stroke, tip position and angle, cell angles)
and plots of voltage, stroke and tip displacement over time, tip deflection over voltage,
the deformed shape at a few instants, the stroke over voltage against the paper's published
values, and a GIF animation of the actuator.

What can be compared with the paper: its Sect. 3 gives numbers for the stroke of a 29 mm
cell only: 40 µm at 1500 V (Eqs. 2, 3), -4 µm at -500 V, and the loop's precision points
12 µm (rising) and 28 µm (falling) at 500 V.  The stroke-versus-voltage plot overlays them
(with the paper's rounded exponents the branches pass 11.556 µm and 29.000 µm instead).
What cannot: the paper's Fig. 12 shows the actuator's tip deflection as a graph without
numbers, and the paper gives neither the layers' widths, thicknesses and moduli nor the
time scale; the tip deflection is therefore compared with beam theory (the theory page of
the documentation), not with the paper.  Key scalars: the tip deflection range over the last
cycle, its values at 500 V on the rising and falling branch (the loop's opening), and
``last_cycle_change``, the largest change of the tip deflection between the last two cycles
(``|y(t) - y(t - T)|`` over the last cycle), which tells how far the response still is from
periodic.  The first cycle never enters it: it starts from rest in the static equilibrium at
U(0) and carries that start's transient (the tip's change from cycle 1 to 2 is about 20 times
the change from 2 to 3 by default), so the scalar needs ``cycles >= 3`` (the default; with fewer
cycles it is not reported, and the JSON's notes say why).  The transient decays by
``exp(-zeta_1 omega_1 T)`` per cycle.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_atcm import BendingActuator, Layer, PiezoDrive
from exudyn_atcm.casework import (Case, CaseOutput, CellChoices, Parameter, Parameters, RunContext, case_dynamic_run,
                                  step_notes)
from exudyn_atcm.model import PAPER_LOOP, Triangle, paper_strain_preisach
from exudyn_atcm.solve import ACCURACY_RANGE
from exudyn_atcm.plots import (
    actuator_as_mechanism,
    animate_mechanism,
    axis_label,
    new_figure,
    plot_actuator_time_series,
    plot_mechanism,
    plot_tip_vs_voltage,
    save_figure,
)

#: Default ``accuracy`` [-] of the run (relative to the travel): 1e-3 of the tip's travel (17.6 mm by default) is
#: 18 µm.  The strokes compared with the paper's numbers are the drive's (voltage through the Preisach loop), which
#: the step changes only through the instants where the voltage is evaluated: the program's corners stay on the grid.
DEFAULT_ACCURACY = 1e-3

PARAMETERS = [
    Parameter("period", 1.0, "s", "period T of the triangle input (Eq. 11)", exclusive_minimum=0.0),
    Parameter("cycles", 3, "-", "number of input periods simulated (last_cycle_change needs >= 3)", minimum=1),
    Parameter("cell", "six-bar", "-", "cell model (beam, ancf: Exudyn's 2-D beam elements, one per cell; "
              "ritz: n_cells assumed modes of the whole bender)",
              choices=CellChoices()),
    Parameter("n_cells", 3, "-", "number of cells", minimum=1),
    Parameter("cell_length", 29e-3, "m", "length of one cell L_j", exclusive_minimum=0.0),
    Parameter("exponents", "exact", "-", "continuous Preisach exponents", choices=("exact", "rounded")),
    Parameter("damping", 0.02, "-", "modal damping ratio of the first bending mode", minimum=0.0),
    Parameter("step", 0.0, "s", "time step (0: chosen for accuracy)", minimum=0.0),
    Parameter("accuracy", DEFAULT_ACCURACY, "-", "largest error of the recorded positions relative to their travel, "
              "for which the step is chosen when step = 0", minimum=ACCURACY_RANGE[0], maximum=ACCURACY_RANGE[1]),
    Parameter("record_every", 1e-3, "s", "recording interval [s] (0: every step); the solution and the scalars (from every "
              "accepted step) are the same, the files smaller (an interval coarser than the program is warned about)", minimum=0.0),
    Parameter("animation", True, "-", "also write a GIF animation of the actuator"),
]


def build(p: Parameters) -> BendingActuator:
    """The paper's actuator driven by the paper's triangle wave through the paper's Preisach loop."""
    drive = PiezoDrive(Triangle(500.0, 1000.0, p.period), hysteresis=paper_strain_preisach(rounded=p.exponents == "rounded"))
    return BendingActuator(
        n_cells=p.n_cells,
        cell_length=p.cell_length,
        width=28e-3,
        passive=Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0),
        active=Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0),
        drive=drive,
        cell=p.cell,
        damping=p.damping,
    )




def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    result = case_dynamic_run(build(p), p.cycles * p.period, step=p.step, accuracy=p.accuracy,
                              default_accuracy=DEFAULT_ACCURACY, record_every=p.record_every, progress=ctx.progress)
    every = result.every_step  # every accepted step: the scalars do not depend on record_every
    t, y = every["time"], every["actuator.tip_y"]
    start = (p.cycles - 1) * p.period
    last = t >= start - 1e-12
    scalars = {
        "tip_y_max_last_cycle": (float(y[last].max()), "m"),
        "tip_y_min_last_cycle": (float(y[last].min()), "m"),
        "tip_y_500V_rising": (float(np.interp(start + 0.25 * p.period, t, y)), "m"),
        "tip_y_500V_falling": (float(np.interp(start + 0.75 * p.period, t, y)), "m"),
        "stroke_max": (float(every["actuator.stroke"].max()), "m"),
        "stroke_min": (float(every["actuator.stroke"].min()), "m"),
    }
    notes = {"rejected_steps": int(result.info["rejected_steps"]), **step_notes(result)}
    change = last_cycle_change(t, y, p.period, p.cycles)
    if change is None:
        notes["last_cycle_change"] = (f"not reported: it compares the last two cycles after the first, which "
                                      f"needs cycles >= {MIN_CYCLES_FOR_CHANGE} (ran {p.cycles})")
    else:
        scalars["last_cycle_change"] = (change, "m")
    return CaseOutput(result, scalars, steps=int(result.info["accepted_steps"]), notes=notes)


#: Cycles needed for :func:`last_cycle_change`: two cycles after the first.
MIN_CYCLES_FOR_CHANGE = 3


def last_cycle_change(t: np.ndarray, y: np.ndarray, period: float, cycles: int) -> float | None:
    """Largest ``|y(t) - y(t - T)|`` over the last of ``cycles`` input periods ``T`` [s], or ``None``.

    The change between the last two cycles, in the unit of ``y``.  The first cycle is never
    one of the two (it starts from rest at the static equilibrium and carries that start's
    transient), so fewer than :data:`MIN_CYCLES_FOR_CHANGE` cycles give ``None``.  ``y`` at
    ``t - T`` is interpolated linearly in the record (exact on a record whose instants repeat
    every period, as the default 1 ms record over a 1 s period does).
    """
    if cycles < MIN_CYCLES_FOR_CHANGE:
        return None
    start = (cycles - 1) * period
    last = t >= start - 1e-12
    previous = np.interp(t[last] - period, t, y)
    return float(np.max(np.abs(y[last] - previous)))


#: The paper's published numbers (Sect. 3) for the stroke of a 29 mm cell: (label, U [V], stroke [m], branch).
PAPER_STROKE_POINTS = [
    ("40 µm at 1500 V (Eqs. 2, 3)", PAPER_LOOP["u_max [V]"], PAPER_LOOP["x_max [m]"], "top"),
    ("-4 µm at -500 V", PAPER_LOOP["u_min [V]"], PAPER_LOOP["x_min [m]"], "bottom"),
    ("12 µm at 500 V, rising", PAPER_LOOP["u_m [V]"], PAPER_LOOP["x_m1 [m]"], "rising"),
    ("28 µm at 500 V, falling", PAPER_LOOP["u_m [V]"], PAPER_LOOP["x_m2 [m]"], "falling"),
]

NOT_COMPARABLE = ("Not comparable: the paper's Fig. 12 gives the tip deflection only as a graph\n"
                  "without numbers (and no layer data); the tip is checked against beam theory instead.")


def paper_comparison(result, period: float, cycles: int) -> list[tuple[str, float, float, float]]:
    """The paper's published strokes against the simulated ones, over the last input cycle.

    The simulated stroke is rescaled to a 29 mm cell (free strain x 29 mm), the length the
    paper's numbers refer to.  Returns ``(label, voltage [V], paper [m], simulated [m])``.
    """
    t, u = result["time"], result["actuator.voltage"]
    stroke = result["actuator.strain"] * PAPER_LOOP["cell_length [m]"]
    start = (cycles - 1) * period
    rising = (t >= start - 1e-12) & (t <= start + 0.5 * period + 1e-12)
    falling = (t >= start + 0.5 * period - 1e-12) & (t <= start + period + 1e-12)
    rows = []
    for label, volts, paper, branch in PAPER_STROKE_POINTS:
        if branch == "top":
            simulated = float(stroke[rising | falling].max())
        elif branch == "bottom":
            simulated = float(stroke[rising | falling].min())
        else:
            mask = rising if branch == "rising" else falling
            order = np.argsort(u[mask], kind="stable")
            simulated = float(np.interp(volts, u[mask][order], stroke[mask][order]))
        rows.append((label, volts, paper, simulated))
    return rows


def plot_stroke_vs_voltage(result, p: Parameters, path: Path) -> Path:
    """Stroke of a 29 mm cell over voltage (last cycle) with the paper's published values."""
    t = result["time"]
    last = t >= (p.cycles - 1) * p.period - 1e-12
    fig, (ax,) = new_figure(1, 1, width=7, height=5)
    ax.plot(result["actuator.voltage"][last], result["actuator.strain"][last] * PAPER_LOOP["cell_length [m]"] * 1e6,
            label=f"simulated, last cycle ({p.exponents} exponents)")
    rows = paper_comparison(result.every_step, p.period, p.cycles)
    ax.plot([r[1] for r in rows], [r[2] * 1e6 for r in rows], "ks", ms=7, mfc="none", mew=1.5,
            label="paper, Sect. 3 (published values)")
    # round, then add 0.0 so that a difference of -0.0004 µm prints as +0.000, not -0.000
    lines = [f"{label}: simulated {sim * 1e6:.3f} µm ({round((sim - paper) * 1e6, 3) + 0.0:+.3f} µm)"
             for label, _, paper, sim in rows]
    ax.text(0.02, 0.98, "\n".join(lines), transform=ax.transAxes, va="top", ha="left", fontsize=7.5,
            bbox={"facecolor": "white", "edgecolor": "0.7", "alpha": 0.9})
    ax.text(0.98, 0.02, NOT_COMPARABLE, transform=ax.transAxes, va="bottom", ha="right", fontsize=7.5,
            color="0.3")
    ax.set_xlabel(axis_label("voltage U", "V"))
    ax.set_ylabel(axis_label("stroke of a 29 mm cell x_a = Λ · 29 mm", "µm"))
    ax.set_title("Fig. 12 case: the drive's stroke against the paper's numbers")
    ax.legend(loc="center right", fontsize=8)
    return save_figure(fig, path)


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    """Time series, loop, stroke against the paper, shape plot and GIF.

    The shape plot (at the largest tip deflection, with the tip's path) and the GIF draw both
    layers, the cell joints and the motor of every cell at true scale (stated in the title;
    the layer offset e, a fraction of a millimetre, is enlarged as the legend says).
    """
    out_dir = Path(out_dir)
    prefix = f"{out_dir / output.case}_"
    files = [Path(prefix + "time_series.png"), Path(prefix + "tip_vs_voltage.png"), Path(prefix + "shapes.png")]
    plot_actuator_time_series(output.result, path=files[0])
    plot_tip_vs_voltage(output.result, path=files[1])
    mechanism, drawn = actuator_as_mechanism(build(p), output.result, name="actuator")
    if p.cell == "ritz":  # one continuous beam: its segments' mean rotations are drawn, not cells
        title = f"Fig. 12 actuator, {p.n_cells} assumed modes (ritz; drawn as {p.n_cells} segments)"
    else:
        title = f"Fig. 12 actuator, {p.n_cells} {p.cell} cells"
    row = int(np.argmax(np.abs(output.result["actuator.tip_y"])))
    plot_mechanism(mechanism, drawn, path=files[2], row=row, trace=("actuator.tip",),
                   title=f"{title}, largest tip deflection")
    files.append(plot_stroke_vs_voltage(output.result, p, Path(out_dir) / f"{output.case}_stroke_vs_paper.png"))
    if p.animation:
        files.append(animate_mechanism(mechanism, drawn, prefix + "animation.gif", trace=("actuator.tip",), title=title))
    return files


#: Cheap settings for the smoke test (one cycle of a rigid chain, no GIF): they change no check the defaults pass.
SMOKE = {"cycles": 1, "cell": 'rigid', "animation": False}

#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "bending_actuator_fig12",
        "quick": True,
        "parameters": {"period": 1.0, "cycles": 3, "cell": "six-bar", "n_cells": 3, "exponents": "exact", "step": 1e-4, "record_every": 1e-3},
        "channels": {
            "actuator.voltage": {"rms": 1e-9, "max": 1e-9},
            "actuator.strain": {"rms": 1e-15, "max": 1e-14},
            "actuator.stroke": {"rms": 1e-12, "max": 1e-11},
            "actuator.tip_y": {"rms": 1e-8, "max": 5e-8},
            "actuator.tip_x": {"rms": 1e-8, "max": 5e-8}
        },
        "scalars": [
            {"scalar": "stroke_max", "analytic": 40e-6, "abs": 1e-11, "source": "paper Sect. 3: 40 µm at 1500 V (the loop's x_max)"},
            {"scalar": "stroke_min", "analytic": -4e-6, "abs": 1e-11, "source": "paper Sect. 3: -4 µm at -500 V"},
            {"scalar": "tip_y_max_last_cycle", "rel": 1e-6},
            {"scalar": "tip_y_500V_rising", "rel": 1e-6},
            {"scalar": "tip_y_500V_falling", "rel": 1e-6},
            {"scalar": "last_cycle_change", "abs": 1e-8}
        ]
    },
]

CASE = Case("paper_bending_actuator", __doc__, PARAMETERS, run, plot, smoke=SMOKE, benchmarks=BENCHMARKS, table_order=4,
            summary="Fig. 12: the actuator driven through the Preisach loop (the paper's strokes; beam theory)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
