"""The mode a run's drives ring: the frequency and damping of the step choice's one-mode stand-in.

The stand-in of :mod:`exudyn_atcm.solve.step_surrogate` is the mechanism's lowest mode driven by the
drives' free strain.  Two things about that mode decide how long it rings and so how fine a step
must be:

* **Which mode.**  The lowest mode is the one a drive rings, unless the drives cannot excite it at
  all: in a symmetric mechanism driven symmetrically (the micro gripper's two mirrored benders,
  one program through equal operators) the lowest mode is antisymmetric (113 Hz), and the two
  drives' modal forces on it cancel to round-off; the drives ring the symmetric mode (211 Hz), whose
  period error per step is 3.5 times larger.  :func:`rung_mode` takes the lowest of the
  :data:`MODES_EXAMINED` lowest modes whose net participation (the modal forces of drives with the same
  strain history added) is more than :data:`CANCELLED` of the largest.
* **Its damping.**  The mode's own damping ratio, ``phi^T D phi / (2 omega phi^T M phi)`` with ``D``
  the damping the simulation has (:func:`~exudyn_atcm.mbs.linear_model.damping_matrix`), not the
  smallest ratio of the parts: in the ``compliant_four_bar`` case the flexures damp at 1.6e-4 at
  55 Hz, the bender at 0.02, the mode at 0.0125 (:mod:`exudyn_atcm.mbs.linear`, ``damped_modes``).

Where the analysis fails (a mechanism whose start state has no equilibrium the solver finds, a
drive whose strain is a prescribed motion), the lowest clamped-free estimate of the benders and
flexures is used with their smallest damping ratio (:func:`lowest_damping_ratio`).
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Callable

import numpy as np

from ..mbs import linear
from ..mbs import linear_model as lm
from ..mechanism import Mechanism
from ..mechanism.damped import MaterialDamped
from . import mechanism_solve
from .mechanism_checks import lowest_first_frequency
from .modes import modes_of_state, modes_state
from .step_surrogate import unit_strain

__all__ = ["MODES_EXAMINED", "CANCELLED", "rung_mode", "rung_analysis", "rung_of_state", "driven_alike",
           "lowest_damping_ratio", "strain_groups"]

#: Modes examined for the one the drives ring (the lowest ones).
MODES_EXAMINED = 4
#: A mode whose net participation is below this share of the largest among those examined is not rung (its
#: drives' modal forces cancel: 2e-8 of the force in the micro gripper's antisymmetric mode).
CANCELLED = 1e-6
#: Samples of the drives' strain over the run to tell equal strain histories apart.
GROUP_SAMPLES = 1001


def lowest_damping_ratio(mech: Mechanism, omega: float) -> float:
    """Smallest damping ratio of the mechanism's laminate parts at ``omega`` [rad/s] (0 without any)."""
    ratios = []
    for comp in mech.components.values():
        if isinstance(comp, MaterialDamped):
            r = comp.rayleigh_damping
            ratios.append(r.alpha / (2.0 * omega) + r.beta * omega / 2.0)
    return max(min(ratios), 0.0) if ratios else 0.0


def strain_groups(mech: Mechanism, t_end: float) -> list[list[str]]:
    """The drives (names) grouped by their free strain over ``t_end`` [s]: drives in one group follow the same
    strain history (one program through equal operators), so their modal forces add.  A drive whose strain is
    not known before the run (a controller's) or does not change is a group of its own."""
    times = np.linspace(0.0, t_end, GROUP_SAMPLES)
    groups: list[tuple[np.ndarray | None, list[str]]] = []
    for name, drive in mech.drives.items():
        strain = unit_strain(drive, times)
        for known, members in groups:
            if strain is not None and known is not None and np.array_equal(known, strain):
                members.append(name)
                break
        else:
            groups.append((strain, [name]))
    return [members for _, members in groups]


