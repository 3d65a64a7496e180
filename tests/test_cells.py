"""Cell kinds as objects (issue 14, part 1): listed once, asked rather than compared by name, and
extensible from outside the package.

References: the chain polygon of a rigid chain under actuation (closed form,
:func:`exudyn_atcm.theory.beam.chain_polygon`), and the parent kind's own results, which a subclass
that changes nothing of the physics must reproduce to round-off.
"""

from __future__ import annotations

import ast
import pathlib

import exudyn as exu
import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm import MechanismError
from exudyn_atcm.cells import CELL_KINDS, CellKind, RigidCell, BeamCell, cell_kind
from exudyn_atcm.mbs import solver_settings
from exudyn_atcm.mbs.cells import add_mechanism_bender
from exudyn_atcm.plots.mechanism import plot_mechanism
from exudyn_atcm import theory as bt

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "exudyn_atcm"
CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)


class MyRigid(RigidCell):
    """A kind defined outside the package: the rigid chain under another name and joint label."""

    name = "my-rigid"
    joint_label = "my joints"


class MyBeam(BeamCell):
    name = "my-beam"


def actuator(cell, voltage=1500.0, n=6):
    return atcm.BendingActuator(n, 0.087 / n, 28e-3, CFC, MFC, atcm.PiezoDrive(voltage), cell=cell)


def bender_with_lever(cell):
    b = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4,
                    drive=atcm.PiezoDrive(atcm.signals.Triangle(750.0, 750.0, 0.1)), cell=cell)
    lever = atcm.Link("lever", {"A": (0.03, 0.0), "E": (0.05, 0.0)}, mass=2e-4, inertia=1e-8)
    return atcm.Mechanism("m").add(b, lever).ground(b.base).weld(b.tip, lever.point("A"))


# ----------------------------------------------------------------------------- resolution
def test_names_resolve_to_the_listed_kinds_and_compare_equal_to_them():
    for name, kind in CELL_KINDS.items():
        assert cell_kind(name) is kind
        assert kind == name and str(kind) == name and hash(kind) == hash(name)
    assert cell_kind(MyRigid) == MyRigid() and cell_kind(MyRigid()).name == "my-rigid"
    assert MyRigid() != RigidCell()  # another kind, although it is built like its parent


@pytest.mark.parametrize("bad", ["beams", 3, None, object()])
def test_unknown_cells_are_refused_naming_the_value_and_the_kinds(bad):
    with pytest.raises(ValueError, match=r"cell must be one of \('six-bar', 'rigid', 'beam', 'ancf', 'ritz', 'rod'\) "
                                         r"or a CellKind, got "):
        actuator(bad)


@pytest.mark.parametrize("typed, meant", [("Rigid", "rigid"), ("sixbar", "six-bar"), ("beams", "beam")])
def test_a_misspelt_cell_name_is_refused_with_the_closest_kind(typed, meant):
    with pytest.raises(ValueError, match=rf"got '{typed}' \(did you mean '{meant}'\?\)"):
        actuator(typed)


def test_no_package_code_compares_cell_names():
    """Outside cells/ no module compares a ``.cell`` (or ``cell``) with a string literal."""
    offenders = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.relative_to(PACKAGE).parts[0] == "cells":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Compare):
                names = [n for n in [node.left, *node.comparators]
                         if (isinstance(n, ast.Attribute) and n.attr == "cell") or (isinstance(n, ast.Name) and n.id == "cell")]
                strings = [n for n in [node.left, *node.comparators] if isinstance(n, ast.Constant) and isinstance(n.value, str)]
                tuples = [n for n in [node.left, *node.comparators] if isinstance(n, (ast.Tuple, ast.Set, ast.List))]
                if names and (strings or tuples):
                    offenders.append(f"{path.relative_to(PACKAGE)}:{node.lineno}")
    assert offenders == []


