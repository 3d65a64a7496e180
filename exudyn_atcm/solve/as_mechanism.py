"""The lone actuator solved as what it is: a one-bender mechanism.

:func:`exudyn_atcm.simulate`, :func:`exudyn_atcm.solve_static`,
:func:`exudyn_atcm.static_sweep` and :func:`exudyn_atcm.eigenfrequencies` hand a
:class:`~exudyn_atcm.BendingActuator` as the one-bender :class:`~exudyn_atcm.Mechanism` of
:func:`actuator_mechanism` (base welded to the ground at the origin, along +x, the dead tip force
at the tip), solve it with the mechanism solves of :mod:`exudyn_atcm.solve.mechanism_solve` (one
builder, one recorder, one set of run checks) and rename the bender's columns to the
actuator's (:func:`actuator_result`).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from .._checks import finite_float
from ..io.result import Result
from ..mechanism.actuator import BendingActuator
from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..model.damping import damping_already_checked

from .interrupts import SimulationInterrupted

__all__ = ["actuator_mechanism", "actuator_result", "actuator_interrupts", "NAME", "STANDARD_UNITS"]

#: The bender's (and its drive's) name in the one-bender mechanism.
NAME = "actuator"

#: Units of an actuator result's columns besides ``cell_angle_j`` [rad].
STANDARD_UNITS = {"time": "s", "voltage": "V", "strain": "-", "stroke": "m", "tip_x": "m", "tip_y": "m",
                  "tip_angle": "rad"}


def actuator_mechanism(actuator: BendingActuator, tip_force: tuple[float, float] = (0.0, 0.0)) -> Mechanism:
    """A :class:`BendingActuator` as a one-bender mechanism named ``"actuator"``: base welded to the
    ground at the origin, along +x, the dead ``tip_force`` [N] at the tip (the same model).

    Raises
    ------
    ValueError
        For an actuator cell that cannot join a mechanism (the reason is the cell kind's own,
        :meth:`~exudyn_atcm.cells.CellKind.mechanism_refusal`).
    """
    refusal = actuator.cell.mechanism_refusal()
    if refusal is not None:
        raise ValueError(f"cell={actuator.cell.name!r} cannot be solved as a one-bender mechanism: {refusal}")
    refusal = actuator.cell.tip_load_refusal()
    if refusal is not None and tuple(map(float, tip_force)) != (0.0, 0.0):
        raise ValueError(f"tip_force must be (0, 0) for cell={actuator.cell.name!r}, got {tuple(tip_force)!r}: "
                         f"{refusal}")
    with damping_already_checked():  # a damping ratio was warned about where the actuator was made
        bender = Bender(NAME, width=actuator.width, passive=actuator.passive, active=actuator.active,
                        length=actuator.length, n_cells=actuator.n_cells, drive=actuator.drive, cell=actuator.cell,
                        stiffness=actuator.stiffness, damping=actuator.damping)
    mech = Mechanism(NAME).add(bender).ground(bender.base)
    fx = finite_float("tip_force[0]", tip_force[0])
    fy = finite_float("tip_force[1]", tip_force[1])
    if (fx, fy) != (0.0, 0.0):
        mech.force(bender.tip, (fx, fy))
    if getattr(actuator.drive, "controller", None) is not None:
        mech.feedback(NAME, f"{NAME}.tip_y")
    return mech


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
    ``cell_angle_1..N``), with the every-step columns when the record was thinned.
    """
    series, units = _columns(actuator, r, cells=True)
    every = None
    if r.every_step is not r:
        every = Result(*_columns(actuator, r.every_step, cells=False), parameters=actuator.parameters(),
                       info=r.every_step.info)
    return Result(series, units, parameters=actuator.parameters(), info=r.info, every_step=every)


@contextmanager
def actuator_interrupts(actuator: BendingActuator) -> Iterator[None]:
    """Turn the partial result of an interrupted one-bender mechanism run into the actuator's columns."""
    try:
        yield
    except SimulationInterrupted as stop:
        if stop.result is not None:
            stop.result = actuator_result(actuator, stop.result)
        raise
