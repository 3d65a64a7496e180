"""The static equilibrium a linear analysis (modes, linear models) is taken about.

:func:`equilibrium_state` builds a mechanism (or takes a :class:`~exudyn_atcm.BuiltSystem`'s model),
solves its static equilibrium at the given voltages or strains with its loads (as
:func:`exudyn_atcm.solve_static`), and leaves the model
in that state, ready for :mod:`exudyn_atcm.mbs.linear_model`.  A static solve that fails is reported
as :class:`NoEquilibriumError` (a :class:`~exudyn_atcm.SolverError` and a ``ValueError``): without an
equilibrium there is nothing to linearise about.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import SolverError
from ..mbs import builder as mb
from ..mechanism.actuator import BendingActuator
from ..mechanism.assembly import Mechanism
from ..mechanism.build_cost import warn_if_eigen_long, warn_if_large
from .long_runs import is_announced
from .mechanism_checks import check_drive_ranges, warn_few_modes
from .mechanism_static import VoltageSpec, describe, describe_voltages, drive_voltages, source_values, start_equilibrium

__all__ = ["NoEquilibriumError", "LinearState", "as_mechanism", "equilibrium_state"]


class NoEquilibriumError(SolverError, ValueError):
    """No static equilibrium was found to linearise about (the message says where and what was tried)."""


@dataclass
class LinearState:
    """A built model at a static equilibrium.

    Attributes
    ----------
    mechanism : Mechanism
    model : MechanismModel
        The built model, in the equilibrium state.
    voltages : dict
        Voltage of every drive [V].
    strains : numpy.ndarray
        Free strain of every strain source [-] at the equilibrium.
    description : str
        The state in words, for messages (``"voltage 300 V"``).
    probe : StabilityProbe or None
        The stability probe of the solve (``probe.last``: the equilibrium's stability); ``None`` for the
        undeformed reference pose.
    """

    mechanism: Mechanism
    model: Any
    voltages: dict
    strains: np.ndarray
    description: str
    probe: Any = None


def as_mechanism(system: Any, what: str) -> Mechanism:
    """A :class:`Mechanism` as it is, a :class:`BendingActuator` as its one-bender mechanism."""
    if isinstance(system, Mechanism):
        return system
    if isinstance(system, BendingActuator):
        return system.as_mechanism()
    raise ValueError(f"{what}: system must be a Mechanism or a BendingActuator, got {type(system).__name__} "
                     f"({system!r})")


def equilibrium_state(mech: Mechanism, what: str, *, voltage: VoltageSpec = None,
                      strains: dict[str, float] | None = None, deformed: bool = True,
                      model: Any = None) -> LinearState:
    """Build ``mech`` (or use ``model``, in its built state) and solve its static equilibrium with its loads.

    Parameters
    ----------
    voltage : None, float or mapping
        Drive voltages [V] (:func:`~exudyn_atcm.solve.mechanism_static.drive_voltages`).
    strains : mapping, optional
        ``{drive: strain}`` to use instead of each drive's static strain at its voltage (a state on
        another branch of the hysteresis).
    deformed : bool
        ``False``: the undeformed reference pose at zero strain (no solve), as
        :func:`exudyn_atcm.eigenfrequencies` without ``voltage``.
    """
    if model is None:
        announced = warn_if_large(mech, what, equilibria=int(deformed), eigen=True, quiet=is_announced(), stacklevel=6)
        model = mb.build(mech)
        warn_if_eigen_long(len(model.coordinates()), describe(mech), quiet=announced or is_announced(), stacklevel=6)
    volts = drive_voltages(mech, voltage)
    per_drive = {k: mech.drives[k].static_strain(v) for k, v in volts.items()}
    if strains is not None:
        per_drive.update(strains)
    eps = source_values(model, per_drive, what) if model.sources else np.zeros(0)
    if not deformed:
        eps = np.zeros(len(model.sources))
        model.scale_loads(0.0)
        model.set_strains(eps)
        return LinearState(mech, model, {k: 0.0 for k in volts}, eps, "the undeformed reference pose")
    text = describe_voltages(volts) if volts else "no drive voltage (the loads alone)"
    check_drive_ranges(model, source_values(model, volts, what), eps)
    try:
        _, _, probe = start_equilibrium(mech, model, eps, text)
    except SolverError as exc:
        raise NoEquilibriumError(
            f"{what}: no static equilibrium of {describe(mech)} at {text} to linearise about; the static solve "
            f"failed: {exc}") from exc
    warn_few_modes(mech, model.truncation_errors())
    model.set_strains(eps)
    return LinearState(mech, model, volts, eps, text, probe)
