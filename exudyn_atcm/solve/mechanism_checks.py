"""Checks of a mechanism run: the actuator's run checks applied to every drive and bender.

Used by :mod:`exudyn_atcm.solve.mechanism_solve`; the thresholds and their reasons are those of
:mod:`exudyn_atcm.solve.run_checks` and :class:`exudyn_atcm.PiezoDrive`:

* :func:`check_steps` -- the step against every drive's voltage program (the message names
  the drive), against the lowest first-frequency estimate of the benders and flexures (naming
  the part), and the up-front run-time estimate over all cells and links;
* :func:`check_drive_ranges` -- voltage range and strain, one warning per drive and run;
* :func:`feedback_controllers` -- each drive set by a controller with the result column it
  observes (:meth:`Mechanism.feedback <exudyn_atcm.Mechanism.feedback>`), or a refusal.

No Exudyn import.
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from ..cells import CellKind, RigidCell
from ..errors import AccuracyWarning
from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..mechanism.flexure import Flexure
from ..mechanism.points import MechanismError
from ..mechanism.build_cost import build_estimate
from .drive_cost import extra_drive_cost
from .run_checks import check_record_interval, check_step_against_frequency, check_step_against_program, warn_if_long

if TYPE_CHECKING:
    from ..mbs.model import MechanismModel

__all__ = ["check_steps", "check_drive_ranges", "feedback_controllers", "lowest_first_frequency", "cost_parts",
           "cost_description",
           "warn_coarse_cells", "MAX_CELL_ROTATION", "warn_few_modes", "MAX_TRUNCATION_ERROR"]

#: Largest rotation of one cell relative to its neighbour [rad] before a warning is issued.
MAX_CELL_ROTATION = 0.5
#: Largest estimated tip error of a ``rod`` bender from its left-out modes, relative to its length, before a
#: warning is issued (:func:`~exudyn_atcm.theory.rotation_rod.truncation_error`).
MAX_TRUNCATION_ERROR = 1e-3


def _drive_names(model: MechanismModel) -> list[str]:
    """The drive name(s) of every strain source, for messages (``"'crank'"`` or ``"'a.1', 'a.2'"``)."""
    names: list[list[str]] = [[] for _ in model.sources]
    for name, k in model.drive_source.items():
        names[k].append(repr(name))
    return [", ".join(n) for n in names]


def check_drive_ranges(model: MechanismModel, volts: np.ndarray, strains: np.ndarray, stacklevel: int = 4) -> None:
    """Voltage-range and strain checks of every drive (one warning per drive and run, naming it).

    ``volts`` and ``strains`` are rows (or one row) of per-source values, as recorded;
    ``stacklevel`` counts from the caller of this function (default: its caller's caller).
    """
    volts = np.atleast_2d(volts)
    strains = np.atleast_2d(strains)
    if volts.shape[0] == 0:
        return
    for k, (drive, names) in enumerate(zip(model.sources, _drive_names(model))):
        what = f"drive {names}"
        drive.check_voltage_range(float(volts[:, k].min()), float(volts[:, k].max()), what=what,
                                  stacklevel=stacklevel + 1)
        drive.check_strain(float(strains[:, k].min()), float(strains[:, k].max()), what=what,
                           stacklevel=stacklevel + 2)


def lowest_first_frequency(mech: Mechanism) -> tuple[float, str]:
    """The lowest first-frequency estimate [Hz] of the mechanism's benders and flexures, and which.

    Each part as a clamped-free beam of its laminate and length (the same formula as
    :attr:`exudyn_atcm.BendingActuator.first_frequency_estimate`); ``(inf, "")`` without such parts.
    """
    best, which = math.inf, ""
    for comp in mech.components.values():
        if isinstance(comp, (Bender, Flexure)):
            f = comp.laminate.first_frequency(comp.length)
            if f < best:
                kind = "bender" if isinstance(comp, Bender) else "flexure"
                best, which = f, f"the first bending mode of {kind} {comp.name!r} (clamped-free estimate)"
    return best, which


def cost_parts(mech: Mechanism) -> tuple[CellKind, int]:
    """Cell kind and number of rigid parts for :func:`~exudyn_atcm.solve.run_checks.warn_if_long`.

    The cells of every bender and ``"cells"`` flexure, two segments per pseudo-rigid-body
    flexure and one body per link; the kind is the benders' dearest per cell (by each kind's
    measured :attr:`~exudyn_atcm.cells.CellKind.cost_per_step`; rigid cells when none is dearer).
    """
    cell, count = RigidCell(), 0
    for comp in mech.components.values():
        if isinstance(comp, Bender):
            count += comp.n_cells
            if _per_cell(comp.cell) > _per_cell(cell):
                cell = comp.cell
        elif isinstance(comp, Flexure):
            count += comp.n_cells if comp.model == "cells" else 2
        else:
            count += 1
    return cell, count


def cost_description(mech: Mechanism) -> str:
    """The parts of :func:`cost_parts` in words: ``"3 rigid cells"`` when the mechanism is benders of one
    cell kind, ``"12 cells and bodies (rigid cells)"`` otherwise."""
    cell, parts = cost_parts(mech)
    kinds = {b.cell for b in mech.benders}
    if len(mech.benders) == len(mech.components) and len(kinds) == 1:
        return f"{parts} {cell} cells"
    return f"{parts} cells and bodies ({cell} cells)"


def _per_cell(kind: CellKind) -> float:
    """Cost of one more cell of ``kind`` at 10 cells [s] (0 when not measured)."""
    return (kind.estimate_step_cost(11) or 0.0) - (kind.estimate_step_cost(10) or 0.0)


def check_steps(mech: Mechanism, grid: Any, t_end: float, schedule: Any = None) -> None:
    """Step checks against every drive's voltage program and the lowest bender frequency; run-time estimate.

    With the run's recording ``schedule``, also the recording interval against every program
    (:func:`~exudyn_atcm.solve.run_checks.check_record_interval`).

    Drives sharing one program object (segments driven by one PiezoDrive) are checked once,
    named together.
    """
    shared: dict[int, tuple[Any, list[str]]] = {}
    for name, drive in mech.drives.items():
        shared.setdefault(id(drive.voltage), (drive.voltage, []))[1].append(repr(name))
    for program, names in shared.values():
        label = "drive " + ", ".join(names) if len(names) == 1 else "drives " + ", ".join(names)
        check_step_against_program(program, grid, t_end, what=f"the voltage program of {label}", stacklevel=5)
        check_record_interval(program, schedule, t_end, what=f"the voltage program of {label}", stacklevel=5)
    frequency, which = lowest_first_frequency(mech)
    check_step_against_frequency(grid, frequency, what=which, stacklevel=5)
    cell, parts = cost_parts(mech)
    warn_if_long(cell, parts, grid.n_steps, parts=cost_description(mech),
                 extra_per_step=extra_drive_cost(mech.drives.values(), grid.step), build=build_estimate(mech),
                 stacklevel=5)


def brief(value: object, limit: int = 100) -> str:
    """``repr(value)`` cut to about ``limit`` characters (a sampled program's repr holds every sample)."""
    text = repr(value)
    return text if len(text) <= limit else f"{text[:limit]}... ({type(value).__name__}, {len(text)} characters)"


def feedback_controllers(mech: Mechanism, model: MechanismModel) -> list[tuple[Any, str]]:
    """``(controller, measurement column)`` of every drive set by a controller.

    Refuses a controller without a declared measurement, and a measurement declared for a
    drive that has no controller (the user meant a closed loop that would not exist).
    """
    out = []
    for k, drive in enumerate(model.sources):
        controller = getattr(drive, "controller", None)
        if controller is None:
            names = [n for n, j in model.drive_source.items() if j == k and n in mech.measurements]
            if names:
                raise MechanismError(
                    f"mechanism {mech.name!r} declares the measurement {mech.measurements[names[0]]!r} for drive "
                    f"{names[0]!r}, but that drive's voltage is not a controller ({brief(drive.voltage)}): nothing "
                    "would observe it. Give the PiezoDrive a controller (exudyn_atcm.model.control) or remove the "
                    "feedback declaration")
            continue
        names = [n for n, j in model.drive_source.items() if j == k]
        declared = {mech.measurements[n] for n in names if n in mech.measurements}
        if not declared:
            raise MechanismError(
                f"drive {names[0]!r} of mechanism {mech.name!r} is set by a controller "
                f"({type(controller).__name__}), but the mechanism declares no measurement for it to observe. "
                f"Declare one: mechanism.feedback({names[0]!r}, 'component.point_y') (any result column, e.g. "
                f"a point's coordinate '{names[0].split('.')[0]}.tip_y', an angle or a spring force)")
        if len(declared) > 1:
            raise MechanismError(f"drives {', '.join(map(repr, names))} share one PiezoDrive but declare different "
                                 f"measurements {sorted(declared)}; declare one")
        out.append((controller, declared.pop()))
    return out


def warn_coarse_cells(mech: Mechanism, rotations: dict[str, float], stacklevel: int = 4) -> None:
    """Warn once per bender whose cells turned by more than :data:`MAX_CELL_ROTATION` [rad] relative to a
    neighbour (``rotations`` from :func:`exudyn_atcm.mbs.recording.cell_rotations`); ``stacklevel`` counts
    from this function."""
    benders = {b.name: b for b in mech.benders}
    for name, per_cell in rotations.items():
        if per_cell > MAX_CELL_ROTATION:
            b = benders[name]
            warnings.warn(
                f"a cell of the {b.cell} bender {name!r} turns by {per_cell:.3g} rad relative to its neighbour (more "
                f"than {MAX_CELL_ROTATION} rad): with {b.n_cells} cells the chain is a coarse discretisation of the "
                "bent bender; use more cells", AccuracyWarning, stacklevel=stacklevel)


def warn_few_modes(mech: Mechanism, errors: dict[str, float], stacklevel: int = 4) -> None:
    """Warn once per ``rod`` bender whose estimated tip error from its left-out modes (``errors`` [m], the
    largest over the states solved, from :meth:`~exudyn_atcm.mbs.model.MechanismModel.truncation_errors`)
    exceeds :data:`MAX_TRUNCATION_ERROR` of its length; ``stacklevel`` counts from this function."""
    benders = {b.name: b for b in mech.benders}
    for name, error in errors.items():
        b = benders[name]
        if error > MAX_TRUNCATION_ERROR * b.length:
            modes = (f"{b.n_cells} modes" if len(b.segments) == 1
                     else "modes " + " + ".join(str(s.n_cells) for s in b.segments) + " (per segment)")
            warnings.warn(
                f"the rod bender {name!r} with {modes} is too coarse for the force at its tip: the first modes it "
                f"leaves out would move the tip by about {error:.3g} m, {error / b.length:.2g} of its length "
                f"(more than {MAX_TRUNCATION_ERROR:g}); use more modes (n_cells), e.g. twice as many",
                AccuracyWarning, stacklevel=stacklevel)
