"""The whole-mechanism checks of :meth:`Mechanism.check <exudyn_atcm.Mechanism.check>`: ground
connection, assembly in the reference pose, drives."""

from __future__ import annotations

from typing import Any

from .joints import joint_label
from .points import GROUND, MechanismError


def check_connected(mech: Any) -> None:
    """Refuse components not connected to the ground through joints (naming them)."""
    parent = {name: name for name in [GROUND, *mech.components]}

    def find(a: str) -> str:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for j in mech.joints:
        parent[find(j.p.component)] = find(GROUND if j.q is None else j.q.component)
    floating = [name for name in mech.components if find(name) != find(GROUND)]
    if floating:
        by_spring = [n for n in floating if any(n in c.components() for c in mech.connections if not c.holds)]
        hint = (f"; {', '.join(by_spring)} hang(s) on springs only, which do not hold a body in place"
                if by_spring else "")
        raise MechanismError(
            f"component(s) {', '.join(repr(n) for n in floating)} of mechanism {mech.name!r} are not connected "
            f"to the ground through any joint{hint}; weld, pin or slide them to the rest of the mechanism")


def check_assembly(mech: Any, tolerance: float) -> None:
    """Refuse joints whose points do not meet in the reference pose (``tolerance`` times the size)."""
    tol = tolerance * max(mech.size, 1e-300)
    for j in mech.joints:
        xp = mech.position(j.p)
        xq = xp if j.q is None else mech.position(j.q)
        gap, what = j.assembly_gap(xp, xq)
        if gap > tol:
            qname = GROUND if j.q is None else str(j.q)
            raise MechanismError(
                f"{joint_label(j)} cannot be assembled: {what} in the reference pose: {j.p} at "
                f"({xp[0]:.9g}, {xp[1]:.9g}) m, {qname} at ({xq[0]:.9g}, {xq[1]:.9g}) m, gap {gap:.3g} m "
                f"(allowed {tol:.3g} m). Describe the mechanism in its assembled pose (benders straight)")


def check_drives(mech: Any) -> None:
    """Refuse different drives sharing one hysteresis operator object."""
    seen: dict[int, tuple[str, Any]] = {}
    for name, drive in mech.drives.items():
        op = drive.hysteresis
        if op is None:
            continue
        first = seen.get(id(op))
        if first is not None and first[1] is not drive:
            raise MechanismError(
                f"drives {first[0]!r} and {name!r} are different PiezoDrive objects sharing one hysteresis "
                "operator object; its memory would be updated twice per step. Give each drive its own "
                "operator, or use one PiezoDrive object for both")
        seen.setdefault(id(op), (name, drive))
