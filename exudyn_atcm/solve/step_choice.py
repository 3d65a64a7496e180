"""Runs with a stated accuracy: ``simulate(system, t_end, accuracy=1e-3)`` chooses the step.

``accuracy`` is the largest error of the recorded positions (every result column in metres)
relative to their travel (the largest range among those columns), against the time-converged
solution of the same model.  The step is chosen from what is known before the run, then the
run's own error is measured:

1. **Prediction** (:func:`predict_steps`, cheap: milliseconds).  The mode the drives ring about
   the start state, with its own damping ratio (:func:`~exudyn_atcm.solve.rung_mode.rung_mode`: the
   lowest mode, unless the drives' forces on it cancel; the clamped-free estimate of the benders
   and their smallest damping ratio if the analysis fails), and every drive's free strain over the run (the voltage program through
   its hysteresis operator: the Preisach slope jumps at every reversal) drive a one-mode
   stand-in of the run (:mod:`exudyn_atcm.solve.step_surrogate`), integrated exactly and by
   the run's generalized-alpha at a ladder of steps (ratio 2^(1/4)).  The chosen step is the
   coarsest of the ladder whose stand-in error is :data:`AIM` of the target, with at least
   :data:`STEPS_PER_FEATURE` steps per shortest drive feature (a piecewise-linear program whose corners
   the grid holds asks only for that grid: :func:`~exudyn_atcm.solve.corner_grid.feature_steps`), rounded so that the run's grid and
   the probe's hold every corner of the drives' programs (:func:`~exudyn_atcm.solve.corner_grid.grid_unit`: a corner between
   steps is a first-order error no probe can estimate).
2. **Check** (one probe run at twice the step, its warnings not shown, over a window only:
   :func:`probe_window`, the first stretch of the run in which the stand-in's error reaches
   :data:`WINDOW_SHARE` of its largest, plus one period of the lowest mode; the whole run when
   that is most of it): Richardson's estimate of the run's error relative to the travel,
   ``|x_h - x_2h| / (2^q - 1)`` with ``q = p - 0.5`` (:data:`CHECK_ORDER_SLACK`), ``p`` the
   integration order of the system's cells (:attr:`~exudyn_atcm.cells.CellKind.time_order`; 1.5 where
   a drive jumps, :data:`JUMP_ORDER`),
   scaled by the stand-in's ratio of its whole run's error to the window's.  The integration is
   causal, so the run's first stretch is the window's fine run; the probe costs half a run times
   the window's share of it.  The probe and the run share one build of the model.
3. **Refinement**, once: if the estimate misses the target, the step is divided by the
   integer ``m`` the estimate asks for and the run repeated; the run at the former step is then
   the probe (``|x_{h/m} - x_h| / (m^q - 1)``).  If that misses too, an
   :class:`~exudyn_atcm.AccuracyWarning` says so with the estimate.

``result.info["step_choice"]`` says what was chosen and why; ``info["accuracy"]`` holds the
numbers.  A step coarser than a tenth of the lowest mode's period is taken when the stand-in
says the drive hardly excites the mode (a slow sine) and the probe confirms it; the run's
coarse-mode warning is then left out, as the measured error replaces that rule of thumb.
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from .._checks import shown
from ..errors import AccuracyWarning
from ..io.result import Result
from ..mechanism import Mechanism
from ..mbs.blas_threads import one_blas_thread
from .corner_grid import controller_samples, distinct_drives, feature_steps, grid_unit, jumps, refinement
from .interrupts import SimulationInterrupted
from .run_checks import COMFORTABLE_STEPS_PER_FEATURE, program_feature
from .rung_mode import lowest_damping_ratio, rung_mode
from .step_surrogate import StandIn, other_excitation, unit_strain

__all__ = ["ACCURACY_RANGE", "AIM", "STEPS_PER_FEATURE", "check_accuracy", "check_step_or_accuracy", "StepPrediction", "predict_steps",
           "position_error", "accurate_run", "probe_window", "lowest_damping_ratio"]

#: Order of the time integration of a system without cells (generalized-alpha; as in :mod:`~exudyn_atcm.solve.step_error`).
NOMINAL_ORDER = 2.0
#: Allowed ``accuracy`` [-]: above 10 % of the travel an "error" is no longer small against the motion
#: (the Richardson estimate assumes the run near convergence); below 1e-6 the differences between runs
#: reach the Newton tolerance (absolute 1e-8 m against millimetre travels), so no step can be verified.
ACCURACY_RANGE = (1e-6, 0.1)
#: The prediction aims the stand-in's error at this share of the target (room for the modes it leaves out and
#: for the check's cautious order, :data:`CHECK_ORDER_SLACK`).
AIM = 0.6
#: A refinement divides the step by the smallest factor ``m`` of 3/2, 2, 5/2, 3, ...
#: (:func:`~exudyn_atcm.solve.corner_grid.refinement`) that brings the estimate to this share of the target
#: (assuming the check's order): its check compares with the run at the former step, ``m`` times coarser, whose
#: difference the order slack overstates less than the probe's.  (0.6, as the prediction's aim, until 2026-11-29: the
#: gripper's triangle asked for ``m`` = 2.01 and took 3, a run 1.5 times dearer than ``m`` = 2, whose estimate is
#: 0.6 of the target.)
REFINE_AIM = 0.8
#: Fewest steps per shortest drive feature of the chosen step (warning-free:
#: :data:`~exudyn_atcm.solve.run_checks.COMFORTABLE_STEPS_PER_FEATURE`).
STEPS_PER_FEATURE = COMFORTABLE_STEPS_PER_FEATURE
#: The check assumes the error falls as ``h^(p - CHECK_ORDER_SLACK)`` between the probe and the run, not ``h^p``:
#: one probe cannot measure the order, and where the probe's step damps a higher mode numerically (the
#: gripper's, the four-bar's under a step program) the differences fall more slowly than ``h^p`` and
#: ``h^p`` would underestimate the error 1.5-2.3 times (``benchmarks/bench_accuracy.py``).  The same slack as
#: :data:`~exudyn_atcm.solve.step_error.ORDER_SLACK`.
CHECK_ORDER_SLACK = 0.5

#: The order of the run's error where a drive jumps (a :class:`~exudyn_atcm.model.signals.Steps` program): the
#: generalized-alpha step evaluates the forcing between its ends, so a jump, even on a grid instant, leaves an
#: error of first order.  Measured on a lone rod actuator switched 0 -> 1000 V once: the differences to runs at
#: h/2 ... h/16 converge as h^1 (0.0074, 0.0114, 0.0135, 0.0146), and assuming order 1.5 estimated 0.0086 for
#: an error of 0.015 (``tests/test_accuracy_runs.py``).
JUMP_ORDER = 1.0
#: The probes run over the shortest first stretch of the run in which the stand-in's error reaches this share of its
#: largest over the whole run (plus one period of the lowest mode); their estimate is scaled up by the stand-in's
#: ratio of the two (at most ``1 / WINDOW_SHARE``).
WINDOW_SHARE = 0.8
#: A window longer than this share of the run is the whole run (the saving would not pay for the extrapolation).
MAX_WINDOW = 0.9
#: Fewest steps of the coarsest probe in a window (fewer: the whole run).
MIN_WINDOW_STEPS = 8
#: Step factor of the probe.  (A second probe at twice its step, to measure the order of the differences, was
#: tried and dropped: that pair is too coarse to be asymptotic, its order was 2 where the run's differences fell as
#: ``h^1`` (the gripper under a step program: the estimate 2.2 times low) and 1 where they fell as ``h^2``.)
PROBE_FACTOR = 2
#: The ladder stops at this many steps per period of the lowest mode (the stand-in's error then ~1e-6).
MAX_STEPS_PER_PERIOD = 2000
#: Fewest steps of a run with a stated accuracy.
MIN_STEPS = 20
#: The run's steps are raised to put the drives' corners on its grid (and the probe's) when that takes at most this
#: many times the steps the accuracy asks for: a switch between two steps is a first-order error no probe estimates
#: (a step program switching at 0.01005 s of 0.05 s asked for 1706 steps, the corners for multiples of 2000; off the
#: grid the check missed and refined by 500, 853,001 steps, until 2026-11-30 when only a grid coarser than the run
#: was taken).
CORNER_GRID_COST = 4
#: Ladder of step counts: each rung this factor above the last.
LADDER = 2.0 ** 0.25
#: The stand-in's strain is sampled this many times per shortest feature (at least 16 times per chosen step at the
#: fewest steps; the stand-in's exact response is exact between samples, so they need only follow the strain).
REFERENCE_SAMPLES = 200
#: Positions whose largest range is within this share of their largest magnitude do not move (:func:`position_error`:
#: the paper actuator switched to 1000 V at ``t = 0`` starts in that equilibrium, and its tip's 7e-12 m of round-off
#: were taken for a travel, against which the runs at two steps differed by 0.3 %: a refinement for nothing).
STILL_TRAVEL = 1e-9
#: Largest step count a recording interval in seconds may impose (a finer interval is kept without a grid).
MAX_RECORD_GRID = 10_000
#: Largest sample count of the stand-in's reference (memory and time stay at milliseconds).
MAX_REFERENCE_SAMPLES = 2_000_000
# the run's warning about a step coarse for the lowest mode, replaced by the measured error
_COARSE_MODE = r"step = .* resolves the first bending mode"


def check_accuracy(accuracy: Any) -> float:
    """``accuracy`` as a float in :data:`ACCURACY_RANGE`, or a ``ValueError`` naming it."""
    low, high = ACCURACY_RANGE
    if isinstance(accuracy, bool) or not isinstance(accuracy, (int, float, np.integer, np.floating)):
        raise ValueError(f"accuracy must be a finite number in [{low:g}, {high:g}] (a relative error of the "
                         f"recorded positions, e.g. 1e-3 of the travel), got {shown(accuracy)}")
    value = float(accuracy)
    if not (math.isfinite(value) and low <= value <= high):
        raise ValueError(f"accuracy must be a finite number in [{low:g}, {high:g}] (a relative error of the "
                         f"recorded positions, e.g. 1e-3 of the travel), got {shown(accuracy)}")
    return value


def check_step_or_accuracy(step: Any, accuracy: Any) -> float | None:
    """``accuracy`` checked (:func:`check_accuracy`), or ``None``; refuses ``step`` and ``accuracy`` together."""
    if accuracy is None:
        return None
    if step is not None:
        raise ValueError(f"give step or accuracy, not both: accuracy={accuracy!r} chooses the step itself "
                         f"(got step={step!r}); leave step out, or give accuracy=None to run at that step")
    return check_accuracy(accuracy)


@dataclass(frozen=True)
class StepPrediction:
    """What the prediction used and chose: ``n_steps`` steps over ``t_end`` [s], and why."""

    n_steps: int
    t_end: float
    frequency: float
    frequency_source: str
    damping_ratio: float
    feature: float
    predicted: float
    order: float
    reason: str
    probe_factor: int = 2
    window: float = math.nan
    window_ratio: float = 1.0

    @property
    def step(self) -> float:
        """The step [s]."""
        return self.t_end / self.n_steps


#: ``built()``: a model of the mechanism in its built state, the one the runs will use (``None``: a build of its own).
Built = Callable[[], Any]


def _shortest_feature(mech: Mechanism, t_end: float) -> float:
    """Shortest feature [s] of the drives' programs before ``t_end`` (``inf`` without one)."""
    features = [program_feature(d.voltage, t_end) for d in mech.drives.values()]
    return min([f[0] for f in features if f is not None], default=math.inf)


