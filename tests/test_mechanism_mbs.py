"""Issue 7, parts 2, 3 and 5: mechanisms inside a user's Exudyn system, hooks, sensors, graphics,
degrees of freedom and eigenfrequencies about the deformed equilibrium.

References: the package's own solve of the same mechanism; Gruebler's count; an independent
minimal-coordinate eigenvalue analysis of the rigid-cell chain (absolute cell angles, numpy/scipy);
the clamped-free Euler-Bernoulli beam (beta_1 L = 1.8751).
"""

from __future__ import annotations

import math
import pathlib
import runpy
import warnings

import exudyn as exu
import numpy as np
import pytest
import scipy.linalg

import exudyn_atcm as atcm
from exudyn_atcm.mbs import solver_settings
from exudyn_atcm.mbs import StepHooks, add_post_newton, add_post_step, add_pre_step
from exudyn_atcm.model.signals import Triangle

CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "docs" / "examples" / "mechanism_add_to.py"


def bender_with_lever(program=Triangle(750.0, 750.0, 0.1)):
    b = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=6,
                    drive=atcm.PiezoDrive(program), cell="rigid")
    lever = atcm.Link("lever", {"A": (0.03, 0.0), "E": (0.05, 0.0)}, mass=2e-4, inertia=1e-8)
    return atcm.Mechanism("m").add(b, lever).ground(b.base).weld(b.tip, lever.point("A"))


def user_system():
    SC = exu.SystemContainer()
    return SC, SC.AddSystem()


# ----------------------------------------------------------------------------- add_to

# incidental warning: both paths run the same coarse step (1 ms for the crank's 302 Hz mode); they must agree
@pytest.mark.filterwarnings("ignore:step = .* resolves the first bending mode:exudyn_atcm.errors.AccuracyWarning")
def test_add_to_and_solve_dynamic_equal_the_package_simulate():
    ref = atcm.simulate(bender_with_lever(), 0.05, step=1e-3)
    SC, mbs = user_system()
    h = atcm.add_to(mbs, bender_with_lever())
    mbs.Assemble()
    settings = solver_settings.dynamic_settings(0.05, 1e-3)
    settings.solution.sensors.writePeriod = 1e-3
    mbs.SolveDynamic(settings)
    r = h.result()
    assert r.names == ref.names
    for name in ref.names:
        np.testing.assert_allclose(r[name], ref[name], rtol=0, atol=1e-12, err_msg=name)
    # the sensors hold the same positions (stored at the write period, from the first step on)
    stored = mbs.GetSensorStoredData(h.sensors["lever.E"])
    np.testing.assert_allclose(stored[:, 2], np.interp(stored[:, 0], ref["time"], ref["lever.E_y"]), atol=1e-12)
    angle = mbs.GetSensorStoredData(h.sensors["lever.angle"])
    np.testing.assert_allclose(angle[:, 3], np.interp(angle[:, 0], ref["time"], ref["lever.angle"]), atol=1e-12)
    assert np.ptp(ref["lever.E_y"]) > 1e-3


