"""The one builder: adds a :class:`~exudyn_atcm.mechanism.Mechanism` to an Exudyn ``MainSystem``.

A lone :class:`~exudyn_atcm.BendingActuator` is built here too, as the one-bender mechanism it
is (:mod:`exudyn_atcm.solve.as_mechanism`).  The builder knows no cell kind: each bender's cells
and ends are added by the realisation registered for its kind, through the calls of the written
contract (:mod:`exudyn_atcm.mbs.realisation`) and the public build context the builder is
(:mod:`exudyn_atcm.mbs.build_context`).  The package's realisations are in
:mod:`exudyn_atcm.mbs.chains`; the rest of this description is about rigid cells.

Model (planar, SI units):

* Every rigid cell of a bender is one body (both layers' mass, the node at the cell's end
  joint, reference angle = the bender's direction).  Neighbouring cells are joined by a
  revolute joint and a torsion spring ``2 EI/(L_j + L_{j+1})`` (``EI/L_c`` for equal cells).
* Rigid groups (see :mod:`exudyn_atcm.mbs.layout`) are one body each (summed mass,
  parallel-axis inertia, node at the centre of mass, reference angle 0); the ground group is
  Exudyn's ground.
* A bender end is an interface joined to its end cell by the end spring ``2 EI/L_c``
  (half a cell).  A *hinge* joins two bodies by a revolute joint at the point and one
  torsion spring-damper made of the compliances in series on the way: a virtual interface's
  end spring, a pin's spring (0: free, weld: rigid), the other end spring.  A free tip's
  interface is massless, so its angle is the last cell's angle plus half a cell's free
  rotation (the tip angle of a lone actuator).
* Actuation: every spring's rest angle is the free rotation of the half cells it stands for,
  realised as torque pairs summed per body (or as the springs' offsets, or user functions:
  :mod:`exudyn_atcm.mbs.actuation`).  For a uniform cantilever that is one torque ``EI kappa``
  on the last cell.
* Damping: every spring ``k`` of a bender gets ``beta k`` (series springs of one ``beta`` keep
  it); with a mass-proportional part ``alpha`` every laminate mass (cells, interface masses,
  flexure segments; not links) gets a force at its own centre and a torque
  (:mod:`exudyn_atcm.mbs.mass_damping`).

The :mod:`exudyn_atcm.mbs` package holds the package's only Exudyn calls.
"""

from __future__ import annotations

import exudyn as exu
import numpy as np
from .exudyn_items import ii

from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender, passive_strip_cells
from ..mechanism.flexure import Flexure
from ..mechanism.link import Link
from ..mechanism.points import GROUND, MechanismError, PointRef
from .actuation import realise_actuation
from .build_context import BuildContext
from .layout import check_end_connections, part_of, rigid_groups
from .items import NOVIS as _NOVIS
from .items import add_body as _add_body
from .items import local_point
from .model import Body, Element, MechanismModel
from .graphics import part_graphics, shift_graphics
from . import chains
from .mass_damping import MassDampers, part_mass_damping_factor
from .realisation import make_realisation
from .redundancy import CELLS_LABEL, end_label, labelled, refuse_redundant

#: The cell kinds' realisation modules (:mod:`exudyn_atcm.mbs.chains`), imported and so registered with it.
REALISATIONS = chains.MODULES


# ---------------------------------------------------------------------------- building

