"""Recording of the lone actuator's runs: the post-step recorder and the result it makes.

Internal API of the solve layer (documented for tests and benchmarks): :class:`ActuatorRecorder`
commits the strain source on every accepted step and stores the recorded ones;
:func:`make_result` turns rows into a :class:`~exudyn_atcm.Result` and checks them.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from ..errors import SolverError
from ..io.result import Result
from ..mbs import solver_runs as runs
from ..mechanism.actuator import BendingActuator
from ..model.recording import RecordingSchedule
from .run_checks import WallClock, snap_time, snap_times
from .step_record import StepRecord, check_view
from ..errors import AccuracyWarning

__all__ = ["ActuatorRecorder", "make_result", "warn_coarse_cells", "cell_rotation", "MAX_CELL_ROTATION",
           "STANDARD_UNITS"]

STANDARD_UNITS = {
    "time": "s",
    "voltage": "V",
    "strain": "-",
    "stroke": "m",
    "tip_x": "m",
    "tip_y": "m",
    "tip_angle": "rad",
}




class ActuatorRecorder:
    """Post-step hook: commits the strain source and records every accepted step.

    Every accepted step is committed and written to a :class:`~exudyn_atcm.solve.step_record.StepRecord`
    (time, voltage, strain and the coordinates the result needs); the
    :class:`~exudyn_atcm.model.recording.RecordingSchedule` decides which rows form the record
    (the last accepted step always does).  When the schedule thins the record, the light
    columns (:data:`EVERY_STEP_COLUMNS`) of every accepted step are kept as well
    (:attr:`exudyn_atcm.Result.every_step`).  Recorded times are put on the step grid where
    they are within round-off of it (:func:`~exudyn_atcm.solve.run_checks.snap_times`, applied
    to the whole record when the result is made).
    """

    def __init__(self, model, source, progress=None, t_end: float = 1.0, step: float | None = None,
                 schedule: RecordingSchedule | None = None, cell_length: float = 0.0) -> None:
        self.model = model
        self.source = source
        # closed loop: the drive's controller observes every accepted step's tip deflection
        self.controller = getattr(getattr(source, "drive", None), "controller", None)
        self.index = model.record_indices
        index = self.index
        # q[record_indices] after every accepted step, read through one view of Exudyn's coordinate
        # vector taken before the run (it stays in place during a run; checked when the result is made)
        self._view = view = model.coordinates()
        whole = index.size == view.size and np.array_equal(index, np.arange(view.size))
        self._read = (lambda: view) if whole else (lambda: view[index])
        self.progress = WallClock(progress, t_end) if progress is not None else None
        self.t_end = t_end
        self.step = step
        self.schedule = schedule
        self.cell_length = cell_length
        thinned = schedule is not None and not schedule.every_step
        self.rows = StepRecord(3 + index.size, schedule.take if schedule is not None else _always,
                               reduce=self._every_step_columns if thinned else None, on_block=self._extremes)
        #: lowest and highest committed strain [-] over every accepted step (the record may be thinned)
        self.strain_low = math.inf
        self.strain_high = -math.inf
        #: largest rotation of a cell relative to its neighbour over every accepted step [rad]
        self.max_cell_rotation = 0.0

    @property
    def accepted(self) -> int:
        """Accepted steps recorded so far (the t = 0 post-step included)."""
        return self.rows.accepted

    def post_step(self, t: float) -> None:
        # hot path (every accepted step): one row written into a preallocated block; recorded
        # times are put on the grid once, vectorised, when the result is made
        u, strain = self.source.commit(t)
        row = self.rows.begin(t)
        row[1] = u
        row[2] = strain
        row[3:] = self._read()
        self.rows.end(t)
        if self.controller is not None or self.progress is not None:
            t = self._snap(t)
            if self.controller is not None:
                # closed loop: the controller observes the accepted step's tip deflection
                self.controller.observe(t, self.model.read_state(self._view, strain)[1])
            if self.progress is not None:
                self.progress(t)

    def _snap(self, t: float) -> float:
        return snap_time(t, self.step) if self.step is not None else t

    def _extremes(self, rows: np.ndarray) -> None:
        strains = rows[:, 2]
        self.strain_low = min(self.strain_low, float(strains.min()))
        self.strain_high = max(self.strain_high, float(strains.max()))

    def _columns(self, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The result's columns (time, voltage, strain, tip x, y, angle) and the cell angles of ``rows``."""
        times = snap_times(rows[:, 0], self.step) if self.step is not None else rows[:, 0].copy()
        x, y, a, angles = self.model.states_from_records(rows[:, 3:], rows[:, 2])
        angles = np.asarray(angles, dtype=float).reshape(len(rows), -1)
        self.max_cell_rotation = max(self.max_cell_rotation, cell_rotation(angles))
        return np.column_stack([times, rows[:, 1], rows[:, 2], x, y, a]), angles

    def _every_step_columns(self, rows: np.ndarray) -> np.ndarray:
        return self._columns(rows)[0]

    def close(self) -> None:
        """Flush the last block; the last accepted step joins the record if the schedule skipped it."""
        self.rows.close()

    def last_time(self) -> float:
        """Time [s] of the last accepted step (0 before the first)."""
        return self._snap(float(self.rows.last[0])) if self.rows.last is not None else 0.0

    def result(self, actuator: BendingActuator, info: dict) -> Result:
        self.close()
        check_view(self._view, self.model.coordinates())
        columns, angles = self._columns(self.rows.rows())
        every = self.rows.every_step()
        every_step = None
        if every is not None:
            every_step = make_result(actuator, every, np.empty((len(every), 0)), info, warn=False)
        return make_result(actuator, columns, angles, info, every_step=every_step,
                           max_cell_rotation=self.max_cell_rotation)


