"""linearise(): state-space models about a static equilibrium, checked against independent references.

References: a closed-form single degree of freedom (a pinned link with a torsion spring and damper),
differences of the nonlinear static solution, sine simulations of the nonlinear model, Exudyn's own
``ComputeLinearizedSystem`` (where it applies: no constraint forces at the state), and the closed-form
branch slopes of a Prandtl-Ishlinskii operator.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.hysteresis.prandtl_ishlinskii import PrandtlIshlinskii
from exudyn_atcm.mbs import builder as mb
from exudyn_atcm.model.drive_gain import drive_gain
from exudyn_atcm.model.signals import Sine

CFC = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)


def sdof(k=2.0, c=1e-3, mass=0.01, inertia=1e-5, length=0.05):
    link = atcm.Link("arm", {"O": (0.0, 0.0), "P": (length, 0.0)}, mass=mass, inertia=inertia)
    return atcm.Mechanism("sdof").add(link).ground("arm.O", joint="pin", stiffness=k, damping=c)


def lever(program, pivot_damping=4e-6, cell="rod", n_cells=3, hysteresis=None, load=0.0):
    """A bender driving a 6:1 lever through a short coupler; ``load`` [N] pushes the lever's end down (the
    joints then carry forces: geometric stiffness)."""
    b = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=n_cells,
                    drive=atcm.PiezoDrive(program, hysteresis=hysteresis), cell=cell)
    cp = atcm.Link("coupler", {"A": (0.03, 0.0), "B": (0.03, 0.005)}, mass=2e-5, inertia=1e-10)
    lev = atcm.Link("lever", {"B": (0.03, 0.005), "O": (0.035, 0.005), "E": (0.065, 0.005)}, mass=2e-4, inertia=2e-8)
    m = atcm.Mechanism("lev").add(b, cp, lev).ground(b.base)
    m.pin(b.tip, "coupler.A").pin("coupler.B", "lever.B").ground("lever.O", joint="pin", damping=pivot_damping)
    if load:
        m.force("lever.E", (0.0, -load))
    return m


def test_single_dof_closed_form():
    k, c, mass, inertia, length = 2.0, 1e-3, 0.01, 1e-5, 0.05
    lin = atcm.linearise(sdof(k, c, mass, inertia, length), inputs=["arm.P_Fy"], outputs=["arm.P_y", "arm.angle"])
    j_o = inertia + mass * (length / 2) ** 2  # about the pivot: the centre of mass is the points' centroid
    f = np.array([0.0, 10.0, math.sqrt(k / j_o) / (2 * math.pi), 100.0])
    w = 2 * math.pi * f
    angle = length / (k - j_o * w**2 + 1j * w * c)  # rad per N of F_y at P
    G = lin.frequency_response(f)
    np.testing.assert_allclose(G[:, 1, 0], angle, rtol=1e-6)
    np.testing.assert_allclose(G[:, 0, 0], length * angle, rtol=1e-6)  # small rotation: P_y = L theta
    assert lin.natural_frequencies[0] == pytest.approx(math.sqrt(k / j_o) / (2 * math.pi), rel=1e-7)
    assert lin.damping_ratios[0] == pytest.approx(c / (2 * math.sqrt(k * j_o)), rel=1e-6)
    ss = lin.to_scipy()
    assert ss.A.shape == (2, 2) and ss.B.shape == (2, 1) and ss.C.shape == (2, 2)
    from scipy import signal  # noqa: PLC0415 - scipy's own response of the exported model

    siso = atcm.linearise(sdof(k, c, mass, inertia, length), inputs=["arm.P_Fy"], outputs=["arm.angle"])
    with warnings.catch_warnings():  # freqresp goes through a transfer function and flags its tiny leading
        warnings.simplefilter("ignore", signal.BadCoefficients)  # numerator terms; the values are checked here
        _, h = signal.freqresp(siso.to_scipy(), w=w[1:])
    np.testing.assert_allclose(h, angle[1:], rtol=1e-6)


def test_dc_gain_matches_differences_of_nonlinear_statics():
    """About a bent state of a closed loop under a load (joints carrying forces): the static gain of the linear
    model equals central differences of the nonlinear static solution (+-10 V), to the differences' own error
    (~1e-5)."""
    lin = atcm.linearise(lever(500.0, load=0.1), voltage=500.0, outputs=["lever.E_y", "lever.angle", "b.tip_y"])
    dc = lin.dc_gain()[:, 0]
    lo, hi = (atcm.solve_static(lever(v, load=0.1)) for v in (490.0, 510.0))
    fd = np.array([(hi[o][-1] - lo[o][-1]) / 20.0 for o in lin.outputs])
    np.testing.assert_allclose(dc, fd, rtol=1e-4)
    static = atcm.solve_static(lever(500.0, load=0.1))
    assert lin.operating_point["lever.E_y"] == pytest.approx(static["lever.E_y"][-1], abs=1e-12)
    # |pole| of the damped model vs the undamped eigenfrequencies: equal for proportional damping; the pivot
    # damper is not proportional, which moves |pole| by the order of the damping ratio squared (~1e-4 here)
    undamped = atcm.eigenfrequencies(lever(500.0, load=0.1), n=2, voltage=500.0)
    np.testing.assert_allclose(lin.natural_frequencies[:2], undamped, rtol=5e-4)


def _sine_gain(result, output, y0, f, amplitude, window):
    t = result["time"]
    keep = t >= t[-1] - window
    w = 2 * math.pi * f
    basis = np.column_stack([np.sin(w * t[keep]), np.cos(w * t[keep]), np.ones(keep.sum())])
    a, b, _ = np.linalg.lstsq(basis, result[output][keep] - y0, rcond=None)[0]
    return complex(a, b) / amplitude


def test_sine_simulations_match_frequency_response():
    """Small sines (5 V about 500 V) through the nonlinear simulation of the lever loaded by 0.1 N at its end:
    gain and phase of the lever's end within 1 % (phase within 0.01 rad) of the linear model from half the first
    resonance (93 Hz) to 1.5 times the second (1.36 kHz).  The load makes the joints carry forces: without their
    geometric stiffness (Exudyn's own linearisation) the first frequency is 3 % lower, which at 1.2 times the
    resonance changes the gain by ~9 % (single-mode estimate), so the check tells the two apart.  Accuracy: the
    step 1e-5 s resolves 2 kHz by 50 steps per period (period error of the integrator ~(w h)^2/12 < 1e-3), the sine's relative size
    5/500 keeps the geometric nonlinearity near 1e-3, and 0.15 s of run lets the first mode's transient (damping
    ratio ~0.1 from the pivot damper, time constant ~17 ms) decay by e^-6 before the fitted window of the last
    whole periods."""
    lin = atcm.linearise(lever(500.0, load=0.1), voltage=500.0, outputs=["lever.E_y"])
    f1, f2 = lin.natural_frequencies[:2]
    assert 0.05 < lin.damping_ratios[0] < 0.2 and f2 > 10 * f1
    _, exudyn_f1 = _exudyn_first_frequency(lever(500.0, load=0.1))
    assert f1 / exudyn_f1 - 1.0 > 0.02  # the geometric stiffness matters here
    errors = []
    for f in (0.5 * f1, 1.2 * f1, 0.7 * f2, 1.5 * f2):
        periods = max(2, round(0.02 * f))
        window = periods / f
        result = atcm.simulate(lever(Sine(500.0, 5.0, 1.0 / f), load=0.1), 0.15, step=1e-5)
        g_sim = _sine_gain(result, "lever.E_y", lin.operating_point["lever.E_y"], f, 5.0, window)
        g_lin = lin.response("lever.E_y", "b", [f])[0]
        errors.append((abs(g_sim) / abs(g_lin) - 1.0, np.angle(g_sim / g_lin)))
    errors = np.array(errors)
    print("sine vs linear: relative gain error, phase error [rad] per frequency\n", errors)
    assert np.all(np.abs(errors[:, 0]) < 0.01), errors
    assert np.all(np.abs(errors[:, 1]) < 0.01), errors


def _exudyn_first_frequency(mech):
    """Exudyn's own ComputeODE2Eigenvalues about the static equilibrium (no constraint forces' stiffness)."""
    from exudyn_atcm.mbs.eigen import exudyn_eigenfrequencies  # noqa: PLC0415 - the comparison routine
    from exudyn_atcm.solve.linear_state import equilibrium_state  # noqa: PLC0415

    state = equilibrium_state(mech, "test", voltage=500.0)
    state.model.before_linearisation()
    return state, float(exudyn_eigenfrequencies(state.model.mbs, 1)[0])


def test_matches_exudyn_compute_linearized_system():
    """A ground-welded bender of rigid cells at its reference pose (no constraint forces): the poles of the
    linear model equal those of Exudyn's ComputeLinearizedSystem projected into the constraints' null space."""
    bender = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=4,
                         drive=atcm.PiezoDrive(0.0), cell="rigid")
    mech = atcm.Mechanism("cant").add(bender).ground(bender.base)
    lin = atcm.linearise(mech, voltage=0.0, outputs=["b.tip_y"])
    model = mb.build(mech)
    M, K, D, _, N = model.mbs.ComputeLinearizedSystem(projectIntoConstraintNullspace=True,
                                                      returnConstraintJacobian=True, returnConstraintNullspace=True)
    m = M.shape[0]
    A = np.block([[np.zeros((m, m)), np.eye(m)], [-np.linalg.solve(M, K), -np.linalg.solve(M, D)]])
    ref = np.linalg.eigvals(A)
    ref = np.sort_complex(ref[np.argsort(np.abs(ref))])
    ours = np.sort_complex(lin.poles)
    np.testing.assert_allclose(np.sort(np.abs(ours)), np.sort(np.abs(ref)), rtol=1e-6)
    np.testing.assert_allclose(np.sort(ours.real), np.sort(ref.real), rtol=1e-5, atol=1e-9)


def test_branch_slopes_of_prandtl_ishlinskii():
    """Closed form: from U_lo up to U the plays of radius r < (U - U_lo)/2 move with the input (slope
    p0 + their weights); down from U_hi those with r < (U_hi - U)/2; right after a reversal only p0."""
    radii, weights, p0 = np.array([0.0, 100.0, 300.0, 600.0]), np.array([1e-7, 2e-7, 3e-7, 4e-7]), 5e-7
    op = PrandtlIshlinskii(radii, weights, p0)  # no input range of its own: the drive's rating (-500, 1500) V
    drive = atcm.PiezoDrive(0.0, hysteresis=op)
    u = 200.0
    asc = drive_gain(drive, u, "ascending")
    assert asc.gain == pytest.approx(p0 + weights[radii < (u + 500.0) / 2].sum(), rel=1e-9)
    desc = drive_gain(drive, u, "descending")
    assert desc.gain == pytest.approx(p0 + weights[radii < (1500.0 - u) / 2].sum(), rel=1e-9)
    assert desc.gain > asc.gain  # the 600 V play moves on the way down only
    rev = drive_gain(drive, u, "reversal")
    assert rev.gain == pytest.approx(p0 + weights[radii == 0.0].sum(), rel=1e-9)
    # the states differ: the descending branch lies above the ascending one at the same voltage
    assert desc.strain > asc.strain == pytest.approx(rev.strain)
    with pytest.raises(ValueError, match="branch must be one of 'ascending', 'descending', 'reversal', got 'up'"):
        drive_gain(drive, u, "up")


def test_linear_drive_gain_scales_the_input():
    lin = atcm.linearise(lever(0.0), voltage=0.0, outputs=["lever.E_y"])
    drive = atcm.PiezoDrive(0.0)
    assert lin.gains["b"] == pytest.approx(drive.d33 / drive.electrode_spacing, rel=1e-12)


def test_bad_inputs_are_refused():
    mech = sdof()
    with pytest.raises(ValueError, match=r"outputs: 'arm.P_z' is not a point coordinate or an angle.*'arm.P_y'"):
        atcm.linearise(mech, inputs=["arm.P_Fy"], outputs=["arm.P_z"])
    with pytest.raises(ValueError, match=r"inputs: 'arm.Q_Fy' is not a drive or a point force.*'arm.P_Fy'"):
        atcm.linearise(mech, inputs=["arm.Q_Fy"], outputs=["arm.P_y"])
    with pytest.raises(ValueError, match="branch must be one of"):
        atcm.linearise(mech, inputs=["arm.P_Fy"], outputs=["arm.P_y"], branch="rising")
    with pytest.raises(ValueError, match="has no drives"):
        atcm.linearise(mech, outputs=["arm.P_y"])


def test_no_equilibrium_is_refused():
    """A link on a frictionless pin under a force has no static equilibrium: refused, saying so."""
    link = atcm.Link("arm", {"O": (0.0, 0.0), "P": (0.05, 0.0)}, mass=0.01, inertia=1e-5)
    mech = atcm.Mechanism("free").add(link).ground("arm.O", joint="pin").force("arm.P", (0.0, 1.0))
    with pytest.raises(ValueError, match="no static equilibrium"):
        atcm.linearise(mech, inputs=["arm.P_Fy"], outputs=["arm.P_y"])


def test_plot_bode_draws_the_frequency_response(tmp_path):
    from exudyn_atcm.plots import plot_bode

    lin = atcm.linearise(sdof(), inputs=["arm.P_Fy"], outputs=["arm.P_y", "arm.angle"])
    f = np.array([1.0, 10.0, 100.0])
    fig = plot_bode(lin, outputs=["arm.P_y"], frequencies_hz=f, path=tmp_path / "bode.png")
    gain_ax, phase_ax = fig.axes
    np.testing.assert_allclose(gain_ax.lines[0].get_ydata(), np.abs(lin.frequency_response(f)[:, 0, 0]))
    assert phase_ax.get_xlabel() == "frequency [Hz]" and (tmp_path / "bode.png").stat().st_size > 0
    with pytest.raises(ValueError, match="outputs must name the model's outputs"):
        plot_bode(lin, outputs=["arm.Q_y"])


def test_built_system_gives_the_same_models():
    """One build, linearised and analysed at two voltages, equals the one-off functions."""
    mech = lever(0.0)
    built = atcm.BuiltSystem(mech)
    for v in (500.0, 200.0):
        a = built.linearise(voltage=v, outputs=["lever.E_y"])
        b = atcm.linearise(mech, voltage=v, outputs=["lever.E_y"])
        np.testing.assert_allclose(a.dc_gain(), b.dc_gain(), rtol=1e-9)
        np.testing.assert_allclose(a.natural_frequencies, b.natural_frequencies, rtol=1e-9)
        np.testing.assert_allclose(built.eigenfrequencies(2, voltage=v), atcm.eigenfrequencies(mech, n=2, voltage=v),
                                   rtol=1e-9)
    assert built.builds == 1


def test_hysteretic_drive_is_linearised_on_its_branch():
    """A Prandtl-Ishlinskii drive: the equilibrium is the one at the branch's strain, and the input is scaled by
    the branch's slope.  Reference: the linear drive (d33 / t_IDE) at the voltage giving the same strain, whose
    model per unit strain must be the same."""
    op = PrandtlIshlinskii([0.0, 100.0, 300.0, 600.0], [1e-7, 2e-7, 3e-7, 4e-7], 5e-7)
    mech = lever(0.0, hysteresis=op)
    linear = atcm.PiezoDrive(0.0)
    per_volt = linear.d33 / linear.electrode_spacing
    for branch in ("ascending", "descending"):
        lin = atcm.linearise(mech, voltage=200.0, outputs=["lever.E_y"], branch=branch)
        gain = drive_gain(mech.drives["b"], 200.0, branch)
        assert lin.gains["b"] == pytest.approx(gain.gain) and lin.strains["b"] == pytest.approx(gain.strain)
        ref = atcm.linearise(lever(0.0), voltage=gain.strain / per_volt, outputs=["lever.E_y"])
        np.testing.assert_allclose(lin.dc_gain() / gain.gain, ref.dc_gain() / per_volt, rtol=1e-6)
        assert lin.operating_point["lever.E_y"] == pytest.approx(ref.operating_point["lever.E_y"], abs=1e-12)


def test_six_bar_drive_input_is_refused():
    bender = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=2,
                         drive=atcm.PiezoDrive(0.0), cell="six-bar")
    mech = atcm.Mechanism("cant").add(bender).ground(bender.base)
    with pytest.raises(ValueError, match="prescribed motion"):
        atcm.linearise(mech, voltage=0.0, outputs=["b.tip_y"])


def test_actuator_is_linearised_as_its_mechanism():
    actuator = atcm.BendingActuator(n_cells=4, cell_length=0.0075, width=10e-3, passive=CFC, active=MFC,
                                    drive=atcm.PiezoDrive(0.0), cell="rigid")
    lin = atcm.linearise(actuator, voltage=0.0, outputs=["actuator.tip_y"])
    lam = actuator.bender.laminate
    # quasi-static tip deflection per volt of the rigid chain's arc, kappa L^2/2 (small strain), to the chain's error
    per_volt = lam.curvature_per_strain * 0.03**2 / 2 * lin.gains["actuator"]
    assert lin.dc_gain()[0, 0] == pytest.approx(per_volt, rel=2e-2)
    np.testing.assert_allclose(atcm.modes(actuator, 2).frequencies, atcm.eigenfrequencies(actuator, n=2), rtol=1e-12)


def test_loads_argument_equals_the_loaded_mechanism():
    """``loads={point: (Fx, Fy)}`` linearises about the equilibrium under the extra dead forces, as the mechanism
    carrying them would be; the mechanism itself is not changed."""
    mech = lever(500.0)
    a = atcm.linearise(mech, voltage=500.0, loads={"lever.E": (0.0, -0.1)}, outputs=["lever.E_y"])
    b = atcm.linearise(lever(500.0, load=0.1), voltage=500.0, outputs=["lever.E_y"])
    np.testing.assert_allclose(a.A, b.A, rtol=1e-9, atol=1e-9 * np.abs(b.A).max())
    np.testing.assert_allclose(a.dc_gain(), b.dc_gain(), rtol=1e-9)
    assert not mech.forces
    with pytest.raises(ValueError, match=r"loads: 'lever.F' is not a named point.*'lever.E'"):
        atcm.linearise(mech, voltage=500.0, loads={"lever.F": (0.0, -0.1)}, outputs=["lever.E_y"])