# ----------------------------------------------------------------------------- a kind from outside
def test_a_subclass_kind_works_in_a_lone_actuator():
    mine, ref = atcm.solve_static(actuator(MyRigid())), atcm.solve_static(actuator("rigid"))
    for name in ref.names:
        np.testing.assert_allclose(mine[name], ref[name], rtol=0, atol=1e-15, err_msg=name)
    assert mine.parameters["cell"] == "my-rigid"
    # and it is the rigid chain: the tip on the chain polygon of the free curvature
    act = actuator(MyRigid())
    kappa = act.free_curvature(act.drive.static_strain(1500.0))
    px, py = bt.chain_polygon(kappa, act.length, act.n_cells)
    assert mine["actuator.tip_x"][0] == pytest.approx(px[-1], abs=1e-9 * act.length)
    assert mine["actuator.tip_y"][0] == pytest.approx(py[-1], abs=1e-9 * act.length)


def test_a_subclass_kind_works_in_dynamics_and_eigenfrequencies():
    mine = atcm.simulate(actuator(MyRigid(), n=4), 0.005, step=1e-4)
    ref = atcm.simulate(actuator("rigid", n=4), 0.005, step=1e-4)
    np.testing.assert_allclose(mine["actuator.tip_y"], ref["actuator.tip_y"], rtol=0, atol=1e-15)
    f_mine = atcm.eigenfrequencies(actuator(MyRigid(), n=4), n=2, voltage=500.0)
    f_ref = atcm.eigenfrequencies(actuator("rigid", n=4), n=2, voltage=500.0)
    np.testing.assert_allclose(f_mine, f_ref, rtol=1e-12)


@pytest.mark.parametrize("mine, parent", [(MyRigid(), "rigid"), (MyBeam(), "beam")], ids=["rigid", "beam"])
def test_a_subclass_kind_works_in_a_mechanism_and_its_eigenfrequencies(mine, parent):
    r_mine = atcm.simulate(bender_with_lever(mine), 0.005, step=1e-4)
    r_ref = atcm.simulate(bender_with_lever(parent), 0.005, step=1e-4)
    assert r_mine.names == r_ref.names
    for name in r_ref.names:
        np.testing.assert_allclose(r_mine[name], r_ref[name], rtol=0, atol=1e-13, err_msg=name)
    f_mine = atcm.eigenfrequencies(bender_with_lever(mine), n=2, voltage=300.0)
    f_ref = atcm.eigenfrequencies(bender_with_lever(parent), n=2, voltage=300.0)
    np.testing.assert_allclose(f_mine, f_ref, rtol=1e-12)


def test_a_subclass_kind_works_through_add_to():
    ref = atcm.simulate(bender_with_lever("rigid"), 0.005, step=1e-4)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    handle = atcm.add_to(mbs, bender_with_lever(MyRigid()))
    mbs.Assemble()
    mbs.SolveDynamic(solver_settings.dynamic_settings(0.005, 1e-4))
    r = handle.result()
    for name in ref.names:
        np.testing.assert_allclose(r[name], ref[name], rtol=0, atol=1e-12, err_msg=name)


def test_a_subclass_kind_is_drawn_with_its_own_joint_label(tmp_path, monkeypatch):
    mech = bender_with_lever(MyRigid())
    r = atcm.simulate(mech, 0.005, step=1e-4)
    labels = []
    import matplotlib.axes

    original = matplotlib.axes.Axes.legend

    def spy(self, *args, **kwargs):
        labels.extend(t.get_label() for t in self.get_lines() + list(self.collections))
        return original(self, *args, **kwargs)

    monkeypatch.setattr(matplotlib.axes.Axes, "legend", spy)
    path = tmp_path / "mine.png"
    plot_mechanism(mech, r, path=path)
    assert pathlib.Path(path).stat().st_size > 1000
    assert any("my joints" in label for label in labels), labels


# ----------------------------------------------------------------------------- a genuinely new kind
class Unrealised(CellKind):
    name = "unrealised"


def test_a_new_kind_without_a_realisation_says_how_to_register_one():
    # one builder: the lone actuator is a one-bender mechanism, so one message for both
    with pytest.raises(ValueError, match=r"cell kind 'unrealised' \(Unrealised\) has no Exudyn realisation: "
                                         r"register one with exudyn_atcm.mbs.realisation.register_realisation"):
        atcm.solve_static(actuator(Unrealised()))
    with pytest.raises(ValueError, match=r"has no Exudyn realisation: register one with "
                                         r"exudyn_atcm.mbs.realisation.register_realisation"):
        atcm.simulate(bender_with_lever(Unrealised()), 0.005, step=1e-4)


