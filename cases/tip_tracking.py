"""The bending actuator follows a wanted tip trajectory: hysteresis compensation and closed loop.

The paper's actuator (three 29 mm cells, CFC on MFC) is driven through a hysteresis operator
that plays the real MFC: the known non-uniform Preisach model behind the shipped record
(``exudyn_atcm.model.reference_record.reference_preisach``, as free strain of a 29 mm cell).  The
compensation does not know it: it uses the Preisach model *identified* from the noisy record
``cases/data/preisach_record.csv`` (:meth:`EverettPreisach.fit`, ``n_levels`` grid, its default
``prior="pi"``: the minor loops inside the major swing follow the measured edges of the
Preisach triangle the way a play operator's would), as a designer would.  The wanted tip deflection is a slow two-tone wave (a major swing with minor
loops inside), turned into a wanted free strain by the constant-curvature arc of a beam bent
by a pure moment, ``tip_y = (1 - cos(κL))/κ`` (Timoshenko 1925), ``κ`` the free curvature.

Four ways to drive it, each one simulation with the hysteresis evaluated inside every solver
step:

(a) linear inversion: the voltage of the best linear voltage-to-stroke model of the record;
(b) inverse-Preisach feedforward: the inverse (bisection on its memory) of the identified
    model (continuous output, so the voltage program has no staircase);
(c) PID on the simulated tip deflection (own sample rate, zero-order hold), no model;
(d) PID plus the feedforward of (b).

Key scalars: the RMS (and largest) tracking error of each after ``settle`` seconds, and the
ratio of (a)'s RMS error to (d)'s.

The time step is fixed (``step``, 2e-4 s), not chosen with :func:`exudyn_atcm.simulate`'s
``accuracy``: the four runs are compared instant by instant on one grid, and a controller's
voltage is not known before its run, so ``accuracy`` would fall back to 20 steps per period of
the first mode for (c) and (d) (1.5e-3 s at 34 Hz, coarser than the PID's 1 ms sampling)
while choosing 5e-4 s for (a) and (b).

A saved model instead of the identification: ``--set model=path.json`` (a file written by
``model.save``, e.g. ``identify_and_predict``'s ``<case>_model.json``) is the designer's model
of (a), (b) and (d), of any rate-independent family; like the record it must give the stroke
[m] of the 29 mm cell against the voltage (``output_unit`` ``"m"``), so the feedforward asks it
for the wanted stroke, ``CELL_LENGTH`` times the wanted free strain.  Its linear model and fit
error are measured on the record from its first sample at the lowest input (where every
Preisach model's memory is known).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_atcm import BendingActuator, Layer, PIDController, PiezoDrive, Result, read_record, simulate
from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, PlannedRun, RunContext
from exudyn_atcm.hysteresis import EverettPreisach, FitReport, HysteresisOperator, load_model, make_report
from exudyn_atcm.model import feedforward_program, linear_program, reference_preisach
from exudyn_atcm.plots import axis_label, new_figure, save_figure

RECORD = Path(__file__).resolve().parent / "data" / "preisach_record.csv"
CELL_LENGTH = 29e-3  # m, the cell of the record's stroke
VOLTAGE_LIMITS = (-500.0, 1500.0)  # V, the MFC's range in the paper

PARAMETERS = [
    Parameter("duration", 4.0, "s", "simulated time", exclusive_minimum=0.0),
    Parameter("tip_mean", 7e-3, "m", "mean wanted tip deflection"),
    Parameter("tip_amplitudes", (4.5e-3, 2e-3), "m", "amplitudes of the two tones"),
    Parameter("frequencies", (0.25, 0.75), "Hz", "frequencies of the two tones", exclusive_minimum=0.0),
    Parameter("settle", 0.5, "s", "start-up left out of the error figures", minimum=0.0),
    Parameter("kp", 2e4, "V/m", "proportional gain"),
    Parameter("ki", 1e7, "V/(m s)", "integral gain"),
    Parameter("kd", 800.0, "V s/m", "derivative gain"),
    Parameter("sample_time", 1e-3, "s", "controller sample time", exclusive_minimum=0.0),
    Parameter("n_levels", 40, "-", "grid levels of the identified Preisach model", minimum=1),
    Parameter("model", "", "-", "saved model (JSON, model.save) of the cell's stroke [m] against voltage used "
              "instead of identifying one from the record (empty: identify it)"),
    Parameter("cell", "rigid", "-", "cell model", choices=("rigid", "six-bar")),
    Parameter("step", 2e-4, "s", "time step, fixed (not chosen for an accuracy): the four runs are compared on one "
              "time grid, and the PID samples at accepted steps, so the step must divide sample_time",
              exclusive_minimum=0.0),
]

METHODS = ("linear", "feedforward", "pid", "pid_feedforward")
LABELS = {
    "linear": "(a) linear inversion",
    "feedforward": "(b) inverse-Preisach feedforward",
    "pid": "(c) PID",
    "pid_feedforward": "(d) PID + feedforward",
}


def build(p: Parameters, voltage) -> BendingActuator:
    """The paper's actuator with the 'true' hysteresis (reference model, as strain)."""
    drive = PiezoDrive(voltage, hysteresis=reference_preisach(scale=1.0 / CELL_LENGTH))
    return BendingActuator(
        n_cells=3, cell_length=CELL_LENGTH, width=28e-3,
        passive=Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0),
        active=Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0),
        drive=drive, cell=p.cell, damping=0.02,
    )