class _Builder:
    """Builds one mechanism into ``mbs`` through the one public :class:`BuildContext` it hands to the extensions."""

    def __init__(self, mbs, mech: Mechanism, ground_item: int | None = None, free_end_bodies: bool = False,
                 stroke_path: str = "prestep", package_solves: bool = False) -> None:
        self.mbs, self.mech = mbs, mech
        self.model = MechanismModel(mechanism=mech, mbs=mbs, stroke_path=stroke_path)
        self.ctx = BuildContext(mbs, mech, self.model, package_solves)
        self.free_end_bodies = free_end_bodies
        self.ground_item = ground_item
        sources: list = []
        for name, drive in mech.drives.items():
            for k, s in enumerate(sources):
                if s is drive:
                    self.model.drive_source[name] = k
                    break
            else:
                self.model.drive_source[name] = len(sources)
                sources.append(drive)
        self.model.sources = sources

    def _labelled(self, label: str):
        """Label the objects added inside this ``with`` block as realising ``label`` (redundancy messages)."""
        return labelled(self.mbs, self.model, label)

    # ---------------------------------------------------------------- ground and groups
    def build(self) -> MechanismModel:
        mbs, mech, model = self.mbs, self.mech, self.model
        for bender in mech.benders:
            bender.cell.check_stroke_path(model.stroke_path)
            if bender.cell.needs_active_layer and bender.active is None:
                raise MechanismError(
                    f"bender {bender.name!r}: the {bender.cell.name} cell models two layers; a passive strip "
                    f"(active=None) needs {' or '.join(f'cell={n!r}' for n in passive_strip_cells())}")
            self.ctx.realisations[bender.name] = make_realisation(bender)
        if self.ground_item is None:
            self.ground_item = mbs.AddObject(ii.ObjectGround(visualization={'show': False, 'graphicsDataUserFunction': 0,
                                                                            'graphicsData': []}))
        gnode = mbs.AddNode(ii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0], visualization=_NOVIS))
        self.ctx.ground_coordinate = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=gnode, coordinate=0))
        self.ctx.dampers = MassDampers(mbs, self.ground_item, self.ctx.ground_coordinate)
        model.bodies[GROUND] = Body(GROUND, None, self.ground_item, np.zeros(3))
        on_group_body = {name for name, r in self.ctx.realisations.items() if r.ends_on_group_body}
        node_ends = {name for name, r in self.ctx.realisations.items() if r.ends_are_nodes}
        self.ctx.groups, self.ctx.group_of = rigid_groups(mech, self.free_end_bodies, on_group_body, node_ends)
        check_end_connections(mech, self.ctx.groups, self.ctx.group_of, self.free_end_bodies)
        self._group_bodies()
        for bender in mech.benders:
            with self._labelled(CELLS_LABEL.format(name=bender.name)):
                self.ctx.realisations[bender.name].add_cells(self.ctx)
        for key, g in self.ctx.groups.items():
            if g.kind == "beam-node":  # the group's body is the first node end among its parts
                keys = (self._end_body_key(p) for p in g.interfaces)
                model.bodies[key] = model.bodies[next(k for k in keys if k is not None)]
        self._anchor_points()
        for bender in mech.benders:
            for end in ("base", "tip"):
                with self._labelled(end_label(mech, bender, end)):
                    self.ctx.realisations[bender.name].connect_end(self.ctx, end)
        # joints with the bodies (their springs join the hinges'), then the loads and other connections
        self._realise_connections(mech.joints)
        self._flexure_pivots()
        for realisation in self.ctx.realisations.values():
            writer, hook = realisation.strain_writer(), realisation.linearisation_hook()
            if writer is not None:
                self.ctx.add_strain_writer(writer)
            if hook is not None:
                self.ctx.add_linearisation_hook(hook)
        realise_actuation(mbs, mech, model, self.ctx.ground_coordinate, self.ctx.zeros, self.ctx.clamped)
        self._realise_connections([c for c in mech.connections if not c.holds])
        return model

    def _end_body_key(self, part: str) -> str | None:
        name, _, end = part.partition("#")
        realisation = self.ctx.realisations.get(name)
        return realisation.end_body_key(end) if realisation is not None else None

    def _flexure_pivots(self) -> None:
        """The pseudo-rigid-body flexures' characteristic pivots: a hinge with the spring ``K``."""
        for comp in self.mech.components.values():
            if isinstance(comp, Flexure) and comp.model == "prbm":
                a, b = self.ctx.group_of[f"{comp.name}#base"], self.ctx.group_of[f"{comp.name}#tip"]
                if a == b:
                    continue  # both segments in one rigid group: the hinge cannot turn
                k = comp.torsion_stiffness
                el = Element(k, comp.stiffness_damping_factor * k, self.ctx.zeros(), self.ctx.zeros())
                with self._labelled(f"the pivot of flexure {comp.name!r}"):
                    self.ctx.hinge_at(a, b, [el], comp.pivot)

    def _group_bodies(self) -> None:
        model = self.model
        for key, g in self.ctx.groups.items():
            if g.kind == "ground":
                model.bodies[key] = model.bodies[GROUND]
                continue
            if g.kind in ("virtual", "beam-node"):
                continue
            if len(g.parts) == 1 and g.interfaces:
                model.bodies[key] = self._interface_body(key, g.parts[0])
                continue
            masses, graphics, damped = [], [], []
            for part in g.parts:
                # a bender end carried by the group's other parts adds what its realisation says
                own = self._part_masses(part, carried=g.kind == "body")
                masses += own
                damped += [(part_mass_damping_factor(self.mech, part), mm, j, c) for mm, j, c in own]
                graphics += part_graphics(self.mech, part)
            m = sum(mm for mm, _, _ in masses)
            com = sum(mm * c for mm, _, c in masses) / m
            inertia = sum(j + mm * float((c - com) @ (c - com)) for mm, j, c in masses)
            local_graphics = [shift_graphics(gd, -com) for gd in graphics]
            model.bodies[key] = _add_body(self.mbs, key, com, 0.0, m, inertia, (0.0, 0.0), local_graphics)
            for alpha, mm, j, c in damped:  # each laminate part's own mass, at its own centre
                self.ctx.add_mass_damping(model.bodies[key], alpha, mm, j, c - com)

    def _part_masses(self, part: str, carried: bool = False) -> list[tuple[float, float, np.ndarray]]:
        """(mass, inertia about own centre, centre) of a rigid part; a bender end's from its realisation."""
        if part == GROUND:
            return []
        name, _, end = part.partition("#")
        comp = self.mech.components[name]
        if isinstance(comp, Link):
            return [(comp.mass, comp.inertia, np.array(comp.center_of_mass))]
        if isinstance(comp, Flexure) and comp.model == "prbm":
            return [comp.segment_masses()[0 if end == "base" else 1]]
        return self._end_realisation(comp).end_masses(end, carried)

    def _end_realisation(self, comp):
        """The realisation of a bender (or a cells flexure's bender)."""
        if comp.name in self.ctx.realisations:
            return self.ctx.realisations[comp.name]
        return make_realisation(comp if isinstance(comp, Bender) else comp.as_bender())

    def _interface_body(self, key: str, part: str) -> Body:
        """A bender end's own interface body: node at the end point, the bender's reference angle."""
        name, _, end = part.partition("#")
        comp = self.mech.components[name]
        realisation = self._end_realisation(comp)
        bender = realisation.bender
        m, j, com = realisation.interface_body_mass(end)
        body = _add_body(self.mbs, key, bender.points[end], bender.angle, m, j, com, [])
        self.ctx.add_mass_damping(body, bender.mass_damping_factor, m, j, com)
        return body

    def end_element(self, bender_name: str, end: str) -> tuple[Element, str, tuple[float, float]]:
        """The end spring of a bender end: element, end cell key, the end point in the cell's frame."""
        return self.ctx.realisations[bender_name].end_spring(self.ctx, end)

    # ---------------------------------------------------------------- points
    def _anchor_points(self) -> None:
        """Body and local position of every component point."""
        mech, model = self.mech, self.model
        for comp in mech.components.values():
            for pname, pos in comp.points.items():
                ref = PointRef(comp.name, pname)
                part = part_of(mech, ref)
                g = self.ctx.groups[self.ctx.group_of[part]]
                rigid = isinstance(comp, Link) or (isinstance(comp, Flexure) and comp.model == "prbm")
                if rigid:
                    model.group_of_component[part] = g.key
                if rigid or g.kind != "virtual":
                    body = model.bodies[g.key]
                    model.anchors[str(ref)] = (g.key, local_point(body, pos))
                else:
                    _, cell, local = self.end_element(comp.name, pname)
                    model.anchors[str(ref)] = (cell, np.array(local, dtype=float))

    def _realise_connections(self, connections) -> None:
        """``connection.realise(self.ctx)`` for each of ``connections``, its items labelled with its description
        (for the messages on dependent joints); refuse one that recorded other columns than it declares."""
        for connection in connections:
            before = len(self.ctx.recorded())
            with self._labelled(connection.describe()):
                connection.realise(self.ctx)
            recorded, declared = list(self.ctx.recorded()[before:]), list(connection.readouts())
            if recorded != declared:
                raise MechanismError(f"{connection.describe()}: realise() recorded the columns {recorded} but "
                                     f"readouts() declares {declared}; call context.add_readout once per declared "
                                     "Readout")


