"""Static equilibrium of the lone actuator's Exudyn model: load steps, then relaxation if Newton stalls.

Internal API of the solve layer (documented for tests): :func:`static_equilibrium`.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import SolverError
from ..mbs import solver_runs as runs
from ..mbs import solver_settings
from ..mechanism.actuator import BendingActuator
from .run_checks import SimulationInterrupted, is_interrupt

__all__ = ["static_equilibrium", "strain_scale"]


def strain_scale(actuator: BendingActuator, strain: float, force: tuple[float, float]) -> float:
    """Rough total tip rotation [rad] expected, for choosing load steps."""
    rot_act = abs(actuator.free_curvature(strain)) * actuator.length
    rot_force = math.hypot(*force) * actuator.length**2 / (2.0 * actuator.bending_stiffness)
    return rot_act + rot_force


def static_equilibrium(actuator, model, strain: float, force: tuple[float, float], load_steps: int | None,
                        what: str) -> str:
    """Solve the static equilibrium at ``strain`` with the tip load; returns the method that succeeded.

    First Exudyn's static solver with strain and load raised together in equal load steps.
    Exudyn's static Jacobian leaves out the derivative of the constraint forces, so under
    large tip forces its Newton iteration converges only linearly, ever slower, and can stall
    (measured on the elastica cases).  Then the equilibrium is found by dynamic relaxation
    (strongly damped implicit dynamics with a smooth load ramp) and polished with one static
    step from there.
    """
    if load_steps is None:
        # ~0.05 rad of tip rotation per load step, at least 4
        load_steps = int(min(400, max(4, math.ceil(strain_scale(actuator, strain, force) / 0.05))))
    try:
        runs.run_static(model, solver_settings.static_settings(load_steps), lambda f: f * strain)
        return "static"
    except runs.ExudynFailure as exc:
        if is_interrupt(exc):
            raise SimulationInterrupted(0.0) from None
        first = exc
    runs.reset_to_reference(model)
    omega1 = 2.0 * math.pi * actuator.first_frequency_estimate
    try:
        # periods counted at half the beam frequency: coarse chains of six-bar cells are softer
        change = runs.run_relaxation(model, strain, 0.5 * omega1, 2.0 / omega1)
    except runs.ExudynFailure as exc:
        raise SolverError(
            f"static equilibrium ({what}) of the {actuator.cell} actuator with {actuator.n_cells} cells did not "
            f"converge. Tried: Exudyn's static solver with {load_steps} load steps (stopped at load factor "
            f"{first.time:.4g}: {first}), then dynamic relaxation (stopped at {exc.time:.3g} of its ramp: {exc}). "
            f"The expected tip rotation is {strain_scale(actuator, strain, force):.3g} rad, "
            f"{strain_scale(actuator, strain, force) / actuator.n_cells:.3g} rad per cell. Use more cells "
            "(the six-bar cell is a discretisation for small rotations per cell), reduce the load, or pass "
            "load_steps."
        ) from exc
    relaxed = np.array(model.coordinates())
    runs.set_current_as_initial(model, zero_velocity=True)
    try:
        runs.run_static(model, solver_settings.static_settings(1), lambda f: strain)
        return "relaxation+static"
    except runs.ExudynFailure:
        pass
    tol = 1e-9 * actuator.length
    if change <= tol:
        runs.set_current_coordinates(model, relaxed)
        return "relaxation"
    raise SolverError(
        f"static equilibrium ({what}) of the {actuator.cell} actuator with {actuator.n_cells} cells did not "
        f"converge: Exudyn's static solver stopped at load factor {first.time:.4g} ({first}); dynamic "
        f"relaxation still moved by {change:.3g} m over its last period (accepted: {tol:.3g} m) and the "
        "static polish step failed. Use more cells, reduce the load, or pass more load_steps."
    )