# incidental warning: the reference runs the example's step (0.5 ms for the bender's 302 Hz mode), to agree with it
@pytest.mark.filterwarnings("ignore:step = .* resolves the first bending mode:exudyn_atcm.errors.AccuracyWarning")
def test_docs_example_runs_and_equals_the_package_mechanism():
    """docs/examples/mechanism_add_to.py: a lone bender (add_to) pushing a user-built rod and lever.

    Reference: the same parts as a package Mechanism.  A lone bender's free tip gets an interface
    body (the laminate over min(h1 + h2, L_c/10)); the reference carries that mass on a welded hub.
    The example uses Exudyn's default settings (dense solver, spectral radius 0.9); the reference
    the package's with the same spectral radius.  Both Newton iterations stop at 1e-8 N but update
    their Jacobians differently (dense full Newton / sparse modified Newton): measured 9e-9 m apart
    on a 1.9 mm stroke, so the tolerance is 3e-8 m (1.6e-5 of the stroke; 4 times that at the lever end).
    """
    ns = runpy.run_path(str(EXAMPLE), run_name="example")
    r = ns["result"]
    drive = atcm.PiezoDrive(Triangle(750.0, 750.0, 0.2))
    b = atcm.Bender("bender", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=8, drive=drive, cell="rigid")
    lam = b.laminate
    s_if = min(0.5e-3, 0.1 * 0.03 / 8)
    m_if = lam.mass_per_length * s_if
    hub = atcm.Link("hub", {"T": (0.03, 0.0)}, mass=m_if, inertia=m_if * (s_if**2 + 0.5e-3**2) / 12)
    rod = atcm.Link("rod", {"A": (0.03, 0.0), "B": (0.03, 0.01)}, mass=1e-4, inertia=1e-4 * 0.01**2 / 12)
    lever = atcm.Link("lever", {"O": (0.02, 0.01), "B": (0.03, 0.01), "E": (0.06, 0.01)}, mass=1e-4,
                      inertia=1e-4 * 0.04**2 / 12, center_of_mass=(0.04, 0.01))
    m = atcm.Mechanism().add(b, hub, rod, lever).ground(b.base).weld(b.tip, "hub.T").pin("hub.T", "rod.A")
    m.pin("rod.B", "lever.B").ground("lever.O", joint="pin")
    # the example keeps Exudyn's default spectral radius 0.9 (the package's default is 0.8)
    ref = atcm.simulate(m, 0.2, step=5e-4, settings={"timeIntegration.generalizedAlpha.spectralRadius": 0.9})
    assert r.n_rows == ref.n_rows == 401
    np.testing.assert_allclose(r["bender.tip_y"], ref["bender.tip_y"], rtol=0, atol=3e-8)
    np.testing.assert_allclose(ns["end_y"], ref["lever.E_y"][-ns["end_y"].size:], rtol=0, atol=1.2e-7)
    # the lever amplifies the tip's stroke about 4 times (arms 10 mm and 40 mm)
    rise = ns["peak"]["y"] - 0.01
    assert 3.5 < rise / r["bender.tip_y"].max() < 4.5


def test_step_hooks_keep_an_earlier_user_function_and_run_all():
    SC, mbs = user_system()
    seen = {"before": 0, "pre": 0, "post": 0}

    def before(mbs_, t):
        seen["before"] += 1
        return True

    mbs.SetPreStepUserFunction(before)
    h = atcm.add_to(mbs, bender_with_lever())
    add_pre_step(mbs, lambda m, t: seen.__setitem__("pre", seen["pre"] + 1) or True)
    add_post_step(mbs, lambda m, t: seen.__setitem__("post", seen["post"] + 1) or True)
    hooks = mbs.variables["exudyn_atcm.step_hooks"]
    assert isinstance(hooks, StepHooks)
    assert hooks.pre[0] is before and len(hooks.pre) == 3 and len(hooks.post) == 2
    mbs.Assemble()
    mbs.SolveDynamic(solver_settings.dynamic_settings(0.01, 1e-3))
    assert seen["before"] == seen["pre"] == 10  # every attempted step (none rejected here)
    assert seen["post"] == 11  # every accepted step and t = 0
    assert h.result().n_rows == 11
    with pytest.raises(ValueError, match="callable"):
        add_pre_step(mbs, 3)


def test_post_newton_checks_run_after_every_newton_solve_and_an_error_above_1_repeats_it():
    # one mass on a spring; check a returns 0, check b returns 5 on its first call of each step and 0
    # on the repeat: Exudyn repeats each step's Newton solve once (its discontinuous iteration,
    # tolerance 1 by default), so both checks run twice per step
    import exudyn.itemInterface as ii

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ii.ObjectGround())
    node = mbs.AddNode(ii.NodePoint2D(referenceCoordinates=[0.0, 0.0]))
    mass = mbs.AddObject(ii.MassPoint2D(mass=1.0, nodeNumber=node))
    markers = [mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=b, localPosition=[0.0, 0.0, 0.0])) for b in (ground, mass)]
    mbs.AddObject(ii.CartesianSpringDamper(markerNumbers=markers, stiffness=[100.0, 100.0, 0.0]))
    mbs.AddLoad(ii.LoadForceVector(markerNumber=markers[1], loadVector=[1.0, 0.0, 0.0]))
    calls = {"a": [], "b": []}

    def check_a(mbs_, t):
        calls["a"].append(t)
        return 0.0

    def check_b(mbs_, t):
        first = t not in calls["b"]
        calls["b"].append(t)
        return 5.0 if first else 0.0

    add_post_newton(mbs, check_a)
    add_post_newton(mbs, check_b)
    assert len(mbs.variables["exudyn_atcm.post_newton"]) == 2
    mbs.Assemble()
    mbs.SolveDynamic(solver_settings.dynamic_settings(0.005, 1e-3))
    assert len(calls["b"]) == 10 and len(set(calls["b"])) == 5  # 5 steps, each solved twice
    assert calls["a"] == calls["b"]
    with pytest.raises(ValueError, match="check must be a callable"):
        add_post_newton(mbs, 3)