def test_a_new_kind_registers_its_own_realisation():
    """A kind that is no subclass of a package kind, realised by delegating to the rigid chain's realisation:
    one registration serves the lone actuator and mechanisms (one builder).  Registered through the
    deprecated generic function of earlier releases (the contract's registration: tests/test_cell_contract.py)."""
    from exudyn_atcm.errors import AtcmDeprecationWarning

    class Delegating(CellKind):
        name = "delegating"

    with pytest.warns(AtcmDeprecationWarning, match="register a CellRealisation subclass"):
        @add_mechanism_bender.register(Delegating)
        def _(cell, builder, bender):
            add_mechanism_bender(RigidCell(), builder, bender)

    ref = atcm.solve_static(actuator("rigid", voltage=800.0))
    mine = atcm.solve_static(actuator(Delegating(), voltage=800.0))
    assert mine["actuator.tip_y"][0] == pytest.approx(ref["actuator.tip_y"][0], abs=1e-15)
    r = atcm.solve_static(bender_with_lever(Delegating()), voltage=500.0)
    r_ref = atcm.solve_static(bender_with_lever("rigid"), voltage=500.0)
    assert r["lever.E_y"][0] == pytest.approx(r_ref["lever.E_y"][0], abs=1e-15)


def test_every_kind_is_one_description_file_and_one_realisation_file_named_alike():
    """``cells/<kind>.py`` describes a kind, ``mbs/chains/<kind>.py`` realises it; the chains package
    imports every file of its folder, so no other file lists the realisations (issue 14's "a new cell
    kind is one new file plus one line": the line is in ``CELL_KINDS``)."""
    from exudyn_atcm.mbs import chains

    described = sorted(p.stem for p in (PACKAGE / "cells").glob("*.py") if p.stem not in ("__init__", "base"))
    assert list(chains.MODULES) == described
    assert sorted(p.stem for p in (PACKAGE / "mbs" / "chains").glob("*.py") if p.stem != "__init__") == described
    from exudyn_atcm.mbs.realisation import realisation_for

    with pytest.raises(ValueError, match="has no Exudyn realisation"):
        realisation_for(CellKind)
    for kind in CELL_KINDS.values():
        realisation = realisation_for(kind)
        stem = type(kind).__module__.rpartition(".")[2]
        assert realisation.__module__ == f"exudyn_atcm.mbs.chains.{stem}"
    # the builder imports the chains package, not the kinds' modules one by one
    builder = (PACKAGE / "mbs" / "builder.py").read_text()
    assert "from . import chains" in builder and not any(f"chains import {m}" in builder for m in described)


# ----------------------------------------------------------------------------- refusals from the kind
CANTILEVER_ONLY = [n for n, k in CELL_KINDS.items() if k.end_refusal("tip", "joined") is not None]


def test_every_kind_joins_a_mechanism():
    # no kind refuses mechanisms as such: the lone actuator is a one-bender mechanism
    assert all(k.mechanism_refusal() is None for k in CELL_KINDS.values())
    assert set(CANTILEVER_ONLY) == {"ancf", "ritz"}


@pytest.mark.parametrize("name", CANTILEVER_ONLY)
@pytest.mark.parametrize("end", ["base", "tip"])
def test_kinds_that_refuse_an_end_connection_say_why_themselves(name, end):
    kind = CELL_KINDS[name]
    b = atcm.Bender("b", width=1e-2, passive=CFC, active=MFC, length=0.03, n_cells=2, cell=name,
                    drive=atcm.PiezoDrive(300.0))
    lever = atcm.Link("lever", {"A": (0.0, 0.0) if end == "base" else (0.03, 0.0), "E": (0.05, 0.01)}, mass=2e-4,
                      inertia=1e-8)
    other = "tip" if end == "base" else "base"
    mech = atcm.Mechanism("m").add(b, lever).ground(b.point(other)).pin(b.point(end), lever.point("A"))
    with pytest.raises(MechanismError) as info:
        atcm.solve_static(mech)
    assert kind.end_refusal(end, "joined") in str(info.value)
    assert kind.end_refusal("base", "ground") is None and kind.end_refusal("tip", "free") is None


