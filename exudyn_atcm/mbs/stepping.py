"""The one pre-step, post-step and recorder of every solve of a built mechanism model.

:func:`exudyn_atcm.simulate`, :func:`exudyn_atcm.solve_static`, :func:`exudyn_atcm.static_sweep`
and :func:`exudyn_atcm.add_to` step and record through a :class:`Stepping` object; this module is
the one place where the drives' hysteresis is trialled and committed:

* :meth:`Stepping.pre_step` (before every attempted step): every strain source's trial from its
  committed memory (:meth:`InStepStrain.trial <exudyn_atcm.model.strain_sources.InStepStrain.trial>`),
  written into the system (actuation, follower loads);
* :meth:`Stepping.post_step` (after every accepted step, Exudyn calls it for accepted steps only, and
  once for the initial state at ``t = 0``): every source committed once
  (:meth:`InStepStrain.commit <exudyn_atcm.model.strain_sources.InStepStrain.commit>`) and the step
  written as one row into the :class:`~exudyn_atcm.mbs.step_record.StepRecord`;
* :meth:`Stepping.hold_path` (static sweeps): every operator committed once per point, the voltage held for ever;
  :meth:`Stepping.record_state` writes an equilibrium into the same record (:meth:`Stepping.state_row` and
  :meth:`Stepping.record_row` in two parts, for a sweep that keeps a state only once it is checked).

The rows are cut back into result columns by :class:`~exudyn_atcm.mbs.recording.RowLayout`, so a
result of :func:`~exudyn_atcm.simulate` and of :meth:`MechanismHandle.result
<exudyn_atcm.mbs.user_system.MechanismHandle.result>` have the same columns made by the same code.
"""

from __future__ import annotations

from typing import Any, Callable, Sequence

import numpy as np

from ..errors import annotate
from ..io.result import Result
from ..model.strain_sources import InStepStrain
from .model import MechanismModel
from .recording import RowLayout
from .step_record import StepRecord, check_view

__all__ = ["Stepping", "held_strain"]

#: ``note(hook, t, label)``: the note added to an error of the user's code in a hook
Note = Callable[[str, float, str], str]


def _plain_note(hook: str, t: float, label: str) -> str:
    return f"({label})"


def held_strain(drive: Any, u: float) -> float:
    """Commit ``drive``'s operator at voltage ``u`` [V] held for ever; its strain [-].

    An operator with creep or a rate lag gives its fully crept output (``commit_held``); a drive
    without hysteresis its linear strain.
    """
    hysteresis = drive.hysteresis
    if hysteresis is None:
        return drive.linear_strain(u)
    return float(getattr(hysteresis, "commit_held", hysteresis.commit)(u))


class _Held:
    """The source of a static solve: its drive only (:meth:`Stepping.hold_path` commits it)."""

    def __init__(self, drive: Any) -> None:
        self.drive = drive


