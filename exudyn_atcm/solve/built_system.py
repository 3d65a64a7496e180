"""A mechanism realised once into an Exudyn system and solved again without rebuilding.

:func:`exudyn_atcm.simulate`, :func:`exudyn_atcm.solve_static` and :func:`exudyn_atcm.static_sweep`
build a new Exudyn ``MainSystem`` for every call.  A :class:`BuiltSystem` builds it once and
solves it as often as asked: each solve starts from the state the build left (the reference
pose, zero strains, the loads in full, the drives' operators reset), so a re-solve gives what a
fresh build gives (``tests/test_one_stepping.py``); the saving is measured in
``benchmarks/bench_rebuild.py``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, Callable

import numpy as np

from .._checks import positive_float, positive_int
from ..io.result import Result
from ..mbs import builder as mb
from ..mbs import solver_runs as runs
from ..mechanism.assembly import Mechanism
from ..mechanism.build_cost import warn_if_large
from .long_runs import is_announced
from . import mechanism_solve
from .bender_checks import check_benders
from .linearise import linearise_model
from .modes import Modes, modes_of_state, modes_state
from .run_setup import DEFAULT_STEP
from .state_space import LinearModel
from .step_choice import accurate_run, check_step_or_accuracy

__all__ = ["BuiltSystem"]


class BuiltSystem:
    """A mechanism built into its Exudyn system once, for many solves.

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism, checked and built here (the dear part for many cells).
    stroke_path : str, optional
        How the strains reach the system (:attr:`exudyn_atcm.cells.CellKind.stroke_paths`), as
        for :func:`exudyn_atcm.simulate`.

    Attributes
    ----------
    mechanism : Mechanism
        The mechanism built.
    builds : int
        Exudyn systems built so far: 1, plus one for each solve that found the mechanism changed
        (its :meth:`~exudyn_atcm.Mechanism.parameters`: parts, joints, loads added or changed),
        which is then built again so that a result never describes an older mechanism.

    Notes
    -----
    Every solve starts from the built state: the reference pose at rest, zero strains, the
    loads in full, and (through :class:`~exudyn_atcm.mbs.stepping.Stepping`) the drives'
    hysteresis reset; the results equal those of the one-off functions for the same mechanism
    and arguments.  Other voltages (``voltage``/``voltages``), other run lengths, steps and
    settings need no new build.

    Examples
    --------
    >>> built = BuiltSystem(four_bar)                                      # doctest: +SKIP
    >>> paths = [built.solve_static(voltage=v) for v in (0.0, 250.0, 500.0)]  # doctest: +SKIP
    """

    def __init__(self, mechanism: Mechanism, *, stroke_path: str = "prestep") -> None:
        if not isinstance(mechanism, Mechanism):
            raise ValueError(f"mechanism must be a Mechanism, got {type(mechanism).__name__} ({mechanism!r})")
        self.mechanism = mechanism
        self.stroke_path = stroke_path
        self.builds = 0
        self._build()

    def _build(self) -> None:
        warn_if_large(self.mechanism, "BuiltSystem", equilibria=1, quiet=is_announced(), stacklevel=4)
        self.model = mb.build(self.mechanism, stroke_path=self.stroke_path)
        self._initial = runs.save_state(self.model)
        self._parameters = repr(self.mechanism.parameters())
        self.builds += 1

    def _fresh(self) -> mb.MechanismModel:
        """The model in its built state (built again if the mechanism changed since)."""
        if repr(self.mechanism.parameters()) != self._parameters:
            self._build()
        else:
            runs.restore_state(self.model, self._initial)
        return self.model

    def solve_static(self, voltage: float | Mapping[str, float] | None = None, *,
                     load_steps: int | None = None) -> Result:
        """Static equilibrium at ``voltage`` [V] (a number, or ``{drive: volts}``) with the mechanism's loads.

        As :func:`exudyn_atcm.solve_static` for a mechanism.
        """
        return mechanism_solve.solve_static(self.mechanism, voltage, load_steps, built=self._fresh())

    def static_sweep(self, voltages: Sequence[float] | Mapping[str, Sequence[float]]) -> Result:
        """Quasi-static path over a voltage sequence [V]; as :func:`exudyn_atcm.static_sweep` for a mechanism."""
        return mechanism_solve.static_sweep(self.mechanism, voltages, built=self._fresh())

    def simulate(self, t_end: float, *, step: float | None = None, settings: Any = None,
                 progress: Callable[[float, float], None] | None = None, record_every: Any = None,
                 accuracy: float | None = None) -> Result:
        """Dynamic response over ``t_end`` [s] with time step ``step`` [s] (default 1e-4), or the step chosen for
        ``accuracy`` [-]; as :func:`exudyn_atcm.simulate` for a mechanism (the same checks, warnings,
        ``record_every``, progress and Ctrl-C; the probe runs of ``accuracy`` reuse this build)."""
        if check_step_or_accuracy(step, accuracy) is not None:
            t_end = positive_float("t_end", t_end)

            def run(h: float, prog: Any, t_stop: float) -> Result:
                result = mechanism_solve.simulate(self.mechanism, t_stop, h, settings, prog, record_every,
                                                  stroke_path=self.stroke_path, built=self._fresh())
                check_benders(self.mechanism, result, stacklevel=5)
                return result
            return accurate_run(run, self.mechanism, t_end, float(accuracy), progress, record_every=record_every,
                                built=self._fresh)
        step = DEFAULT_STEP if step is None else step
        result = mechanism_solve.simulate(self.mechanism, t_end, step, settings, progress, record_every,
                                          stroke_path=self.stroke_path, built=self._fresh())
        check_benders(self.mechanism, result, stacklevel=3)  # every bender's cell-kind checks, at the caller's line
        return result

    def modes(self, n: int = 3, *, voltage: float | Mapping[str, float] | None = None, loaded: bool = False) -> Modes:
        """The ``n`` lowest modes about the static equilibrium at ``voltage``; as :func:`exudyn_atcm.modes`."""
        n = positive_int("n", n)
        return modes_of_state(modes_state(self.mechanism, voltage, loaded, model=self._fresh()), n)

    def eigenfrequencies(self, n: int = 3, *, voltage: float | Mapping[str, float] | None = None,
                         loaded: bool = False) -> np.ndarray:
        """The ``n`` lowest eigenfrequencies [Hz] (the frequencies of :meth:`modes`; as
        :func:`exudyn_atcm.eigenfrequencies` for a mechanism)."""
        return self.modes(n, voltage=voltage, loaded=loaded).frequencies

    def linearise(self, *, voltage: float | Mapping[str, float] | None = None, inputs: Sequence[str] | None = None,
                  outputs: Sequence[str], branch: str = "ascending", voltage_step: float = 1.0) -> LinearModel:
        """A state-space model about the static equilibrium at ``voltage``; as :func:`exudyn_atcm.linearise`."""
        return linearise_model(self.mechanism, self._fresh(), voltage=voltage, inputs=inputs, outputs=outputs,
                               branch=branch, voltage_step=voltage_step)

    def __repr__(self) -> str:
        return f"BuiltSystem({self.mechanism.name!r}, builds={self.builds})"
