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

import math

import exudyn as exu
import numpy as np
from exudyn import itemInterface as ii

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
from .items import rigid_marker as _rigid_marker
from .model import Body, Element, MechanismModel
from .graphics import part_graphics, shift_graphics
from .connection_context import ConnectionContext, realise_connections
from . import chains
from .mass_damping import MassDampers, part_mass_damping_factor
from .realisation import make_realisation
from .redundancy import CELLS_LABEL, end_label, labelled, refuse_redundant

#: The cell kinds' realisation modules (:mod:`exudyn_atcm.mbs.chains`), imported and so registered with it.
REALISATIONS = chains.MODULES


# ---------------------------------------------------------------------------- building

class _Builder(BuildContext):
    def __init__(self, mbs, mech: Mechanism, ground_item: int | None = None, free_end_bodies: bool = False,
                 stroke_path: str = "prestep", package_solves: bool = False) -> None:
        super().__init__(mbs, mech, MechanismModel(mechanism=mech, mbs=mbs, stroke_path=stroke_path), package_solves)
        self.mech = mech
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
            self.realisations[bender.name] = make_realisation(bender)
        if self.ground_item is None:
            self.ground_item = mbs.AddObject(ii.ObjectGround(visualization={'show': False, 'graphicsDataUserFunction': 0,
                                                                            'graphicsData': []}))
        gnode = mbs.AddNode(ii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0], visualization=_NOVIS))
        self.ground_coordinate = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=gnode, coordinate=0))
        self.dampers = MassDampers(mbs, self.ground_item, self.ground_coordinate)
        model.bodies[GROUND] = Body(GROUND, None, self.ground_item, np.zeros(3))
        on_group_body = {name for name, r in self.realisations.items() if r.ends_on_group_body}
        node_ends = {name for name, r in self.realisations.items() if r.ends_are_nodes}
        self.groups, self.group_of = rigid_groups(mech, self.free_end_bodies, on_group_body, node_ends)
        check_end_connections(mech, self.groups, self.group_of, self.free_end_bodies)
        self._group_bodies()
        for bender in mech.benders:
            with self._labelled(CELLS_LABEL.format(name=bender.name)):
                self.realisations[bender.name].add_cells(self)
        for key, g in self.groups.items():
            if g.kind == "beam-node":  # the group's body is the first node end among its parts
                keys = (self._end_body_key(p) for p in g.interfaces)
                model.bodies[key] = model.bodies[next(k for k in keys if k is not None)]
        self._anchor_points()
        for bender in mech.benders:
            for end in ("base", "tip"):
                with self._labelled(end_label(mech, bender, end)):
                    self.realisations[bender.name].connect_end(self, end)
        context = ConnectionContext(model, self.ground_coordinate, self._pin, self._slider)
        # joints with the bodies (their springs join the hinges'), then the loads and other connections
        realise_connections(context, mech.joints, self._labelled)
        self._flexure_pivots()
        for realisation in self.realisations.values():
            writer, hook = realisation.strain_writer(), realisation.linearisation_hook()
            if writer is not None:
                self.add_strain_writer(writer)
            if hook is not None:
                self.add_linearisation_hook(hook)
        realise_actuation(mbs, mech, model, self.ground_coordinate, self.zeros, self.clamped)
        realise_connections(context, [c for c in mech.connections if not c.holds], self._labelled)
        return model

    def _end_body_key(self, part: str) -> str | None:
        name, _, end = part.partition("#")
        realisation = self.realisations.get(name)
        return realisation.end_body_key(end) if realisation is not None else None

    def _flexure_pivots(self) -> None:
        """The pseudo-rigid-body flexures' characteristic pivots: a hinge with the spring ``K``."""
        for comp in self.mech.components.values():
            if isinstance(comp, Flexure) and comp.model == "prbm":
                a, b = self.group_of[f"{comp.name}#base"], self.group_of[f"{comp.name}#tip"]
                if a == b:
                    continue  # both segments in one rigid group: the hinge cannot turn
                k = comp.torsion_stiffness
                el = Element(k, comp.stiffness_damping_factor * k, self.zeros(), self.zeros())
                with self._labelled(f"the pivot of flexure {comp.name!r}"):
                    self.hinge_at(a, b, [el], comp.pivot)

    def _group_bodies(self) -> None:
        model = self.model
        for key, g in self.groups.items():
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
                self.add_mass_damping(model.bodies[key], alpha, mm, j, c - com)

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
        if comp.name in self.realisations:
            return self.realisations[comp.name]
        return make_realisation(comp if isinstance(comp, Bender) else comp.as_bender())

    def _interface_body(self, key: str, part: str) -> Body:
        """A bender end's own interface body: node at the end point, the bender's reference angle."""
        name, _, end = part.partition("#")
        comp = self.mech.components[name]
        realisation = self._end_realisation(comp)
        bender = realisation.bender
        m, j, com = realisation.interface_body_mass(end)
        body = _add_body(self.mbs, key, bender.points[end], bender.angle, m, j, com, [])
        self.add_mass_damping(body, bender.mass_damping_factor, m, j, com)
        return body

    def end_element(self, bender_name: str, end: str) -> tuple[Element, str, tuple[float, float]]:
        """The end spring of a bender end: element, end cell key, the end point in the cell's frame."""
        return self.realisations[bender_name].end_spring(self, end)

    # ---------------------------------------------------------------- points
    def _anchor_points(self) -> None:
        """Body and local position of every component point."""
        mech, model = self.mech, self.model
        for comp in mech.components.values():
            for pname, pos in comp.points.items():
                ref = PointRef(comp.name, pname)
                part = part_of(mech, ref)
                g = self.groups[self.group_of[part]]
                rigid = isinstance(comp, Link) or (isinstance(comp, Flexure) and comp.model == "prbm")
                if rigid:
                    model.group_of_component[part] = g.key
                if rigid or g.kind != "virtual":
                    body = model.bodies[g.key]
                    model.anchors[str(ref)] = (g.key, local_point(body, pos))
                else:
                    _, cell, local = self.end_element(comp.name, pname)
                    model.anchors[str(ref)] = (cell, np.array(local, dtype=float))

    # ---------------------------------------------------------------- joints
    def _side(self, ref: PointRef | None) -> str:
        """Group key, or the interface part if ``ref`` is a virtual bender end."""
        part = part_of(self.mech, ref)
        g = self.groups[self.group_of[part]]
        return part if g.kind == "virtual" else g.key

    def _movable(self, label: str, side_a: str, side_b: str) -> None:
        """Refuse a joint between two points of one rigid group (welded together): it could not move."""
        if side_a == side_b:
            group = self.groups[self.group_of[side_a]] if side_a in self.group_of else self.groups[side_a]
            parts = ", ".join(sorted(p.replace("#", ".") for p in group.parts))
            raise MechanismError(
                f"{label} joins two points of one rigid group (welded together: {parts}); it cannot "
                "move. Remove the joint or one of the welds")

    def _pin(self, p: PointRef, q: PointRef | None, stiffness: float, damping: float, label: str) -> None:
        side_a, side_b = self._side(p), self._side(q)
        self._movable(label, side_a, side_b)
        pin_el = Element(stiffness, damping, self.zeros(), self.zeros())
        self.join_in_series(side_a, pin_el, side_b, self.mech.position(p))

    def _slider(self, p: PointRef, q: PointRef | None, axis: tuple[float, float], stiffness: float, damping: float,
                label: str) -> None:
        mbs, model = self.mbs, self.model
        a, b = self._side(p), self._side(q)
        self._movable(label, a, b)
        body_a, body_b = model.bodies[a], model.bodies[b]
        pos = self.mech.position(p)
        pos_q = pos if q is None else self.mech.position(q)
        la, lb = local_point(body_a, pos), local_point(body_b, pos_q)
        ca, sa = math.cos(body_a.reference[2]), math.sin(body_a.reference[2])
        cb, sb = math.cos(body_b.reference[2]), math.sin(body_b.reference[2])
        ax, ay = axis
        axis_a = [ca * ax + sa * ay, -sa * ax + ca * ay, 0.0]
        normal_b = [cb * (-ay) + sb * ax, -sb * (-ay) + cb * ax, 0.0]
        ma, mb = _rigid_marker(mbs, body_a, la), _rigid_marker(mbs, body_b, lb)
        mbs.AddObject(ii.ObjectJointPrismatic2D(markerNumbers=[ma, mb], axisMarker0=axis_a, normalMarker1=normal_b,
                                                constrainRotation=True, visualization=_NOVIS))
        if stiffness > 0.0 or damping > 0.0:
            # the sliding coordinate: relative translation along the axis (zero in the reference pose)
            coord = mbs.AddMarker(ii.MarkerBodiesRelativeTranslationCoordinate(
                bodyNumbers=[body_a.item, body_b.item], localPosition0=[la[0], la[1], 0.0],
                localPosition1=[lb[0], lb[1], 0.0], axis0=axis_a))
            item = mbs.AddObject(ii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[self.ground_coordinate, coord], stiffness=stiffness, damping=damping, visualization=_NOVIS))
            model.springs.append((item, stiffness, "damping"))


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
