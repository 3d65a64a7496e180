"""A bender's cell kind and count chosen for a run's accuracy: :func:`choose_cells`.

A bender built with ``n_cells="auto"`` (and, or, ``cell="auto"``) leaves its discretisation to
the package.  ``simulate(mechanism, t_end, accuracy=a)`` chooses it before it chooses the step:
the discretisation may use :data:`SPACE_SHARE` of ``a``, and the step what twice the cells'
estimated error leaves of ``a`` (at least ``1 - SPACE_SHARE`` of it), so that the run stays within
``a`` of the solution converged in both.

**The kind** (``cell="auto"``): the cheapest of :data:`~exudyn_atcm.mechanism.bender.AUTO_CELLS`
that the bender's connections and loads allow (the kinds' own refusals,
:meth:`~exudyn_atcm.cells.CellKind.end_refusal` and
:meth:`~exudyn_atcm.cells.CellKind.tip_load_refusal`, and a trial build): ``ritz`` for a
one-segment cantilever without tip loads, ``rod`` otherwise.  Both span the same assumed modes and have equal errors at equal
count; ``ritz`` costs about a quarter of ``rod`` a step (``benchmarks/bench_rod_vs_ritz.py``).

**The count** (``n_cells="auto"``): every open bender takes the same count, tried in a ladder
(modal kinds, whose error falls by an order of magnitude per mode: 2, 3, 4, ...; chains of cells,
second order: 4, 8, 16, ...).  Each count is compared with the next one on what decides a run's
error, measured on the mechanism itself:

- the **static poses**: the equilibria at the drives' start voltages and at the voltages where
  each drive's program is highest and lowest over the run, under the mechanism's loads (one
  static sweep); the largest difference of a position column [m] relative to the travel
  between those poses (where they do not move: relative to their distance from the reference pose);
- the **lowest eigenfrequency** about the reference pose (unloaded: its convergence in the count is the
  discretisation's, and no equilibrium is needed; the mode the drives ring where their forces on the
  lowest cancel, :func:`~exudyn_atcm.solve.rung_mode.rung_analysis`): its relative change ``delta``, turned into a
  position error by the one-mode stand-in of the run (:mod:`exudyn_atcm.solve.step_surrogate`:
  the drives' free strain drives the mode at ``omega`` and at ``omega (1 + delta)``, damped as the
  count's lowest mode (:func:`~exudyn_atcm.mbs.linear.damped_modes`), both solved
  exactly; the largest difference of the unit travel, as a period error shifts the ringing's phase).

The difference to the next count is the count's error for the modal kinds; for the chains it is
scaled by Richardson's factor ``1 / (1 - 2^-p)`` with ``p`` the kind's
:attr:`~exudyn_atcm.cells.CellKind.space_order`.  The first count whose estimate is within the
share is taken.  ``result.info["cell_choice"]`` says what was chosen and why.

What it does not see: a mode above the lowest that the drive excites more than the lowest (its
frequency converges more slowly in the count), the discretisation's effect on the damping, and the
higher modes an impact against a stop rings: for a mechanism with stops, ``simulate`` runs the next count
at the chosen step too and compares (:func:`~exudyn_atcm.solve.impact_check.impacts_checked`; a lever driven against a stop was
2.2e-3 off for 1e-3, its cells' share 1.9e-3 where the choice estimated 1.1e-4).
The tests compare the chosen run with a run of twice the count at a fine step
(``tests/test_cell_choice.py``).
"""

from __future__ import annotations

import copy
import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._checks import positive_float
from ..cells import cell_kind
from ..errors import AccuracyWarning
from ..io.result import Result
from ..mechanism import Mechanism
from ..mechanism.bender import AUTO_CELLS, Bender, Segment, is_auto
from ..mechanism.points import MechanismError
from .interrupts import SimulationInterrupted
from ..mbs import builder as mb
from ..mbs import solver_runs as runs
from ..mbs.layout import check_end_connections, rigid_groups
from ..mbs.blas_threads import one_blas_thread
from . import mechanism_solve
from .corner_grid import distinct_drives
from .step_choice import check_accuracy, lowest_damping_ratio
from .rung_mode import rung_analysis, strain_groups
from .step_surrogate import ExactResponse, other_excitation, program_voltages, unit_strain

