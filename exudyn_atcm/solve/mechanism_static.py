"""Static equilibrium of a built mechanism model: drive voltages to strains, load steps, relaxation.

Internal API of the solve layer (documented for tests): :func:`drive_voltages`,
:func:`source_values`, :func:`equilibrium` (a static sweep's points after the first are continued by
:mod:`exudyn_atcm.solve.sweep_continuation`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .._checks import finite_float
from .static_fallback import equilibrium_with_fallback
from .static_stability import free_motion_note, load_path_note, stability_probe
from ..mbs import builder as mb
from ..mbs import solver_runs as runs
from ..mbs import solver_settings
from ..mbs.stability import StabilityProbe, snapshot
from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..mechanism.flexure import Flexure
from ..mechanism.points import MechanismError, closest

__all__ = ["drive_voltages", "source_values", "static_scales", "equilibrium", "start_equilibrium", "describe",
           "describe_voltages"]

VoltageSpec = Any  # None | float | Mapping[str, float]


# ------------------------------------------------------------------------------ voltages

def drive_voltages(mech: Mechanism, voltage: VoltageSpec) -> dict[str, float]:
    """Voltage [V] of every drive: ``None`` -> each program at t = 0; a number -> every drive;
    a mapping ``{drive_name: volts}`` (drives not named: their program at t = 0)."""
    drives = mech.drives
    out = {name: d.voltage_at(0.0) for name, d in drives.items()}
    if voltage is None:
        return out
    if isinstance(voltage, Mapping):
        for name, value in voltage.items():
            if name not in drives:
                raise MechanismError(f"voltage: unknown drive {name!r}{closest(str(name), drives)} "
                                     f"(drives: {', '.join(drives) or 'none'})")
            out[name] = finite_float(f"voltage[{name!r}]", value)
        return out
    value = finite_float("voltage", voltage)
    return {name: value for name in drives}


def describe_voltages(volts: Mapping[str, float]) -> str:
    """``"voltage 1500 V"`` for one drive, ``"voltages 'a' 300 V, 'b' -200 V"`` for several (messages)."""
    if len(volts) == 1:
        return f"voltage {next(iter(volts.values())):g} V"
    return "voltages " + ", ".join(f"{name!r} {v:g} V" for name, v in volts.items())


def describe(mech: Mechanism) -> str:
    """``"mechanism 'm' (bender 'b': 4 rigid cells)"``: the mechanism and its benders' cells (messages)."""
    cells = "; ".join(f"bender {b.name!r}: {b.n_cells} {b.cell} cells" for b in mech.benders)
    return f"mechanism {mech.name!r}" + (f" ({cells})" if cells else "")


def source_values(model: mb.MechanismModel, per_drive: Mapping[str, float], what: str) -> np.ndarray:
    """One value per strain source; drives sharing one PiezoDrive object must agree."""
    values = np.full(len(model.sources), np.nan)
    owner: dict[int, str] = {}
    for name, k in model.drive_source.items():
        v = per_drive[name]
        if k in owner and values[k] != v:
            raise MechanismError(
                f"{what}: drives {owner[k]!r} and {name!r} are one PiezoDrive object and cannot take "
                f"different voltages ({values[k]!r} V and {v!r} V); give them separate PiezoDrive objects")
        owner.setdefault(k, name)
        values[k] = v
    return values


# ------------------------------------------------------------------------------ static equilibrium

def static_scales(mech: Mechanism, model: mb.MechanismModel, strains: np.ndarray) -> tuple[float, float]:
    """Expected rotation [rad] (for load steps) and the lowest cantilever frequency [rad/s] of the parts."""
    rot, omega = 0.0, math.inf
    min_ei = math.inf
    for comp in mech.components.values():
        if isinstance(comp, (Bender, Flexure)):
            lam = comp.laminate
            min_ei = min(min_ei, lam.bending_stiffness)
            omega = min(omega, 2.0 * math.pi * lam.first_frequency(comp.length))
            if isinstance(comp, Bender):
                for name in comp.drives:
                    rot = max(rot, abs(lam.curvature_per_strain * strains[model.drive_source[name]]) * comp.length)
    size = mech.size
    for f in mech.forces:
        value = f.force(0.0) if callable(f.force) else f.force
        if math.isfinite(min_ei):
            rot += math.hypot(*value) * size**2 / (2.0 * min_ei)
    return rot, (omega if math.isfinite(omega) else 2.0 * math.pi * 10.0)


