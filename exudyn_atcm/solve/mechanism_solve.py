"""Static, quasi-static and dynamic solution of a :class:`~exudyn_atcm.mechanism.Mechanism`.

:func:`exudyn_atcm.simulate`, :func:`exudyn_atcm.solve_static` and
:func:`exudyn_atcm.eigenfrequencies` hand a mechanism to this module; :func:`static_sweep`
is its own.  Each solve builds the system, or takes one already built (``built=``, from
:class:`~exudyn_atcm.solve.built_system.BuiltSystem`, at the same call depth so that warnings
point at the user's line either way).  Every solve trials, commits and records
through one :class:`~exudyn_atcm.mbs.stepping.Stepping` (the same as :func:`exudyn_atcm.add_to`):
the hysteresis of every drive is trialled from the committed memory in the pre-step hook and
committed in the post-step hook of accepted steps only.

The result columns are described in :mod:`exudyn_atcm.mbs.recording` and on the
:doc:`/mechanisms` page of the documentation.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, Callable

import numpy as np

from .._checks import finite_array, positive_int, shown
from ..mbs import builder as mb
from ..mbs import linear
from ..mbs import solver_runs as runs
from ..mbs import solver_settings
from ..mbs.recording import RowLayout, cell_rotations, measurement_reader
from ..mbs.stepping import Stepping
from ..mechanism.assembly import Mechanism
from ..mechanism.points import MechanismError, closest
from .mechanism_checks import check_drive_ranges, check_steps, feedback_controllers, warn_coarse_cells, warn_few_modes
from ..io.result import Result
from .run_checks import SimulationInterrupted, WallClock, snap_time, snap_times
from .dynamic_run import integrate, mark_partial
from ..mechanism.build_cost import warn_if_eigen_long, warn_if_large
from .long_runs import is_announced
from .sweep_continuation import SweepPoint, continue_sweep
from .mechanism_static import (VoltageSpec, describe, describe_voltages, drive_voltages, equilibrium, start_equilibrium,
                               source_values)
from .run_setup import DEFAULT_STEP, prepare_run, report_controller, run_info
from .static_stability import load_path_note, stability_probe, warn_unstable
from ..errors import SolverError, annotate
from .run_checks import is_interrupt



# ------------------------------------------------------------------------------ public solves

def solve_static(mech: Mechanism, voltage: VoltageSpec = None, load_steps: int | None = None, *,
                 built: mb.MechanismModel | None = None) -> Result:
    """Static equilibrium of a mechanism at ``voltage`` with its loads (see :func:`exudyn_atcm.solve_static`).

    ``built``: a model of ``mech`` already built and in its built state (:class:`~exudyn_atcm.BuiltSystem`).
    """
    if load_steps is not None:
        load_steps = positive_int("load_steps", load_steps)
    volts = drive_voltages(mech, voltage)  # checked before the build: a bad voltage is refused at once
    strains_by_drive = {n: mech.drives[n].static_strain(v) for n, v in volts.items()}
    if built is None:
        warn_if_large(mech, "solve_static", equilibria=1, quiet=is_announced(), stacklevel=5)  # before the build
    model = built if built is not None else mb.build(mech)
    strains = source_values(model, strains_by_drive, "solve_static")
    source_volts = source_values(model, volts, "solve_static")
    check_drive_ranges(model, source_volts, strains)
    probe = stability_probe(mech, model)
    what = describe_voltages(volts)
    method = equilibrium(mech, model, np.zeros_like(strains), strains, True, load_steps, what, probe)
    stepping = Stepping.static(model)
    stepping.record_state(0.0, source_volts, strains)
    rows = stepping.close()
    _, _, row_strains, q, _ = stepping.layout.parts(rows)
    warn_coarse_cells(mech, cell_rotations(model, q, row_strains))
    warn_few_modes(mech, model.truncation_errors())
    warn_unstable(describe(mech), [(f"load factor 1 (the loads and {what} in full)", probe.last)],
                  load_path_note(probe))
    return stepping.result({"solver": method, "load_steps": load_steps if load_steps is not None else "auto",
                            "stability": probe.last.state})


def sweep_table(mech: Mechanism, voltages: Sequence[float] | Mapping[str, Sequence[float]]) -> list[dict[str, float]]:
    """The voltage [V] of every drive at every point of a :func:`static_sweep` (checked)."""
    drives = mech.drives
    if isinstance(voltages, Mapping):
        series = {}
        for name, values in voltages.items():
            if name not in drives:
                raise MechanismError(f"voltages: unknown drive {name!r}{closest(str(name), drives)} "
                                     f"(drives: {', '.join(drives) or 'none'})")
            series[name] = finite_array(f"voltages[{name!r}]", values)
        lengths = {len(v) for v in series.values()}
        if len(lengths) != 1:
            raise ValueError(f"voltages: every drive's sequence must have the same length, got "
                             f"{ {n: len(v) for n, v in series.items()} }")
        n = lengths.pop()
        base = drive_voltages(mech, None)
        return [{**base, **{name: float(v[i]) for name, v in series.items()}} for i in range(n)]
    values = finite_array("voltages", voltages)
    return [{name: float(v) for name in drives} for v in values]


SWEEP_METHODS = ("continuation", "points")


def check_sweep_method(method: str) -> str:
    """``method`` of :func:`static_sweep`, checked."""
    if method not in SWEEP_METHODS:
        raise ValueError(f"method: expected one of {', '.join(map(repr, SWEEP_METHODS))}, got {shown(method)}")
    return method


def static_sweep(mech: Mechanism, voltages: Sequence[float] | Mapping[str, Sequence[float]], *,
                 built: mb.MechanismModel | None = None, method: str = "continuation") -> Result:
    """Quasi-static path of a mechanism over a voltage sequence (see :func:`exudyn_atcm.static_sweep`).

    ``built``: a model of ``mech`` already built and in its built state (:class:`~exudyn_atcm.BuiltSystem`).
    ``method``: ``"continuation"`` (the points after the first as the load steps of one static
    solve continuing from the first equilibrium, :func:`~exudyn_atcm.solve.sweep_continuation.continue_sweep`,
    falling back to ``"points"`` for a point where that fails or ends unstable) or ``"points"``
    (each point its own equilibrium in load steps, :func:`~exudyn_atcm.solve.mechanism_static.equilibrium`).
    """
    check_sweep_method(method)
    table = sweep_table(mech, voltages)
    if built is None:
        warn_if_large(mech, "static_sweep", equilibria=len(table), quiet=is_announced(), stacklevel=5)  # before the build
    model = built if built is not None else mb.build(mech)
    source_table = np.array([source_values(model, per_drive, f"static_sweep point {i}")
                             for i, per_drive in enumerate(table)]).reshape(len(table), len(model.sources))
    stepping = Stepping.static(model)
    # each point is held for ever: an operator with creep or a rate lag gives its fully crept output
    strain_table = stepping.hold_path(source_table)
    check_drive_ranges(model, source_table, strain_table)
    methods = []
    readings: list[dict] = []  # every point's truncation readings, estimated together at the end
    probe = stability_probe(mech, model)
    states = []  # (point, stability) per point; the point described only where a warning names it

    def where(i: int) -> str:
        return f"sweep point {i} ({describe_voltages(table[i])})"

    def keep(point: SweepPoint) -> None:
        methods.append(point.method)
        states.append((point.index, point.stability))
        stepping.record_row(point.row)
        readings.append(point.truncation)

    previous = np.zeros(len(model.sources))
    fallbacks: list[str] = []
    for i in range(len(table) if method == "points" else min(1, len(table))):
        strains = strain_table[i]
        used = equilibrium(mech, model, previous, strains, i == 0, None, where(i), probe)
        runs.set_current_as_initial(model, zero_velocity=True)
        keep(SweepPoint(i, stepping.state_row(float(i), source_table[i], strains), model.truncation_readings(),
                        probe.last, used))
        previous = strains
    if method == "continuation" and len(table) > 1:
        fallbacks = continue_sweep(mech, model, source_table, strain_table, probe, stepping, where, keep)
    rows = stepping.close()
    _, _, row_strains, q, _ = stepping.layout.parts(rows)
    warn_coarse_cells(mech, cell_rotations(model, q, row_strains))
    warn_few_modes(mech, model.largest_truncation_errors(readings))
    warn_unstable(describe(mech), [(where(i) if s.state != "stable" else "", s) for i, s in states])
    unstable = [i for i, (_, s) in enumerate(states) if s.state != "stable"]
    info = {"solver": "static sweep", "sweep_method": method, "methods": ",".join(sorted(set(methods))),
            "points": len(table), "unstable_points": ",".join(map(str, unstable))}
    if method == "continuation":
        info["continued_points"] = len(table) - 1 - len(fallbacks)
        info["fallback_points"] = " | ".join(fallbacks)
    return stepping.result(info, base=("point", "-"))


def simulate(mech: Mechanism, t_end: float, step: float = DEFAULT_STEP, settings: Any = None,
             progress: Callable[[float, float], None] | None = None, record_every: Any = None, *,
             sources: Sequence[Any] | None = None, stroke_path: str = "prestep",
             built: mb.MechanismModel | None = None) -> Result:
    """Dynamic response of a mechanism to its drives' voltage programs (see :func:`exudyn_atcm.simulate`).

    The same checks as for an actuator (:mod:`exudyn_atcm.solve.run_checks`): the step against every
    drive's voltage program and against the lowest first-frequency estimate of the benders
    and flexures, the step used when it does not divide ``t_end``, a warning up front for a
    long run (cells of all benders and flexures plus the links), one voltage-range and strain
    warning per drive, ``record_every``, progress, and Ctrl-C as
    :class:`~exudyn_atcm.solve.run_checks.SimulationInterrupted` carrying the partial result.
    A drive set by a controller observes the column declared with
    :meth:`Mechanism.feedback <exudyn_atcm.Mechanism.feedback>`.

    Internal choices that tests and benchmarks compare: ``sources``, one strain source per
    distinct drive in the order of ``model.sources`` (default: an
    :class:`~exudyn_atcm.model.strain_sources.InStepStrain` each; a
    :class:`~exudyn_atcm.model.strain_sources.TableStrain` follows a precomputed table), and
    ``stroke_path`` (:attr:`exudyn_atcm.cells.CellKind.stroke_paths`); ``built``: a model of ``mech``
    already built (with its own stroke path) and in its built state (:class:`~exudyn_atcm.BuiltSystem`).
    """
    t_end, grid, schedule = prepare_run(t_end, step, settings, progress, record_every)
    check_steps(mech, grid, t_end, schedule)
    model = built if built is not None else mb.build(mech, stroke_path=stroke_path)
    feedback = feedback_controllers(mech, model)
    observers = [(c, measurement_reader(model, column)) for c, column in feedback]
    for controller, _ in feedback:
        controller.reset()
    where = describe(mech)
    n_src = len(model.sources)
    # each source's drive(s), for the note on an error the user's program or controller raises
    labels = [f"drive {', '.join(repr(n) for n, j in model.drive_source.items() if j == k)} of {where}"
              for k in range(n_src)]
    # extremes over every accepted step (the record may be thinned), for the range checks
    extremes = np.array([[np.inf] * n_src, [-np.inf] * n_src, [np.inf] * n_src, [-np.inf] * n_src])
    rotations: dict[str, float] = {}  # largest relative cell rotation per bender over every accepted step
    layout = RowLayout(model)

    def block_extremes(block: np.ndarray) -> None:
        _, volts, strains, q, _ = layout.parts(block)
        for name, value in cell_rotations(model, q, strains).items():
            rotations[name] = max(value, rotations.get(name, 0.0))
        np.minimum(extremes[0], volts.min(axis=0), out=extremes[0])
        np.maximum(extremes[1], volts.max(axis=0), out=extremes[1])
        np.minimum(extremes[2], strains.min(axis=0), out=extremes[2])
        np.maximum(extremes[3], strains.max(axis=0), out=extremes[3])

    def every_step_columns(block: np.ndarray) -> np.ndarray:
        return layout.every_step_columns(block, snap_times(block[:, 0], grid.step))

    stepping = Stepping(model, sources, labels=labels, system=where, keep=schedule.take, on_block=block_extremes,
                        reduce=None if schedule.every_step else every_step_columns)
    sources = stepping.sources
    strains0 = np.zeros(n_src)
    for k, source in enumerate(sources):
        try:
            strains0[k] = source.trial(0.0)
        except Exception as exc:  # the user's own error, as it is, naming the drive
            annotate(exc, f"({labels[k]}, at the start of simulate)")
            raise
    if np.any(strains0 != 0.0) or model.loads:
        try:
            stability, note, _ = start_equilibrium(mech, model, strains0, "initial state at t = 0")
        except KeyboardInterrupt:
            raise SimulationInterrupted(0.0) from None
        except SolverError as exc:  # Ctrl-C inside Exudyn's static solver surfaces as its failure
            if is_interrupt(exc.__cause__ or exc):
                raise SimulationInterrupted(0.0) from None
            raise
        warn_unstable(where, [("the initial state at t = 0 (load factor 1: the loads in full)", stability)], note)
    model.ramp_loads, model.load_factor = False, 1.0
    sim_settings = solver_settings.dynamic_settings(t_end, grid.step)
    model.adjust_settings(sim_settings)
    solver_settings.apply_user_settings(sim_settings, settings)
    model.check_settings(sim_settings)
    clock = WallClock(progress, t_end) if progress is not None else None
    stepping.start()  # the record and its view of Exudyn's coordinates (they stay in place during a run)
    if model.stroke_path == "user_function":  # the user functions ask the sources at their t
        model.uf_strains = stepping.trial_strains
    strain_slice = slice(1 + n_src, 1 + 2 * n_src)

    def observe(t: float, row: np.ndarray) -> None:
        t = snap_time(t, grid.step)  # observed times on the step grid, as recorded
        for controller, read in observers:
            try:
                controller.observe(t, read(row[strain_slice].copy()))
            except Exception as exc:  # the user's controller: its own error, naming it
                annotate(exc, f"(raised by {type(controller).__name__}.observe at t = {t:.9g} s, the controller of "
                              f"{where})")
                raise
        if clock is not None:
            try:
                clock(t)
            except Exception as exc:
                annotate(exc, f"(raised by the progress callback at t = {t:.9g} s)")
                raise

    if observers or clock is not None:
        stepping.after_commit.append(observe)
    record = stepping.record
    stats, interrupted = integrate(
        model, sim_settings, stepping.pre_step, stepping.post_step, what=where, step=grid.step,
        last_time=lambda: snap_time(float(record.last[0]), grid.step) if record.last is not None else 0.0,
        advice="Try a smaller step, a slower voltage program, more cells, or check that the mechanism is not locked "
               "(mechanism.degrees_of_freedom()).")
    # every accepted step's row was written by the post-step hook (the guard stops passing steps
    # on after an interrupt), so the last row is the last accepted step: it closes the record
    rows = stepping.close()
    accepted = max(record.accepted - 1, 0)
    info = run_info(grid, accepted, schedule, stats,
                    hysteresis_evaluations=sum(getattr(s, "evaluations", 0) for s in sources))
    info["recorded_channels"] = layout.width - 1  # floats per accepted step besides the time
    for controller, column in feedback:
        report_controller(controller, info, f"the controller observing {column!r}")
        info["controller"]["measurement"] = column
    if record.accepted and n_src:
        check_drive_ranges(model, extremes[:2], extremes[2:])
    warn_coarse_cells(mech, rotations)
    every = record.every_step()
    every_step = layout.every_step_result(every, info) if every is not None else None
    result = stepping.result(info, snap_times(rows[:, 0], grid.step), every_step) if len(rows) else None
    if interrupted:
        t_stop = float(result["time"][-1]) if result is not None else 0.0
        mark_partial(info, t_stop, accepted)
        if result is not None:
            result.info.update(info)
        raise SimulationInterrupted(t_stop, result)
    return result


def eigenfrequencies(mech: Mechanism, n: int = 3, voltage: VoltageSpec = None, loaded: bool = False, *,
                     built: mb.MechanismModel | None = None, damping: bool = False) -> Any:
    """Lowest ``n`` eigenfrequencies [Hz] of a mechanism about its static equilibrium at ``voltage``.

    ``voltage=None`` linearises about the undeformed reference pose without loads (as for a
    lone actuator); otherwise about the equilibrium at those voltages with the mechanism's
    loads (see :func:`drive_voltages`).  The tangent stiffness includes the geometric stiffness
    of the joints' internal forces (loads, closed-loop prestress, six-bar cells bent by their
    motors), which Exudyn's own ``ComputeODE2Eigenvalues`` leaves out
    (:func:`exudyn_atcm.mbs.linear.eigenfrequencies`).  ``loaded=True`` with ``voltage=None``: about
    the equilibrium under the loads at zero strain (a lone actuator's ``tip_force``).
    ``built``: a model of ``mech`` already built and in its built state (it is left at the
    analysed state: :func:`~exudyn_atcm.mbs.solver_runs.restore_state` puts it back).
    ``damping=True`` returns ``(frequencies, damping ratios)``: each mode's ratio of the damping
    the simulation has (:func:`exudyn_atcm.mbs.linear.damped_modes`).
    """
    n = positive_int("n", n)
    announced = warn_if_large(mech, "eigenfrequencies", equilibria=int(voltage is not None or loaded), eigen=True,
                              quiet=is_announced(), stacklevel=5)
    model = built if built is not None else mb.build(mech)  # its coordinates make the eigenproblem's estimate exact
    warn_if_eigen_long(len(model.coordinates()), describe(mech), quiet=announced or is_announced(), stacklevel=5)
    if voltage is None and loaded:
        zero = np.zeros(len(model.sources))
        # the stable branch is followed; an unstable state is reported by the negative frequency itself
        start_equilibrium(mech, model, zero, "the loads at zero strain")
    elif voltage is not None:
        volts = drive_voltages(mech, voltage)
        strains = source_values(model, {k: mech.drives[k].static_strain(v) for k, v in volts.items()},
                                 "eigenfrequencies")
        check_drive_ranges(model, source_values(model, volts, "eigenfrequencies"), strains)
        start_equilibrium(mech, model, strains, describe_voltages(volts))  # a run from there takes it as solved
    else:
        model.scale_loads(0.0)
    if voltage is not None or loaded:
        warn_few_modes(mech, model.truncation_errors())
    model.before_linearisation()
    if damping:
        return linear.damped_modes(model, n)
    freqs = linear.eigenfrequencies(model, n)
    if freqs.size < n:
        raise ValueError(f"n must be <= the number of degrees of freedom ({freqs.size}), got {n}")
    return freqs