__all__ = ["SPACE_SHARE", "CellChoice", "open_benders", "with_cells", "choose_cells", "frequency_error_share"]

#: Share of a run's ``accuracy`` the discretisation may use (the step gets the rest).
SPACE_SHARE = 0.3
#: Counts tried for the modal kinds (the count is the number of assumed modes).
MODAL_COUNTS = (2, 3, 4, 5, 6, 8, 10, 12, 16)
#: Counts tried for chains of cells (second order: each doubles the last).
CHAIN_COUNTS = (4, 8, 16, 32, 64, 128, 256)
#: Voltage samples per run to find where each drive's program is highest and lowest.
VOLTAGE_SAMPLES = 2001
#: The stand-in's strain is sampled at least this many times per period of the lowest mode.
SAMPLES_PER_PERIOD = 40
#: Largest sample count of the stand-in.
MAX_SAMPLES = 400_000
#: Static poses whose travel (or deflection) is below this share of the mechanism's size (the span of its parts'
#: points in the reference pose) do not move: their differences between counts are round-off, not a count's error
#: (a straight column under an axial load: its inextensible rod stays within 1e-17 m, and the differences of two
#: counts were 1 and 5 times that "travel").
STILL_POSES = 1e-9


@dataclass
class CellChoice:
    """What :func:`choose_cells` chose.

    Attributes
    ----------
    mechanism : Mechanism
        A copy of the mechanism with every open choice fixed (the same mechanism when none was open).
    cells : dict
        Bender name -> ``(kind name, count)`` for the benders that had an open choice.
    estimated_error : float
        The discretisation's estimated error [-] of the travel (``nan`` when nothing was open).
    line : str
        What was chosen and why, in words (``result.info["cell_choice"]``).
    tried : list
        ``(count, lowest frequency [Hz], static difference to the next count [-], estimate [-])`` per count tried.
    """

    mechanism: Mechanism
    cells: dict[str, tuple[str, int]] = field(default_factory=dict)
    estimated_error: float = math.nan
    line: str = ""
    tried: list[tuple[int, float, float, float]] = field(default_factory=list)
    #: a build of :attr:`mechanism` in its built state (``None``: none made), for the run to take
    built: Any = None
    #: the mechanism with the next count of the ladder (``None``: the largest count was taken), for the check of a
    #: mechanism with stops (:func:`~exudyn_atcm.solve.impact_check.impacts_checked`)
    finer: Mechanism | None = None

    def step_target(self, accuracy: float) -> float:
        """The step's part [-] of a run's ``accuracy``: what the cells leave of it, counting their estimated error
        twice (an estimate: measured 0.7-1.5 times their error), and at least ``1 - SPACE_SHARE`` of it."""
        used = 2.0 * self.estimated_error if math.isfinite(self.estimated_error) else SPACE_SHARE * accuracy
        return accuracy * max(1.0 - SPACE_SHARE, 1.0 - used / accuracy)

    def noted(self, result: Result, accuracy: float) -> Result:
        """``result`` of the accuracy run (its step chosen for :meth:`step_target`) with this choice in its
        ``info``: ``"cell_choice"``, the ``"step_choice"`` line and the ``"accuracy"`` numbers."""
        step_target = self.step_target(accuracy)
        result.info["cell_choice"] = self.line
        result.info["accuracy"].update({"target": accuracy, "cells_estimated_error": self.estimated_error,
                                        "step_target": step_target,
                                        "cells": {name: f"{n} {kind}" for name, (kind, n) in self.cells.items()}})
        result.info["step_choice"] = (f"cells: {self.line}; step, for {step_target:.2g} of {accuracy:g} (what twice "
                                      f"the cells' estimate leaves, at least {1.0 - SPACE_SHARE:g} of it): "
                                      f"{result.info['step_choice']}")
        return result


