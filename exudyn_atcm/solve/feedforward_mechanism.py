"""Feedforward for any output of a mechanism: the voltage program that makes a point follow a wanted path.

:func:`mechanism_feedforward` composes three steps, each a model of one part of the chain
voltage -> free strain -> mechanism at rest -> mechanism in motion, inverted from the end:

1. **Dynamic pre-filter** (:mod:`exudyn_atcm.model.prefilter`): the wanted trajectory ``r(t)`` becomes
   the quasi-static command ``q(t)``, the output the mechanism is asked to have *at rest* at each
   instant, so that its lightly damped mode does not ring (inversion of the dominant mode, or input
   shaping, or rounding the corners).  The mode's frequency comes from
   :func:`~exudyn_atcm.solve.mechanism_solve.eigenfrequencies` about the equilibria at the lowest, the
   middle and the highest wanted output (linear in between); its damping ratio (and the second
   mode's) from the linear model about the middle one (:func:`~exudyn_atcm.solve.linearise.linearise`
   on the ascending branch, ``Prefilter(damping_from="linear")``, the default: the damping the simulation has),
   or from the mechanism's damping description (below, ``Prefilter(damping_from="description")``), or
   ``Prefilter(damping_ratio=...)``.
2. **Output map** (:mod:`exudyn_atcm.solve.output_map`): ``q`` to the drive's free strain, from a
   static sweep (continuation), checked monotone over the wanted range and refused beyond the
   reachable one.
3. **Hysteresis inverse** (:func:`~exudyn_atcm.hysteresis.inverse.inverse_operator`): the strain to
   the voltage, with the operator's memory following the program from its reset state (as in the
   simulation); an operator with creep or a rate lag is inverted with the time
   (:class:`~exudyn_atcm.hysteresis.dynamics_inverse.DynamicsInverse`).

Damping ratio from the linear model: ``-Re(p) / |p|`` of the first (second) oscillating pole of
:attr:`LinearModel.A <exudyn_atcm.LinearModel>`, whose damping matrix is the derivative of the
simulated forces with respect to the velocities, so it holds for any mix of Rayleigh coefficients
over the parts (a rigid link's mass is not damped by a bender's ``alpha``).  Its input is the drive's
voltage, or for six-bar cells (whose strain is a prescribed motion, not an input of a linear model) a
force at the output's point: the damping ratios do not depend on the input.  A drive whose operator
has creep or rate dynamics has no linear model (:func:`~exudyn_atcm.linearise` refuses it); there the
description is used and ``damping_source`` says so.

Damping ratio from the description: the mechanism's benders and flexures carry Rayleigh damping
``C = alpha M + beta K`` on their own stiffness and masses (:mod:`exudyn_atcm.model.damping`); rigid
links add mass but no stiffness.  When every such part has the same ``alpha`` and ``beta`` and
``alpha = 0`` (the default: a damping *ratio* per bender is ``beta = 2 zeta / omega_1``), the
damping matrix is ``beta K`` and every mode of circular frequency ``omega`` has exactly
``zeta = beta omega / 2`` (the joints' geometric stiffness from external loads is undamped; it is
zero without loads).  Otherwise the smallest ``alpha / (2 omega) + beta omega / 2`` over the parts is
used (the lightest damping: an estimate, reported as such); give ``Prefilter(damping_ratio=...)`` from a
measured decay (:func:`~exudyn_atcm.model.damping.damping_ratio_from_log_decrement`) to override.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._checks import finite_array, positive_float, positive_int, shown
from ..hysteresis.inverse import inverse_operator
from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..mechanism.flexure import Flexure
from ..model.feedforward import feedforward_program
from ..model.prefilter import DAMPING_FROM, Prefilter, invert_mode, shape, smooth, uniform_grid
from ..model.sampled_program import SampledProgram
from .linearise import linearise
from .mechanism_solve import eigenfrequencies
from .output_map import OutputMap, drive_name, output_map, voltage_limits
from .state_space import LinearModel

__all__ = ["FeedforwardReport", "mechanism_feedforward", "damping_ratio_of", "DAMPING_FROM"]



@dataclass
class FeedforwardReport:
    """What :func:`mechanism_feedforward` did, with the arrays it computed (SI units).

    Attributes
    ----------
    output, drive, prefilter : str
        The output column, the drive compensated and the pre-filter used.
    voltage_range : (float, float)
        Voltages [V] the program may use.
    reachable : (float, float)
        Outputs reachable at rest over that range (output units).
    fit_error : float
        Largest error of the quasi-static map at points kept out of it (output units).
    frequencies : list of float
        First eigenfrequency [Hz] about the equilibria at the lowest, middle and highest wanted output.
    second_frequency : float
        Second eigenfrequency [Hz] about the middle one.
    damping_ratio : float
        Damping ratio [-] of the first mode used by the pre-filter; ``damping_source`` says whence.
    damping_source : str
        Whence the damping ratio: the linear model, the damping description or ``Prefilter(damping_ratio=...)``.
    window : float
        Rounding window of the corners [s] (0 for none).
    times, wanted, rounded, command, strain, voltage : numpy.ndarray
        Program samples [s]; the wanted output; the wanted output with rounded corners (what the
        mechanism is expected to follow); the quasi-static command; the free strain [-]; the
        voltage [V].
    output_map : OutputMap
        The quasi-static map (:mod:`exudyn_atcm.solve.output_map`).
    linear_model : LinearModel or None
        The model (drive voltage, or a point force for six-bar cells, to the output) about the middle
        wanted output the damping ratios came from (``None`` when they did
        not: ``Prefilter(damping_from="description")``, ``Prefilter(damping_ratio=...)`` or a drive with creep or rate dynamics).
    """

    output: str
    drive: str
    prefilter: str
    voltage_range: tuple[float, float]
    reachable: tuple[float, float]
    fit_error: float
    frequencies: list[float]
    second_frequency: float
    damping_ratio: float
    damping_source: str
    window: float
    clipped_samples: int
    times: np.ndarray = field(repr=False)
    wanted: np.ndarray = field(repr=False)
    rounded: np.ndarray = field(repr=False)
    command: np.ndarray = field(repr=False)
    strain: np.ndarray = field(repr=False)
    voltage: np.ndarray = field(repr=False)
    output_map: OutputMap = field(repr=False)
    linear_model: LinearModel | None = field(default=None, repr=False)

    def summary(self) -> dict[str, Any]:
        """The scalars, with units in the keys (for a case's JSON)."""
        d = {k: getattr(self, k) for k in ("output", "drive", "prefilter", "voltage_range", "reachable", "fit_error",
                                            "frequencies", "second_frequency", "damping_ratio", "damping_source",
                                            "window", "clipped_samples")}
        return {"output": d["output"], "drive": d["drive"], "prefilter": d["prefilter"],
                "voltage_range [V]": list(d["voltage_range"]), "reachable [output unit]": list(d["reachable"]),
                "fit_error [output unit]": d["fit_error"], "first_frequency [Hz]": d["frequencies"],
                "second_frequency [Hz]": d["second_frequency"], "damping_ratio [-]": d["damping_ratio"],
                "damping_source": d["damping_source"],
                "linear_model": None if self.linear_model is None else
                f"{', '.join(self.linear_model.outputs)} per {', '.join(self.linear_model.inputs)} about "
                f"{self.linear_model.state} ({self.linear_model.branch} branch)",
                "window [s]": d["window"],
                "clipped_samples": d["clipped_samples"],
                "peak_voltage [V]": float(np.max(self.voltage)), "lowest_voltage [V]": float(np.min(self.voltage))}


def damping_ratio_of(mech: Mechanism, frequency: float) -> tuple[float, str]:
    """Damping ratio [-] of a mode of ``frequency`` [Hz] from the mechanism's Rayleigh damping, and how.

    Exact (``"beta omega / 2"``) when all benders and flexures share one ``beta`` and have
    ``alpha = 0``; otherwise the smallest ``alpha/(2 omega) + beta omega/2`` over them (an estimate).
    """
    omega = 2.0 * math.pi * positive_float("frequency", frequency)
    parts = [c for c in mech.components.values() if isinstance(c, (Bender, Flexure))]
    if not parts:
        raise ValueError(f"mechanism {mech.name!r} has no bender or flexure, so no damping description; give "
                         "prefilter=Prefilter(damping_ratio=...)")
    coeffs = [(c.rayleigh_damping.alpha, c.rayleigh_damping.beta) for c in parts]
    ratios = [a / (2.0 * omega) + b * omega / 2.0 for a, b in coeffs]
    betas = [b for _, b in coeffs]
    if all(a == 0.0 for a, _ in coeffs) and max(betas) - min(betas) <= 1e-12 * max(betas):
        return ratios[0], "model: zeta = beta omega / 2 (one stiffness-proportional damping for every part: exact)"
    return min(ratios), ("model estimate: the smallest alpha/(2 omega) + beta omega/2 over the parts (their "
                         "Rayleigh coefficients differ; give Prefilter(damping_ratio=...) from a measured decay to be exact)")


def _modes(mech: Mechanism, drive: str, omap: OutputMap, levels: np.ndarray) -> tuple[list[float], float, float]:
    """First eigenfrequency [Hz] at the equilibria of the output ``levels``; second at the middle one; the
    middle one's voltage [V]."""
    firsts, second = [], math.nan
    volts = np.interp(omap.strain(levels), omap.strains, omap.voltages)
    for k, v in enumerate(volts):
        f = eigenfrequencies(mech, n=2, voltage={drive: float(v)})
        firsts.append(float(f[0]))
        if k == len(volts) // 2:
            second = float(f[1])
    return firsts, second, float(volts[len(volts) // 2])


def _has_dynamics(mech: Mechanism) -> bool:
    """Whether a drive's operator has creep or rate dynamics (no linear model: :func:`linearise` refuses it)."""
    return any(callable(getattr(d.hysteresis, "static_output", None)) for d in mech.drives.values())


def _damping_input(mech: Mechanism, output: str, drive: str) -> str:
    """The linear model's input: the drive, or for six-bar cells (their strain is a prescribed motion, no input
    of a linear model) a force at the output's point (at the first named point for an angle)."""
    if not any(getattr(getattr(c, "cell", None), "name", None) == "six-bar" for c in mech.components.values()):
        return drive
    points = [f"{c.name}.{p}" for c in mech.components.values() for p in c.points]
    point = output[:-2] if output.endswith(("_x", "_y")) and output[:-2] in points else points[0]
    return f"{point}_Fy"


def _linear_damping(mech: Mechanism, output: str, drive: str, voltage: float) -> tuple[LinearModel, float, float, str]:
    """The linear model about ``voltage`` (ascending branch) and its first two modes' damping ratios [-]."""
    model = linearise(mech, voltage={drive: voltage}, inputs=[_damping_input(mech, output, drive)], outputs=[output],
                      branch="ascending")
    ratios = model.damping_ratios
    if ratios.size == 0:
        raise ValueError(f"the linear model of {mech.name!r} about {model.state} has no oscillating mode, so no "
                         "damping ratio for the pre-filter; give prefilter=Prefilter(damping_ratio=...) or prefilter='smooth'/'none'")
    second = float(ratios[1]) if ratios.size > 1 else float(ratios[0])
    return model, float(ratios[0]), second, (f"linear model: -Re(p)/|p| of its first mode about {model.state} "
                                             "(ascending branch; the damping the simulation has)")


def _voltages(pdrive: Any, times: np.ndarray, strain: np.ndarray, limits: tuple[float, float]) -> tuple[np.ndarray,
                                                                                                           int]:
    """Voltage [V] samples that give the free strain through the drive's operator (reset state first)."""
    model = pdrive.hysteresis
    if model is None:
        gain = pdrive.d33 / pdrive.electrode_spacing
        return strain / gain, 0
    if getattr(model, "time_dependent", False):
        inverse = inverse_operator(model, limits)
        volts = np.array([inverse.commit(float(s), float(t)) for s, t in zip(strain, times)])
        return volts, int(getattr(inverse, "clip_count", 0))
    program, info = feedforward_program(model, times, strain, limits)
    return program.values.copy(), int(info["clipped_samples"])


def mechanism_feedforward(
    mechanism: Mechanism,
    output: str,
    times: Any,
    wanted: Any,
    *,
    drive: str | None = None,
    prefilter: str | Prefilter = "inversion",
    sample_time: float = 1e-3,
    voltage_range: tuple[float, float] | None = None,
    map_points: int = 41,
) -> tuple[SampledProgram, FeedforwardReport]:
    """Voltage program [V] that makes the output column ``output`` of a mechanism follow ``wanted``.

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism (its drives' programs do not matter; the drive's hysteresis does).
    output : str
        A result column of the mechanism, e.g. ``"lever.end_y"`` [m] or ``"lever.angle"`` [rad].
    times : array_like
        Sample times [s] of the wanted trajectory, strictly increasing (linear in between).
    wanted : array_like
        The wanted output at those times (the column's unit); the mechanism starts at rest at the
        first value and is held at rest at the last one after the program.
    drive : str, optional
        The drive to compensate (default: the mechanism's only drive); other drives keep their
        programs' voltages at t = 0.
    prefilter : {"inversion", "zv", "zvd", "smooth", "none"} or Prefilter
        The dynamic pre-filter by name with its default settings, or a
        :class:`~exudyn_atcm.model.prefilter.Prefilter` (its corner window, shaped modes and
        where the damping ratio comes from: by default the linear model about the middle wanted
        output).  ``"inversion"`` (default): the first mode inverted, corners rounded over one
        period of the second mode; ``"zv"`` / ``"zvd"``: input shaping; ``"smooth"``: corners
        rounded; ``"none"``: the quasi-static inverse only.  See :mod:`exudyn_atcm.model.prefilter`.
    sample_time : float, optional
        Sample spacing [s] of the program (default 1 ms); at most a tenth of the first mode's period.
    voltage_range : (float, float), optional
        Voltages [V] the program may use (default: the drive's rating within its operator's range).
    map_points : int, optional
        Points of the quasi-static map (as many again check it).

    Returns
    -------
    (SampledProgram, FeedforwardReport)
        The program (for the drive's ``PiezoDrive``) and what was computed.

    Raises
    ------
    ValueError
        An unknown ``output`` or ``drive`` (with the closest name), wanted outputs beyond the
        reachable range (which is given), a map that is not monotone over the wanted range (where
        it turns back), a command the pre-filter pushes beyond the reachable range, bad arguments.
    """
    t = finite_array("times", times, min_length=2)
    y = finite_array("wanted", wanted, min_length=2)
    if t.size != y.size:
        raise ValueError(f"times and wanted must have the same length, got {t.size} and {y.size}")
    options = prefilter if isinstance(prefilter, Prefilter) else Prefilter(prefilter)
    prefilter, window, shaped_modes = options.kind, options.window, options.shaped_modes
    damping_ratio, damping_from = options.damping_ratio, options.damping_from
    dt = positive_float("sample_time", sample_time)
    name = drive_name(mechanism, drive)
    pdrive = mechanism.drives[name]
    limits = voltage_limits(pdrive, voltage_range)
    points = positive_int("map_points", map_points)
    if points < 4:
        raise ValueError(f"map_points must be >= 4 (points of the quasi-static map), got {shown(map_points)}")
    omap = output_map(mechanism, output, name, limits, points)
    low, high = float(y.min()), float(y.max())
    omap.check(low, high)
    grid, wanted_grid = uniform_grid(t, y, dt)
    levels = np.array([low, 0.5 * (low + high), high])
    firsts, second, mid_voltage = _modes(mechanism, name, omap, levels)
    if dt > 0.1 / max(firsts):
        raise ValueError(f"sample_time = {dt:g} s is too coarse for the first mode ({max(firsts):.4g} Hz); it must be "
                         f"at most a tenth of its period, {0.1 / max(firsts):.3g} s")
    mid = firsts[1]
    linear_model = None
    if damping_ratio is None and damping_from == "linear" and not _has_dynamics(mechanism):
        linear_model, zeta, zeta2, source = _linear_damping(mechanism, output, name, mid_voltage)
    elif damping_ratio is None:
        zeta, source = damping_ratio_of(mechanism, mid)
        zeta2, _ = damping_ratio_of(mechanism, second)
        if damping_from == "linear":
            source = "a drive has creep or rate dynamics, so no linear model: " + source
    else:
        zeta, source, zeta2 = float(damping_ratio), "given (Prefilter(damping_ratio=...))", float(damping_ratio)
    rounded, used_window = wanted_grid, 0.0
    if prefilter == "inversion":
        used_window = 1.0 / second if window is None else window
        freq = np.interp(wanted_grid, levels, firsts) if high > low else mid
        command, rounded = invert_mode(grid, wanted_grid, freq, zeta, used_window)
    elif prefilter in ("zv", "zvd"):
        modes = [(mid, zeta)] + ([(second, zeta2)] if shaped_modes == 2 else [])
        command = shape(grid, wanted_grid, modes, prefilter)
        rounded = command
    elif prefilter == "smooth":
        used_window = 1.0 / mid if window is None else window
        command = smooth(grid, wanted_grid, used_window)
        rounded = command
    else:
        command = wanted_grid
    if prefilter != "none":
        try:
            omap.check(float(command.min()), float(command.max()), what=f"the {prefilter!r} pre-filter's command")
        except ValueError as exc:
            raise ValueError(f"{exc}. The pre-filter asks for more than the wanted range near the corners; round them "
                             f"over a longer Prefilter(window=...) (now {used_window:g} s) or keep the wanted path further "
                             "inside the reachable range") from None
    strain = omap.strain(command)
    volts, clipped = _voltages(pdrive, grid, strain, limits)
    report = FeedforwardReport(output, name, prefilter, limits, omap.reachable, omap.fit_error, firsts, second, zeta,
                               source, used_window, clipped, grid, wanted_grid, rounded, command, strain, volts, omap,
                               linear_model)
    return SampledProgram(grid, volts), report
