"""The lone actuator solved as what it is: a one-bender mechanism.

:func:`exudyn_atcm.simulate`, :func:`exudyn_atcm.solve_static`,
:func:`exudyn_atcm.static_sweep` and :func:`exudyn_atcm.eigenfrequencies` solve a
:class:`~exudyn_atcm.BendingActuator` as its one-bender :class:`~exudyn_atcm.Mechanism`
(:meth:`BendingActuator.as_mechanism <exudyn_atcm.BendingActuator.as_mechanism>`: base welded to the
ground at the origin, along +x, a dead tip force at the tip) with the mechanism solves of
:mod:`exudyn_atcm.solve.mechanism_solve` (one builder, one recorder, one set of run checks).  The
result (:func:`actuator_result`) holds the actuator's columns (``tip_y``, ...) and reads every column
of any bender under its mechanism name as well (``actuator.tip_y``, ``actuator.base_x``, ...).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from ..io.result import Result
from ..mechanism.actuator import NAME, BendingActuator
from ..mechanism.assembly import Mechanism

from .interrupts import SimulationInterrupted

__all__ = ["actuator_mechanism", "actuator_result", "actuator_interrupts", "NAME", "STANDARD_UNITS"]

#: Units of an actuator result's columns besides ``cell_angle_j`` [rad].
STANDARD_UNITS = {"time": "s", "voltage": "V", "strain": "-", "stroke": "m", "tip_x": "m", "tip_y": "m",
                  "tip_angle": "rad"}


def actuator_mechanism(actuator: BendingActuator, tip_force: tuple[float, float] = (0.0, 0.0)) -> Mechanism:
    """``actuator.as_mechanism(tip_force)`` (see :meth:`~exudyn_atcm.BendingActuator.as_mechanism`)."""
    return actuator.as_mechanism(tip_force)


def _columns(actuator: BendingActuator, r: Result, cells: bool) -> tuple[dict, dict]:
    base = "time" if "time" in r else "point"
    p = f"{NAME}."
    series = {base: r[base], "voltage": r[p + "voltage"], "strain": r[p + "strain"],
              "stroke": r[p + "strain"] * actuator.cell_length, "tip_x": r[p + "tip_x"],
              "tip_y": r[p + "tip_y"], "tip_angle": r[p + "tip_angle"]}
    units = dict(STANDARD_UNITS)
    units[base] = r.unit(base)
    if cells:
        for j in range(actuator.n_cells):
            series[f"cell_angle_{j + 1}"] = r[f"{p}cell_angle_{j + 1}"]
            units[f"cell_angle_{j + 1}"] = "rad"
    return series, units


def actuator_result(actuator: BendingActuator, r: Result) -> Result:
    """The columns of :func:`exudyn_atcm.simulate` for an actuator from its one-bender mechanism's result
    (``time`` or ``point``, ``voltage``, ``strain``, ``stroke``, ``tip_x``, ``tip_y``, ``tip_angle``,
    ``cell_angle_1..N``), with the every-step columns when the record was thinned; the mechanism's own
    columns (``actuator.tip_y``, ...) stay readable by name (:attr:`Result.bender_columns
    <exudyn_atcm.Result.bender_columns>`), so a lone actuator's result reads like any bender's.
    """
    series, units = _columns(actuator, r, cells=True)
    every = None
    if r.every_step is not r:
        every = Result(*_columns(actuator, r.every_step, cells=False), parameters=actuator.parameters(),
                       info=r.every_step.info, bender_columns=r.every_step)
    return Result(series, units, parameters=actuator.parameters(), info=r.info, every_step=every,
                  bender_columns=r)


@contextmanager
def actuator_interrupts(actuator: BendingActuator) -> Iterator[None]:
    """Turn the partial result of an interrupted one-bender mechanism run into the actuator's columns."""
    try:
        yield
    except SimulationInterrupted as stop:
        if stop.result is not None:
            stop.result = actuator_result(actuator, stop.result)
        raise