def open_benders(mech: Mechanism) -> list[Bender]:
    """The benders of ``mech`` that leave their cell kind or count to the package."""
    return [b for b in mech.benders if b.open_choices]


def _fixed(bender: Bender, kind: str, n: int) -> Bender:
    """A copy of ``bender`` with its open kind and count fixed to ``kind`` and ``n`` (fixed ones kept)."""
    new = copy.copy(bender)
    new.__dict__.pop("_derived", None)  # its cached laminate and damping: made again for the copy
    if "n_cells" in bender.open_choices:
        new.segments = tuple(Segment(s.length, n, s.drive) if is_auto(s.n_cells) else s for s in bender.segments)
    if "cell" in bender.open_choices:
        new.cell = kind
    return new


def with_cells(mech: Mechanism, cells: dict[str, tuple[str, int]]) -> Mechanism:
    """A copy of ``mech`` whose benders named in ``cells`` take its ``(kind, count)`` where theirs was open."""
    new = copy.copy(mech)
    new.components = {name: (_fixed(c, *cells[name]) if name in cells else c) for name, c in mech.components.items()}
    new.connections = list(mech.connections)
    new.measurements = dict(mech.measurements)
    return new


def _kind_of(mech: Mechanism, bender: Bender) -> str:
    """The cheapest kind of :data:`AUTO_CELLS` that ``bender`` in ``mech`` can be made of: its connections and loads
    pass the kind's refusals, and a build of it succeeds (``ritz`` models one uniform segment: said at the build)."""
    if "cell" not in bender.open_choices:
        return bender.cell.name
    for kind in AUTO_CELLS[:-1]:
        trial = with_cells(mech, {b.name: (kind if b is bender else AUTO_CELLS[-1], 2) for b in open_benders(mech)})
        try:
            groups, group_of = rigid_groups(trial)
            check_end_connections(trial, groups, group_of)
            mb.build(trial)
        except MechanismError:
            continue
        return kind
    return AUTO_CELLS[-1]


def _ladder(kinds: list[str]) -> tuple[tuple[int, ...], float]:
    """The counts to try and the factor turning a difference to the next count into the count's error."""
    order = min(float(cell_kind(k).space_order) for k in kinds)
    if math.isinf(order):
        return MODAL_COUNTS, 1.0
    return CHAIN_COUNTS, 1.0 / (1.0 - 2.0 ** -order)


def _pose_points(mech: Mechanism, t_end: float) -> list[dict[str, float]] | None:
    """The drives' voltages [V] at the start and where each program is highest and lowest before ``t_end``."""
    drives = mech.drives
    if not drives:
        return [{}]
    if any(getattr(d, "controller", None) is not None for d in drives.values()):
        return None  # a controller's voltage depends on the run
    times = np.linspace(0.0, t_end, VOLTAGE_SAMPLES)
    volts = {name: program_voltages(d, times) for name, d in drives.items()}
    picks = [0] + [int(f(v)) for v in volts.values() for f in (np.argmax, np.argmin)]
    return [{name: float(v[i]) for name, v in volts.items()} for i in sorted(set(picks))]


