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
from ..errors import AccuracyWarning

__all__ = ["ActuatorRecorder", "make_result", "warn_coarse_cells", "MAX_CELL_ROTATION", "STANDARD_UNITS"]

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
    """Post-step hook: commits the strain source and stores the recorded steps' state.

    Every accepted step is committed; :class:`~exudyn_atcm.model.recording.RecordingSchedule`
    decides which are stored (the last accepted step always is).  Recorded times are put on
    the step grid where they are within round-off of it (:func:`~exudyn_atcm.solve.run_checks.snap_time`,
    applied to the whole record when the result is made).
    """

    def __init__(self, model, source, progress=None, t_end: float = 1.0, step: float | None = None,
                 schedule: RecordingSchedule | None = None) -> None:
        self.model = model
        self.source = source
        # closed loop: the drive's controller observes every accepted step's tip deflection
        self.controller = getattr(getattr(source, "drive", None), "controller", None)
        self.index = model.record_indices
        index = self.index
        # q[record_indices] after every accepted step; a model may offer a quicker read
        self._read = getattr(model, "recorded_coordinates", None) or (lambda: model.coordinates()[index])
        self.scalars: list[tuple] = []
        self.states: list[np.ndarray] = []
        self.progress = WallClock(progress, t_end) if progress is not None else None
        self.t_end = t_end
        self.step = step
        self.schedule = schedule
        self.accepted = 0
        self._pending = None
        self._last_t = 0.0
        #: lowest and highest committed strain [-] over every accepted step (the record may be thinned)
        self.strain_low = math.inf
        self.strain_high = -math.inf

    def post_step(self, t: float) -> None:
        # hot path (every accepted step): recorded times are put on the grid once, vectorised,
        # when the result is made (_snap); the schedule's own tolerance absorbs the round-off
        u, strain = self.source.commit(t)
        self.accepted += 1
        if strain < self.strain_low:
            self.strain_low = strain
        if strain > self.strain_high:
            self.strain_high = strain
        self._last_t = t
        if self.schedule is None or self.schedule.take(t):
            self.scalars.append((t, u, strain))
            self.states.append(self._read())
            self._pending = None
        else:
            self._pending = (t, u, strain, self._read())
        if self.controller is not None or self.progress is not None:
            t = self._snap(t)
            if self.controller is not None:
                # closed loop: the controller observes the accepted step's tip deflection
                self.controller.observe(t, self.model.read_state(self.model.coordinates(), strain)[1])
            if self.progress is not None:
                self.progress(t)

    def _snap(self, t: float) -> float:
        return snap_time(t, self.step) if self.step is not None else t

    def close(self) -> None:
        """Add the last accepted step if the schedule skipped it."""
        if self._pending is not None:
            t, u, strain, state = self._pending
            self.scalars.append((t, u, strain))
            self.states.append(state)
            self._pending = None

    @property
    def n_rows(self) -> int:
        return len(self.scalars)

    def last_time(self) -> float:
        """Time [s] of the last accepted step (0 before the first)."""
        if self._pending is not None:
            return self._snap(self._pending[0])
        return self._snap(self.scalars[-1][0]) if self.scalars else 0.0

    def result(self, actuator: BendingActuator, info: dict) -> Result:
        self.close()
        scalars = np.array(self.scalars, dtype=float).reshape(-1, 3)
        if self.step is not None:
            scalars[:, 0] = snap_times(scalars[:, 0], self.step)
        states = np.array(self.states, dtype=float).reshape(len(self.states), self.index.size)
        x, y, a, angles = self.model.states_from_records(states, scalars[:, 2])
        rows = np.column_stack([scalars, x, y, a])
        return make_result(actuator, rows, angles, info)


def make_result(actuator: BendingActuator, rows: np.ndarray, angles: np.ndarray, info: dict) -> Result:
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
    for j in range(actuator.n_cells):
        series[f"cell_angle_{j + 1}"] = angles[:, j]
        units[f"cell_angle_{j + 1}"] = "rad"
    info = dict(info)
    info.setdefault("exudyn_version", runs.exudyn_version())
    warn_coarse_cells(actuator, angles)
    result = Result(series, units, parameters=actuator.parameters(), info=info)
    for name in result:
        values = result[name]
        if values.size and not np.all(np.isfinite(values)):
            bad = int(np.argmax(~np.isfinite(values)))
            raise SolverError(
                f"the solution contains a non-finite {name} at row {bad} (t = {rows[bad, 0]!r} s); "
                "the solver diverged. Try a smaller step or more cells."
            )
    return result


#: Largest rotation of one cell relative to its neighbour [rad] before a warning is issued.
MAX_CELL_ROTATION = 0.5


def warn_coarse_cells(actuator: BendingActuator, angles: np.ndarray) -> None:
    """Warn when a cell turns by more than :data:`MAX_CELL_ROTATION` (coarse discretisation)."""
    if angles.size == 0 or not actuator.cell.chain_of_cells:
        # e.g. the ritz model's columns are segments of one continuous rotation field, not cells
        # of a chain: its statics are exact at any n (docs: actuator page)
        return
    # passive bar j sits at the mean of its interfaces: the first bar turns half a cell
    padded = np.concatenate([-angles[:, :1], angles], axis=1)
    per_cell = float(np.max(np.abs(np.diff(padded, axis=1))))
    if per_cell > MAX_CELL_ROTATION:
        warnings.warn(
            f"a cell of the {actuator.cell} actuator turns by {per_cell:.3g} rad relative to its "
            f"neighbour (more than {MAX_CELL_ROTATION} rad): with {actuator.n_cells} cells the chain is a "
            "coarse discretisation of the bent actuator; use more cells",
            AccuracyWarning,
            stacklevel=3,
        )
