"""Path synthesis of the compliant four-bar: rocker pivot and coupler point through precision points, with hysteresis.

The mechanism is the one of the ``compliant_four_bar`` case (its builder is reused): an A-TCM
bender (CFC 0.2 mm under MFC 0.3 mm, 60 mm) as input crank, flexure hinges (Howell's
pseudo-rigid-body model) at the crank tip, the coupler - rocker joint and the rocker's ground
pivot D*, a triangular coupler carrying the coupler point P.  The crank's MFC is driven through
one voltage cycle -500 V -> 1500 V -> -500 V through the paper's Preisach loop, solved
quasi-statically (each step continues from the previous state and hysteresis memory).

**Design variables** (three, in metres): the height of the rocker's ground pivot D* (which
sets the rocker's length) and the coupler point's position on the coupler, along and normal
to B -> C (``rocker_pivot_height``, ``coupler_point_x``, ``coupler_point_y``; bounds in
``BOUNDS``).  The coupler length stays fixed: over the coupler's small rotation it hardly
changes the path (measured at the reference design: 1 mm of coupler length moves the five
precision points by 0.8 µm RMS, 1 mm of pivot height by 14 µm), so it cannot be identified
from precision points.

**Precision points** are prescribed coupler point positions at given voltages on the rising
branch of the cycle (function generation with prescribed timing: *where* P is at *which*
voltage).  Hysteresis matters here: quasi-statically the rising and falling branch trace the
same coupler curve, but at a given voltage the coupler point sits at different places on it
(2.7 mm apart at 500 V on the reference design).  The objective ``rms_rising`` is the RMS
distance between the rising-branch coupler points at the precision voltages and the
precision points; ``rms_both`` uses the falling branch at the same voltages as well.

``mode = "synthesise"`` (default) runs :func:`exudyn_atcm.study.optimize` with this case
in ``mode = "evaluate"`` as the inner run (differential evolution with the population run in
parallel by the study engine, polished by Nelder-Mead; or Nelder-Mead alone from the middle
of the bounds) three times:

* ``hysteresis``: the design for the Preisach drive (objective ``rms_rising``);
* ``linear``: the design a designer would make with a linear voltage-to-strain law through
  the same end points (objective ``rms_rising`` with the linear drive), then evaluated with
  the hysteretic drive: the path error that ignoring hysteresis causes;
* ``both``: a compromise for both branches (objective ``rms_both``, Nelder-Mead from the
  hysteresis design), to show the error floor that hysteresis sets when the points must be
  met in both directions.

**Validation.**  Unless ``precision_points`` are given, they are the simulated rising-branch
coupler points of a reference design at known dimensions (``reference_*``, the
``compliant_four_bar`` defaults) and the same crank discretisation: the optimum must recover
those dimensions (key scalars ``*_error``) and reach the points (``distance_rms``).  The
synthesised mechanism is also checked against the rigid four-bar through its characteristic
pivots (:mod:`exudyn_atcm.theory.four_bar`, circle intersection for the simulated crank-tip pivot
B*; ``rigid_four_bar_error``, relative to the coupler point's travel).

Outputs: the precision points and the three designs' coupler points at the precision
voltages (CSV), the optimisation histories, the synthesised mechanism's path over a finer
voltage cycle; plots of the precision points with the designs' rising and falling points,
of each design's distance to the points over the voltage, and of the optimisation history;
a GIF of the synthesised mechanism over the cycle.  With an output directory the runs are
stored in ``runs/compliant_four_bar_<hash>/`` (a store per version of the imported builder:
the store's keys hash this file only), so a repeated synthesis replays them.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

import numpy as np

from exudyn_atcm import Result, static_sweep
from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, RunContext, case_module
from exudyn_atcm.plots import animate_mechanism, axis_label, new_figure, save_figure


#: The ``compliant_four_bar`` case file beside this one, as a module (its builder and helpers).
FOUR_BAR = case_module(Path(__file__).with_name("compliant_four_bar.py"))

#: The design variables and their bounds [m] (the middle of the bounds differs from the reference design).
BOUNDS = {
    "rocker_pivot_height": (0.005, 0.045),
    "coupler_point_x": (0.0, 0.06),
    "coupler_point_y": (0.005, 0.045),
}
DESIGN = tuple(BOUNDS)
U_LOW, U_HIGH = -500.0, 1500.0  # the voltage cycle [V]

PARAMETERS = [
    Parameter("mode", "synthesise", "-", "synthesise a design, or evaluate one design", choices=("synthesise", "evaluate")),
    Parameter("drive", "hysteresis", "-", "evaluate: the crank's voltage-to-strain law", choices=("hysteresis", "linear")),
    Parameter("rocker_pivot_height", 0.02, "m", "evaluate: height of the rocker's ground pivot D* (design variable)"),
    Parameter("coupler_point_x", 0.025, "m", "evaluate: coupler point from B along B -> C (design variable)"),
    Parameter("coupler_point_y", 0.02, "m", "evaluate: coupler point from B normal to B -> C (design variable)"),
    Parameter("coupler_length", 0.05, "m", "distance B* - C* (fixed)", exclusive_minimum=0.0),
    Parameter("n_cells", 3, "-", "rigid cells of the crank bender", minimum=1),
    Parameter("n_steps", 4, "-", "static steps per voltage cycle (the precision voltages are added)"),
    Parameter("exponents", "exact", "-", "continuous Preisach exponents", choices=("exact", "rounded")),
    Parameter("precision_voltages", (-500.0, 0.0, 500.0, 1000.0, 1500.0), "V",
              "voltages of the precision points on the rising branch, within -500 ... 1500 V"),
    Parameter("precision_points", (), "m",
              "x1,y1,x2,y2,...: the coupler point at the precision voltages; empty (default, or --set precision_points=): "
              "the reference design's rising branch"),
    Parameter("reference_rocker_pivot_height", 0.02, "m", "reference design generating the precision points"),
    Parameter("reference_coupler_point_x", 0.025, "m", "reference design generating the precision points"),
    Parameter("reference_coupler_point_y", 0.02, "m", "reference design generating the precision points"),
    Parameter("reference_cells", 0, "-", "crank cells of the reference design's simulation; 0: n_cells"),
    Parameter("method", "differential_evolution", "-", "synthesise: optimiser (Nelder-Mead starts at the middle of the bounds)",
              choices=("differential_evolution", "nelder-mead")),
    Parameter("maxiter", 15, "-", "synthesise: generations of differential evolution (Nelder-Mead: at most 60 x as many iterations)", minimum=1),
    Parameter("popsize", 6, "-", "synthesise: population size per design variable", minimum=1),
    Parameter("xatol", 1e-5, "-", "synthesise: Nelder-Mead tolerance, fraction of each range", exclusive_minimum=0.0, exclusive_maximum=1.0),
    Parameter("fatol", 1e-6, "-", "synthesise: Nelder-Mead tolerance on the RMS distance, fraction of its value on the initial simplex", minimum=0.0, exclusive_maximum=1.0),
    Parameter("workers", 2, "-", "synthesise: worker processes evaluating the population", minimum=1),
    Parameter("compare", True, "-", "synthesise: also the linear-drive design and the both-branch design"),
    Parameter("path_steps", 40, "-", "synthesise: static steps per cycle of the plotted paths and the GIF", minimum=2),
    Parameter("animation", True, "-", "synthesise: write a GIF of the synthesised mechanism"),
]


# ----------------------------------------------------------------------------- one design
def cycle(n_steps: int, precision_voltages) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The voltage cycle through the precision voltages, and their rows on the rising and falling branch.

    ``n_steps`` equal steps over -500 -> 1500 -> -500 V with the precision voltages added
    on both branches.
    """
    if isinstance(n_steps, bool) or n_steps < 2 or n_steps % 2:
        raise ValueError(f"n_steps must be an even integer >= 2, got {n_steps!r}")
    v = np.asarray(precision_voltages, dtype=float)
    if v.size < 2 or not np.all(np.isfinite(v)) or np.any(v < U_LOW) or np.any(v > U_HIGH) or np.unique(v).size != v.size:
        raise ValueError(f"precision_voltages must be at least 2 distinct voltages within [{U_LOW:g}, {U_HIGH:g}] V, "
                         f"got {tuple(precision_voltages)!r}")
    rising = np.union1d(np.linspace(U_LOW, U_HIGH, n_steps // 2 + 1), v)
    voltages = np.concatenate([rising, rising[-2::-1]])
    up = np.searchsorted(rising, v)
    down = voltages.size - 1 - up
    return voltages, up, down


def four_bar_parameters(p: Parameters, design: dict[str, float], n_cells: int | None = None) -> Parameters:
    """The ``compliant_four_bar`` parameters of a design (the rest: that case's defaults)."""
    values = {"n_cells": n_cells or p.n_cells, "coupler_length": p.coupler_length, "exponents": p.exponents, **design}
    p4 = FOUR_BAR.CASE.resolve(values)
    FOUR_BAR.check_geometry(p4)
    return p4


def solve_design(p: Parameters, design: dict[str, float], drive: str, voltages: np.ndarray, n_cells: int | None = None):
    """The mechanism of a design and its quasi-static sweep over ``voltages``; coupler points [m]."""
    p4 = four_bar_parameters(p, design, n_cells)
    mech = FOUR_BAR.build_mechanism(p4, FOUR_BAR.strain_laws(p.exponents)[drive])
    sweep = static_sweep(mech, voltages)
    points = np.stack([sweep["coupler.P_x"], sweep["coupler.P_y"]], axis=-1)
    return mech, sweep, points


def distances(points: np.ndarray, targets: np.ndarray, up: np.ndarray, down: np.ndarray) -> dict[str, tuple[float, str]]:
    """Distances of the rising- and falling-branch coupler points to the precision points [m]."""
    d_up = np.linalg.norm(points[up] - targets, axis=1)
    d_down = np.linalg.norm(points[down] - targets, axis=1)
    both = np.concatenate([d_up, d_down])
    return {
        "rms_rising": (float(np.sqrt(np.mean(d_up**2))), "m"),
        "rms_falling": (float(np.sqrt(np.mean(d_down**2))), "m"),
        "rms_both": (float(np.sqrt(np.mean(both**2))), "m"),
        "max_rising": (float(d_up.max()), "m"),
        "max_both": (float(both.max()), "m"),
        "loop_width_max": (float(np.max(np.linalg.norm(points[up] - points[down], axis=1))), "m"),
    }


def precision_points(p: Parameters) -> np.ndarray:
    """The precision points [m], shape (n, 2): given, or the reference design's rising branch."""
    voltages, up, _ = cycle(p.n_steps, p.precision_voltages)
    n = len(p.precision_voltages)
    if p.precision_points:
        given = np.asarray(p.precision_points, dtype=float)
        if given.size != 2 * n or not np.all(np.isfinite(given)):
            raise ValueError(f"precision_points must be {2 * n} finite coordinates x1,y1,...,x{n},y{n} [m] "
                             f"(one point per precision voltage), got {len(p.precision_points)} values")
        return given.reshape(n, 2)
    if p.reference_cells < 0:
        raise ValueError(f"reference_cells must be >= 0 (0: n_cells), got {p.reference_cells!r}")
    _, _, points = solve_design(p, reference_design(p), "hysteresis", voltages, n_cells=p.reference_cells or p.n_cells)
    return points[up]


def reference_design(p: Parameters) -> dict[str, float]:
    return {name: float(p[f"reference_{name}"]) for name in DESIGN}


def evaluate(p: Parameters) -> CaseOutput:
    """One design: coupler points at the precision voltages, distances to the precision points."""
    voltages, up, down = cycle(p.n_steps, p.precision_voltages)
    targets = precision_points(p)
    design = {name: float(p[name]) for name in DESIGN}
    _, _, points = solve_design(p, design, p.drive, voltages)
    scalars = distances(points, targets, up, down)
    series = {"voltage": np.asarray(p.precision_voltages, dtype=float), "target_x": targets[:, 0], "target_y": targets[:, 1],
              "rising_x": points[up, 0], "rising_y": points[up, 1], "falling_x": points[down, 0], "falling_y": points[down, 1]}
    units = {name: "V" if name == "voltage" else "m" for name in series}
    return CaseOutput(Result(series, units), scalars, steps=len(voltages))


# ----------------------------------------------------------------------------- synthesis
def _fixed(p: Parameters, targets: np.ndarray, **changes) -> dict:
    names = ("coupler_length", "n_cells", "n_steps", "exponents", "precision_voltages")
    return {"mode": "evaluate", **{n: p[n] for n in names}, "precision_points": tuple(float(v) for v in targets.ravel()),
            **changes}


def synthesise(p: Parameters, ctx: RunContext) -> CaseOutput:
    from exudyn_atcm.study import OptimizeOptions, RunOptions, column, optimize

    voltages, up, down = cycle(p.n_steps, p.precision_voltages)
    targets = precision_points(p)
    # the run store's keys hash this file only: keep the runs of each version of the imported builder apart
    builder = hashlib.sha256(Path(FOUR_BAR.__file__).read_bytes()).hexdigest()[:12]
    store = ctx.out_dir / "runs" / f"compliant_four_bar_{builder}" if ctx.out_dir is not None else None
    search = OptimizeOptions(maxiter=p.maxiter, popsize=p.popsize, xatol=p.xatol, fatol=p.fatol, rerun_best=False)
    options = dict(method=p.method, options=search, run=RunOptions(workers=p.workers, store=store))
    best = {"hysteresis": optimize(CASE, "rms_rising", BOUNDS, fixed=_fixed(p, targets), **options)}
    ctx.progress(1, 3 if p.compare else 1)
    if p.compare:
        best["linear"] = optimize(CASE, "rms_rising", BOUNDS, fixed=_fixed(p, targets, drive="linear"), **options)
        ctx.progress(2, 3)
        best["both"] = optimize(CASE, "rms_both", BOUNDS, fixed=_fixed(p, targets), **{
            **options, "method": "nelder-mead", "run": RunOptions(workers=1, store=store)}, x0=best["hysteresis"].design)
        ctx.progress(3, 3)

    # every design evaluated with the hysteretic drive (in this process)
    evaluated = {}
    for label, opt in best.items():
        _, _, points = solve_design(p, opt.design, "hysteresis", voltages)
        evaluated[label] = (points, distances(points, targets, up, down))
    hyst = best["hysteresis"]
    d_hyst = evaluated["hysteresis"][1]
    scalars: dict[str, tuple[float, str]] = {
        "distance_rms": (hyst.objective, "m"),
        "distance_max": d_hyst["max_rising"],
        "distance_rms_both_branches": d_hyst["rms_both"],
        "loop_width_max": d_hyst["loop_width_max"],
    }
    for name in DESIGN:
        scalars[f"{name}_optimum"] = (hyst.design[name], "m")
    if not p.precision_points:
        for name, value in reference_design(p).items():
            scalars[f"{name}_error"] = (hyst.design[name] - value, "m")
        scalars["design_error_max"] = (max(abs(scalars[f"{n}_error"][0]) for n in DESIGN), "m")
    scalars["evaluations"] = (float(hyst.evaluations), "-")
    scalars["runs_executed"] = (float(hyst.executed), "-")
    if p.compare:
        lin, both = best["linear"], best["both"]
        d_lin, d_both = evaluated["linear"][1], evaluated["both"][1]
        scalars.update({
            "linear_design_distance_rms_linear_drive": (lin.objective, "m"),
            "linear_design_distance_rms": d_lin["rms_rising"],
            "linear_design_distance_max": d_lin["max_rising"],
            "linear_design_distance_rms_both_branches": d_lin["rms_both"],
            "hysteresis_path_error": (d_lin["rms_rising"][0] - d_hyst["rms_rising"][0], "m"),
            "both_design_distance_rms_both_branches": d_both["rms_both"],
            "both_design_distance_rms": d_both["rms_rising"],
            "evaluations_linear": (float(lin.evaluations), "-"),
            "evaluations_both": (float(both.evaluations), "-"),
            "runs_executed_linear": (float(lin.executed), "-"),
            "runs_executed_both": (float(both.executed), "-"),
        })
        for name in DESIGN:
            scalars[f"linear_{name}_optimum"] = (lin.design[name], "m")
            scalars[f"both_{name}_optimum"] = (both.design[name], "m")

    # the synthesised mechanism over a finer cycle, checked against the rigid four-bar
    fine, _, _ = cycle(p.path_steps, p.precision_voltages)
    mech, sweep, path = solve_design(p, hyst.design, "hysteresis", fine)
    four_bar = FOUR_BAR.reference_four_bar(mech)
    rigid = four_bar.coupler_point_from_crank_tip(FOUR_BAR.pivot(sweep, mech, "hinge_B"))
    travel = float(np.max(np.linalg.norm(path - path[0], axis=1)))
    scalars["rigid_four_bar_error"] = (float(np.max(np.linalg.norm(path - rigid, axis=1))) / travel, "-")
    scalars["coupler_travel"] = (travel, "m")

    series = {"voltage": np.asarray(p.precision_voltages, dtype=float), "target_x": targets[:, 0], "target_y": targets[:, 1]}
    for label, (points, _) in evaluated.items():
        for branch, rows in (("rising", up), ("falling", down)):
            series[f"{label}.{branch}_x"], series[f"{label}.{branch}_y"] = points[rows, 0], points[rows, 1]
    units = {name: "V" if name == "voltage" else "m" for name in series}
    result = Result(series, units, parameters={"design variables": list(DESIGN),
                                               "bounds [m]": {k: list(v) for k, v in BOUNDS.items()}})
    tables = {"path": sweep}
    for label, opt in best.items():
        objective = "rms_both" if label == "both" else "rms_rising"
        history = {"evaluation": np.arange(len(column(opt.history, objective)), dtype=float)}
        history.update({name: np.asarray(column(opt.history, name), dtype=float) for name in DESIGN})
        history[objective] = np.asarray(column(opt.history, objective), dtype=float)
        tables[f"history_{label}"] = Result(history, {"evaluation": "-", **{n: "m" for n in DESIGN}, objective: "m"})
    notes = {"optimiser": hyst.message, "evaluation rate": hyst.describe_rate(),
             "precision points": "given" if p.precision_points else
             "simulated rising-branch coupler points of the reference design",
             "rigid four-bar": "through the PRBM pivots B*, C*, D* for the simulated crank-tip pivot B*; "
                               "error relative to the coupler point's travel"}
    return CaseOutput(result, scalars, steps=int(sum(opt.evaluations for opt in best.values())), tables=tables, notes=notes)


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    for name in DESIGN:
        for value, what in ((p[name], name), (p[f"reference_{name}"], f"reference_{name}")):
            if not math.isfinite(value):
                raise ValueError(f"{what} must be finite [m], got {value!r}")
    if p.mode == "evaluate":
        return evaluate(p)
    return synthesise(p, ctx)


# ----------------------------------------------------------------------------- plots
_STYLES = {"hysteresis": ("C0", "designed with hysteresis"), "linear": ("C3", "designed with a linear drive"),
           "both": ("C2", "designed for both branches")}


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    if p.mode != "synthesise":
        return []
    r = output.result
    files = []
    fig, (ax,) = new_figure(1, 1, width=7.0, height=5.0)
    path = output.tables["path"]
    ax.plot(path["coupler.P_x"] * 1e3, path["coupler.P_y"] * 1e3, "-", color="0.75", lw=1.0,
            label="coupler curve of the synthesised design")
    for label, (color, text) in _STYLES.items():
        if f"{label}.rising_x" not in r.names:
            continue
        ax.plot(r[f"{label}.rising_x"] * 1e3, r[f"{label}.rising_y"] * 1e3, "^-", color=color, ms=5, lw=0.8,
                label=f"{text}: rising")
        ax.plot(r[f"{label}.falling_x"] * 1e3, r[f"{label}.falling_y"] * 1e3, "v--", color=color, ms=5, lw=0.8,
                mfc="none", label=f"{text}: falling")
    ax.plot(r["target_x"] * 1e3, r["target_y"] * 1e3, "o", ms=10, mfc="none", mec="k", mew=1.5, label="precision points")
    for v, x, y in zip(r["voltage"], r["target_x"], r["target_y"]):
        ax.annotate(f"{v:g} V", (x * 1e3, y * 1e3), textcoords="offset points", xytext=(4, 8), fontsize=7)
    ax.set_xlabel(axis_label("x", "mm"))
    ax.set_ylabel(axis_label("y", "mm"))
    s = output.scalars
    title = f"coupler point at the precision voltages (all with the Preisach drive)\nRMS distance {s['distance_rms']:.2g} m"
    if "linear_design_distance_rms" in s:
        title += f"; designed with a linear drive: {s['linear_design_distance_rms'] * 1e3:.3g} mm"
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)
    files.append(save_figure(fig, out_dir / f"{output.case}_paths.png"))

    fig, (ax,) = new_figure(1, 1, width=6.4, height=4.0)
    for label, (color, text) in _STYLES.items():
        if f"{label}.rising_x" not in r.names:
            continue
        for branch, style in (("rising", "^-"), ("falling", "v--")):
            d = np.hypot(r[f"{label}.{branch}_x"] - r["target_x"], r[f"{label}.{branch}_y"] - r["target_y"])
            ax.plot(r["voltage"], d * 1e3, style, color=color, ms=5, mfc=color if branch == "rising" else "none",
                    label=f"{text}: {branch}")
    ax.set_xlabel(axis_label("precision voltage U", "V"))
    ax.set_ylabel(axis_label("distance to the precision point", "mm"))
    ax.set_title("all designs evaluated with the Preisach drive", fontsize=9)
    ax.legend(fontsize=7)
    files.append(save_figure(fig, out_dir / f"{output.case}_distances.png"))

    fig, (ax,) = new_figure(1, 1, width=6.4, height=4.2)
    for label, (color, text) in _STYLES.items():
        table = output.tables.get(f"history_{label}")
        if table is None:
            continue
        objective = "rms_both" if label == "both" else "rms_rising"
        # each design once, in the order first evaluated (Nelder-Mead revisits stored designs)
        designs = np.stack([table[name] for name in DESIGN], axis=1)
        first = np.sort(np.unique(designs, axis=0, return_index=True)[1])
        values = np.asarray(table[objective])[first]
        count = np.arange(1, first.size + 1)
        ax.semilogy(count, np.where(np.isfinite(values), values, np.nan), ".", color=color, ms=2, alpha=0.5)
        ax.semilogy(count, np.fmin.accumulate(np.nan_to_num(values, nan=np.inf)), "-", color=color,
                    label=f"{text} ({objective}, best so far)")
    ax.set_xlabel(axis_label("designs evaluated", "-"))
    ax.set_ylabel(axis_label("RMS distance to the precision points", "m"))
    ax.legend(fontsize=7)
    files.append(save_figure(fig, out_dir / f"{output.case}_history.png"))
    if p.animation:
        design = {name: s[f"{name}_optimum"] for name in DESIGN}
        mech = FOUR_BAR.build_mechanism(four_bar_parameters(p, design), FOUR_BAR.strain_laws(p.exponents)["hysteresis"])
        files.append(animate_mechanism(mech, path, out_dir / f"{output.case}_animation.gif",
                                       frames=min(path.n_rows, 41), trace=["coupler.P"],
                                       title="synthesised four-bar, -500 -> 1500 -> -500 V"))
    return files


#: Cheap settings for the smoke test (the known design evaluated, not searched): they change no check the defaults pass.
SMOKE = {"mode": 'evaluate'}

CASE = Case("synthesise_path", __doc__, PARAMETERS, run, plot, smoke=SMOKE, table_order=13,
            summary="four-bar dimensions through precision points, with hysteresis (a known design recovered)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
