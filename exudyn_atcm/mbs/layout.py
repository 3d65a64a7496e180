"""How a mechanism maps onto rigid bodies and hinges (pure Python; the Exudyn items come later).

Rigid parts are the ground, each link, the two rigid segments of a pseudo-rigid-body
flexure and each bender end's interface.  Welds merge parts into rigid groups (union-find).
A group holding the ground is the ground; a group holding a link or a flexure segment is one
body.  A group of bender-end interfaces only stays *virtual* (massless, no body) when that
is exact:

* one interface, no joint: a free end;
* one interface and one pin: the pin joins the end cell directly; the end spring and the
  pin's spring act in series;
* two interfaces welded together, no other joint: the two end cells are joined directly,
  their end springs in series (for one laminate and cell length this is exactly the inner
  joint of one longer bender).

A group of bender ends holding a beam bender's end node (cell ``"beam"``) has that node as its
body, without a mass of its own (a slider needs a real body: then an interface body).
Any other interface group (and, on request, a free end) becomes a small interface body (the laminate over a length
``min(h1 + h2, L_c/10)`` per interface, as the six-bar cell's interface elements).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender
from ..mechanism.flexure import Flexure
from ..mechanism.link import Link
from ..mechanism.points import GROUND, MechanismError, PointRef


def part_of(mech: Mechanism, ref: PointRef | None) -> str:
    """Key of the rigid part that carries ``ref`` (``None``: the ground)."""
    if ref is None:
        return GROUND
    comp = mech.components[ref.component]
    if isinstance(comp, Link):
        return comp.name
    if isinstance(comp, Flexure) and comp.model == "prbm":
        return f"{comp.name}#{ref.point}"
    return f"{comp.name}#{ref.point}"  # bender (or cells flexure) end interface


def is_interface(mech: Mechanism, part: str) -> bool:
    """True if ``part`` is a bender end's interface."""
    if part == GROUND or "#" not in part:
        return False
    comp = mech.components[part.split("#")[0]]
    return isinstance(comp, Bender) or (isinstance(comp, Flexure) and comp.model == "cells")


@dataclass
class Group:
    """A rigid group of parts (one body, the ground, or a virtual interface group)."""

    key: str
    parts: list[str] = field(default_factory=list)
    kind: str = "body"            # "ground" | "body" | "interface-body" | "virtual"
    joints: list = field(default_factory=list)  # non-weld joints touching the group
    interfaces: list[str] = field(default_factory=list)  # bender-end interface parts


def rigid_groups(mech: Mechanism, free_end_bodies: bool = False,
                 six_bar: frozenset[str] | set[str] = frozenset(),
                 beam: frozenset[str] | set[str] = frozenset()) -> tuple[dict[str, Group], dict[str, str]]:
    """Groups by key and the group key of every part.

    ``free_end_bodies=True`` gives free bender ends an interface body too (so that a user's
    joints can attach to them; see :func:`exudyn_atcm.add_to`).  The ends of the benders named
    in ``six_bar`` are real interface bodies of the six-bar chain, never virtual.  The ends of
    the benders named in ``beam`` are beam nodes: a group of bender ends holding one is a
    ``"beam-node"`` group whose body is that node (a slider needs a real body: then an
    interface body, the node welded to it).
    """
    parts = [GROUND]
    for comp in mech.components.values():
        if isinstance(comp, Link):
            parts.append(comp.name)
        else:
            parts += [f"{comp.name}#base", f"{comp.name}#tip"]
    parent = {p: p for p in parts}

    def find(a: str) -> str:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for j in mech.joints:
        if j.fuses:
            a, b = find(part_of(mech, j.p)), find(part_of(mech, j.q))
            if a != b:
                # keep the ground as the root so that its group key is "ground"
                if b == GROUND:
                    a, b = b, a
                parent[b] = a
    groups: dict[str, Group] = {}
    group_of: dict[str, str] = {}
    for p in parts:
        root = find(p)
        groups.setdefault(root, Group(root)).parts.append(p)
        group_of[p] = root
    for j in mech.joints:
        if j.fuses:
            continue
        for ref in (j.p, j.q):
            g = groups[group_of[part_of(mech, ref)]]
            if j not in g.joints:
                g.joints.append(j)
    for g in groups.values():
        ifaces = g.interfaces = [p for p in g.parts if is_interface(mech, p)]
        others = [p for p in g.parts if not is_interface(mech, p)]
        if GROUND in g.parts:
            g.kind = "ground"
        elif others or any(p.partition("#")[0] in six_bar for p in ifaces):
            g.kind = "body"
        elif any(p.partition("#")[0] in beam for p in ifaces):
            g.kind = "interface-body" if any(j.kind == "slider" for j in g.joints) else "beam-node"
        elif (len(ifaces) == 1 and not g.joints and not free_end_bodies) or \
                (len(ifaces) == 1 and len(g.joints) == 1 and g.joints[0].kind == "pin") or \
                (len(ifaces) == 2 and not g.joints):
            g.kind = "virtual"
        else:
            g.kind = "interface-body"
    return groups, group_of


def check_end_connections(mech: Mechanism, groups: dict[str, Group], group_of: dict[str, str],
                          free_end_bodies: bool = False) -> None:
    """Refuse the end connections and loads a bender's cell kind cannot realise, in the cell's own words
    (:meth:`~exudyn_atcm.cells.CellKind.end_refusal`, :meth:`~exudyn_atcm.cells.CellKind.tip_load_refusal`,
    and with ``free_end_bodies`` (:func:`~exudyn_atcm.add_to`) :meth:`~exudyn_atcm.cells.CellKind.add_to_refusal`).

    Raises
    ------
    MechanismError
        Naming the bender and the end or the load.
    """
    for bender in mech.benders:
        refusal = bender.cell.add_to_refusal() if free_end_bodies else None
        if refusal is not None:
            raise MechanismError(f"add_to: bender {bender.name!r}: {refusal}")
        for end in ("base", "tip"):
            part = f"{bender.name}#{end}"
            g = groups[group_of[part]]
            if g.kind == "ground":
                connection = "ground"
            elif g.parts == [part] and not g.joints and (not free_end_bodies or g.kind == "beam-node"):
                # free (a user's joints may attach to an end node through add_to, as to a beam's)
                connection = "free"
            else:
                connection = "joined"
            refusal = bender.cell.end_refusal(end, connection)
            if refusal is not None:
                raise MechanismError(f"bender {bender.name!r}: {refusal}")
    loaded = [(c.name, ref) for c in mech.connections if c.loads_points for ref in c.points()]
    for name, ref in loaded:
        comp = mech.components.get(ref.component) if ref is not None else None
        refusal = comp.cell.tip_load_refusal() if isinstance(comp, Bender) else None
        if refusal is not None:
            raise MechanismError(f"{name!r} acts at {ref} of bender {comp.name!r}: {refusal}")
