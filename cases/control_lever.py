"""A positioning stage from its model to its drive: modes, feedforward for the lever's end, and a PID beside it.

The stage: the paper's laminate (CFC 0.2 mm / 70 GPa under MFC 0.3 mm / 30.336 GPa, 28 mm wide) as a
48 mm bender of rigid cells, with a rigid 120 mm lever of 2.7 g welded to its tip along the tangent.
The lever's end moves ``(L/2 + a) / (L/2) = 6`` times the bender's tip (a 6:1 lever) and reaches
-2.9 ... 28.4 mm over the MFC's -500 ... 1500 V (the paper's continuous Preisach loop as free strain).
Its first mode (about 17 Hz: the lever's mass on the bender's stiffness) has the damping ratio
``beta omega / 2 = 0.29 %``: the bender's default 2 % at its own 118 Hz clamped-free mode, realised as
stiffness-proportional damping, is 0.29 % at 17 Hz.

The lever's end should follow a ramp of ``low -> high -> low`` over ``ramp_time`` (6 -> 20 -> 6 mm in
2 s), after ``rest`` at ``low``.  The control story, step by step:

1. **Linear model** (:func:`exudyn_atcm.linearise`): about the static equilibrium at the middle of the
   range (``(low + high) / 2``, 13 mm, reached at the voltage ``U0`` of the output map: about 752 V), on the
   *ascending* branch (the voltage rose from the operator's lowest input to ``U0``: the state of the
   ramp's rising half), input the bender's voltage, output the lever's end.  Its first modes are drawn
   (:func:`exudyn_atcm.plots.plot_modes`) and its Bode plot (:func:`exudyn_atcm.plots.plot_bode`) is the
   plant the PID is tuned on, with the loop gain beside it.
2. **PID** (:class:`exudyn_atcm.PIDController`), tuned from that model's static gain ``K0 = dc_gain()``
   [m/V] and its first mode's ``w = 2 pi natural_frequencies[0]`` and ``zeta = damping_ratios[0]``
   (the damping the simulation has), as for ``G(s) = K0 w^2 / (s^2 + 2 zeta w s + w^2)``:
   ``kp = kp_fraction / K0`` stiffens the loop to ``w_c = w sqrt(1 + K0 kp)``; ``kd`` adds damping up to
   ``zeta_target`` at ``w_c``: ``kd = 2 (zeta_target w_c - zeta w) / (K0 w^2)``; ``ki`` puts the closed
   loop's cubic ``s^3 + a2 s^2 + a1 s + a0`` (``a2 = 2 zeta_target w_c``, ``a1 = w_c^2``) at a quarter of
   its Routh limit, ``a0 = K0 w^2 ki = a2 a1 / 4`` (a gain margin of 4 in ``ki``).  The closed loop of the
   whole linear model (all its modes) with the continuous PID is checked: ``pid_closed_loop_max_real``
   is the largest real part of its poles [1/s] (negative: stable).
3. **Feedforward** (:func:`exudyn_atcm.mechanism_feedforward`): the quasi-static output map, the
   hysteresis inverse and a pre-filter of the first mode (frequency and damping ratio from the linear
   model about the middle output, like the PID's).

Four drives, each one simulation with the hysteresis in the step:

(a) naive: the quasi-static output map and the hysteresis inverse, no pre-filter
    (``prefilter="none"``): the mode rings at every corner;
(b) compensated: the same with the first mode inverted (``prefilter``, default ``"inversion"``);
(c) PID alone on the lever's end, tuned as in 2.;
(d) PID plus the program of (b), the derivative acting on the error (the program adds ``kd``
    times the wanted velocity, which cancels the derivative-on-measurement's share of the wanted motion).

Written besides the time series: the tables ``modes`` (undeformed pose), ``output_map`` and
``frequency_response`` (the linear model's plant and the PID loop, gain and phase over frequency).

References: the wanted path itself (the errors are simulated minus wanted); the linear model
(validated in ``tests/test_linearise.py``; the map's slope at the middle, ``static_gain_map``, is the same
static gain from the static sweep); the output map against the rigid chain's polygon plus the rigid lever
(``map_error_polygon``).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from exudyn_atcm import (Bender, Layer, Link, LinearModel, Mechanism, PIDController, PiezoDrive, Result,
                         eigenfrequencies, linearise, mechanism_feedforward, modes, simulate)
from exudyn_atcm import theory
from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, PlannedRun, RunContext
from exudyn_atcm.model import PiecewiseLinear, paper_strain_preisach
from exudyn_atcm.plots import axis_label, new_figure, plot_bode, plot_modes, save_figure

PARAMETERS = [
    Parameter("n_cells", 4, "-", "rigid cells of the bender", minimum=1),
    Parameter("length", 0.048, "m", "bender length L", exclusive_minimum=0.0),
    Parameter("lever", 0.12, "m", "lever length a (the end moves (L/2 + a)/(L/2) times the bender tip)",
              exclusive_minimum=0.0),
    Parameter("lever_mass", 2.7e-3, "kg", "lever mass (a slender bar)", exclusive_minimum=0.0),
    Parameter("low", 6e-3, "m", "lowest wanted lever-end position"),
    Parameter("high", 20e-3, "m", "highest wanted lever-end position"),
    Parameter("ramp_time", 2.0, "s", "time of the ramp up and down", exclusive_minimum=0.0),
    Parameter("rest", 0.1, "s", "rest at 'low' before the ramp", minimum=0.0),
    Parameter("settle", 0.4, "s", "rest at 'low' after the ramp", minimum=0.0),
    Parameter("prefilter", "inversion", "-", "pre-filter of the compensated program",
              choices=("inversion", "zv", "zvd", "smooth", "none")),
    Parameter("kp_fraction", 0.5, "-", "PID: K0 kp (the loop's static stiffening)", minimum=0.0),
    Parameter("zeta_target", 0.7, "-", "PID: damping ratio the derivative term gives the first mode",
              exclusive_minimum=0.0),
    Parameter("controller_sample_time", 5e-4, "s", "PID sample time (a multiple of step)", exclusive_minimum=0.0),
    Parameter("step", 2.5e-4, "s", "time step", exclusive_minimum=0.0),
    Parameter("record_every", 5e-4, "s", "recording interval [s] (0: every step); the error scalars come from every "
              "accepted step", minimum=0.0),
]

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
WIDTH = 28e-3
VOLTAGE_LIMITS = (-500.0, 1500.0)  # V, the MFC P1's rating (and the paper loop's input range)
OUTPUT = "lever.end_y"
METHODS = ("naive", "compensated", "pid", "pid_feedforward")
LABELS = {"naive": "(a) map + hysteresis inverse", "compensated": "(b) + mode inversion",
          "pid": "(c) PID", "pid_feedforward": "(d) PID + (b)"}


def build(p: Parameters, voltage=0.0) -> Mechanism:
    """The bender along +x with the lever welded to its tip; ``voltage`` its program or controller."""
    drive = PiezoDrive(voltage, hysteresis=paper_strain_preisach())
    bender = Bender("bender", width=WIDTH, passive=CFC, active=MFC, length=p.length, n_cells=p.n_cells, drive=drive,
                    cell="rigid")
    arm = Link("lever", {"root": (p.length, 0.0), "end": (p.length + p.lever, 0.0)},
               mass=p.lever_mass, inertia=p.lever_mass * p.lever**2 / 12.0)
    mech = Mechanism("control_lever").add(bender, arm).ground(bender.base).weld(bender.tip, arm.point("root"))
    return mech.feedback("bender", OUTPUT) if isinstance(voltage, PIDController) else mech


def wanted_path(p: Parameters) -> tuple[np.ndarray, np.ndarray]:
    """Corner times [s] and positions [m] of the wanted lever-end path."""
    t = np.array([0.0, p.rest, p.rest + 0.5 * p.ramp_time, p.rest + p.ramp_time, p.rest + p.ramp_time + p.settle])
    return t, np.array([p.low, p.low, p.high, p.low, p.low])


def pid_gains(static_gain: float, frequency: float, zeta: float, p: Parameters) -> tuple[float, float, float]:
    """(kp [V/m], ki [V/(m s)], kd [V s/m]) from the static gain [m/V] and the first mode's frequency [Hz] and
    damping ratio [-] (see the module)."""
    w = 2.0 * math.pi * frequency
    kp = p.kp_fraction / static_gain
    wc = w * math.sqrt(1.0 + static_gain * kp)
    kd = max(0.0, 2.0 * (p.zeta_target * wc - zeta * w) / (static_gain * w * w))
    a2, a1 = 2.0 * p.zeta_target * wc, wc * wc
    ki = 0.25 * a2 * a1 / (static_gain * w * w)
    return kp, ki, kd


def linear_model(p: Parameters, voltage: float) -> LinearModel:
    """The stage's linear model about its equilibrium at ``voltage`` [V] on the ascending branch (bender voltage
    to lever end)."""
    return linearise(build(p), voltage={"bender": voltage}, inputs=["bender"], outputs=[OUTPUT], branch="ascending")


def pid_response(frequencies: np.ndarray, kp: float, ki: float, kd: float) -> np.ndarray:
    """The continuous PID's response ``kp + ki/s + kd s`` at ``s = i 2 pi f`` [V/m]."""
    s = 2j * math.pi * frequencies
    return kp + ki / s + kd * s


