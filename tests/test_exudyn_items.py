"""The builder's short item dictionaries (:mod:`exudyn_atcm.mbs.exudyn_items`) store what Exudyn's item interface does.

Reference: Exudyn's own ``exudyn.itemInterface`` classes.  Each mechanism is built twice, once with the
short dictionaries and once with every item made through the item interface (the factory patched to call
it), and every node, object, marker, load and sensor Exudyn stores is compared field by field (user
functions, new closures at every build, by their qualified names).  The mechanisms cover every cell kind,
every connection and load the builder writes, Rayleigh mass damping and :func:`exudyn_atcm.add_to`'s sensors.
"""

from __future__ import annotations

import math

import exudyn as exu
import numpy as np
import pytest
from exudyn import itemInterface

import exudyn_atcm as atcm
from exudyn_atcm import mbs as mb
from exudyn_atcm.mbs.exudyn_items import ItemFactory, ii
from exudyn_atcm.model import Triangle

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
CATEGORIES = (("Node", "GetNode"), ("Object", "GetObject"), ("Marker", "GetMarker"), ("Load", "GetLoad"),
              ("Sensor", "GetSensor"))


def four_bar(cell: str, n_cells: int, damping=None) -> atcm.Mechanism:
    extra = {} if damping is None else {"damping": damping}
    crank = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=n_cells,
                        drive=atcm.PiezoDrive(Triangle(0.0, 1000.0, 0.1)), angle=math.pi / 2, cell=cell, **extra)
    coupler = atcm.Link("coupler", {"A": (0.0, 0.03), "B": (0.04, 0.03), "P": (0.02, 0.05)}, mass=1e-4, inertia=1e-8)
    rocker = atcm.Link("rocker", {"B": (0.04, 0.03), "O": (0.04, 0.0)}, mass=1e-4, inertia=1e-8)
    m = atcm.Mechanism("four_bar").add(crank, coupler, rocker).ground(crank.base)
    m.pin(crank.tip, coupler.point("A")).pin("coupler.B", "rocker.B").ground("rocker.O", joint="pin")
    return m


def cantilever(cell: str, n_cells: int) -> atcm.Mechanism:
    bender = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.06, n_cells=n_cells,
                         drive=atcm.PiezoDrive(500.0), cell=cell)
    return atcm.Mechanism("lone").add(bender).ground(bender.base)


def loaded() -> atcm.Mechanism:
    """Sliders, a pin with a spring and damper, a follower and a dead force, a torque, a spring, a stop, flexures."""
    base = atcm.Link("base", {"O": (0.0, 0.0), "S": (0.02, 0.0)}, mass=1e-3, inertia=1e-7)
    slide = atcm.Link("slide", {"S": (0.02, 0.0), "P": (0.03, 0.0), "Q": (0.03, 0.01)}, mass=1e-3, inertia=1e-7)
    arm = atcm.Link("arm", {"O": (0.0, 0.02), "P": (0.02, 0.02), "F": (0.0, 0.03)}, mass=1e-4, inertia=1e-8)
    hinge = atcm.Flexure("hinge", base=(0.0, 0.03), tip=(0.0, 0.035), width=5e-3, layer=CFC)
    strip = atcm.Flexure("strip", base=(0.03, 0.01), tip=(0.03, 0.02), width=5e-3, layer=CFC, model="cells", n_cells=3)
    m = atcm.Mechanism("loaded").add(base, slide, arm, hinge, strip).ground("base.O")
    m.slider("base.S", "slide.S", axis=(1.0, 0.0), stiffness=50.0, damping=0.01)
    m.ground("arm.O", joint="pin", stiffness=0.05, damping=1e-4)
    m.weld("arm.F", "hinge.base").weld("slide.Q", "strip.base")
    m.force("arm.P", (0.0, 0.1), follower=True).force("slide.P", (0.2, 0.0)).torque("arm", 1e-3)
    m.spring("arm.P", "slide.P", 20.0, damping=0.01)
    m.stop("slide.P", position=(0.035, 0.0), normal=(-1.0, 0.0), stiffness=1e4, name="wall")
    return m