def equilibrium(mech: Mechanism, model: mb.MechanismModel, start: np.ndarray, end: np.ndarray, from_reference: bool,
                 load_steps: int | None, what: str, probe: StabilityProbe | None = None) -> str:
    """Static equilibrium with the strains moved from ``start`` to ``end``; returns the method used.

    From the reference pose the loads are raised with the strains; otherwise they stay.
    First Exudyn's static solver in load steps, then (as for a lone actuator) dynamic
    relaxation polished by one static step.  With a stability ``probe``
    (:func:`~exudyn_atcm.solve.static_stability.stability_probe`), a converged but unstable static
    solution is replaced by the relaxation's stable one when there is one
    (:mod:`~exudyn_atcm.solve.static_fallback`), and ``probe.last`` holds the final state's stability.
    """
    # From the reference pose Exudyn's load factor raises the loads (as for a lone actuator, so
    # that a one-bender mechanism takes the very same Newton path); later sweep points keep
    # the loads and move the strains only.
    model.load_factor = 1.0
    model.set_path(start, end, ramp_loads=False)
    rot, omega1 = static_scales(mech, model, np.abs(end - start))
    if load_steps is None:
        load_steps = int(min(400, max(4, math.ceil(rot / 0.05))))
    settings = solver_settings.static_settings(load_steps)
    settings.staticSolver.useLoadFactor = from_reference

    def relaxation() -> None:
        model.set_path(start, end, ramp_loads=from_reference)
        if from_reference:
            runs.reset_to_reference(model)
        else:
            model.set_strain(0.0)

    def polish() -> None:
        model.load_factor = 1.0
        model.set_path(end, end, ramp_loads=False)
        last = solver_settings.static_settings(1)
        last.staticSolver.useLoadFactor = False
        runs.run_static(model, last, lambda f: f)

    free = free_motion_note(model, probe)  # a motion without stiffness: the failure's reason, not the cells
    method = equilibrium_with_fallback(
        model, static=lambda: runs.run_static(model, settings, lambda f: f), relaxation=relaxation, relax_target=1.0,
        omega1=omega1, polish=polish, size=mech.size, subject=describe(mech), what=what,
        load_steps=load_steps,
        advice=f"{free}." if free else f"Expected rotation about {rot:.3g} rad. Use more cells, reduce the loads, "
        "check that the mechanism is not locked, or pass load_steps.",
        unstable=None if probe is None else lambda: probe.check().state == "unstable",
        snapshot=None if probe is None else lambda: snapshot(model))
    if probe is not None and method != "static":
        probe.check()  # the relaxation's state (a converged static state was checked on the way)
    return method


def start_equilibrium(mech: Mechanism, model: mb.MechanismModel, strains: np.ndarray,
                      what: str) -> tuple[Any, str, StabilityProbe]:
    """The equilibrium from the reference pose at ``strains`` [-] with the loads in full, made the model's initial state
    at rest; ``(stability, note, probe)``: its stability, the load path's note
    (:func:`~exudyn_atcm.solve.static_stability.load_path_note`) and the stability probe of the solve (the
    runs, the eigenvalue analyses and the linear models about a state all start here).

    Solved once per build and strains (the model in its built state: a fresh build, or one a
    :class:`~exudyn_atcm.BuiltSystem` or an accuracy run restored): the state is kept on the model and put back
    for the next run starting there (an accuracy run's prediction, probe, run and refinement each started with
    the same static solve and stability probe, 3 to 5 ms each on a lone actuator)."""
    # the strains and the loads' values at t = 0 (a load given as a function could give another value now)
    key = (tuple(np.asarray(strains, dtype=float).tolist()), tuple(load.at(0.0) for load in model.loads))
    kept = model.start_equilibria.get(key)
    if kept is not None:
        state, stability, note, probe = kept
        runs.restore_state(model, state)
        model.set_path(np.asarray(strains, dtype=float), np.asarray(strains, dtype=float), ramp_loads=False)
        model.set_strain(1.0)
        return stability, note, probe
    probe = stability_probe(mech, model)
    equilibrium(mech, model, np.zeros_like(strains), strains, True, None, what, probe)
    runs.set_current_as_initial(model, zero_velocity=True)
    note = load_path_note(probe)
    model.start_equilibria[key] = (runs.save_state(model), probe.last, note, probe)
    return probe.last, note, probe