def closed_loop_poles(lin: LinearModel, kp: float, ki: float, kd: float) -> np.ndarray:
    """Poles [1/s] of the linear model in a loop with the continuous PID ``u = -(kp y + ki int y + kd y')``."""
    A, B, C = lin.A, lin.B[:, :1], lin.C[:1]
    gain = kp * C + kd * C @ A  # y' = C A x (C B = 0: the output is a position)
    top = np.hstack([A - B @ gain, -ki * B])
    return np.linalg.eigvals(np.vstack([top, np.hstack([C, np.zeros((1, 1))])]))


def lever_end_polygon(p: Parameters, strains: np.ndarray) -> np.ndarray:
    """Lever end y [m] at rest: the rigid chain's polygon on the free arc (Timoshenko's curvature) plus the lever."""
    out = []
    for s in strains:
        kappa = theory.free_curvature(CFC.youngs_modulus, CFC.thickness, MFC.youngs_modulus, MFC.thickness, WIDTH,
                                      float(s))
        x, y = theory.chain_polygon(kappa, p.length, p.n_cells)
        out.append(theory.rigid_extension_point(x[-1], y[-1], kappa * p.length, p.lever)[1])
    return np.array(out)


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    if not p.high > p.low:
        raise ValueError(f"high must be above low, got low = {p.low!r} m, high = {p.high!r} m")
    t_path, y_path = wanted_path(p)
    t_end = float(t_path[-1])
    probe = build(p)
    freqs = eigenfrequencies(probe, n=3)
    naive, naive_report = mechanism_feedforward(probe, OUTPUT, t_path, y_path, prefilter="none")
    program, report = mechanism_feedforward(probe, OUTPUT, t_path, y_path, prefilter=p.prefilter)
    omap = report.output_map
    mid = 0.5 * (p.low + p.high)
    operating_voltage = float(np.interp(mid, omap.values, omap.voltages))
    lin = linear_model(p, operating_voltage)
    static_gain = float(lin.dc_gain()[0, 0])
    lin_frequency, lin_zeta = float(lin.natural_frequencies[0]), float(lin.damping_ratios[0])
    kp, ki, kd = pid_gains(static_gain, lin_frequency, lin_zeta, p)
    f = np.logspace(np.log10(0.05 * lin_frequency), np.log10(3.0 * lin.natural_frequencies[1]), 400)
    plant = lin.response(OUTPUT, "bender", f)
    loop = plant * pid_response(f, kp, ki, kd)
    setpoint = PiecewiseLinear(report.times, report.rounded)
    velocity = np.gradient(report.rounded, report.times)

    def pid(feedforward):
        return PIDController(kp, ki, kd, sample_time=p.controller_sample_time, setpoint=setpoint,
                             feedforward=feedforward, output_limits=VOLTAGE_LIMITS)

    drives = {"naive": naive, "compensated": program, "pid": pid(None),
              "pid_feedforward": pid(PiecewiseLinear(report.times, program.values + kd * velocity))}
    plan = ctx.plan([PlannedRun(probe, t_end, p.step, label=LABELS[name]) for name in METHODS])
    results = {}
    with plan:
        for k, (name, voltage) in enumerate(drives.items()):
            results[name] = simulate(build(p, voltage), t_end, step=p.step, progress=plan.progress(k),
                                     record_every=p.record_every if p.record_every > 0.0 else None)
    t = results["naive"]["time"]
    series = {"time": t, "wanted": np.interp(t, t_path, y_path)}
    units = {"time": "s", "wanted": "m"}
    scalars = {"first_frequency": (report.frequencies[1], "Hz"), "second_frequency": (report.second_frequency, "Hz"),
               "first_frequency_unloaded": (float(freqs[0]), "Hz"), "damping_ratio": (report.damping_ratio, "-"),
               "operating_voltage": (operating_voltage, "V"), "static_gain": (static_gain, "m/V"),
               "static_gain_map": (float(np.interp(mid, omap.values, np.gradient(omap.values, omap.voltages))), "m/V"),
               "linear_first_frequency": (lin_frequency, "Hz"), "linear_damping_ratio": (lin_zeta, "-"),
               "linear_second_frequency": (float(lin.natural_frequencies[1]), "Hz"),
               "pid_closed_loop_max_real": (float(np.max(closed_loop_poles(lin, kp, ki, kd).real)), "1/s"),
               "map_fit_error": (report.fit_error, "m"),
               "map_error_polygon": (float(np.max(np.abs(omap.values - lever_end_polygon(p, omap.strains)))), "m"),
               "kp": (kp, "V/m"), "ki": (ki, "V/(m s)"), "kd": (kd, "V s/m")}
    for name, r in results.items():
        if r.n_rows != t.size or not np.allclose(r["time"], t):
            raise RuntimeError(f"run {name!r} recorded other instants than run 'naive' (step size reduced)")
        series[f"end_{name}"], units[f"end_{name}"] = r[OUTPUT], "m"
        series[f"voltage_{name}"], units[f"voltage_{name}"] = r["bender.voltage"], "V"
        every = r.every_step
        error = every[OUTPUT] - np.interp(every["time"], t_path, y_path)
        ramp = (every["time"] >= t_path[1]) & (every["time"] <= t_path[3])
        scalars[f"rms_error_{name}"] = (float(np.sqrt(np.mean(error[ramp] ** 2))), "m")
        scalars[f"max_error_{name}"] = (float(np.max(np.abs(error[ramp]))), "m")
    scalars["naive_over_compensated"] = (scalars["rms_error_naive"][0] / scalars["rms_error_compensated"][0], "-")
    response_table = Result({"frequency": f, "plant_gain": np.abs(plant), "plant_phase": np.degrees(np.unwrap(np.angle(
        plant))), "loop_gain": np.abs(loop), "loop_phase": np.degrees(np.unwrap(np.angle(loop)))},
        {"frequency": "Hz", "plant_gain": "m/V", "plant_phase": "deg", "loop_gain": "-", "loop_phase": "deg"})
    mode_table = Result({"mode": np.arange(1.0, freqs.size + 1.0), "frequency": freqs}, {"mode": "-", "frequency": "Hz"})
    map_table = Result({"voltage": omap.voltages, "strain": omap.strains, "lever_end_y": omap.values,
                        "polygon_lever_end_y": lever_end_polygon(p, omap.strains)},
                       {"voltage": "V", "strain": "-", "lever_end_y": "m", "polygon_lever_end_y": "m"})
    notes = {"feedforward": report.summary(), "naive_feedforward": naive_report.summary(),
             "controller_pid": results["pid"].info["controller"],
             "controller_pid_feedforward": results["pid_feedforward"].info["controller"],
             "error_window [s]": [float(t_path[1]), float(t_path[3])],
             "linear_model": f"{lin.outputs[0]} per {lin.inputs[0]} voltage about {lin.state}, {lin.branch} branch "
                             f"(local gain {lin.gains['bender']:.4g} 1/V)",
             "pid_tuning": "from the linear model: K0 = dc_gain(), w and zeta of its first mode; kp = kp_fraction/K0; "
                           "kd: zeta_target at w_c = w sqrt(1 + K0 kp); ki at a quarter of the Routh limit (see the "
                           "case's description)"}
    return CaseOutput(Result(series, units), scalars, tables={"modes": mode_table, "output_map": map_table,
                                                           "frequency_response": response_table},
                      notes=notes)