MECHANISMS = {
    **{f"four-bar {cell}": (lambda cell=cell: four_bar(cell, 3 if cell in ("rod", "ritz") else 4))
       for cell in ("rigid", "six-bar", "beam", "rod")},
    "four-bar rigid, mass damping": lambda: four_bar("rigid", 4, atcm.RayleighDamping(alpha=5.0, beta=1e-5)),
    "cantilever ritz": lambda: cantilever("ritz", 3),
    "cantilever ancf": lambda: cantilever("ancf", 3),
    "loaded links and flexures": loaded,
}


def stored_items(mbs) -> dict:
    out = {}
    for category, getter in CATEGORIES:
        count = getattr(mbs.systemData, f"NumberOf{category}s")()
        get = getattr(mbs, getter)
        out[category] = [get(i, addGraphicsData=True) if category == "Object" else get(i) for i in range(count)]
    return out


def same(a, b) -> bool:
    """Equal field by field (arrays elementwise, user functions by name)."""
    if callable(a) or callable(b):
        return getattr(a, "__qualname__", repr(type(a))) == getattr(b, "__qualname__", repr(type(b)))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if type(a).__name__.endswith("Index"):  # Exudyn's NodeIndex, MarkerIndex...: no equality of their own
        return type(a) is type(b) and int(a) == int(b)
    if type(a).__name__ == "MatrixContainer":
        return type(b) is type(a) and np.array_equal(a.Convert2DenseMatrix(), b.Convert2DenseMatrix())
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a), np.asarray(b))
    return type(a) is type(b) and a == b


def through_interface(self: ItemFactory, **fields) -> dict:
    return dict(getattr(itemInterface, self.interface)(**fields))


def build_items(make, monkeypatch=None, add_to=False) -> dict:
    if add_to:
        sc = exu.SystemContainer()
        mbs = sc.AddSystem()
        atcm.add_to(mbs, make())
        return stored_items(mbs)
    return stored_items(mb.build(make()).mbs)


@pytest.mark.parametrize("name", list(MECHANISMS))
def test_every_item_is_stored_as_through_the_item_interface(name, monkeypatch):
    short = build_items(MECHANISMS[name])
    with monkeypatch.context() as patch:
        patch.setattr(ItemFactory, "__call__", through_interface)
        reference = build_items(MECHANISMS[name])
    for category, _ in CATEGORIES:
        assert len(short[category]) == len(reference[category]), category
        for k, (a, b) in enumerate(zip(short[category], reference[category])):
            assert same(a, b), f"{category} {k}: {a} != {b}"
    assert sum(len(v) for v in short.values()) >= 5  # the build really added items


def test_add_to_sensors_are_stored_as_through_the_item_interface(monkeypatch):
    make = MECHANISMS["four-bar rigid"]
    short = build_items(make, add_to=True)
    with monkeypatch.context() as patch:
        patch.setattr(ItemFactory, "__call__", through_interface)
        reference = build_items(make, add_to=True)
    assert len(short["Sensor"]) == len(reference["Sensor"]) > 0
    for category, _ in CATEGORIES:
        assert all(same(a, b) for a, b in zip(short[category], reference[category])), category


def test_a_misspelt_keyword_or_item_is_refused_as_by_the_item_interface():
    with pytest.raises(TypeError, match="markerNumber"):
        ii.ObjectJointRevolute2D(markerNumber=[0, 1])
    with pytest.raises(TypeError):
        itemInterface.ObjectJointRevolute2D(markerNumber=[0, 1])
    with pytest.raises(AttributeError, match="NoSuchJoint"):
        ii.ObjectNoSuchJoint
    assert ii.MarkerNodeCoordinate(nodeNumber=3, coordinate=2) == {
        "markerType": "NodeCoordinate", "nodeNumber": 3, "coordinate": 2}