class Stepping:
    """Trial and commit of every drive's hysteresis and the record of every accepted step of one solve.

    Parameters
    ----------
    model : MechanismModel
        The built model (:func:`~exudyn_atcm.mbs.builder.build` or :func:`~exudyn_atcm.add_to`).
    sources : sequence, optional
        One strain source per entry of ``model.sources`` (default: an
        :class:`~exudyn_atcm.model.strain_sources.InStepStrain` each, which resets the drive's operator).
    labels : sequence of str, optional
        Per source, the words naming its drive(s) in an error note.
    note : callable, optional
        ``note(hook, t, label) -> str``: the note on an error of the user's code (program,
        controller, load function) in the ``"pre"`` or ``"post"`` hook at ``t`` [s].
    system : str, optional
        The system in the note on an error writing the strains and loads (``"mechanism 'm'"``).
    keep : callable, optional
        ``keep(t) -> bool``: whether an accepted step joins the record (default: every step).
    reduce, on_block : callable, optional
        Passed to :class:`~exudyn_atcm.mbs.step_record.StepRecord`.
    fixed_view : bool, optional
        Read Exudyn's coordinate vector through one view taken at the first post step (the
        package's own runs; checked by :meth:`close`).  ``False`` (``add_to``): a fresh view per step,
        since the user may assemble the system again between solves.

    Attributes
    ----------
    commits : int
        Accepted steps committed (post steps, including the initial state at ``t = 0``).
    after_commit : list of callable
        ``f(t, row)`` called after each committed step's row is written (observers, progress).
    """

    def __init__(self, model: MechanismModel, sources: Sequence[Any] | None = None, *,
                 labels: Sequence[str] | None = None, note: Note | None = None, system: str | None = None,
                 keep: Callable[[float], bool] | None = None, reduce: Callable[[np.ndarray], np.ndarray] | None = None,
                 on_block: Callable[[np.ndarray], None] | None = None, fixed_view: bool = True) -> None:
        self.model = model
        if sources is None:
            sources = [InStepStrain(drive) for drive in model.sources]
        elif len(sources) != len(model.sources):
            raise ValueError(f"sources: one strain source per drive ({len(model.sources)}), got {len(sources)}")
        self.sources = list(sources)
        n = len(self.sources)
        self.labels = list(labels) if labels is not None else [f"source {k}" for k in range(n)]
        self.note = note or _plain_note
        self.system = system or f"mechanism {model.mechanism.name!r}"
        self.trial = np.zeros(n)  # the attempted step's strains, written in place (the hot path)
        self.commits = 0
        self.after_commit: list[Callable[[float, np.ndarray], Any]] = []
        self._keep = keep or (lambda t: True)
        self._reduce, self._on_block = reduce, on_block
        self._fixed_view = fixed_view
        self._indexed = list(enumerate(self.sources))
        self._only_trial = getattr(self.sources[0], "trial", None) if n == 1 else None
        self._write: Callable[[np.ndarray], None] | None = None
        self.layout: RowLayout | None = None
        self.record: StepRecord | None = None
        self._q_view: np.ndarray | None = None
        self._plan: tuple | None = None

    @classmethod
    def static(cls, model: MechanismModel) -> "Stepping":
        """The recorder of a static solve: no strain sources (the operators are left as they are; see :meth:`hold_path`)."""
        return cls(model, [_Held(drive) for drive in model.sources])

    # ------------------------------------------------------------------ set-up
    def start(self) -> None:
        """Make the record for the assembled system (done by the first post step if not called)."""
        model = self.model
        self.layout = layout = RowLayout(model)
        self.record = StepRecord(layout.width, self._keep, reduce=self._reduce, on_block=self._on_block)
        n = len(self.sources)
        read_forces = model.connector_reader() if layout.n_forces else None  # its plan made once
        self._q_view = model.coordinates() if self._fixed_view else None
        q_slice = slice(1 + 2 * n, 1 + 2 * n + layout.n_coordinates)
        self._plan = ([(source, 1 + k, 1 + n + k, self.labels[k]) for k, source in self._indexed], q_slice,
                      slice(1 + 2 * n + layout.n_coordinates, None), read_forces)

    def trial_strains(self, t: float) -> np.ndarray:
        """Every source's trial strain [-] at ``t`` [s] (in the run's array; no side effect on the memories)."""
        trial = self.trial
        for k, source in self._indexed:
            trial[k] = source.trial(t)
        return trial

    # ------------------------------------------------------------------ the hooks
    def pre_step(self, t: float) -> None:
        """Before every attempted step ending at ``t`` [s]: trial strains, written into the system."""
        model = self.model
        model.time = t
        trial = self.trial
        k = 0
        try:
            if self._only_trial is not None:  # one drive (every lone bender): no loop
                trial[0] = self._only_trial(t)
            else:
                for k, source in self._indexed:
                    trial[k] = source.trial(t)
            k = -1
            if self._write is None or model.strains is not trial:
                model.strains = trial  # the run's array: written in place, the model reads it
                self._write = model.strain_writer()
            self._write(trial)
        except Exception as exc:
            label = self.labels[k] if k >= 0 else f"writing the strains and loads of {self.system}"
            annotate(exc, self.note("pre", t, label))
            raise

    def post_step(self, t: float) -> np.ndarray:
        """After the accepted step ending at ``t`` [s]: commit every source once, record the step; the row."""
        if self.record is None:
            self.start()
        commits, q_slice, force_slice, read_forces = self._plan
        record = self.record
        row = record.begin(t)  # hot path: element writes into the preallocated block
        for source, volt_column, strain_column, label in commits:
            try:
                row[volt_column], row[strain_column] = source.commit(t)
            except Exception as exc:  # the user's program (called when the trial's time differs)
                annotate(exc, self.note("post", t, label))
                raise
        self.commits += 1
        row[q_slice] = self._q_view if self._q_view is not None else self.model.coordinates()
        if read_forces is not None:
            row[force_slice] = read_forces()
        record.end(t)
        for f in self.after_commit:
            f(t, row)
        return row

    # ------------------------------------------------------------------ statics
    def hold_path(self, volts: np.ndarray) -> np.ndarray:
        """Strains [-] at rows ``volts`` [V] (one column per source), each row held for ever, in order from
        every operator's reset state (each row committed once)."""
        drives = [source.drive for source in self.sources]
        for drive in drives:
            if drive.hysteresis is not None:
                drive.hysteresis.reset()
        strains = np.array([[held_strain(d, float(u)) for d, u in zip(drives, row)] for row in volts])
        return strains.reshape(np.shape(volts))

    def record_state(self, t: float, volts: np.ndarray, strains: np.ndarray) -> None:
        """Record the model's current (equilibrium) state as a row at ``t`` (a time [s] or a point index)."""
        self.record_row(self.state_row(t, volts, strains))

    def state_row(self, t: float, volts: np.ndarray, strains: np.ndarray) -> np.ndarray:
        """The row :meth:`record_state` would record for the model's current state, as an array of its own (for
        a state that joins the record only once it is known to be kept: :meth:`record_row`)."""
        if self.record is None:
            self.start()
        n = len(self.sources)
        _, q_slice, force_slice, read_forces = self._plan
        row = np.empty(self.record.width)
        row[0] = t
        row[1:1 + n], row[1 + n:1 + 2 * n] = volts, strains
        row[q_slice] = self.model.coordinates()
        if read_forces is not None:
            row[force_slice] = read_forces()
        return row

    def record_row(self, row: np.ndarray) -> None:
        """Add a row of :meth:`state_row` to the record."""
        if self.record is None:
            self.start()
        self.record.begin(row[0])[:] = row
        self.record.end(row[0])

    # ------------------------------------------------------------------ the result
    def close(self) -> np.ndarray:
        """Close the record (the last accepted step joins it); the kept rows."""
        if self.record is None:
            self.start()
        self.record.close()
        if self._q_view is not None:
            check_view(self._q_view, self.model.coordinates())
        return self.record.rows()

    def result(self, info: dict, times: np.ndarray | None = None, every_step: Result | None = None,
               base: tuple[str, str] = ("time", "s")) -> Result:
        """The :class:`~exudyn_atcm.Result` of the kept rows (call :meth:`close` first); ``times``: the first
        column (default: the recorded times)."""
        rows = self.record.rows()
        return self.layout.result(rows, rows[:, 0] if times is None else times, info, every_step, base=base)
