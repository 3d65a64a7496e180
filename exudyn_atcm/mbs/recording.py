"""Recorded states of a mechanism model and the :class:`~exudyn_atcm.Result` made from them.

Columns (``name [unit]``): ``time [s]``; per drive ``{drive}.voltage [V]`` and
``{drive}.strain [-]``; per named point ``{comp}.{point}_x [m]`` and ``_y``; per link
``{link}.angle [rad]`` (rotation from the reference pose); per bender and flexure
``{comp}.base_angle``, ``{comp}.tip_angle`` and ``{comp}.cell_angle_{j}`` [rad] (absolute
direction of the axis; the reference value is the component's angle; a pseudo-rigid-body
flexure has two "cells", its segments); per spring and stop ``{name}.force [N]`` (tension
positive for springs, compression positive for stops).
"""

from __future__ import annotations

from typing import Callable

import exudyn as exu
import numpy as np

from . import solver_runs as runs
from ..mechanism.link import Link
from ..mechanism.points import MechanismError, closest
from ..io.result import Result
from ..errors import SolverError
from .model import MechanismModel


class Rows:
    """Accepted states: time, voltages and strains per source, ODE2 coordinates, spring forces."""

    def __init__(self, model: MechanismModel) -> None:
        self.model = model
        self.times: list[float] = []
        self.volts: list[np.ndarray] = []
        self.strains: list[np.ndarray] = []
        self.q: list[np.ndarray] = []
        self.forces: list[list[float]] = []

    def add(self, t: float, volts: np.ndarray, strains: np.ndarray) -> None:
        """Record the model's current state (coordinates copied, spring and stop forces) at time ``t`` [s]."""
        self.times.append(t)
        self.volts.append(np.array(volts, dtype=float))
        self.strains.append(np.array(strains, dtype=float))
        self.q.append(np.array(self.model.coordinates()))
        self.forces.append(self.model.connector_forces())

    def last_time(self) -> float:
        return self.times[-1] if self.times else 0.0

    def result(self, info: dict, base: tuple[str, str] = ("time", "s")) -> Result:
        """The recorded rows as a :class:`Result`; ``base`` names the first column and its unit."""
        return make_result(self.model, np.array(self.times), np.array(self.volts).reshape(len(self.times), -1),
                           np.array(self.strains).reshape(len(self.times), -1), np.array(self.q),
                           np.array(self.forces).reshape(len(self.times), -1), info, base=base)


def restore_start_of_step(model: MechanismModel) -> None:
    """Make the state at the start of the last computed step the model's current state.

    Exudyn keeps the state at the start of every step (``ConfigurationType.StartOfStep``):
    the last step it accepted before the one it computed last.  When a run stops because
    a pre-step hook returned ``False``, Exudyn still completes that step and calls the
    post-step hook; a caller that did not accept it (an interrupt caught by
    :class:`~exudyn_atcm.solve.run_checks.InterruptGuard`) closes its record with this state
    (measured with Exudyn 1.13; see ``tests/test_mechanism_recording.py``).
    """
    data = model.mbs.systemData
    state = data.GetSystemState(configuration=exu.ConfigurationType.StartOfStep)
    data.SetSystemState(systemStateList=state, configuration=exu.ConfigurationType.Current)