def rung_of_state(state: Any, groups: list[list[str]]) -> tuple[float, float, int]:
    """Frequency [Hz], damping ratio [-] and index (0: the lowest) of the mode the drive ``groups``
    (:func:`strain_groups`) ring about a :class:`~exudyn_atcm.solve.linear_state.LinearState`; ``nan`` frequency
    where that mode is unstable or has none."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a linearisation for the choices only; the run says what matters
        modes = modes_of_state(state, max(1, min(MODES_EXAMINED, linear.degrees_of_freedom(state.model).dof)))
    freqs = modes.frequencies
    j = _rung(modes, groups) if freqs[0] > 0.0 else 0
    f = float(freqs[j])
    if not (f > 0.0 and math.isfinite(f)):
        return math.nan, math.nan, j
    phi = modes.coordinates[:, j]
    damping = float(phi @ lm.damping_matrix(state.model) @ phi)
    return f, max(damping / (2.0 * (2.0 * math.pi * f) * float(modes.modal_masses[j])), 0.0), j


def driven_alike(groups: list[list[str]]) -> bool:
    """Whether two or more drives follow one strain history (only then can their forces on a mode cancel; else the
    lowest mode is the one rung, and the cheaper eigenvalue analysis gives it)."""
    return any(len(members) > 1 for members in groups)


def rung_analysis(mech: Mechanism, voltage: Any, loaded: bool, model: Any,
                  groups: list[list[str]]) -> tuple[float, float, int]:
    """Frequency [Hz], damping ratio [-] and index of the mode the drive ``groups`` ring about the equilibrium at
    ``voltage`` (``None``, ``loaded``: as :func:`exudyn_atcm.eigenfrequencies`) of ``model`` (a build of ``mech`` in
    its built state; ``None``: a build of its own): :func:`rung_of_state` where drives are driven alike, else the
    lowest mode by the cheaper eigenvalue analysis.  ``nan`` frequency where the mode is unstable or has none."""
    if driven_alike(groups):
        return rung_of_state(modes_state(mech, voltage, loaded, model=model), groups)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a linearisation for the choices only; the run says what matters
        freqs, zetas = mechanism_solve.eigenfrequencies(mech, 1, voltage, loaded=loaded, built=model, damping=True)
    f = float(freqs[0])
    if not (f > 0.0 and math.isfinite(f) and math.isfinite(zetas[0])):
        return math.nan, math.nan, 0
    return f, max(float(zetas[0]), 0.0), 0


def rung_mode(mech: Mechanism, t_end: float, built: Callable[[], Any] | None = None) -> tuple[float, float, str]:
    """Frequency [Hz] and damping ratio [-] of the mode the drives ring about the start state, and in words where
    they come from (see the module notes).  ``built()``: the model to analyse, in its built state (the runs' one
    build); default a build of its own."""
    volts = {n: d.voltage_at(0.0) for n, d in mech.drives.items() if getattr(d, "controller", None) is None}
    try:
        f, zeta, j = rung_analysis(mech, volts if len(volts) == len(mech.drives) else None, bool(mech.forces),
                                   built() if built else None, strain_groups(mech, t_end))
        if math.isfinite(f):
            if j == 0:
                return f, zeta, "the lowest eigenfrequency about the start state and its mode's damping"
            return f, zeta, (f"mode {j + 1} about the start state and its damping: the drives' forces on the "
                             f"{'lowest' if j == 1 else f'{j} lowest'} cancel (a symmetric mechanism driven alike)")
    except Exception:  # noqa: BLE001 - any failure: the cheaper estimate below
        pass
    f, which = lowest_first_frequency(mech)
    return f, lowest_damping_ratio(mech, 2.0 * math.pi * f), which


def _rung(modes: Any, groups: list[list[str]]) -> int:
    """Index of the lowest stable mode whose net participation (per group of drives, the largest) is more than
    :data:`CANCELLED` of the largest of the modes (0 without modal forces: every mode counts as rung)."""
    if modes.participation is None or not groups:
        return 0
    column = {name: k for k, name in enumerate(modes.drives)}
    stable = np.isfinite(modes.participation).all(axis=1) & (modes.frequencies > 0.0)
    net = np.zeros(len(modes.frequencies))
    for members in groups:
        total = np.abs(modes.participation[:, [column[m] for m in members if m in column]].sum(axis=1))
        net = np.maximum(net, np.where(stable, total, 0.0))
    largest = float(net.max())
    if not largest > 0.0:
        return 0
    return int(np.argmax(net > CANCELLED * largest))