def _always(t: float) -> bool:
    return True


def cell_rotation(angles: np.ndarray) -> float:
    """Largest rotation [rad] of a cell relative to its neighbour in rows of cell angles."""
    if angles.size == 0:
        return 0.0
    # passive bar j sits at the mean of its interfaces: the first bar turns half a cell
    padded = np.concatenate([-angles[:, :1], angles], axis=1)
    return float(np.max(np.abs(np.diff(padded, axis=1))))


def make_result(actuator: BendingActuator, rows: np.ndarray, angles: np.ndarray, info: dict, *,
                every_step: Result | None = None, max_cell_rotation: float | None = None,
                warn: bool = True) -> Result:
    """The :class:`~exudyn_atcm.Result` of rows ``(time, voltage, strain, tip_x, tip_y, tip_angle)``.

    ``angles`` holds the cell angles per row (no columns for the every-step result); ``every_step``
    is attached as :attr:`Result.every_step <exudyn_atcm.Result.every_step>`;
    ``max_cell_rotation`` [rad] is the largest relative cell rotation over every accepted step
    (default: over ``angles``), warned about with ``warn``.

    Raises
    ------
    SolverError
        For a non-finite value, naming the column, the row and its time.
    """
    series = {
        "time": rows[:, 0],
        "voltage": rows[:, 1],
        "strain": rows[:, 2],
        "stroke": rows[:, 2] * actuator.cell_length,
        "tip_x": rows[:, 3],
        "tip_y": rows[:, 4],
        "tip_angle": rows[:, 5],
    }
    units = dict(STANDARD_UNITS)
    for j in range(angles.shape[1]):
        series[f"cell_angle_{j + 1}"] = angles[:, j]
        units[f"cell_angle_{j + 1}"] = "rad"
    info = dict(info)
    info.setdefault("exudyn_version", runs.exudyn_version())
    if warn:
        warn_coarse_cells(actuator, cell_rotation(angles) if max_cell_rotation is None else max_cell_rotation)
    for name, values in series.items():
        values = np.asarray(values)
        if values.size and not np.all(np.isfinite(values)):
            bad = int(np.argmax(~np.isfinite(values)))
            raise SolverError(
                f"the solution contains a non-finite {name} at row {bad} (t = {rows[bad, 0]!r} s); "
                "the solver diverged. Try a smaller step or more cells."
            )
    return Result(series, units, parameters=actuator.parameters(), info=info, every_step=every_step)


#: Largest rotation of one cell relative to its neighbour [rad] before a warning is issued.
MAX_CELL_ROTATION = 0.5


def warn_coarse_cells(actuator: BendingActuator, per_cell: float) -> None:
    """Warn when a cell turned by more than :data:`MAX_CELL_ROTATION` [rad] relative to its neighbour."""
    if not actuator.cell.chain_of_cells:
        # e.g. the ritz model's columns are segments of one continuous rotation field, not cells
        # of a chain: its statics are exact at any n (docs: actuator page)
        return
    if per_cell > MAX_CELL_ROTATION:
        warnings.warn(
            f"a cell of the {actuator.cell} actuator turns by {per_cell:.3g} rad relative to its "
            f"neighbour (more than {MAX_CELL_ROTATION} rad): with {actuator.n_cells} cells the chain is a "
            "coarse discretisation of the bent actuator; use more cells",
            AccuracyWarning,
            stacklevel=3,
        )