def strain_for_tip(actuator: BendingActuator, tip: np.ndarray) -> np.ndarray:
    """Free strain giving tip deflection ``tip`` [m] on a constant-curvature arc (pure bending)."""
    length = actuator.length
    kappa = np.linspace(-0.5 * math.pi / length, 0.9 * math.pi / length, 4001)
    with np.errstate(invalid="ignore", divide="ignore"):
        y = np.where(kappa == 0.0, 0.0, (1.0 - np.cos(kappa * length)) / kappa)
    if tip.min() < y.min() or tip.max() > y.max():
        raise ValueError(f"wanted tip deflections {tip.min():.4g} ... {tip.max():.4g} m lie outside the arc table")
    return np.interp(tip, y, kappa) / actuator.curvature_per_strain


def saved_model(path: Path, record: Any) -> tuple[HysteresisOperator, FitReport]:
    """The designer's stroke model read from ``path`` (see the module), and its report on ``record`` (a
    :class:`~exudyn_atcm.io.record.Record`).

    Raises
    ------
    ValueError
        If the file holds no rate-independent operator, or one whose output is not in metres.
    """
    model = load_model(path)
    if not isinstance(model, HysteresisOperator) or getattr(model, "time_dependent", False):
        raise ValueError(f"model: {str(path)!r} holds a {type(model).__name__}; tip_tracking's feedforward inverts a "
                         "rate-independent hysteresis operator of the voltage [V] (save the operator itself)")
    unit = getattr(model, "output_unit", "")
    if unit != "m":
        raise ValueError(f"model: {str(path)!r} gives output_unit {unit!r}; tip_tracking needs the stroke [m] of the "
                         "record's 29 mm cell against the voltage, like the record (identify_and_predict saves it so; "
                         "set model.output_unit = 'm' before model.save if that is what it gives)")
    u, y = record.input, record.output
    report = make_report(model, u, y, u.size, int(np.argmin(u)), f"saved model {path.name}", output_unit=unit)
    return model, report


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    if len(p.tip_amplitudes) != len(p.frequencies):
        raise ValueError(f"tip_amplitudes and frequencies must have the same length, got {p.tip_amplitudes}, {p.frequencies}")
    if not 0.0 <= p.settle < p.duration:
        raise ValueError(f"settle must lie in [0, duration), got {p.settle!r}")

    def wanted(t):
        t = np.asarray(t, dtype=float)
        value = p.tip_mean + sum(a * np.sin(2 * math.pi * f * t) for a, f in zip(p.tip_amplitudes, p.frequencies))
        return float(value) if value.ndim == 0 else value

    record = read_record(RECORD, time="time", input="voltage", output="displacement")
    saved = saved_model(Path(p.model), record) if p.model else None  # a bad file is refused before anything runs

    # four simulations of the same actuator: announced once as a whole, before the preparation
    # (the feedforward program of a long duration takes a while), one progress display across them
    probe = build(p, 0.0)
    plan = ctx.plan([PlannedRun(probe, p.duration, p.step, label=LABELS[name]) for name in METHODS])

    if saved is not None:  # the designer's model from a file: asked for the wanted stroke
        model, report = saved
        wanted_per_strain = CELL_LENGTH
    else:  # the designer's model: identified from the noisy record, then expressed as strain
        stroke_model, report = EverettPreisach.fit(record.input, record.output, p.n_levels)
        model = EverettPreisach(stroke_model.edges, stroke_model.alpha, stroke_model.beta,
                                stroke_model.weights / CELL_LENGTH, offset=stroke_model.offset / CELL_LENGTH)
        wanted_per_strain = 1.0

    times = np.arange(0.0, p.duration + 0.5 * p.sample_time, p.sample_time)
    strain_wanted = strain_for_tip(probe, wanted(times))
    slope = report.linear_model["a"] / CELL_LENGTH
    intercept = report.linear_model["b"] / CELL_LENGTH
    linear, linear_info = linear_program(slope, intercept, times, strain_wanted, VOLTAGE_LIMITS)
    feedforward, ff_info = feedforward_program(model, times, wanted_per_strain * strain_wanted, VOLTAGE_LIMITS)

    def pid(ff):
        return PIDController(p.kp, p.ki, p.kd, sample_time=p.sample_time, setpoint=wanted,
                             feedforward=ff, output_limits=VOLTAGE_LIMITS)

    drives = {"linear": linear, "feedforward": feedforward, "pid": pid(None), "pid_feedforward": pid(feedforward)}
    results = {}
    with plan:
        for k, (name, voltage) in enumerate(drives.items()):
            results[name] = simulate(build(p, voltage), p.duration, step=p.step, progress=plan.progress(k))

    t = results["linear"]["time"]
    target = wanted(t)
    series = {"time": t, "tip_wanted": target}
    units = {"time": "s", "tip_wanted": "m"}
    scalars = {}
    after = t >= p.settle
    for name, r in results.items():
        if r.n_rows != t.size or not np.allclose(r["time"], t):
            raise RuntimeError(f"run {name!r} recorded other time steps than run 'linear' (step size reduced)")
        error = r["actuator.tip_y"] - target
        series[f"tip_{name}"] = r["actuator.tip_y"]
        series[f"voltage_{name}"] = r["actuator.voltage"]
        units[f"tip_{name}"] = "m"
        units[f"voltage_{name}"] = "V"
        scalars[f"rms_error_{name}"] = (float(np.sqrt(np.mean(error[after] ** 2))), "m")
        scalars[f"max_error_{name}"] = (float(np.max(np.abs(error[after]))), "m")
    scalars["linear_over_pid_feedforward"] = (
        scalars["rms_error_linear"][0] / scalars["rms_error_pid_feedforward"][0], "-")
    scalars["model_fit_rms"] = (report.model_errors["fit"]["rms"], "m")
    result = Result(series, units, parameters={"model": repr(model), "record": RECORD.name})
    notes = {
        "linear_program": linear_info,
        "feedforward_program": ff_info,
        "controller_pid": results["pid"].info["controller"],
        "controller_pid_feedforward": results["pid_feedforward"].info["controller"],
        "error_window [s]": [p.settle, p.duration],
        "designer_model": f"saved: {p.model}" if p.model else f"EverettPreisach.fit of {RECORD.name}, {p.n_levels} levels",
    }
    return CaseOutput(result, scalars, notes=notes)


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    t = r["time"]
    fig, axes = new_figure(3, 1, width=8.0, height=8.0, sharex=True)
    axes[0].plot(t, 1e3 * r["tip_wanted"], color="black", linewidth=2.0, label="wanted")
    for name in METHODS:
        axes[0].plot(t, 1e3 * r[f"tip_{name}"], linewidth=1.0, label=LABELS[name])
        rms = output.scalars[f"rms_error_{name}"]
        rms = rms[0] if isinstance(rms, tuple) else rms
        axes[1].plot(t, 1e3 * (r[f"tip_{name}"] - r["tip_wanted"]), linewidth=1.0,
                     label=f"{LABELS[name]}: RMS {1e3 * rms:.3g} mm")
        axes[2].plot(t, r[f"voltage_{name}"], linewidth=1.0)
    axes[0].set_ylabel(axis_label("tip deflection", "mm"))
    axes[1].set_ylabel(axis_label("tracking error", "mm"))
    axes[2].set_ylabel(axis_label("voltage", "V"))
    axes[2].set_xlabel(axis_label("time", "s"))
    axes[0].legend(loc="upper right", fontsize=7)
    axes[1].set_yscale("symlog", linthresh=1e-2)
    low, high = axes[1].get_ylim()
    axes[1].set_ylim(low, max(high, 1e2))  # an empty band on top for the legend (errors stay below 10 mm)
    axes[1].legend(loc="upper center", fontsize=7, ncol=2)
    axes[0].set_title("Tip tracking through the MFC hysteresis")
    return [save_figure(fig, out_dir / f"{output.case}.png")]


#: Cheap settings for the smoke test (1 s instead of the whole trajectory): they change no check the defaults pass.
SMOKE = {"duration": 1.0}

#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "tip_tracking",
        "quick": True,
        "scalars": [
            {"scalar": "rms_error_linear", "rel": 1e-6},
            {"scalar": "rms_error_feedforward", "rel": 1e-6},
            {"scalar": "rms_error_pid", "rel": 1e-6},
            {"scalar": "rms_error_pid_feedforward", "rel": 1e-6},
            {"scalar": "linear_over_pid_feedforward", "rel": 1e-6}
        ]
    },
]

CASE = Case("tip_tracking", __doc__, PARAMETERS, run, plot, smoke=SMOKE, benchmarks=BENCHMARKS, table_order=11,
            summary="linear inversion, inverse-Preisach feedforward, PID, and both")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