def add_mechanism(mbs, mechanism: Mechanism, ground_item: int | None = None,
                  free_end_bodies: bool = False, stroke_path: str = "prestep",
                  package_solves: bool = False) -> MechanismModel:
    """Add the items of ``mechanism`` to ``mbs`` (not assembled); ``mechanism.check()`` must have passed.

    ``free_end_bodies=True`` gives free bender ends small interface bodies (for user joints);
    ``stroke_path`` chooses how the strains reach the system (:attr:`exudyn_atcm.cells.CellKind.stroke_paths`);
    ``package_solves=True``: only the package's runs solve the system, so cells may rely on
    their changes to the solver settings (``model.settings_adjusters``).
    """
    return _Builder(mbs, mechanism, ground_item, free_end_bodies, stroke_path, package_solves).build()


def build(mechanism: Mechanism, stroke_path: str = "prestep", refuse_dependent: bool = True) -> MechanismModel:
    """A new Exudyn system holding ``mechanism``, assembled.

    ``refuse_dependent``: refuse a mechanism whose constraints are dependent in the reference pose,
    naming the joints (:func:`~exudyn_atcm.mbs.redundancy.refuse_redundant`); ``False`` for the
    degrees-of-freedom count, which reports them.
    """
    mechanism.check(redundancy=False)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    model = add_mechanism(mbs, mechanism, stroke_path=stroke_path, package_solves=True)
    model.SC = SC
    # static tolerances of the cells when every bender's kind sets them (rigid: relative to the
    # deformation) and no part of the model set its own (beam elements' round-off floor)
    kinds = {b.cell for b in mechanism.benders}
    tolerances = {k.static_tolerances for k in kinds}
    if len(tolerances) == 1 and None not in tolerances and model.static_relative_tolerance is None:
        model.static_absolute_tolerance, model.static_relative_tolerance = tolerances.pop()
    if model.static_absolute_tolerance is not None:
        # one absolute tolerance for the whole residual: a rod's own (1e-12 EI/L) must not lie below the round-off
        # floor of beam elements beside it (a rod welded to 16 elements: 1.5e-13 N m against 8e-9 N, load factor 0)
        model.static_absolute_tolerance = max(model.static_absolute_tolerance, model.newton_tolerance_floor)
    mbs.Assemble()
    model.resolve_indices()
    if refuse_dependent:
        refuse_redundant(model)
    n = len(model.sources)
    model.path_from = np.zeros(n)
    model.path_to = np.zeros(n)
    model.set_strains(np.zeros(n))
    return model