def _measure(mech: Mechanism, points: list[dict[str, float]] | None,
             groups: list[list[str]]) -> tuple[float, float, dict[str, np.ndarray], Any]:
    """The frequency [Hz] about the reference pose, unloaded, of the mode the drive ``groups`` ring (the lowest,
    unless their forces on it cancel: :func:`~exudyn_atcm.solve.rung_mode.rung_analysis`) and its damping ratio [-]
    (both ``nan`` where the analysis fails), the
    position columns [m] of the static equilibria at ``points`` (``{}`` without them), and the one build of
    ``mech`` they used, put back in its built state (:func:`~exudyn_atcm.mbs.solver_runs.restore_state`).

    The frequency is compared between counts, so it is taken where it costs least: about the built state,
    without the equilibrium and its stability check that a loaded start state needs (the poses carry the
    loads); its convergence in the count is the discretisation's, whatever the state."""
    model = mb.build(mech)
    built = runs.save_state(model)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # analyses for the choice only; the run says what matters
        try:
            frequency, damping, _ = rung_analysis(mech, None, False, model, groups)
        except Exception:  # noqa: BLE001 - no frequency: the poses alone decide
            frequency = damping = math.nan
        runs.restore_state(model, built)
        poses: dict[str, np.ndarray] = {}
        if points is not None:
            voltages = {name: [p[name] for p in points] for name in mech.drives} if mech.drives else [0.0]
            result: Result = mechanism_solve.static_sweep(mech, voltages, built=model)
            poses = {c: np.asarray(result[c], dtype=float) for c in result.names if result.unit(c) == "m"}
            runs.restore_state(model, built)
    return frequency, damping, poses, model


def _reference_points(mech: Mechanism) -> dict[str, float]:
    """The position columns' values [m] in the reference pose, by column name."""
    return {f"{name}.{point}_{axis}": xy[k] for name, comp in mech.components.items()
            for point, xy in comp.points.items() for k, axis in enumerate("xy")}


def _size(mech: Mechanism) -> float:
    """The span [m] of the mechanism's points in the reference pose (its largest extent along x or y)."""
    reference = _reference_points(mech)
    spans = [max(v) - min(v) for v in ([x for c, x in reference.items() if c.endswith(axis)] for axis in ("_x", "_y"))
             if v]
    return max(spans, default=0.0)


def _travel(mech: Mechanism, poses: dict[str, np.ndarray]) -> float:
    """The largest range [m] of a position column over the static poses (a run starts from the first: under the
    loads, at the drives' start voltages).  Where they do not move (no drive, or a constant program), the largest
    distance of a pose from the reference pose instead: the deflection is then the only scale of a pose's error."""
    travel = max((float(np.ptp(v)) for v in poses.values()), default=0.0)
    if travel > 0.0 and all(v.size > 1 for v in poses.values()):
        return travel
    reference = _reference_points(mech)
    return max((float(np.max(np.abs(v - reference[c]))) for c, v in poses.items() if c in reference), default=0.0)


def frequency_error_share(mech: Mechanism, t_end: float, frequency: float, delta: float, zeta: float,
                          strains: dict | None = None) -> float:
    """Largest position error [-] of the unit travel that a relative error ``delta`` of the lowest mode's
    ``frequency`` [Hz] causes over ``t_end`` [s] (the one-mode stand-in, both responses exact; the worst drive's).
    Without a strain that changes: 0 where nothing else excites the mode (the run starts at rest in its
    equilibrium under constant loads), else (a controller's drive, a load given as a function of time) the
    phase drift ``2 pi f t_end delta``, at most 2.  ``strains``: a dict that keeps the drives' unit strains by
    sample count between calls for one mechanism's drives."""
    if delta == 0.0:
        return 0.0
    omega = 2.0 * math.pi * frequency
    n = int(min(MAX_SAMPLES, max(VOLTAGE_SAMPLES, math.ceil(t_end * frequency * SAMPLES_PER_PERIOD))))
    n = VOLTAGE_SAMPLES * math.ceil(n / VOLTAGE_SAMPLES)  # close frequencies share their samples (and ``strains``)
    times = np.linspace(0.0, t_end, n + 1)
    kept = {} if strains is None else strains
    if n not in kept:
        kept[n] = [s for s in (unit_strain(d, times) for d in distinct_drives(mech)) if s is not None]
    strains = kept[n]
    if not strains:
        excited = other_excitation(mech) is not None
        return min(2.0, 2.0 * math.pi * frequency * t_end * delta) if excited else 0.0
    dt = t_end / n
    worst = 0.0
    # one BLAS thread: the responses' block products are small, and a threaded BLAS (OpenBLAS) leaves its
    # workers spinning about 0.1 s of CPU after them (measured: 130 ms on the four-bar's choice, a tenth of a core
    # taken from a parallel study's other worker)
    with one_blas_thread():
        for s in strains:
            a = ExactResponse(s, dt, omega, zeta)(times)
            b = ExactResponse(s, dt, omega * (1.0 + delta), zeta)(times)
            worst = max(worst, float(np.max(np.abs(a - b))))
    return worst


