"""The lone actuator solved as what it is: a one-bender mechanism.

:func:`exudyn_atcm.simulate`, :func:`exudyn_atcm.solve_static`,
:func:`exudyn_atcm.static_sweep` and :func:`exudyn_atcm.eigenfrequencies` solve a
:class:`~exudyn_atcm.BendingActuator` as its one-bender :class:`~exudyn_atcm.Mechanism`
(:meth:`BendingActuator.as_mechanism <exudyn_atcm.BendingActuator.as_mechanism>`: base welded to the
ground at the origin, along +x, a dead tip force at the tip) with the mechanism solves of
:mod:`exudyn_atcm.solve.mechanism_solve` (one builder, one recorder, one set of run checks).  The
result (:func:`actuator_result`) holds the mechanism's columns (``actuator.tip_y``, ...) plus
``actuator.stroke``, named like any bender's.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from ..io.result import Result
from ..mechanism.actuator import NAME, BendingActuator
from ..mechanism.assembly import Mechanism

from .interrupts import SimulationInterrupted

__all__ = ["actuator_mechanism", "actuator_result", "actuator_interrupts", "NAME", "OLD_NAMES"]

#: The column names of a lone actuator's result before 0.3.0, each to its name now (``cell_angle_j`` ->
#: ``actuator.cell_angle_j`` besides); readable for one release with an AtcmDeprecationWarning.
OLD_NAMES = {old: f"{NAME}.{old}" for old in ("voltage", "strain", "stroke", "tip_x", "tip_y", "tip_angle")}

def actuator_mechanism(actuator: BendingActuator, tip_force: tuple[float, float] = (0.0, 0.0)) -> Mechanism:
    """``actuator.as_mechanism(tip_force)`` (see :meth:`~exudyn_atcm.BendingActuator.as_mechanism`)."""
    return actuator.as_mechanism(tip_force)


def _columns(actuator: BendingActuator, r: Result) -> tuple[dict, dict, dict]:
    """The mechanism's columns with ``actuator.stroke`` after ``actuator.strain``, their units and old names."""
    series, units = {}, {}
    for name in r:
        series[name], units[name] = r[name], r.unit(name)
        if name == f"{NAME}.strain":
            series[f"{NAME}.stroke"], units[f"{NAME}.stroke"] = r[name] * actuator.cell_length, "m"
    old = {o: n for o, n in OLD_NAMES.items() if n in series}
    old.update({n[len(NAME) + 1:]: n for n in series if n.startswith(f"{NAME}.cell_angle_")})
    return series, units, old


def actuator_result(actuator: BendingActuator, r: Result) -> Result:
    """The result of :func:`exudyn_atcm.simulate` (or a static solve) for a lone actuator from its
    one-bender mechanism's result: the mechanism's columns (``time`` or ``point``,
    ``actuator.voltage``, ``actuator.strain``, ``actuator.base_x``, ..., ``actuator.tip_y``,
    ``actuator.tip_angle``, ``actuator.cell_angle_1..N``) plus ``actuator.stroke`` [m] (the motor
    stroke of one cell, strain times cell length), with the every-step columns when the record was
    thinned.  The names before 0.3.0 (``tip_y``, ``stroke``, ``cell_angle_1``, ...; :data:`OLD_NAMES`)
    are readable for one release, with an :class:`~exudyn_atcm.AtcmDeprecationWarning`.
    """
    series, units, old = _columns(actuator, r)
    every = None
    if r.every_step is not r:
        s, u, o = _columns(actuator, r.every_step)
        every = Result(s, u, parameters=actuator.parameters(), info=r.every_step.info, old_names=o)
    return Result(series, units, parameters=actuator.parameters(), info=r.info, every_step=every, old_names=old)


@contextmanager
def actuator_interrupts(actuator: BendingActuator) -> Iterator[None]:
    """Turn the partial result of an interrupted one-bender mechanism run into the actuator's columns."""
    try:
        yield
    except SimulationInterrupted as stop:
        if stop.result is not None:
            stop.result = actuator_result(actuator, stop.result)
        raise