def _value(scalar) -> float:
    return float(scalar[0] if isinstance(scalar, tuple) else scalar)


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r, s = output.result, output.scalars
    t = r["time"]
    files = []
    fig, axes = new_figure(3, 1, width=8.0, height=8.5, sharex=True)
    axes[0].plot(t, 1e3 * r["wanted"], color="black", linewidth=2.0, label="wanted")
    for name in METHODS:
        axes[0].plot(t, 1e3 * r[f"end_{name}"], linewidth=1.0, label=LABELS[name])
        axes[1].plot(t, 1e6 * (r[f"end_{name}"] - r["wanted"]), linewidth=1.0,
                     label=f"{LABELS[name]}: RMS {1e6 * _value(s[f'rms_error_{name}']):.3g} µm")
        axes[2].plot(t, r[f"voltage_{name}"], linewidth=1.0, label=LABELS[name])
    axes[0].set_ylabel(axis_label("lever end y", "mm"))
    axes[1].set_ylabel(axis_label("tracking error", "µm"))
    axes[1].set_yscale("symlog", linthresh=10.0)
    axes[2].set_ylabel(axis_label("voltage U", "V"))
    axes[2].set_xlabel(axis_label("time t", "s"))
    axes[0].legend(fontsize=7, loc="upper right")
    axes[1].legend(fontsize=7, loc="lower center", ncol=2)
    axes[0].set_title(f"Lever end on a ramp; first mode {_value(s['first_frequency']):.3g} Hz, "
                      f"damping ratio {100 * _value(s['damping_ratio']):.2g} %")
    files.append(save_figure(fig, out_dir / f"{output.case}_tracking.png"))

    # the linear model the PID was tuned on (plot_bode) with the loop gain beside it; its first modes
    lin = linear_model(p, _value(s["operating_voltage"]))
    kp, ki, kd = _value(s["kp"]), _value(s["ki"]), _value(s["kd"])
    f = np.logspace(np.log10(0.05 * lin.natural_frequencies[0]), np.log10(3.0 * lin.natural_frequencies[1]), 400)
    fig, axes = new_figure(2, 1, width=6.4, height=6.0, sharex=True)
    plot_bode(lin, frequencies_hz=f, ax=axes)
    loop = lin.response(OUTPUT, "bender", f) * pid_response(f, kp, ki, kd)
    axes[0].loglog(f, np.abs(loop), label="loop G C [-] (PID, continuous)")
    axes[0].axhline(1.0, color="grey", linewidth=0.8)
    axes[0].set_ylabel(axis_label("gain", "m/V; loop -"))
    axes[0].legend(fontsize=7)
    axes[1].semilogx(f, np.degrees(np.unwrap(np.angle(loop))), label="loop G C")
    axes[1].legend(fontsize=7)
    files.append(save_figure(fig, out_dir / f"{output.case}_bode.png"))
    files.append(save_figure(plot_modes(modes(build(p), n=2, voltage={"bender": _value(s["operating_voltage"])})),
                             out_dir / f"{output.case}_modes.png"))
    return files


#: Cheap settings for the smoke test: the defaults are cheap (four runs of 2.5 s at 0.25 ms, a few seconds).
SMOKE: dict = {}

CASE = Case("control_lever", __doc__, PARAMETERS, run, plot, smoke=SMOKE, table_order=14,
            summary="a bender with a 6:1 lever: modes, feedforward for the lever end, a PID beside it (the wanted "
                    "ramp; chain polygon plus lever)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