def choose_cells(mechanism: Mechanism, t_end: float, accuracy: float = 1e-3, *, progress: Any = None) -> CellChoice:
    """Fix the cell kinds and counts that a mechanism's benders leave to the package (``n_cells="auto"``,
    ``cell="auto"``), as ``simulate(mechanism, t_end, accuracy=accuracy)`` does before it chooses the step.

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism; it is not changed.
    t_end : float
        Duration [s] of the run the cells are chosen for (its drives' programs up to ``t_end``
        decide the static poses compared and excite the lowest mode), > 0.
    accuracy : float, optional
        The run's wanted error of the recorded positions relative to their travel [-], in
        [1e-6, 0.1] (default 1e-3); the cells may use :data:`SPACE_SHARE` of it (the step the rest).
    progress : optional
        A display with ``stage(label, share, detail)`` (the command line's) is told each count tried;
        anything else is not called.

    Returns
    -------
    CellChoice
        Its ``mechanism`` is a copy with the choices fixed (``mechanism`` itself when none is open),
        ``cells`` the choices, ``line`` what was chosen and why (see the module notes).

    Raises
    ------
    ValueError
        For a ``mechanism`` that is not a :class:`~exudyn_atcm.Mechanism`, or a ``t_end`` or
        ``accuracy`` out of range.

    SimulationInterrupted
        On Ctrl-C (a ``KeyboardInterrupt``), saying that the choice stopped before any step (``result`` None).

    Warns
    -----
    AccuracyWarning
        When the largest count tried still misses the share (that count is taken).

    Examples
    --------
    >>> import exudyn_atcm as atcm
    >>> strip = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550)
    >>> mfc = atcm.Layer(thickness=0.3e-3, youngs_modulus=30e9, density=5440)
    >>> b = atcm.Bender("b", width=0.01, passive=strip, active=mfc, length=0.03, n_cells="auto",
    ...                 cell="auto", drive=atcm.PiezoDrive(atcm.signals.Steps([0.0], [500.0])))
    >>> choice = atcm.choose_cells(atcm.Mechanism().add(b).ground(b.base), 0.05)
    >>> choice.cells["b"][0]  # a cantilever without tip loads: the cheaper of the two kinds
    'ritz'
    """
    if not isinstance(mechanism, Mechanism):
        raise ValueError(f"mechanism: expected an exudyn_atcm Mechanism, got {type(mechanism).__name__} "
                         f"{mechanism!r:.80}")
    t_end, share = positive_float("t_end", t_end), SPACE_SHARE * check_accuracy(accuracy)
    try:
        return _choose(mechanism, t_end, share, progress)
    except KeyboardInterrupt as exc:  # a static solve's SimulationInterrupted says "t = 0 s": no run had started
        stopped = SimulationInterrupted(0.0)
        stopped.args = ("interrupted while choosing the cells (static poses and eigenfrequencies), before any step "
                        "of the run: no result",)
        raise stopped from exc