def measurement_reader(model: MechanismModel, column: str) -> Callable[[np.ndarray], float]:
    """A function ``read(strains) -> float`` giving result column ``column`` for the model's current state.

    ``column`` is a column name of :func:`make_result` without unit (``"crank.tip_y"``,
    ``"lever.angle"``, ``"spring_1.force"``); ``strains`` are the current free strains per
    source (needed for the angles of free bender ends).  A point coordinate is read directly;
    any other column through :func:`make_result` of the one state.

    Raises
    ------
    MechanismError
        For a name that is not a column, with the closest column names.
    """
    column = column.split(" [")[0]
    nsrc = len(model.sources)
    probe = make_result(model, np.zeros(1), np.zeros((1, nsrc)), np.zeros((1, nsrc)),
                        np.atleast_2d(np.array(model.coordinates())),
                        np.array(model.connector_forces(), dtype=float).reshape(1, -1), {})
    if column not in probe or column in ("time",):
        names = [n for n in probe if n != "time"]
        raise MechanismError(f"measurement: {column!r} is not a result column of mechanism "
                             f"{model.mechanism.name!r}{closest(column, names)}")
    point, _, axis = column.rpartition("_")
    if axis in ("x", "y") and point in model.anchors:
        key, local = model.anchors[point]
        body = model.bodies[key]
        axis_index = 0 if axis == "x" else 1

        def read_point(strains: np.ndarray) -> float:
            pose = body.reference if body.node is None else body.reference + model.coordinates()[body.ode2:body.ode2 + 3]
            c, s = np.cos(pose[2]), np.sin(pose[2])
            xy = (pose[0] + c * local[0] - s * local[1], pose[1] + s * local[0] + c * local[1])
            return float(xy[axis_index])

        return read_point

    def read_any(strains: np.ndarray) -> float:
        strains = np.atleast_2d(np.asarray(strains, dtype=float))
        result = make_result(model, np.zeros(1), np.zeros_like(strains), strains,
                             np.atleast_2d(np.array(model.coordinates())),
                             np.array(model.connector_forces(), dtype=float).reshape(1, -1), {})
        return float(result[column][0])

    return read_any


def make_result(model: MechanismModel, times: np.ndarray, volts: np.ndarray, strains: np.ndarray, q: np.ndarray,
                forces: np.ndarray, info: dict, base: tuple[str, str] = ("time", "s")) -> Result:
    """The :class:`Result` of recorded rows (columns as in the module documentation).

    ``base`` is the first column's name and unit: ``("time", "s")`` for a time series,
    ``("point", "-")`` for the point index of a quasi-static sweep.
    """
    mech = model.mechanism
    series: dict[str, np.ndarray] = {base[0]: times}
    units: dict[str, str] = {base[0]: base[1]}
    for name, k in model.drive_source.items():
        series[f"{name}.voltage"], units[f"{name}.voltage"] = volts[:, k], "V"
        series[f"{name}.strain"], units[f"{name}.strain"] = strains[:, k], "-"
    poses = model.poses(q)
    points = model.point_positions(poses)
    benders = {b.name: b for b in mech.benders}
    for comp in mech.components.values():
        for pname in comp.points:
            xy = points[f"{comp.name}.{pname}"]
            for axis, col in (("x", 0), ("y", 1)):
                key = f"{comp.name}.{pname}_{axis}"
                series[key], units[key] = xy[:, col], "m"
        c = comp.name
        if isinstance(comp, Link):
            series[f"{c}.angle"] = model.rotation(poses, model.group_of_component[c])
            units[f"{c}.angle"] = "rad"
            continue
        if c in benders:
            angle = benders[c].angle
            base = angle + model.end_rotation(poses, strains, f"{c}.base")
            tip = angle + model.end_rotation(poses, strains, f"{c}.tip")
            cells = [angle + model.rotation(poses, key) for key in model.cells[c]]
            if c in model.beam_benders:  # a beam cell's angle: the mean of its two nodes' rotations
                cells = [0.5 * (a + b) for a, b in zip(cells[:-1], cells[1:])]
        else:  # pseudo-rigid-body flexure
            angle = comp.angle
            cells = [angle + model.rotation(poses, model.group_of_component[f"{c}#{end}"]) for end in ("base", "tip")]
            base, tip = cells
        series[f"{c}.base_angle"], series[f"{c}.tip_angle"] = base, tip
        units[f"{c}.base_angle"] = units[f"{c}.tip_angle"] = "rad"
        for j, values in enumerate(cells):
            series[f"{c}.cell_angle_{j + 1}"], units[f"{c}.cell_angle_{j + 1}"] = values, "rad"
    for k, name in enumerate(model.connector_names()):
        series[f"{name}.force"], units[f"{name}.force"] = forces[:, k], "N"
    info = dict(info)
    info.setdefault("exudyn_version", runs.exudyn_version())
    result = Result(series, units, parameters=mech.parameters(), info=info)
    for name in result:
        values = result[name]
        if values.size and not np.all(np.isfinite(values)):
            bad = int(np.argmax(~np.isfinite(values)))
            where = f"t = {times[bad]!r} s" if base[0] == "time" else f"{base[0]} {times[bad]!r}"
            raise SolverError(f"the solution contains a non-finite {name} at row {bad} ({where}); "
                              "the solver diverged. Try a smaller step or more cells.")
    return result
