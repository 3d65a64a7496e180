"""Synthesis with compensation: a compliant four-bar designed for precision *positions*, its drive for the *times*.

The mechanism is the ``compliant_four_bar`` case's (its builder is reused): an A-TCM bender (CFC
0.2 mm under MFC 0.3 mm, 60 mm, rigid cells) as input crank, flexure hinges (Howell's
pseudo-rigid-body model), a triangular coupler carrying the coupler point P, driven through the
paper's Preisach loop.  ``synthesise_path`` designs it for precision points at given *voltages*
on the rising branch; on the falling branch hysteresis puts the coupler point elsewhere (about
1 mm at the same voltages).  Here the two tasks are split:

1. **Geometry for positions.**  The design variables of ``synthesise_path`` (the rocker pivot's
   height, the coupler point along and normal to B -> C) are fitted so that the coupler curve
   passes through the precision points (scipy's ``least_squares``, from the middle of the bounds):
   the residual of a point is the difference between its ``y`` and the curve's ``y`` at its ``x``
   (the curve from a static sweep over the drive's range; its ``x`` grows with the voltage).  The
   curve of a quasi-static drive does not depend on the branch (an elastic mechanism at rest
   depends on the free strain only), so positions can be met in both directions.
2. **The drive for the times.**  :func:`exudyn_atcm.mechanism_feedforward` computes the voltage
   program that makes the coupler point's ``x`` pass the precision points' ``x`` at the wanted
   times, up and down again (quasi-static map, hysteresis inverse, the first mode inverted); the
   curve gives ``y``.  The program's voltage range and its margin to the MFC's rating
   (-500 ... 1500 V) are reported.

**Check.**  A dynamic simulation of the synthesised mechanism with its program (hysteresis in every
step; the time step chosen for ``accuracy``, default 1e-4 of the coupler point's travel: the distances
are micrometres against a travel of millimetres; ``--set step=...`` fixes it instead): the distances of the coupler point to the precision points at the wanted times, on the rising
and on the falling branch (``rms_both``), against the same design driven through the voltages of the
points on the rising branch, both ways, quasi-statically (``uncompensated_rms_both``: hysteresis alone).

**Validation.**  The precision points are the rising-branch coupler points of a reference design
(``reference_*``, the ``compliant_four_bar`` defaults) at ``precision_voltages``; the fit must
recover its dimensions (``*_error``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import least_squares

from exudyn_atcm import Result, mechanism_feedforward, static_sweep
from exudyn_atcm.casework import (Case, CaseOutput, Parameter, Parameters, RunContext, case_dynamic_run, case_module,
                                  step_notes)
from exudyn_atcm.solve import ACCURACY_RANGE
from exudyn_atcm.plots import axis_label, new_figure, save_figure


#: The ``compliant_four_bar`` case file beside this one, as a module (its builder and helpers).
FOUR_BAR = case_module(Path(__file__).with_name("compliant_four_bar.py"))

#: The design variables and their bounds [m] (those of synthesise_path).
BOUNDS = {"rocker_pivot_height": (0.005, 0.045), "coupler_point_x": (0.0, 0.06), "coupler_point_y": (0.005, 0.045)}
DESIGN = tuple(BOUNDS)
RATING = (-500.0, 1500.0)  # V, the MFC P1's rated range
#: Default ``accuracy`` [-] of the check (relative to the recorded positions' travel, millimetres): the distances it
#: measures are micrometres.
DEFAULT_ACCURACY = 1e-4

PARAMETERS = [
    Parameter("n_cells", 3, "-", "rigid cells of the crank bender", minimum=1),
    Parameter("coupler_length", 0.05, "m", "distance B* - C* (fixed)", exclusive_minimum=0.0),
    Parameter("precision_voltages", (0.0, 250.0, 500.0, 750.0, 1000.0), "V",
              "voltages at which the reference design's rising branch gives the precision points"),
    Parameter("reference_rocker_pivot_height", 0.02, "m", "reference design generating the precision points"),
    Parameter("reference_coupler_point_x", 0.025, "m", "reference design generating the precision points"),
    Parameter("reference_coupler_point_y", 0.02, "m", "reference design generating the precision points"),
    Parameter("curve_points", 41, "-", "static points of the coupler curve in the fit", minimum=5),
    Parameter("rest", 0.1, "s", "rest before the motion", minimum=0.0),
    Parameter("interval", 0.2, "s", "time between two precision points", exclusive_minimum=0.0),
    Parameter("approach", 0.2, "s", "time from the start position to the first precision point",
              exclusive_minimum=0.0),
    Parameter("dwell", 0.1, "s", "hold at the last precision point before going back", minimum=0.0),
    Parameter("settle", 0.3, "s", "rest after the motion", minimum=0.0),
    Parameter("step", 0.0, "s", "time step of the check (0: chosen for accuracy)", minimum=0.0),
    Parameter("accuracy", DEFAULT_ACCURACY, "-", "largest error of the check's recorded positions relative to their "
              "travel, for which the step is chosen when step = 0", minimum=ACCURACY_RANGE[0],
              maximum=ACCURACY_RANGE[1]),
]


def design_parameters(p: Parameters, design: dict[str, float]) -> Parameters:
    p4 = FOUR_BAR.CASE.resolve({"n_cells": p.n_cells, "coupler_length": p.coupler_length, **design})
    FOUR_BAR.check_geometry(p4)
    return p4


def build(p: Parameters, design: dict[str, float], voltage=0.0):
    return FOUR_BAR.build_mechanism(design_parameters(p, design), FOUR_BAR.strain_laws("exact")["hysteresis"], voltage)


def coupler_points(p: Parameters, design: dict[str, float], voltages) -> np.ndarray:
    sweep = static_sweep(build(p, design), list(voltages))
    return np.stack([sweep["coupler.P_x"], sweep["coupler.P_y"]], axis=-1)


def curve_residuals(p: Parameters, design: dict[str, float], targets: np.ndarray) -> np.ndarray:
    """y of each precision point minus the coupler curve's y at its x [m] (the curve's x must grow)."""
    curve = coupler_points(p, design, np.linspace(RATING[0], RATING[1], p.curve_points))
    x, y = curve[:, 0], curve[:, 1]
    if not np.all(np.diff(x) > 0.0):
        return np.full(len(targets), 1.0)  # not a design whose x grows with the drive: far from any solution
    inside = np.clip(targets[:, 0], x[0], x[-1])
    return (targets[:, 1] - PchipInterpolator(x, y)(inside)) + (targets[:, 0] - inside)


def schedule(p: Parameters, targets: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Corner times [s] and wanted x [m] of the path, and the times of the precision points (up, then down)."""
    n = len(targets)
    start = targets[0, 0] - 0.5 * abs(targets[1, 0] - targets[0, 0])  # below the first point, as far as half a step
    up = p.rest + p.approach + p.interval * np.arange(n)
    top = up[-1] + p.dwell
    down = top + p.interval * np.arange(1, n)
    times = np.concatenate([[0.0, p.rest], up, down, [down[-1] + p.approach, down[-1] + p.approach + p.settle]])
    xs = np.concatenate([[start, start], targets[:, 0], targets[-2::-1, 0], [start, start]])
    if p.dwell > 0.0:
        times = np.insert(times, 2 + n, top)
        xs = np.insert(xs, 2 + n, targets[-1, 0])
    visits = np.concatenate([up[:-1], [up[-1] + 0.5 * p.dwell], down])
    return times, xs, visits


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    reference = {name: float(p[f"reference_{name}"]) for name in DESIGN}
    targets = coupler_points(p, reference, sorted(p.precision_voltages))
    lo = np.array([BOUNDS[n][0] for n in DESIGN])
    hi = np.array([BOUNDS[n][1] for n in DESIGN])

    def residuals(z: np.ndarray) -> np.ndarray:
        return curve_residuals(p, dict(zip(DESIGN, lo + z * (hi - lo))), targets)

    fit = least_squares(residuals, np.full(len(DESIGN), 0.5), bounds=(0.0, 1.0), diff_step=1e-4, xtol=1e-10,
                        ftol=1e-12, gtol=1e-12, max_nfev=200)
    ctx.progress(1, 3)
    design = dict(zip(DESIGN, (lo + fit.x * (hi - lo)).tolist()))
    times, xs, visits = schedule(p, targets)
    program, report = mechanism_feedforward(build(p, design), "coupler.P_x", times, xs)
    ctx.progress(2, 3)
    result = case_dynamic_run(build(p, design, program), float(times[-1]), step=p.step, accuracy=p.accuracy,
                              default_accuracy=DEFAULT_ACCURACY)
    ctx.progress(3, 3)
    every = result.every_step
    wanted = np.concatenate([targets, targets[-2::-1]])
    reached = np.stack([np.interp(visits, every["time"], every["coupler.P_x"]),
                        np.interp(visits, every["time"], every["coupler.P_y"])], axis=-1)
    distance = np.linalg.norm(reached - wanted, axis=1)
    # the same design driven through the points' voltages up and down, quasi-statically: hysteresis alone
    v = np.asarray(sorted(p.precision_voltages), dtype=float)
    static = coupler_points(p, design, np.concatenate([[RATING[0]], v, [RATING[1]], v[::-1]]))
    n = len(v)
    uncompensated = np.concatenate([np.linalg.norm(static[1:n + 1] - targets, axis=1),
                                    np.linalg.norm(static[n + 2:] - targets[::-1], axis=1)])
    low, high = float(program.values.min()), float(program.values.max())
    scalars = {
        "rms_both": (float(np.sqrt(np.mean(distance**2))), "m"),
        "max_both": (float(distance.max()), "m"),
        "rms_rising": (float(np.sqrt(np.mean(distance[:n] ** 2))), "m"),
        "rms_falling": (float(np.sqrt(np.mean(distance[n:] ** 2))), "m"),
        "uncompensated_rms_both": (float(np.sqrt(np.mean(uncompensated**2))), "m"),
        "curve_fit_rms": (float(np.sqrt(np.mean(fit.fun**2))), "m"),
        "program_lowest_voltage": (low, "V"),
        "program_highest_voltage": (high, "V"),
        "rating_margin": (min(low - RATING[0], RATING[1] - high), "V"),
        "first_frequency": (report.frequencies[1], "Hz"),
        "fit_evaluations": (float(fit.nfev), "-"),
    }
    for name in DESIGN:
        scalars[f"{name}_optimum"] = (design[name], "m")
        scalars[f"{name}_error"] = (design[name] - reference[name], "m")
    series = Result({"time": every["time"], "coupler.P_x": every["coupler.P_x"], "coupler.P_y": every["coupler.P_y"],
                     "voltage": every["crank.voltage"], "wanted_x": np.interp(every["time"], times, xs)},
                    {"time": "s", "coupler.P_x": "m", "coupler.P_y": "m", "voltage": "V", "wanted_x": "m"})
    points = Result({"time": visits, "target_x": wanted[:, 0], "target_y": wanted[:, 1], "reached_x": reached[:, 0],
                     "reached_y": reached[:, 1], "distance": distance},
                    {"time": "s", "target_x": "m", "target_y": "m", "reached_x": "m", "reached_y": "m",
                     "distance": "m"})
    notes = {"feedforward": report.summary(), "design": design, "least_squares": {"status": int(fit.status),
                                                                                  "message": str(fit.message)},
             **step_notes(result)}
    return CaseOutput(series, scalars, tables={"points": points}, notes=notes)


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    pts = output.tables["points"]
    fig, axes = new_figure(1, 2, width=11.0, height=4.5)
    axes[0].plot(1e3 * r["coupler.P_x"], 1e3 * r["coupler.P_y"], linewidth=1.0, label="coupler point (simulated)")
    axes[0].plot(1e3 * pts["target_x"], 1e3 * pts["target_y"], "k+", markersize=10, label="precision points")
    axes[0].set_xlabel(axis_label("x", "mm"))
    axes[0].set_ylabel(axis_label("y", "mm"))
    axes[0].legend(fontsize=8)
    axes[1].plot(pts["time"], 1e6 * pts["distance"], "o-")
    axes[1].set_xlabel(axis_label("time t", "s"))
    axes[1].set_ylabel(axis_label("distance to the precision point", "µm"))
    axes[1].set_title("rising, then falling branch")
    return [save_figure(fig, out_dir / f"{output.case}.png")]


#: Cheap settings for the smoke test: the defaults are cheap enough (a fit of ~40 static sweeps and one run).
SMOKE: dict = {}

CASE = Case("synthesise_compensated", __doc__, PARAMETERS, run, plot, smoke=SMOKE, table_order=15,
            summary="four-bar dimensions for precision positions, met on both branches by a compensated drive "
                    "(a known design recovered; a dynamic check)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