def predict_steps(mech: Mechanism, t_end: float, accuracy: float, grid: int = 1,
                  built: Built | None = None) -> StepPrediction:
    """The number of steps the one-mode stand-in predicts for ``accuracy`` over ``t_end`` [s], and the probe's
    step factor (see module notes).  ``grid``: the step count must be a multiple of it too (a recording
    interval of ``t_end / grid``, evenly spaced records).  ``built``: the runs' model for the eigenvalue
    analysis (:data:`Built`; default a build of its own)."""
    frequency, zeta, source = rung_mode(mech, t_end, built)
    order = min((float(b.cell.time_order) for b in mech.benders), default=NOMINAL_ORDER)
    jumping = jumps(mech, t_end)
    if jumping:
        order = min(order, JUMP_ORDER + CHECK_ORDER_SLACK)  # a jump in the forcing: first order, however it is sampled
    feature = _shortest_feature(mech, t_end)
    unit = grid_unit(mech, t_end)  # the drives' corners on the run's grid, the probe's and the stand-in's samples
    n_features, sampled = feature_steps(mech, t_end, STEPS_PER_FEATURE, PROBE_FACTOR, unit)
    n_min = max(MIN_STEPS, n_features)
    # the stand-in's strain follows the features that fall between steps; a program with its corners on the grid
    # is sampled at each corner (n_min holds them) and is smooth between them
    per_feature = t_end / sampled if math.isfinite(sampled) else 0.0
    if not (frequency > 0.0 and math.isfinite(frequency)):
        n = _on_corners(unit, n_min, PROBE_FACTOR, grid)
        return StepPrediction(n, t_end, frequency, source, 0.0, feature, math.nan, order,
                              "no mode to resolve: the drive's features decide", 2, t_end)
    omega = 2.0 * math.pi * frequency
    n_ref = min(MAX_REFERENCE_SAMPLES, max(math.ceil(per_feature * REFERENCE_SAMPLES), 16 * n_min))
    n_ref = unit * math.ceil(n_ref / unit)
    dt = t_end / n_ref
    strains = [s for s in (unit_strain(d, np.arange(n_ref + 1) * dt) for d in distinct_drives(mech)) if s is not None]
    if not strains:
        other = other_excitation(mech)
        if other is None:  # nothing moves it: the run stays at rest in the equilibrium it starts from
            return StepPrediction(_on_corners(unit, n_min, PROBE_FACTOR, grid), t_end, frequency, source, zeta,
                                  feature, 0.0, order, "no drive's strain changes during the run and the loads are "
                                  f"constant: the mechanism stays at rest in its start equilibrium, its lowest mode "
                                  f"({frequency:.4g} Hz) not excited", 2, t_end)
        n = _on_corners(unit, max(n_min, math.ceil(t_end * frequency * 20.0)), PROBE_FACTOR, grid)
        return StepPrediction(n, t_end, frequency, source, zeta, feature, math.nan, order,
                              f"{other} (its response is not known before the run): 20 steps per period"
                              + (", and its samples on the step grid" if any(controller_samples(d.voltage, t_end) is not None
                                                                           for d in distinct_drives(mech)) else ""),
                              2, t_end)
    n_max = max(n_min, math.ceil(t_end * frequency * MAX_STEPS_PER_PERIOD))
    with one_blas_thread():  # small block products: a threaded BLAS would leave its workers spinning (cell_choice)
        stand_in = StandIn(strains, dt, t_end, omega, zeta)
        # each rung is tried as the run would take it, its count rounded onto the drives' grid: a rung with a
        # corner between steps has an error of first order that changes from rung to rung (a square wave's
        # stand-in missed 0.0086, 0.014, 0.0069, 0.014 at the rungs 1351 ... 2274, its rungs on the grid fall
        # steadily), and the first to pass off the grid said little about the count on it
        n = n_min
        n_used = _on_corners(unit, n, PROBE_FACTOR, grid)
        predicted = stand_in.error(n_used)
        while predicted > AIM * accuracy and n < n_max:
            n = min(n_max, max(n + 1, math.ceil(n * LADDER)))
            rung = _on_corners(unit, n, PROBE_FACTOR, grid)
            if rung != n_used:
                n_used = rung
                predicted = stand_in.error(n_used)
        errors = stand_in.errors(n_used)
    predicted = float(np.max(errors))
    window, ratio = probe_window(errors, t_end, frequency, math.lcm(PROBE_FACTOR, n_used // grid if grid > 1 else 1))
    if jumping:
        # a jump on a grid instant was taken on the side the instant's round-off said (the window's grid t_stop / k
        # and the run's t_end / n differ in the last bit): the probe over a window took the gripper's switch a step
        # apart from the run, its estimate 2.7 times the whole run's.  Steps now samples a switch within round-off
        # consistently (SWITCH_TOLERANCE); windows were measured again then and kept out: on the benchmark's step
        # programs they cover 0.85-1 of the run and the gripper's probe over one asked for a finer refinement
        window, ratio = t_end, 1.0
    reason = (f"one-mode stand-in ({frequency:.4g} Hz, damping ratio {zeta:.3g}) driven by the drives' free strain "
              f"misses {predicted:.2g} of its travel at this step")
    return StepPrediction(n_used, t_end, frequency, source, zeta, feature, predicted, order, reason,
                          PROBE_FACTOR, window, ratio)


def probe_window(errors: np.ndarray, t_end: float, frequency: float, block: int) -> tuple[float, float]:
    """The probes' window [s] and the factor scaling their estimate to the whole run, from the stand-in's ``errors``.

    ``errors`` at the ``n + 1`` instants of the run's step; the window is the first stretch in
    which their running maximum reaches :data:`WINDOW_SHARE` of the whole run's, plus one period
    of the lowest mode (``frequency`` [Hz]), rounded up to a multiple of ``block`` steps (the
    coarsest probe's step and the recording interval).  ``(t_end, 1.0)`` when that is more than
    :data:`MAX_WINDOW` of the run or the coarsest probe would take fewer than
    :data:`MIN_WINDOW_STEPS` steps in it.
    """
    n = errors.size - 1
    h = t_end / n
    running = np.maximum.accumulate(errors)
    if not running[-1] > 0.0:
        return t_end, 1.0
    k = int(np.argmax(running >= WINDOW_SHARE * running[-1]))
    k += math.ceil(1.0 / (frequency * h)) if frequency > 0.0 and math.isfinite(frequency) else n
    block = max(1, block)
    k = block * math.ceil(k / block)
    if k > MAX_WINDOW * n or k < MIN_WINDOW_STEPS * PROBE_FACTOR or not running[k] > 0.0:
        return t_end, 1.0
    return k * h, float(running[-1] / running[k])


def _on_corners(corner_unit: int, n: int, factor: int, grid: int = 1) -> int:
    """``n`` rounded up to a multiple of ``factor`` whose grid, and the probe's, hold the drives' corners (a multiple
    of ``corner_unit``, :func:`~exudyn_atcm.solve.corner_grid.grid_unit`; and a multiple of ``grid``)."""
    unit = corner_unit * factor  # the probe takes every factor-th instant: n / factor a multiple of the corners' unit
    if unit > CORNER_GRID_COST * n:  # a corner grid far finer than the run needs: only the probe's factor
        unit = factor
    if grid > 1 and grid <= n:
        unit = unit * grid // math.gcd(unit, grid)
    return unit * math.ceil(n / unit)


def position_error(fine: Result, coarse: Result, coarse_step: float) -> float:
    """Largest difference of the position columns [m] between two runs at the coarse grid's common instants,
    relative to the largest range of those columns in ``fine`` (0 when none moves: a range within
    :data:`STILL_TRAVEL` of the columns' largest magnitude is round-off).

    Both runs are compared at every accepted step (:attr:`Result.every_step <exudyn_atcm.Result.every_step>`), not at
    the recorded instants only: a coarse ``record_every`` neither hides the error nor shrinks the travel."""
    fine, coarse = fine.every_step, coarse.every_step
    names = [n for n in fine.names if n != "time" and fine.unit(n) == "m"]
    travel = max((float(np.ptp(fine[n])) for n in names), default=0.0)
    size = max((float(np.max(np.abs(fine[n]))) for n in names), default=0.0)
    if not names or not travel > STILL_TRAVEL * size:  # round-off is no travel to compare with
        return 0.0
    keys = []
    for run in (fine, coarse):
        t = np.asarray(run["time"], dtype=float)
        k = np.rint(t / coarse_step)
        on = np.abs(t - k * coarse_step) <= 1e-6 * coarse_step
        keys.append((k[on].astype(np.int64), np.flatnonzero(on)))
    common = np.intersect1d(keys[0][0], keys[1][0])
    if common.size < 2:
        return math.inf
    rows = [r[np.searchsorted(k, common)] for k, r in keys]
    diff = max(float(np.max(np.abs(np.asarray(fine[n])[rows[0]] - np.asarray(coarse[n])[rows[1]]))) for n in names)
    return diff / travel


#: ``run(step, progress, t_stop)``: the run at ``step`` [s] up to ``t_stop`` [s] (the whole run at ``t_end``).
Runner = Callable[[float, Any, float], Result]


def _record_grid(record_every: Any, t_end: float) -> int:
    """Step-count multiple for a recording interval in seconds that divides ``t_end`` (1 otherwise)."""
    if isinstance(record_every, float) and record_every > 0.0 and math.isfinite(record_every):
        k = t_end / record_every
        if abs(k - round(k)) <= 1e-9 * k and round(k) <= MAX_RECORD_GRID:
            return max(1, int(round(k)))
    return 1


def _quiet(run: Runner, step: float, progress: Any, t_stop: float, stage: str) -> tuple[Result, list]:
    """``run(step, progress, t_stop)`` and its warnings (every one, in order), for the caller to re-issue or drop.
    An interrupt names the ``stage`` of the choice and its step: a probe's partial result must not pass for the run's."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            return run(step, progress, t_stop), caught
        except SimulationInterrupted as exc:
            where = f"{stage}, step {step:.4g} s"
            exc.args = (f"{exc.args[0]} in the {where} of simulate(accuracy=...)",)
            if exc.result is not None:
                exc.result.info["interrupted_in"] = where
            raise


def _stage(progress: Any, label: str, share: float, weight: float, detail: str) -> Any:
    """A progress callback for one run of the choice: the display's ``stage`` when it has one, else ``None``."""
    stage = getattr(progress, "stage", None)
    if not callable(stage):
        return None
    return lambda t, t_end: stage(label, share + weight * t / t_end, detail)


def accurate_run(run: Runner, mech: Mechanism, t_end: float, accuracy: float, progress: Any = None,
                 stacklevel: int = 3, record_every: Any = None, built: Built | None = None) -> Result:
    """Run ``run(step, progress, t_stop)`` at the step :func:`predict_steps` chooses for ``accuracy``, checked by two
    probes over a window.

    ``mech`` is the mechanism run (a lone actuator's one-bender mechanism); ``progress`` the
    user's: a display with ``stage(label, share, detail)`` is told every run of the choice and
    the step chosen, a plain ``progress(t, t_end)`` sees the final run only.  ``record_every``: the
    run's recording interval; one in seconds that divides ``t_end`` is kept a multiple of the step.
    ``built``: the model ``run`` uses, in its built state (:data:`Built`), for the prediction's eigenvalue
    analysis; each run must put it back in its built state (as
    :func:`~exudyn_atcm.mbs.solver_runs.restore_state` does).  Default: the analysis builds its own.
    """
    prediction = predict_steps(mech, t_end, accuracy, _record_grid(record_every, t_end), built)
    n, r = prediction.n_steps, prediction.probe_factor
    order = prediction.order - CHECK_ORDER_SLACK
    h, window = t_end / n, prediction.window
    chose = (f"step {h:.4g} s ({n} steps) for {accuracy:g} of the travel: {prediction.reason}"
             f" ({prediction.frequency_source}); " + (f"shortest drive feature {prediction.feature:.4g} s"
                                                      if math.isfinite(prediction.feature) else
                                                      "no drive feature before the run's end known (a constant "
                                                      "program, or one given as a function)"))
    share = (window / t_end / r) / (1.0 + window / t_end / r)  # the probe's part of the work
    probe, _ = _quiet(run, r * h, _stage(progress, "accuracy probe", 0.0, share, f"step {r * h:.3g} s"), window,
                      "accuracy probe (a check at twice the chosen step; the run itself had not started)")
    result, caught = _quiet(run, h, _stage(progress, "accuracy run", share, 1.0 - share, chose) or progress, t_end,
                            "accuracy run (the step chosen, not yet checked)")
    estimate = position_error(result, probe, r * h) / (r ** order - 1.0) * prediction.window_ratio
    over = (f" over the first {window:.4g} s (scaled by {prediction.window_ratio:.3g}, the stand-in's ratio of its "
            f"whole run's error to the window's)" if window < t_end else "")
    why = "a drive jumps" if prediction.order <= JUMP_ORDER + CHECK_ORDER_SLACK else f"of the cells' {prediction.order:g}"
    checks = [f"probe at {r * h:.4g} s{over}: estimated error {estimate:.2g} (Richardson, assuming order {order:g}: "
              f"{why})"]
    refined = False
    if estimate > accuracy:
        m = refinement(n, (estimate / (REFINE_AIM * accuracy)) ** (1.0 / order), grid_unit(mech, t_end),
                       _record_grid(record_every, t_end))
        coarse, coarse_h = result, h
        h = coarse_h / float(m)
        result, caught = _quiet(run, h, _stage(progress, "accuracy refinement", 1.0, 0.0, f"step {h:.3g} s")
                                or progress, t_end, f"accuracy refinement (the run at {coarse_h:.4g} s missed the "
                                "target and was complete)")
        # compared where both runs have steps: every coarse step (m an integer) or every other one (m = k/2)
        estimate = position_error(result, coarse, coarse_h * m.denominator) / (float(m) ** order - 1.0)
        checks.append(f"missed {accuracy:g}: refined once by {m} to {h:.4g} s ({int(m * n)} steps), estimated error "
                      f"{estimate:.2g} against the run at {coarse_h:.4g} s")
        refined = True
    for w in caught:  # the result's own warnings, at the caller's line (the coarse-mode rule replaced by the check)
        if not (issubclass(w.category, AccuracyWarning) and re.match(_COARSE_MODE, str(w.message))):
            warnings.warn(w.message, w.category, stacklevel=stacklevel)
    line = chose + "; " + "; ".join(checks)
    result.info["step_choice"] = line
    result.info["accuracy"] = {"target": accuracy, "estimated_error": estimate, "step [s]": h,
                               "predicted_error": prediction.predicted, "refined": refined,
                               "probe_step [s]": r * prediction.step, "probe_window [s]": window,
                               "window_ratio": prediction.window_ratio,
                               "mode_frequency [Hz]": prediction.frequency, "damping_ratio": prediction.damping_ratio}
    stage = getattr(progress, "stage", None)
    if callable(stage):
        stage("accuracy run", 1.0, line)
    if estimate > accuracy:
        warnings.warn(f"simulate(accuracy={accuracy:g}): the run's estimated error {estimate:.2g} of the travel still "
                      f"misses the target after one refinement ({line}). Give a smaller step yourself "
                      f"(step=...) or check with exudyn_atcm.step_error", AccuracyWarning, stacklevel=stacklevel)
    return result

