"""The stability check of every static equilibrium the package solves, and its warning.

After every static solve (:func:`exudyn_atcm.solve_static`, each point of
:func:`exudyn_atcm.static_sweep`, the initial state of :func:`exudyn_atcm.simulate`) the lowest
eigenvalue of the constrained tangent stiffness is checked (:mod:`exudyn_atcm.mbs.stability`),
the same way for every cell kind.  A converged static solution that is unstable is not kept
when a stable one lies on the loading path: the equilibrium is found again by dynamic
relaxation (:mod:`exudyn_atcm.solve.static_fallback`), whose damped motion comes to rest only
in a stable state, on the side an imperfection (a small transverse load) pushes it to.  What is
still unstable or critical afterwards is warned about (:class:`~exudyn_atcm.errors.StabilityWarning`),
once per run, naming the load factor or the sweep points.

Why the static solver lands there: Newton's method converges to the equilibrium nearest its
start, stable or not.  With load steps larger than the path's curvature near a bifurcation
(a column passing its buckling load with a small imperfection), a step jumps over the stable
branch onto the straight, unstable state or onto a higher buckling mode (measured on a
cantilever at 10 times the Euler load with a 1 mN nudge: 16 beam elements returned an S-shaped
state with the tip 5 mm up, against the nudge, 4 rod modes and 16 ANCF elements the straight
state; all three unstable, the lowest eigenvalue about -25 to -48 times the unloaded one).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from ..errors import StabilityWarning
from ..mbs.stability import CRITICAL_MARGIN, Stability, StabilityProbe
from ..mechanism.assembly import Mechanism
from .mechanism_checks import lowest_first_frequency

__all__ = ["stability_probe", "warn_unstable", "load_path_note", "free_motion_note", "FREE_MOTION"]

#: An unloaded lowest eigenvalue ``omega^2`` below this share of the parts' own (their clamped-free estimates') is a
#: motion without stiffness: a link on a free pin (measured 3.4e-5 Hz against a bender's 260 Hz: 1.7e-14).
FREE_MOTION = 1e-8


def stability_probe(mech: Mechanism, model) -> StabilityProbe:
    """The probe of a freshly built ``model`` (in its reference pose): its unloaded lowest eigenvalue is the scale.

    The fallback scale, for a mechanism with a direction of no stiffness when unloaded, is the
    lowest clamped-free frequency estimate of its benders and flexures (1 rad/s without them).
    """
    frequency, _ = lowest_first_frequency(mech)
    omega = 2.0 * math.pi * frequency if math.isfinite(frequency) else 1.0
    return StabilityProbe(model, omega * omega)


def load_path_note(probe: StabilityProbe) -> str:
    """For an unstable or critical equilibrium solved from the reference pose: the load factor at which its loading
    path lost stability (:meth:`~exudyn_atcm.mbs.stability.StabilityProbe.critical_load_factor`), as a sentence for
    :func:`warn_unstable`; ``""`` for a stable one or when there is no estimate."""
    if probe.last is None or probe.last.state == "stable":
        return ""
    factor = probe.critical_load_factor()
    if not math.isfinite(factor):
        return ""
    return (f"The loading path lost its stability at about load factor {factor:.3g} (a linear estimate from the "
            "unloaded and the final stiffness; exact for a column that stays straight)")


def free_motion_note(model, probe: StabilityProbe | None) -> str:
    """When the unloaded mechanism has a motion without stiffness (:data:`FREE_MOTION`): a sentence naming it and the
    parts that move in it, for a failed static solve's message (Newton's method has no equilibrium to find along
    it, whatever the cells); ``""`` otherwise."""
    if probe is None or not probe.reference_lowest < FREE_MOTION * probe.fallback_scale:
        return ""
    mode = np.asarray(probe.reference_mode, dtype=float)
    owners = {body: part for part, body in model.group_of_component.items()}
    for bender, keys in model.cells.items():
        owners.update({key: bender for key in keys})
    amplitude: dict[str, float] = {}
    for key, body in model.bodies.items():
        index = getattr(body, "ode2", None)
        part = owners.get(key, key).split("#")[0]
        if index is not None and index >= 0 and index + 3 <= mode.size:
            amplitude[part] = max(amplitude.get(part, 0.0), float(np.max(np.abs(mode[index:index + 3]))))
    largest = max(amplitude.values(), default=0.0)
    moving = [part for part, a in amplitude.items() if largest > 0.0 and a >= 0.5 * largest]
    frequency = math.sqrt(max(probe.reference_lowest, 0.0)) / (2.0 * math.pi)
    return (f"The mechanism has a motion without stiffness in its reference pose (lowest eigenfrequency "
            f"{frequency:.2g} Hz{'; moving most: ' + ', '.join(moving) if moving else ''}): no load holds it, so it "
            "has no static equilibrium to find. Hold it (a pin or slider with stiffness=, a spring, a ground "
            "connection) or follow its motion with simulate()")


def _describe(s: Stability) -> str:
    return (f"omega_1^2/omega_ref^2 = {s.margin:.3g}, a lowest frequency of {s.frequency:.3g} Hz "
            "(negative: an unstable direction)")


def warn_unstable(subject: str, states: list[tuple[str, Stability]], note: str = "", stacklevel: int = 3) -> None:
    """One :class:`~exudyn_atcm.errors.StabilityWarning` for the unstable and critical equilibria of a run.

    Parameters
    ----------
    subject : str
        Who (``"mechanism 'm' (bender 'b': 16 beam cells)"``).
    states : list of (str, Stability)
        ``(where, stability)`` per equilibrium, ``where`` as ``"load factor 1 (voltage 0 V)"`` or
        ``"sweep point 3 (voltage 500 V)"``; stable ones are left out of the message.
    note : str
        A last sentence (:func:`load_path_note`).
    stacklevel : int
        Counted from this function.
    """
    unstable = [(w, s) for w, s in states if s.state == "unstable"]
    critical = [(w, s) for w, s in states if s.state == "critical"]
    if not unstable and not critical:
        return
    parts = []
    if unstable:
        where, first = unstable[0]
        more = f" (and {len(unstable) - 1} more of {len(states)})" if len(unstable) > 1 else ""
        parts.append(
            f"the static equilibrium of {subject} at {where}{more} is UNSTABLE: the lowest eigenvalue of its "
            f"constrained tangent stiffness is negative ({_describe(first)}). A real mechanism would not rest there "
            "(e.g. a column above its buckling load held straight), and dynamic relaxation along the loading path "
            "found no stable state (a perfectly symmetric load has no side to buckle to). Add the imperfection "
            "you expect (a small transverse force) so that the stable branch can be followed, reduce the loads, "
            "or follow the motion with simulate()")
    if critical:
        where, first = critical[0]
        more = f" (and {len(critical) - 1} more of {len(states)})" if len(critical) > 1 else ""
        parts.append(
            f"the static equilibrium of {subject} at {where}{more} is CRITICAL (at a stability limit: buckling or "
            f"snap-through): {_describe(first)}, below {CRITICAL_MARGIN:g} of the unloaded mechanism's; its pose "
            f"depends on imperfections the model does not hold, amplified about {1.0 / max(abs(first.margin), 1e-300):.3g}"
            " times. Add the imperfection you expect, or keep the loads away from this limit")
    warnings.warn("; ".join(parts) + (f". {note}" if note else ""), StabilityWarning, stacklevel=stacklevel + 1)