@pytest.mark.parametrize("name", ["ritz", "ancf"])
def test_cantilever_kinds_in_a_turned_mechanism_follow_the_arc(name):
    # a user's cantilever at base (x0, y0), angle a: the arc of the free curvature, turned and shifted
    # (ritz: the exact arc for any number of modes, to round-off; ancf: the bound of the lone actuator's
    # arc test, 1.2e-2 (kappa L_c)^4 + 1e-9, tests/test_actuator_ancf.py)
    a, x0, length = 0.7, np.array([0.01, -0.02]), 0.087
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=length, n_cells=6, cell=name,
                    drive=atcm.PiezoDrive(1500.0), base=tuple(x0), angle=a)
    r = atcm.solve_static(atcm.Mechanism("m").add(b).ground(b.base))
    kappa = b.laminate.curvature_per_strain * b.drives["b"].static_strain(1500.0)
    rel = 1e-9 if name == "ritz" else 1.2e-2 * (kappa * length / 6) ** 4 + 1e-9
    x, y = bt.arc_point(kappa, length)
    c, s = np.cos(a), np.sin(a)
    assert r["b.tip_x"][0] == pytest.approx(x0[0] + c * x - s * y, abs=rel * length)
    assert r["b.tip_y"][0] == pytest.approx(x0[1] + s * x + c * y, abs=rel * length)
    assert r["b.tip_angle"][0] == pytest.approx(a + kappa * length, rel=rel)


def test_tip_load_refusal_comes_from_the_kind():
    kinds = [k for k in CELL_KINDS.values() if not k.carries_tip_load]
    assert kinds, "some kind refuses tip loads (ritz)"
    for kind in kinds:
        assert kind.tip_load_refusal()
        with pytest.raises(ValueError, match="tip_force"):
            atcm.solve_static(actuator(kind, n=2), tip_force=(0.0, -0.01))


def test_run_cost_estimate_comes_from_the_kind():
    from exudyn_atcm.solve.run_checks import estimate_run_time

    for name, kind in CELL_KINDS.items():
        if kind.cost_per_step is None:
            assert estimate_run_time(kind, 10, 1000) is None
        else:
            a, b, c = kind.cost_per_step
            assert estimate_run_time(name, 10, 1000) == pytest.approx(1000 * (a + 10 * b + 100 * c))


# ----------------------------------------------------------------------------- one surface
def test_solves_take_the_system_first_and_the_rest_by_keyword():
    import inspect

    for function in (atcm.simulate, atcm.solve_static, atcm.eigenfrequencies, atcm.static_sweep):
        parameters = list(inspect.signature(function).parameters.values())
        assert parameters[0].name == "system"
        positional = [p.name for p in parameters if p.kind is not inspect.Parameter.KEYWORD_ONLY]
        assert positional == {"simulate": ["system", "t_end"], "static_sweep": ["system", "voltages"]}.get(
            function.__name__, ["system"]), function.__name__


def test_the_old_positional_calls_are_refused_after_their_release():
    """0.2 kept the positional forms of 0.1 for one release with a warning; 0.3 takes keywords only."""
    act = actuator("rigid", voltage=800.0, n=4)
    with pytest.raises(TypeError, match="positional argument"):
        atcm.solve_static(act, 500.0)
    with pytest.raises(TypeError, match="positional argument"):
        atcm.eigenfrequencies(act, 2)
    with pytest.raises(TypeError, match="positional argument"):
        atcm.simulate(act, 0.002, 1e-4)


def test_warnings_of_a_solve_point_at_the_callers_line():
    """No wrapper frame between the caller and the solve: a run-check warning names this file."""
    act = actuator("rigid", voltage=800.0, n=4)
    with pytest.warns(RuntimeWarning) as record:
        atcm.simulate(act, 0.02, step=5e-3)
    assert any(pathlib.Path(w.filename).name == "test_cells.py" for w in record), [w.filename for w in record]


