"""The drives' corners on the step grid: where a voltage program's slope jumps or it reverses, and the
smallest step count whose grid holds them all (for :mod:`exudyn_atcm.solve.step_choice`).

A corner between two steps is sampled up to a step late: a first-order error that no probe at
another step can estimate, and a hysteresis reversal off by a share of a step.  The runs of
``simulate(..., accuracy=...)`` and their probes therefore take step counts that are multiples of
:func:`grid_unit`.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from ..mechanism import Mechanism
from ..model.signals import Signal, Sine, Steps, Triangle
from .run_checks import corners_on_grid, program_feature

__all__ = ["MAX_GRID_UNIT", "distinct_drives", "grid_unit", "program_corners", "controller_samples", "jumps",
           "feature_steps", "refinement"]

#: Largest step count that puts the drives' corners on the grid (:func:`grid_unit`): a measured voltage record
#: of 20 s sampled every millisecond needs 20,000 (10,000 until 2026-11-29: such a record fell off the grid, and its
#: run took 20 steps per sample with the samples between steps).
MAX_GRID_UNIT = 1_000_000
#: A corner lies on a grid of ``n`` steps when it is within this share of a step of a grid instant (a corner at
#: ``k / N`` of the run, ``N`` up to :data:`MAX_GRID_UNIT`, is within 1e-10 of a step in floating point; the
#: corners of a triangle of period ``pi / 30`` s lie on no grid up to that size: bounding the distance by
#: 1e-9 of the run instead, as until 2026-11-29, found one of 364,913 steps).
ON_GRID = 1e-9


def distinct_drives(mech: Mechanism) -> list[Any]:
    """Each PiezoDrive of ``mech`` once (segments share one)."""
    seen: dict[int, Any] = {}
    for drive in mech.drives.values():
        seen.setdefault(id(drive), drive)
    return list(seen.values())


def controller_samples(program: Any, t_end: float) -> np.ndarray | None:
    """A controller's sample instants [s] in ``(0, t_end)`` (it holds its output between them: a jump at each),
    ``None`` for a program that is no sampled controller."""
    sample = getattr(program, "sample_time", None)
    if not callable(getattr(program, "observe", None)) or not isinstance(sample, float) or not sample > 0.0:
        return None
    return sample * np.arange(1, math.ceil(t_end / sample - 1e-9))


#: Samples over the run at which a program given as a function is looked at for jumps (:func:`jumps`).
JUMP_SAMPLES = 4000


def jumps(mech: Mechanism, t_end: float) -> bool:
    """Whether a drive's voltage jumps during the run: a step program (:class:`~exudyn_atcm.model.signals.Steps`), a
    sampled controller, whose output is held between samples (the PID's zero-order hold), or a program given as a
    function whose largest change between samples does not shrink when they are twice as dense
    (:data:`JUMP_SAMPLES`; a continuous one's halves).  The run's error then falls as the step, not its square
    (measured on the control_lever case's bender with a PID sampled every 0.5 ms: 5.4e-3, 2.6e-3, 1.3e-3 of the
    travel at 5e-4, 2.5e-4, 1.25e-4 s; a voltage step given as a function, checked at order 1.5, was estimated
    7.2e-3 for an error of 9.4e-3)."""
    for drive in distinct_drives(mech):
        program = drive.voltage
        if isinstance(program, Steps) or controller_samples(program, t_end) is not None:
            return True
        if callable(program) and not isinstance(program, Signal):
            v = np.array([drive.voltage_at(float(t)) for t in np.linspace(0.0, t_end, 2 * JUMP_SAMPLES + 1)])
            fine, coarse = float(np.max(np.abs(np.diff(v)))), float(np.max(np.abs(np.diff(v[::2]))))
            if fine > 0.0 and coarse < 1.5 * fine:
                return True
    return False


def program_corners(program: Any, t_end: float) -> np.ndarray | None:
    """Times [s] in ``(0, t_end)`` where the program's slope jumps or it reverses: the triangle's peaks, the
    sine's extrema, the step program's switches, a piecewise-linear program's corners, a sampled controller's
    samples; ``None`` for others."""
    samples = controller_samples(program, t_end)
    if samples is not None:
        return samples
    if isinstance(program, Steps):
        change = np.flatnonzero(np.diff(program.values) != 0.0) + 1
        times = program.times[change]
    elif callable(getattr(program, "corner_times", None)):
        times = np.asarray(program.corner_times(t_end), dtype=float)
    elif isinstance(program, Triangle):
        times = 0.5 * program.period * np.arange(1, math.floor(2.0 * t_end / program.period) + 1)
    elif isinstance(program, Sine):
        first = ((0.5 * math.pi - program.phase) / (2.0 * math.pi)) % 0.5 * program.period
        times = first + 0.5 * program.period * np.arange(0, math.floor(2.0 * t_end / program.period) + 1)
    else:
        return None
    return times[(times > 0.0) & (times < t_end)]


def grid_unit(mech: Mechanism, t_end: float) -> int:
    """Smallest step count putting every drive's corners (:func:`program_corners`) on the grid ``t_end / n``.

    1 when a program's corners are unknown or need more than :data:`MAX_GRID_UNIT` steps.
    """
    unit = 1
    for drive in distinct_drives(mech):
        corners = program_corners(drive.voltage, t_end)
        if corners is None or corners.size == 0:
            continue
        x = np.asarray(corners, dtype=float) / t_end
        while True:  # the first corner off the grid refines it (a few rounds: the corners share denominators)
            off = ~_on_grid(x, unit, each=True)
            if not off.any():
                break
            c = float(x[int(np.argmax(off))])
            fraction = Fraction(c).limit_denominator(MAX_GRID_UNIT)
            if abs(c * fraction.denominator - fraction.numerator) > ON_GRID:
                return 1
            unit = unit * fraction.denominator // math.gcd(unit, fraction.denominator)
            if unit > MAX_GRID_UNIT:
                return 1
    return unit


def _on_grid(x: np.ndarray, unit: int, each: bool = False) -> Any:
    """Whether the fractions ``x`` of the run lie on the grid of ``unit`` steps (each, or all of them)."""
    on = np.abs(x * unit - np.rint(x * unit)) <= ON_GRID
    return on if each else bool(on.all())


def feature_steps(mech: Mechanism, t_end: float, per_feature: float, factor: int,
                  unit: int | None = None) -> tuple[int, float]:
    """Fewest steps over ``t_end`` [s] the drives' programs ask for, and the shortest feature [s] that asks.

    ``per_feature`` steps per shortest feature (``program_feature``) of each program, except for a
    piecewise-linear program (one with ``corner_times``: a table, a measured record, a feedforward
    program) whose corners all lie on the grid of :func:`grid_unit`: sampled exactly at every
    corner and linear between them, it loses nothing between two steps (the run checks exempt it
    too, :func:`~exudyn_atcm.solve.run_checks.corners_on_grid`), so it asks only for that grid, and
    the probe's (``factor`` times coarser) to hold it as well, where that is no more.  The feature
    returned is the shortest of the other programs (``inf`` without one).  A measured voltage record has a
    reversal at nearly every sample: at ``per_feature`` steps per sample its accuracy run took a
    step 10 times finer than the accuracy needed (``tests/test_accuracy_runs.py``).  ``(0, inf)``
    without a feature.  ``unit``: :func:`grid_unit` of the mechanism, if known.
    """
    unit = grid_unit(mech, t_end) if unit is None else unit
    steps, feature = 0, math.inf
    for drive in distinct_drives(mech):
        samples = controller_samples(drive.voltage, t_end)
        if samples is not None and samples.size and unit > 1 and _on_grid(samples / t_end, unit):
            # a sampled controller: its samples on the run's steps and the probe's (a sample between steps comes late,
            # and the controller's integral and derivative assume its sample time)
            steps = max(steps, unit * factor)
            continue
        known = program_feature(drive.voltage, t_end)
        if known is None:
            continue
        asked = math.ceil(t_end / known[0] * per_feature - 1e-9)
        if (callable(getattr(drive.voltage, "corner_times", None)) and unit * factor <= asked
                and corners_on_grid(drive.voltage, t_end / unit, t_end)):
            steps = max(steps, unit * factor)
            continue
        feature = min(feature, known[0])
        steps = max(steps, asked)
    return steps, feature


def refinement(n: int, needed: float, unit: int, grid: int = 1) -> Fraction:
    """The factor ``r`` by which a run of ``n`` steps is refined: the smallest of 3/2, 2, 5/2, 3, ... that is at
    least ``needed`` and keeps ``n r`` steps a multiple of the drives' ``unit`` (:func:`grid_unit`) and of the
    recording ``grid``.  A half-integer factor shares every other step of the coarse run (the check compares the
    two runs there); an integer one, every step.  (Until 2026-11-29 the factor was an integer, at least 2: a
    run that missed its target by a fifth was refined to half its step, where two thirds sufficed.)"""
    for k in range(3, 2 * MAX_GRID_UNIT):
        r = Fraction(k, 2)
        m = n * r
        if r >= needed and m.denominator == 1 and m % unit == 0 and (grid <= 1 or m % grid == 0):
            return r
    raise ValueError(f"no refinement of {n} steps by a factor >= {needed:g} keeps the grid of {unit} steps")