@pytest.mark.parametrize("cell", ["rigid", "six-bar"])
def test_lone_bender_markers_bodies_and_graphics(cell):
    SC, mbs = user_system()
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4,
                    drive=atcm.PiezoDrive(0.0), cell=cell)
    h = atcm.add_to(mbs, b)
    tip_body = h.body(b.tip)
    # the free tip has its own interface body at (0.03, 0)
    obj = mbs.GetObject(tip_body)
    assert obj["objectType"] == "RigidBody2D"
    assert mbs.GetNode(obj["nodeNumber"])["referenceCoordinates"][0] == pytest.approx(0.03)
    assert mbs.GetMarker(h.marker(b.tip))["markerType"] == "BodyRigid"
    assert mbs.GetMarker(h.position_marker("b.tip"))["markerType"] == "BodyPosition"
    # every cell body carries graphics data for Exudyn's renderer
    for key in h.model.cells["b"]:
        assert len(mbs.GetObject(h.model.bodies[key].item)["VgraphicsData"]) > 0
    with pytest.raises(atcm.MechanismError, match="no rigid component 'b'"):
        h.body("b")
    # clamp_base=False leaves the base free: an interface body there too
    SC2, mbs2 = user_system()
    h2 = atcm.add_to(mbs2, b, clamp_base=False)
    assert mbs2.GetObject(h2.body(b.base))["objectType"] == "RigidBody2D"


# ----------------------------------------------------------------------------- degrees of freedom

def test_degrees_of_freedom_of_rigid_and_compliant_four_bars():
    def four_bar(crank):
        coupler = atcm.Link("coupler", {"A": (0, .03), "B": (.04, .03)}, mass=1e-4, inertia=1e-8)
        rocker = atcm.Link("rocker", {"B": (.04, .03), "O": (.04, 0)}, mass=1e-4, inertia=1e-8)
        m = atcm.Mechanism().add(crank, coupler, rocker).pin("crank.tip", "coupler.A")
        return m.pin("coupler.B", "rocker.B").ground("rocker.O", joint="pin")

    rigid = four_bar(atcm.Link("crank", {"base": (0, 0), "tip": (0, .03)}, mass=1e-4, inertia=1e-8))
    rigid.ground("crank.base", joint="pin")
    # Gruebler: 3 (n - 1) - 2 j = 3 * 3 - 2 * 4 = 1
    assert rigid.degrees_of_freedom() == atcm.mbs.DofReport(dof=1, coordinates=9, constraints=8, redundant=0)
    bender = atcm.Bender("crank", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=5,
                         drive=atcm.PiezoDrive(0.0), angle=math.pi / 2, cell="rigid")
    compliant = four_bar(bender).ground("crank.base")
    # 5 cell bodies + 2 links = 21 coordinates; clamp, 4 inner joints and 3 pins = 16 constraints
    report = compliant.degrees_of_freedom()
    assert (report.dof, report.coordinates, report.constraints, report.redundant) == (5, 21, 16, 0)


# ----------------------------------------------------------------------------- eigenfrequencies

def chain_reference(b: atcm.Bender, strain: float) -> np.ndarray:
    """Eigenfrequencies [Hz] of the clamped rigid-cell chain about its stress-free bent state.

    Minimal coordinates: the absolute cell angles phi_j.  Kinetic energy of cell j: its centre
    (0.5 L_c, -e_m) in the cell frame, carried by all earlier cells; potential: springs 2EI/L_c at the
    clamp and EI/L_c between cells (the rest angles equal the bent angles: no prestress, so the
    stiffness matrix is that of the straight chain; the mass matrix is the bent one).
    """
    lam, n = b.laminate, b.n_cells
    lc = b.length / n
    m, off, j_com = lam.rigid_cell(lc)
    theta = lam.curvature_per_strain * lc * strain
    phi = 0.5 * theta + theta * np.arange(n)
    M = np.zeros((n, n))
    for k in range(n):
        J = np.zeros((2, n))
        for i in range(k):
            J[:, i] = lc * np.array([-math.sin(phi[i]), math.cos(phi[i])])
        c, s = math.cos(phi[k]), math.sin(phi[k])
        J[:, k] = [-s * 0.5 * lc + c * off, c * 0.5 * lc + s * off]
        M += m * J.T @ J
        M[k, k] += j_com
    ei = lam.bending_stiffness
    K = np.diag(np.full(n, 2 * ei / lc))
    K[0, 0] = 3 * ei / lc
    K[-1, -1] = ei / lc
    K -= np.diag(np.full(n - 1, ei / lc), 1) + np.diag(np.full(n - 1, ei / lc), -1)
    return np.sqrt(scipy.linalg.eigh(K, M, eigvals_only=True)) / (2 * math.pi)