def test_the_retired_actuator_registry_warns_and_says_where_to_register():
    from exudyn_atcm.errors import AtcmDeprecationWarning
    from exudyn_atcm.mbs.cells import add_actuator_cells

    class Old(RigidCell):
        name = "old"

    with pytest.warns(AtcmDeprecationWarning, match="register a CellRealisation subclass with "
                                                    r"exudyn_atcm.mbs.realisation.register_realisation"):
        @add_actuator_cells.register(Old)
        def _(cell, SC, mbs, act, stroke_path, tip_force):
            raise AssertionError("never called: the one builder realises Old as its parent kind")
    # the registration had no effect: the kind is built as its parent, the rigid chain
    ref = atcm.solve_static(actuator("rigid", voltage=800.0))
    assert atcm.solve_static(actuator(Old(), voltage=800.0))["actuator.tip_y"][0] == ref["actuator.tip_y"][0]
    with pytest.raises(ValueError, match="add_actuator_cells is retired"):
        add_actuator_cells(Old(), None, None, None, "prestep", (0.0, 0.0))


def test_three_kinds_in_one_mechanism_agree_with_beam_theory():
    # ritz, ancf and rigid cantilevers side by side in one system (one builder, the ritz cell's dense
    # solver and mass hooks for the whole system): each keeps its own accuracy.  f1 against the clamped-free
    # beam: ritz +0.03 % at 3 modes, ancf +0.05 % at 2 elements (less at 3), the rigid chain -0.45/N^2
    # (docs: actuator page, discretisation table); the static tips at 1000 V agree with the arc.
    prog = atcm.signals.Triangle(500.0, 1000.0, 0.05)
    length = 0.06
    benders = [atcm.Bender(name, width=28e-3, passive=CFC, active=MFC, length=length, n_cells=n, cell=name,
                           drive=atcm.PiezoDrive(prog), base=(0.0, 0.02 * k))
               for k, (name, n) in enumerate((("ritz", 3), ("ancf", 3), ("rigid", 6)))]
    mech = atcm.Mechanism("three").add(*benders)
    for b in benders:
        mech.ground(b.base)
    lam = benders[0].laminate
    f_beam = bt.first_bending_frequency(lam.bending_stiffness, lam.mass_per_length, length)
    f = atcm.eigenfrequencies(mech, n=3)
    assert f[0] == pytest.approx(f_beam * (1 - 0.45 / 36), rel=2e-3)  # the rigid chain's, lowest
    np.testing.assert_allclose(f[1:], f_beam, rtol=1e-3)
    s = atcm.solve_static(mech, voltage=1000.0)
    kappa = lam.curvature_per_strain * benders[0].drives["ritz"].static_strain(1000.0)
    x, y = bt.arc_point(kappa, length)
    for k, b in enumerate(benders):
        assert s[f"{b.name}.tip_y"][0] - 0.02 * k == pytest.approx(float(y), rel=1e-4), b.name


def ancf_cantilever(cell):
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.06, n_cells=3, cell=cell,
                    drive=atcm.PiezoDrive(atcm.signals.Triangle(750.0, 750.0, 0.1)))
    return atcm.Mechanism("m").add(b).ground(b.base)


@pytest.mark.parametrize("cell", ["ancf", "rod"])
def test_an_ancf_or_rod_cantilever_works_through_add_to_and_a_ritz_one_says_why_not(cell):
    # add_to with the user's own solver run: the same answer as simulate (the ANCF end node and the rod's
    # tip node carry the user's markers as a beam node does; the rod's updates run in the package's
    # pre-step hook and in Exudyn's PostNewton hook, which a user's solve runs too)
    ref = atcm.simulate(ancf_cantilever(cell), 0.005, step=1e-4)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    handle = atcm.add_to(mbs, ancf_cantilever(cell))
    tip = handle.position_marker("b.tip")  # a user's marker at the free tip: the end node's position
    assert mbs.GetMarker(tip)["markerType"] == "NodePosition"
    mbs.Assemble()
    mbs.SolveDynamic(solver_settings.dynamic_settings(0.005, 1e-4))
    r = handle.result()
    for name in ("b.tip_x", "b.tip_y", "b.tip_angle"):
        np.testing.assert_allclose(r[name], ref[name], rtol=0, atol=1e-12, err_msg=name)
    assert np.ptp(r["b.tip_y"]) > 1e-4  # it moved
    # the ritz cell's dynamics need its own solver settings, which a user's run would not set
    mbs2 = exu.SystemContainer().AddSystem()
    with pytest.raises(MechanismError, match=r"add_to: bender 'b': the ritz cell needs solver settings of its own"):
        atcm.add_to(mbs2, ancf_cantilever("ritz"))
