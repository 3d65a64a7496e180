"""Static equilibrium of the lone actuator's Exudyn model: load steps, then relaxation if Newton stalls.

Internal API of the solve layer (documented for tests): :func:`static_equilibrium`.
"""

from __future__ import annotations

import math

from ..mbs import solver_runs as runs
from ..mbs import solver_settings
from ..mechanism.actuator import BendingActuator
from .static_fallback import equilibrium_with_fallback

__all__ = ["static_equilibrium", "strain_scale"]


def strain_scale(actuator: BendingActuator, strain: float, force: tuple[float, float]) -> float:
    """Rough total tip rotation [rad] expected, for choosing load steps."""
    rot_act = abs(actuator.free_curvature(strain)) * actuator.length
    rot_force = math.hypot(*force) * actuator.length**2 / (2.0 * actuator.bending_stiffness)
    return rot_act + rot_force


def static_equilibrium(actuator, model, strain: float, force: tuple[float, float], load_steps: int | None,
                        what: str) -> str:
    """Solve the static equilibrium at ``strain`` with the tip load; returns the method that succeeded.

    First Exudyn's static solver with strain and load raised together in equal load steps,
    then dynamic relaxation polished by one static step
    (:func:`~exudyn_atcm.solve.static_fallback.equilibrium_with_fallback`).
    """
    if load_steps is None:
        # ~0.05 rad of tip rotation per load step, at least 4
        load_steps = int(min(400, max(4, math.ceil(strain_scale(actuator, strain, force) / 0.05))))
    rotation = strain_scale(actuator, strain, force)
    return equilibrium_with_fallback(
        model,
        static=lambda: runs.run_static(model, solver_settings.static_settings(load_steps), lambda f: f * strain),
        relaxation=lambda: runs.reset_to_reference(model), relax_target=strain,
        omega1=2.0 * math.pi * actuator.first_frequency_estimate,
        polish=lambda: runs.run_static(model, solver_settings.static_settings(1), lambda f: strain),
        size=actuator.length, subject=f"the {actuator.cell} actuator with {actuator.n_cells} cells", what=what,
        load_steps=load_steps,
        advice=f"The expected tip rotation is {rotation:.3g} rad, {rotation / actuator.n_cells:.3g} rad per cell. Use "
               "more cells (the six-bar cell is a discretisation for small rotations per cell), reduce the load, or "
               "pass load_steps.")