def _choose(mech: Mechanism, t_end: float, accuracy: float, progress: Any = None) -> CellChoice:
    """:func:`choose_cells` for the discretisation's share ``accuracy`` [-] of the travel."""
    benders = open_benders(mech)
    if not benders:
        return CellChoice(mech)
    kinds = {b.name: _kind_of(mech, b) for b in benders}
    names = ", ".join(repr(b.name) for b in benders)
    what = "/".join(sorted(set(kinds.values())))
    if all("n_cells" not in b.open_choices for b in benders):  # the kind alone was open
        cells = {b.name: (kinds[b.name], b.n_cells) for b in benders}
        line = (f"bender{'s' if len(benders) > 1 else ''} {names}: {what} cells, the cheapest kind of "
                f"{', '.join(AUTO_CELLS)} that the connections and loads allow")
        return CellChoice(with_cells(mech, cells), cells, 0.0, line)
    counts, factor = _ladder(list(kinds.values()))
    unit = "modes" if factor == 1.0 else "cells"
    points = None
    tried: list[tuple[int, float, float, float]] = []
    previous: tuple[int, float, float, dict, Any] | None = None
    chosen_n, estimate, delta, finer = counts[-1], math.inf, math.nan, None
    stage = getattr(progress, "stage", None)
    kept: dict = {}  # the drives' unit strains for the stand-in, by sample count
    size, still, dynamic = _size(mech), False, 0.0
    groups = strain_groups(mech, t_end)  # drives driven alike: their forces may cancel on the lowest mode
    for n in counts:
        if callable(stage):
            stage("cell choice", 0.0, f"{names}: {n} {what} {unit} (static poses, lowest eigenfrequency)")
        candidate = with_cells(mech, {b.name: (kinds[b.name], n) for b in benders})
        if points is None:
            points = _pose_points(candidate, t_end)
        f, zeta, poses, model = _measure(candidate, points, groups)
        if previous is not None:
            n0, f0, zeta0, poses0, model0 = previous
            travel = _travel(mech, poses)
            still = not travel > STILL_POSES * size
            common = [c for c in poses if c in poses0]
            static = (max(float(np.max(np.abs(poses[c] - poses0[c]))) for c in common) / travel
                      if common and not still else 0.0)
            known = math.isfinite(f) and math.isfinite(f0)
            delta = abs(f0 - f) / f if known else 0.0
            dynamic = (frequency_error_share(candidate, t_end, f0, factor * delta,
                                             zeta0 if math.isfinite(zeta0) else
                                             lowest_damping_ratio(candidate, 2.0 * math.pi * f0), kept) if known else 0.0)
            estimate = factor * static + dynamic
            tried.append((n0, f0, static, estimate))
            if estimate <= accuracy:
                chosen_n, built, finer = n0, model0, candidate
                break
        previous = (n, f, zeta, poses, model)
    else:
        built = model
    cells = {b.name: (kinds[b.name], chosen_n) for b in benders}
    head = f"bender{'s' if len(benders) > 1 else ''} {names}: {chosen_n} {what} {unit} for {accuracy:g} of the travel"
    if estimate <= accuracy:
        n0, f0, static, _ = tried[-1]
        frequency = f"the next count moves the lowest eigenfrequency ({f0:.4g} Hz) by {delta:.2g}"
        if delta > 0.0 and dynamic == 0.0:
            frequency += " (nothing in the run excites that mode: it starts at rest under constant loads)"
        poses_said = (f"the static poses by {static:.2g} of their travel" if not still else
                      f"the static poses do not move (by less than {STILL_POSES:g} of the mechanism's size: "
                      "no scale to compare the counts' poses with)")
        line = f"{head}: {frequency} and {poses_said} (estimated error {estimate:.2g})"
    else:
        line = (f"{head}: the most tried, not checked (the count below it still differs from it by an estimated "
                f"{estimate:.2g})")
        warnings.warn(f"the cells chosen for the accuracy: {names} at the largest count tried, {chosen_n}, not "
                      f"checked: the count below it was estimated {estimate:.2g} off against {accuracy:g} of the "
                      "travel (the cells' share of the accuracy); fix n_cells yourself and compare runs",
                      AccuracyWarning, stacklevel=4)
    return CellChoice(built.mechanism, cells, estimate, line, tried, built, finer)