@pytest.mark.parametrize("n_cells", [4, 8])
def test_eigenfrequencies_about_the_bent_equilibrium_match_the_minimal_coordinate_chain(n_cells):
    drive = atcm.PiezoDrive(500.0)
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=n_cells, drive=drive, cell="rigid")
    m = atcm.Mechanism().add(b).ground(b.base)
    undeformed = atcm.eigenfrequencies(m, n=3)
    bent = atcm.eigenfrequencies(m, n=3, voltage=1500.0)
    np.testing.assert_allclose(undeformed, chain_reference(b, 0.0)[:3], rtol=1e-9)
    np.testing.assert_allclose(bent, chain_reference(b, drive.static_strain(1500.0))[:3], rtol=1e-9)
    # bending changes the spectrum (the test is not about the straight chain only)
    assert abs(bent[1] / undeformed[1] - 1) > 1e-3
    # the same as today's BendingActuator about the undeformed state
    act = atcm.BendingActuator(n_cells, 0.087 / n_cells, 28e-3, CFC, MFC, drive, cell="rigid")
    np.testing.assert_allclose(undeformed, atcm.eigenfrequencies(act, n=3), rtol=1e-9)


def test_first_frequency_tends_to_the_beam():
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=32, drive=atcm.PiezoDrive(0.0), cell="rigid")
    f1 = atcm.eigenfrequencies(atcm.Mechanism().add(b).ground(b.base), n=1)[0]
    # Euler-Bernoulli cantilever; the 32-cell chain is 0.05 % low (discretisation error ~ 1/N^2)
    assert f1 == pytest.approx(b.laminate.first_frequency(0.087), rel=1e-3)


def test_eigenfrequencies_about_a_prestressed_six_bar_equilibrium_match_the_rigid_chain():
    """A six-bar chain bent by its motors carries internal forces (~50 N at 1500 V) whose
    geometric stiffness Exudyn's own eigenvalue routine leaves out (-67 % at 4 cells); the
    package's tangent includes it.  References: the rigid chain bent the same way (stress-free,
    equal to the minimal-coordinate chain above) changes f1 by the same share (+0.2 % at
    1500 V; the two cell models differ by O(1/N^2) in f1 itself, 2.6 % at 8 cells, but their
    shifts agree to 1.2e-4), and the lone actuator's path (tests/test_actuator_eigen.py)."""
    drive = atcm.PiezoDrive(0.0)
    shift = {}
    for cell in ("six-bar", "rigid"):
        b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=8, drive=drive, cell=cell)
        m = atcm.Mechanism().add(b).ground(b.base)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            bent = atcm.eigenfrequencies(m, n=1, voltage=1500.0)[0]
            straight = atcm.eigenfrequencies(m, n=1)[0]
        shift[cell] = bent / straight - 1
        act = atcm.BendingActuator(8, 0.087 / 8, 28e-3, CFC, MFC, drive, cell=cell)
        assert bent == pytest.approx(atcm.eigenfrequencies(act, n=1, voltage=1500.0)[0], rel=1e-6)
    assert 1e-3 < shift["rigid"] < 5e-3
    assert shift["six-bar"] == pytest.approx(shift["rigid"], abs=5e-4)


def test_actuator_eigenfrequencies_about_its_bent_equilibrium_use_the_mechanism_path():
    drive = atcm.PiezoDrive(0.0)
    act = atcm.BendingActuator(4, 0.087 / 4, 28e-3, CFC, MFC, drive, cell="rigid")
    b = atcm.Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=4, drive=drive, cell="rigid")
    np.testing.assert_allclose(atcm.eigenfrequencies(act, n=3, voltage=1500.0),
                               chain_reference(b, drive.static_strain(1500.0))[:3], rtol=1e-9)
    # a tip load: the joints carry it; the actuator path's tangent includes that (see
    # tests/test_actuator_eigen.py for the Rayleigh-quotient check of the shift)
    loaded = atcm.eigenfrequencies(act, n=1, tip_force=(-0.1, 0.0))[0]
    assert loaded < atcm.eigenfrequencies(act, n=1)[0]  # a compressive axial load lowers f1
