"""modes(): mode shapes, modal masses and participation, against closed-form and independent references.

References: the Euler-Bernoulli clamped-free beam (frequencies, shapes, modal mass ``m L / 4`` at unit tip
displacement, the modal expansion of the static deflection under a uniform free strain), and a rigid four-bar
with a torsion spring at the crank pivot linearised here by plain numpy (one degree of freedom: the effective
inertia from the kinematics by differences, ``omega^2 = k / J_eff``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.mechanism.points import MechanismError

CFC = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
BETA_L = np.array([1.8751040687119611, 4.6940911329741746, 7.8547574382376126])  # cos(bL) cosh(bL) = -1


def cantilever(n_cells=24, cell="beam", length=0.03):
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=length, n_cells=n_cells,
                    drive=atcm.PiezoDrive(0.0), cell=cell)
    return b, atcm.Mechanism("cantilever").add(b).ground(b.base)


def euler_bernoulli_shape(beta_l, xi):
    """Clamped-free mode shape at xi = x / L, normalised to 1 at the tip."""
    sigma = (math.cosh(beta_l) + math.cos(beta_l)) / (math.sinh(beta_l) + math.sin(beta_l))
    x = beta_l * np.asarray(xi)
    w = np.cosh(x) - np.cos(x) - sigma * (np.sinh(x) - np.sin(x))
    tip = math.cosh(beta_l) - math.cos(beta_l) - sigma * (math.sinh(beta_l) - math.sin(beta_l))
    return w / tip


def test_cantilever_frequencies_shapes_and_modal_masses():
    """24 geometrically exact beam elements: frequencies within 2e-4, 3e-3, 1e-2 of Euler-Bernoulli (the
    elements' discretisation and their shear and rotary inertia raise the higher modes a little), node shapes
    within 2e-3, 5e-3, 1e-2 of the tip displacement, modal masses within 1e-3, 3e-3, 1e-2 of m L / 4."""
    length = 0.03
    bender, mech = cantilever(length=length)
    lam = bender.laminate
    m = atcm.modes(mech, 3)
    omega = BETA_L**2 / length**2 * math.sqrt(lam.bending_stiffness / lam.mass_per_length)
    errors = m.frequencies / (omega / (2 * math.pi)) - 1.0
    assert np.all(np.abs(errors) < [2e-4, 3e-3, 1e-2]), errors
    np.testing.assert_allclose(m.frequencies, atcm.eigenfrequencies(mech, n=3), rtol=1e-12)
    nodes = [f"b.cell_{j + 1}" for j in range(25)]
    xi = np.array([m.positions[m.points.index(p), 0] for p in nodes]) / length
    shape_errors = [np.max(np.abs(np.array([m.shape(p)[j, 1] for p in nodes]) - euler_bernoulli_shape(beta_l, xi)))
                    for j, beta_l in enumerate(BETA_L)]
    print("frequency errors", errors, "shape errors", shape_errors)
    # the shapes' error grows with the mode as the frequencies' does (the elements' discretisation)
    assert np.all(np.array(shape_errors) < [2e-3, 5e-3, 1e-2]), shape_errors
    for j in range(3):
        assert m.shape("b.tip")[j, 1] == pytest.approx(1.0, abs=1e-6)  # the tip moves most, +y
    mass_errors = m.modal_masses / (lam.mass_per_length * length / 4) - 1.0
    print("modal mass errors", mass_errors)
    assert np.all(np.abs(mass_errors) < [1e-3, 3e-3, 1e-2]), mass_errors


def test_participation_is_the_modal_expansion_of_the_static_deflection():
    """A uniform free strain bends the cantilever to the arc of curvature kappa: tip deflection kappa L^2 / 2 per
    unit... summed over all modes, participation times the tip's shape gives it (to 1e-6)."""
    bender, mech = cantilever(n_cells=8)
    lam = bender.laminate
    m = atcm.modes(mech, 20)
    tip = np.sum(m.participation[:, 0] * m.shape("b.tip")[:, 1])
    assert tip == pytest.approx(lam.curvature_per_strain * 0.03**2 / 2, rel=1e-5)
    assert m.drives == ("b",) and abs(m.participation[0, 0]) > 10 * abs(m.participation[1, 0])


def _four_bar_reference(points, masses, inertias, k):
    """Rigid four-bar linearised by plain numpy: omega [rad/s], point velocities per unit crank rate."""
    A, B, C, D = (np.array(points[n]) for n in "ABCD")
    a, b, c = np.linalg.norm(B - A), np.linalg.norm(C - B), np.linalg.norm(C - D)
    theta0 = math.atan2(*(B - A)[::-1])

    def pose(theta):
        Bt = A + a * np.array([math.cos(theta), math.sin(theta)])
        d = np.linalg.norm(D - Bt)
        x = (b**2 - c**2 + d**2) / (2 * d)
        h = math.sqrt(b**2 - x**2)
        e = (D - Bt) / d
        n = np.array([-e[1], e[0]])
        cands = [Bt + x * e + s * h * n for s in (1, -1)]
        Ct = min(cands, key=lambda p: np.linalg.norm(p - C))  # the assembly branch of the reference pose
        return Bt, Ct

    def rigid(ref_pts, new_pts):
        """Rotation and translation of a link from two of its points."""
        (p0, p1), (q0, q1) = ref_pts, new_pts
        phi = math.atan2(*(q1 - q0)[::-1]) - math.atan2(*(p1 - p0)[::-1])
        R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        return phi, lambda p: q0 + R @ (np.asarray(p) - p0)

    def state(theta):
        Bt, Ct = pose(theta)
        links = {"crank": rigid((A, B), (A, Bt)), "coupler": rigid((B, C), (Bt, Ct)), "rocker": rigid((D, C), (D, Ct))}
        return links

    h = 1e-6
    lp, lm = state(theta0 + h), state(theta0 - h)
    j_eff = 0.0
    velocities = {}
    for name, pts in points_by_link(points).items():
        com = np.mean([points[p] for p in pts], axis=0)
        v = (lp[name][1](com) - lm[name][1](com)) / (2 * h)
        w = (lp[name][0] - lm[name][0]) / (2 * h)
        j_eff += masses[name] * v @ v + inertias[name] * w**2
        for p in pts:
            velocities[f"{name}.{p}"] = (lp[name][1](points[p]) - lm[name][1](points[p])) / (2 * h)
    return math.sqrt(k / j_eff), j_eff, velocities


def points_by_link(points):
    return {"crank": ["A", "B"], "coupler": ["B", "C", "P"], "rocker": ["D", "C"]}


def test_four_bar_against_plain_linearisation():
    """Rigid four-bar, torsion spring at the crank pivot: frequency (1e-6), the normalised shape of every point
    (1e-6) and the modal mass J_eff / s^2 (1e-6) of an independent one-degree-of-freedom linearisation."""
    points = {"A": (0.0, 0.0), "B": (0.01, 0.03), "C": (0.05, 0.035), "D": (0.045, 0.0), "P": (0.03, 0.05)}
    masses = {"crank": 2e-3, "coupler": 3e-3, "rocker": 2.5e-3}
    inertias = {"crank": 2e-7, "coupler": 5e-7, "rocker": 3e-7}
    k = 0.5
    mech = atcm.Mechanism("four_bar")
    for name, pts in points_by_link(points).items():
        mech.add(atcm.Link(name, {p: points[p] for p in pts}, mass=masses[name], inertia=inertias[name]))
    mech.ground("crank.A", joint="pin", stiffness=k)
    mech.pin("crank.B", "coupler.B").pin("coupler.C", "rocker.C").ground("rocker.D", joint="pin")
    m = atcm.modes(mech, 1)
    omega, j_eff, velocities = _four_bar_reference(points, masses, inertias, k)
    assert m.frequencies[0] == pytest.approx(omega / (2 * math.pi), rel=1e-6)
    scale = max(np.linalg.norm(v) for v in velocities.values())
    biggest = max(velocities, key=lambda p: np.linalg.norm(velocities[p]))
    sign = math.copysign(1.0, velocities[biggest][np.argmax(np.abs(velocities[biggest]))])
    for name, v in velocities.items():
        np.testing.assert_allclose(m.shape(name)[0], sign * v / scale, atol=1e-6)
    assert m.modal_masses[0] == pytest.approx(j_eff / scale**2, rel=1e-6)
    assert m.drives == () and m.participation is None


def test_modes_refuses_bad_input():
    _, mech = cantilever(n_cells=4, cell="rigid")
    with pytest.raises(ValueError, match="n must be"):
        atcm.modes(mech, 0)
    with pytest.raises(ValueError, match=r"n must be <= the number of degrees of freedom \(4\), got 9"):
        atcm.modes(mech, 9)
    with pytest.raises(ValueError, match="system must be a Mechanism or a BendingActuator"):
        atcm.modes("four_bar")
    m = atcm.modes(mech, 2)
    with pytest.raises(MechanismError, match="'b.tipp'.*b.tip"):
        m.shape("b.tipp")


def test_plot_modes_draws_one_panel_per_mode(tmp_path):
    from exudyn_atcm.plots import plot_modes

    _, mech = cantilever(n_cells=6)
    m = atcm.modes(mech, 2)
    fig = plot_modes(m, path=tmp_path / "modes.png")
    axes = fig.axes
    assert len(axes) == 2 and (tmp_path / "modes.png").stat().st_size > 0
    assert axes[0].get_xlabel() == "x [m]" and axes[0].get_ylabel() == "y [m]"
    # the drawn tip of mode 1 is the equilibrium tip moved by 0.1 of the size in the shape's direction
    moved = axes[0].lines[1].get_ydata()[-1]
    assert moved == pytest.approx(m.positions[m.points.index("b.tip"), 1] + 0.1 * 0.03 * 1.0, rel=1e-6)


def test_loaded_modes_match_eigenfrequencies_under_the_loads():
    """``loaded=True`` without voltage: about the equilibrium under the loads at zero strain, as
    eigenfrequencies of an actuator with a tip force (the tension stiffens the rigid cells' joints: geometric
    stiffness)."""
    actuator = atcm.BendingActuator(n_cells=6, cell_length=0.005, width=10e-3, passive=CFC, active=MFC,
                                    drive=atcm.PiezoDrive(0.0), cell="rigid")
    mech = actuator.as_mechanism((0.5, 0.0))
    m = atcm.modes(mech, 2, loaded=True)
    np.testing.assert_allclose(m.frequencies, atcm.eigenfrequencies(actuator, n=2, tip_force=(0.5, 0.0)), rtol=1e-12)
    np.testing.assert_allclose(atcm.BuiltSystem(mech).modes(2, loaded=True).frequencies, m.frequencies, rtol=1e-12)
    unloaded = atcm.modes(mech, 2)
    assert m.frequencies[0] > 1.01 * unloaded.frequencies[0]  # the tension stiffens the first mode
