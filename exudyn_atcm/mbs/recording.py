"""Recorded states of a mechanism model and the :class:`~exudyn_atcm.Result` made from them.

Columns (``name [unit]``): ``time [s]``; per drive ``{drive}.voltage [V]`` and
``{drive}.strain [-]``; per named point ``{comp}.{point}_x [m]`` and ``_y``; per link
``{link}.angle [rad]`` (rotation from the reference pose); per bender and flexure
``{comp}.base_angle``, ``{comp}.tip_angle`` and ``{comp}.cell_angle_{j}`` [rad] (absolute
direction of the axis; the reference value is the component's angle; a pseudo-rigid-body
flexure has two "cells", its segments); the columns each connection declares
(:meth:`~exudyn_atcm.mechanism.connection.Connection.readouts`, e.g. per spring and stop
``{name}.force [N]``: tension positive for springs, compression positive for stops).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from . import solver_runs as runs
from ..mechanism.link import Link
from ..mechanism.points import MechanismError, closest
from ..io.result import Result
from ..errors import SolverError
from .model import MechanismModel


class RowLayout:
    """Where time, voltages, strains, coordinates and forces sit in one flat row of floats.

    A mechanism run records each accepted step as one row ``t, volts (one per source), strains
    (one per source), ODE2 coordinates, spring and stop forces``
    (:class:`~exudyn_atcm.mbs.step_record.StepRecord`, written by :class:`~exudyn_atcm.mbs.stepping.Stepping`); this object cuts rows back into
    those parts and makes the :class:`Result` of them.
    """

    def __init__(self, model: MechanismModel) -> None:
        self.model = model
        self.n_sources = len(model.sources)
        self.n_coordinates = len(model.coordinates())
        self.n_forces = len(model.readouts)
        self.width = 1 + 2 * self.n_sources + self.n_coordinates + self.n_forces
        self._every_names: list[str] | None = None
        self._every_units: list[str] | None = None

    def parts(self, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(times, volts, strains, q, forces)`` of ``rows`` (views)."""
        ns, nq = self.n_sources, self.n_coordinates
        return (rows[:, 0], rows[:, 1:1 + ns], rows[:, 1 + ns:1 + 2 * ns], rows[:, 1 + 2 * ns:1 + 2 * ns + nq],
                rows[:, 1 + 2 * ns + nq:])

    def result(self, rows: np.ndarray, times: np.ndarray, info: dict, every_step: Result | None = None,
               base: tuple[str, str] = ("time", "s")) -> Result:
        """The :class:`Result` of ``rows`` with the (snapped) ``times`` [s] (``base``: as for :func:`make_result`)."""
        _, volts, strains, q, forces = self.parts(rows)
        return make_result(self.model, times, volts, strains, q, forces, info, base=base, every_step=every_step)

    def every_step_columns(self, rows: np.ndarray, times: np.ndarray) -> np.ndarray:
        """Every column but the cell angles, of ``rows`` with ``times`` [s], as a 2-D array."""
        _, volts, strains, q, forces = self.parts(rows)
        with np.errstate(all="ignore"):  # checked for finite values when the run's result is made
            r = make_result(self.model, times, volts, strains, q, forces, {}, check_finite=False)
        if self._every_names is None:
            self._every_names = [n for n in r if ".cell_angle_" not in n]
            self._every_units = [r.unit(n) for n in self._every_names]
        return np.column_stack([r[n] for n in self._every_names])

    def every_step_result(self, columns: np.ndarray, info: dict) -> Result:
        """The :class:`Result` of the stacked :meth:`every_step_columns`."""
        names, units = self._every_names or [], self._every_units or []
        finite = bool(np.isfinite(columns).all()) if len(names) else True
        for k, name in enumerate(() if finite else names):  # the first non-finite column, named
            if not np.all(np.isfinite(columns[:, k])):
                bad = int(np.argmax(~np.isfinite(columns[:, k])))
                raise SolverError(f"the solution contains a non-finite {name} at accepted step {bad} "
                                  f"(t = {float(columns[bad, 0]):.6g} s); the solver diverged. Try a smaller step or more cells.")
        return Result({n: columns[:, k] for k, n in enumerate(names)}, dict(zip(names, units)),
                      parameters=self.model.mechanism.parameters(), info=info)


def cell_rotations(model: MechanismModel, q: np.ndarray, strains: np.ndarray) -> dict[str, float]:
    """Largest rotation [rad] of a cell relative to its neighbour (the first: to the bender's base), per bender
    whose cells form a chain (:attr:`~exudyn_atcm.cells.CellKind.chain_of_cells`), over rows ``q`` of ODE2
    coordinates with the rows ``strains`` of the sources' strains."""
    q = np.atleast_2d(q)
    out: dict[str, float] = {}
    chains = [b for b in model.mechanism.benders if b.cell.chain_of_cells]
    if q.shape[0] == 0 or not chains:
        return out
    needed: set[str] = set()  # the poses the cells and the base ends need, no others (they may be dear)
    for bender in chains:
        needed.update(model.cells[bender.name])
        base = model.ends[f"{bender.name}.base"]
        needed.update([base.body] if base.kind != "hinge" else [model.hinges[base.hinge].a, model.hinges[base.hinge].b])
    poses = model.poses(q, needed)
    for bender in chains:
        cells = np.column_stack([model.rotation(poses, key) for key in model.cells[bender.name]])
        if bender.name in model.beam_benders:  # a cell's angle: the mean of its two nodes' rotations
            cells = 0.5 * (cells[:, :-1] + cells[:, 1:])
        base = model.end_rotation(poses, strains, f"{bender.name}.base")
        # the first cell's axis sits halfway between the base and its end: it turns twice its angle
        padded = np.column_stack([2.0 * base - cells[:, 0], cells])
        out[bender.name] = float(np.max(np.abs(np.diff(padded, axis=1))))
    return out


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
            pose = body.pose_rows(np.atleast_2d(model.coordinates()))[0]
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
                forces: np.ndarray, info: dict, base: tuple[str, str] = ("time", "s"),
                every_step: Result | None = None, check_finite: bool = True) -> Result:
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
    with np.errstate(invalid="ignore", over="ignore"):  # a diverged state is refused below, by its column and row
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
    for k, (name, unit) in enumerate(zip(model.connector_names(), model.connector_units())):
        series[name], units[name] = forces[:, k], unit
    info = dict(info)
    info.setdefault("exudyn_version", runs.exudyn_version())
    result = Result(series, units, parameters=mech.parameters(), info=info, every_step=every_step)
    names = list(result) if check_finite else []
    finite = not names or bool(np.isfinite(np.stack([result[name] for name in names])).all())
    for name in (() if finite else names):  # the first non-finite column, named
        values = result[name]
        if values.size and not np.all(np.isfinite(values)):
            bad = int(np.argmax(~np.isfinite(values)))
            where = f"t = {float(times[bad]):.6g} s" if base[0] == "time" else f"{base[0]} {float(times[bad]):.6g}"
            raise SolverError(f"the solution contains a non-finite {name} at row {bad} ({where}); "
                              "the solver diverged. Try a smaller step or more cells.")
    return result
