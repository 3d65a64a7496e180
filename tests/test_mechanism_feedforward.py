"""Feedforward for a mechanism output (issue 32, part 3): exudyn_atcm.mechanism_feedforward.

The mechanism: the paper's laminate (CFC 0.2 mm under MFC 0.3 mm, 28 mm wide) as a 48 mm bender of
4 rigid cells, with a 120 mm rigid lever of 2.7 g welded to its tip: the lever end moves
(L/2 + a)/(L/2) = 6 times the bender tip (a 6:1 lever), reaches -2.9 ... 28.4 mm over -500 ... 1500 V,
and its first mode (17.1 Hz) has the damping ratio beta omega / 2 = 0.29 % (the bender's default 2 %
at its own 118 Hz clamped-free mode).  The goal: the lever end follows 6 -> 20 -> 6 mm in 2 s.

References: the actual simulation of the program (exudyn_atcm.simulate) against the wanted path;
the naive program (no pre-filter) in the same simulation; the rigid chain's polygon plus the
rigid lever (theory.chain_polygon, rigid_extension_point) for the map; scipy.signal.lsim of a
single mode for the pre-filters; closed-form corner rounding of a moving average; for the control case's
PID, the closed loop of the linear model built here with numpy (continuous and sampled with a zero-order hold).
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from scipy import signal as sps
from scipy.linalg import expm

import exudyn_atcm as atcm
from exudyn_atcm import theory
from exudyn_atcm.casework import load_case
from exudyn_atcm.hysteresis.creep import Creep
from exudyn_atcm.hysteresis.dynamics import WithDynamics
from exudyn_atcm.model import paper_strain_preisach
from exudyn_atcm.model.prefilter import Prefilter, invert_mode, shape, shaper_impulses, smooth

from _cli_helpers import CASES

CFC = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
L, A, M, WIDTH, CELLS = 0.048, 0.12, 2.7e-3, 28e-3, 4
#: rest before the ramp [s], the ramp 6 -> 20 -> 6 mm in 2 s, rest after [s]
T_WANTED = np.array([0.0, 0.1, 1.1, 2.1, 2.5])
Y_WANTED = np.array([6.0, 6.0, 20.0, 6.0, 6.0]) * 1e-3
#: 0.25 ms: within the run checks' bounds (the bender's 118 Hz clamped-free estimate; 20 steps over the
#: program's shortest monotone stretch, 6 ms at the corners of the inverted mode); from 0.4 ms to
#: 0.2 ms the RMS errors below change by < 0.05 um (inversion) and < 0.5 um (naive), measured
STEP = 2.5e-4


def lever(program=0.0, hysteresis=None) -> atcm.Mechanism:
    drive = atcm.PiezoDrive(program, hysteresis=paper_strain_preisach() if hysteresis is None else hysteresis)
    bender = atcm.Bender("bender", width=WIDTH, passive=CFC, active=MFC, length=L, n_cells=CELLS, drive=drive,
                         cell="rigid")
    arm = atcm.Link("lever", {"root": (L, 0.0), "end": (L + A, 0.0)}, mass=M, inertia=M * A**2 / 12.0)
    return atcm.Mechanism("lever_stage").add(bender, arm).ground(bender.base).weld(bender.tip, arm.point("root"))


def ramp_errors(program) -> tuple[float, float]:
    """RMS and largest error [m] of the simulated lever end over the 2 s ramp."""
    result = atcm.simulate(lever(program), float(T_WANTED[-1]), step=STEP)
    t = result["time"]
    error = result["lever.end_y"] - np.interp(t, T_WANTED, Y_WANTED)
    ramp = (t >= T_WANTED[1]) & (t <= T_WANTED[3])
    return float(np.sqrt(np.mean(error[ramp] ** 2))), float(np.max(np.abs(error[ramp])))


def lever_end_theory(strain) -> np.ndarray:
    """Lever end y [m] at rest: the 4-cell chain's polygon on the free arc plus the rigid lever."""
    out = []
    for s in np.atleast_1d(strain):
        kappa = theory.free_curvature(CFC.youngs_modulus, CFC.thickness, MFC.youngs_modulus, MFC.thickness, WIDTH,
                                      float(s))
        x, y = theory.chain_polygon(kappa, L, CELLS)
        out.append(theory.rigid_extension_point(x[-1], y[-1], kappa * L, A)[1])
    return np.array(out, dtype=float)


@pytest.fixture(scope="module")
def programs():
    return {pf: atcm.mechanism_feedforward(lever(), "lever.end_y", T_WANTED, Y_WANTED, prefilter=pf)
            for pf in ("inversion", "none")}


def test_compensated_ramp_meets_10_um_rms_and_naive_is_far_worse(programs):
    # the goal of issue 32: dynamic RMS <= 10 um (measured 1.2 um; max 33 um, at the corners, where
    # the path is rounded over one period of the 176 Hz second mode); the naive program (static map
    # and hysteresis inverse only) rings at every corner of the lightly damped 17 Hz mode
    rms, largest = ramp_errors(programs["inversion"][0])
    naive_rms, naive_largest = ramp_errors(programs["none"][0])
    assert rms <= 10e-6
    assert naive_rms > 50e-6 and naive_rms > 20.0 * rms  # measured 103 um, 200 um max
    assert largest < naive_largest / 3.0


@pytest.mark.parametrize("prefilter", ["smooth", "zvd"])
def test_shaping_and_smoothing_ring_less_than_the_naive_program(programs, prefilter):
    # rounding the corners over one period (measured 8.4 um RMS) or ZVD shaping (16.7 um) removes most of
    # the ringing but leaves the corners' rounding (about slope x period / 4 at a corner), so the mode
    # inversion's 1.2 um is better than both
    program, report = atcm.mechanism_feedforward(lever(), "lever.end_y", T_WANTED, Y_WANTED, prefilter=prefilter)
    rms, _ = ramp_errors(program)
    naive_rms, _ = ramp_errors(programs["none"][0])
    assert rms < naive_rms / 3.0 and rms <= 25e-6
    assert report.window == (pytest.approx(1.0 / report.frequencies[1]) if prefilter == "smooth" else 0.0)


def test_prefilter_settings_are_checked_where_they_are_given():
    for kwargs, message in (({"kind": "zvdd"}, r"prefilter must be one of 'inversion', .*got 'zvdd'"),
                            ({"shaped_modes": 3}, r"shaped_modes must be 1 or 2, got 3"),
                            ({"window": -0.1}, r"window must be"),
                            ({"damping_ratio": 1.5}, r"damping_ratio must be in \[0, 1\)"),
                            ({"damping_from": "modal"}, r"damping_from must be one of 'linear', 'description'")):
        with pytest.raises(ValueError, match=message):
            Prefilter(**kwargs)
    with pytest.raises(ValueError, match=r"prefilter must be one of"):
        atcm.mechanism_feedforward(lever(), "lever.end_y", [0.0, 1.0], [6e-3, 8e-3], prefilter="shaper")


def test_damping_ratio_override_and_a_too_coarse_sample_time():
    _, report = atcm.mechanism_feedforward(lever(), "lever.end_y", [0.0, 1.0], [6e-3, 8e-3],
                                           prefilter=Prefilter(damping_ratio=0.05))
    assert report.damping_ratio == 0.05 and report.damping_source.startswith("given")
    with pytest.raises(ValueError, match=r"sample_time = 0.01 s is too coarse for the first mode"):
        atcm.mechanism_feedforward(lever(), "lever.end_y", [0.0, 1.0], [6e-3, 8e-3], sample_time=0.01)


def test_quasi_static_error_within_the_fit_error(programs):
    # the program's voltages held one after another (a static sweep follows the hysteresis memory
    # through them, including the reversal at the top): the lever end at rest equals the wanted one
    # to the map's own fit error (measured at points kept out of the map) plus the bisection's 1e-9
    program, report = programs["none"]
    top = int(np.argmax(report.voltage))
    idx = np.unique(np.concatenate([np.arange(0, report.times.size, 100), [top, report.times.size - 1]]))
    sweep = atcm.static_sweep(lever(), report.voltage[idx])
    error = np.abs(sweep["lever.end_y"] - report.wanted[idx])
    assert report.fit_error < 1e-7  # 41 points of a smooth map: a few nm
    assert error.max() <= report.fit_error + 1e-9


def test_map_matches_the_chain_polygon_and_the_damping_is_beta_omega_over_2(programs):
    _, report = programs["inversion"]
    omap = report.output_map
    np.testing.assert_allclose(omap.values, lever_end_theory(omap.strains), rtol=0, atol=1e-9)
    bender = lever().components["bender"]
    beta = 2.0 * 0.02 / (2.0 * math.pi * bender.laminate.first_frequency(L))  # the default ratio at its own mode
    assert report.damping_ratio == pytest.approx(beta * 2.0 * math.pi * report.frequencies[1] / 2.0, rel=1e-12)
    assert 10.0 < report.frequencies[1] < 30.0 and report.damping_ratio < 0.01  # lightly damped, 10-30 Hz


def test_unreachable_wanted_output_is_refused_with_the_reachable_range():
    with pytest.raises(ValueError, match=r"not reachable at rest") as info:
        atcm.mechanism_feedforward(lever(), "lever.end_y", [0.0, 1.0], [6e-3, 30e-3])
    high = float(re.search(r"reaches lever\.end_y from (\S+) to (\S+)", str(info.value)).group(2))
    top_strain = paper_strain_preisach().apply([-500.0, 1500.0])[-1]  # the operator's saturated strain
    assert high == pytest.approx(float(lever_end_theory(top_strain)[0]), rel=1e-5)


def test_non_monotone_map_is_refused_naming_where_it_turns():
    # the lever end's x is largest for the straight bender (strain 0) and falls for either sign of
    # the curvature: a wanted x near the top has two strains
    with pytest.raises(ValueError, match=r"not monotone") as info:
        atcm.mechanism_feedforward(lever(), "lever.end_x", [0.0, 1.0], [L + A - 1e-5, L + A - 2e-6])
    lo, hi = (float(v) for v in re.search(r"between free strain (\S+) and (\S+) \(", str(info.value)).groups())
    assert lo <= 0.0 <= hi


@pytest.mark.parametrize("kwargs, match", [
    ({"output": "lever.endy"}, r"not a column .*did you mean 'lever\.end_y'"),
    ({"output": "lever.end_y", "drive": "bendr"}, r"no drive 'bendr' \(did you mean 'bender'\?\)"),
    ({"output": "lever.end_y", "prefilter": "notch"}, r"prefilter must be one of"),
])
def test_bad_names_are_refused_with_the_closest_name(kwargs, match):
    with pytest.raises(ValueError, match=match):
        atcm.mechanism_feedforward(lever(), times=[0.0, 1.0], wanted=[6e-3, 8e-3], **kwargs)


# ------------------------------------------------------------------ the pre-filters on one mode

F, ZETA = 17.0, 0.003


def mode_response(t, command):
    """y'' + 2 zeta w y' + w^2 y = w^2 q, at rest at q[0] (scipy's exact zero-order-hold-free lsim)."""
    w = 2.0 * math.pi * F
    system = sps.lti([w * w], [1.0, 2.0 * ZETA * w, w * w])
    _, y, _ = sps.lsim(system, command - command[0], t)
    return y + command[0]


def test_zv_and_zvd_shaped_step_leave_no_residual_vibration():
    t = np.arange(0.0, 1.0, 1e-4)
    step = (t >= 0.1).astype(float)
    plain = mode_response(t, step)
    late = t > 0.3
    assert np.max(np.abs(plain[late] - 1.0)) > 0.5  # 0.3 % damping: the step rings on
    for kind in ("zv", "zvd"):
        shaped = mode_response(t, shape(t, step, [(F, ZETA)], kind, advance=False))
        # exact cancellation of the mode; what is left is the sampling of the impulse times (1e-4 s)
        assert np.max(np.abs(shaped[late] - 1.0)) < 0.01
    times, amps = shaper_impulses(F, 0.0, "zv")
    np.testing.assert_allclose(times, [0.0, 0.5 / F]), np.testing.assert_allclose(amps, [0.5, 0.5])


def test_mode_inversion_follows_the_rounded_path():
    t = np.arange(0.0, 2.0, 1e-4)
    ramp = np.interp(t, [0.0, 0.5, 1.0, 1.5, 2.0], [0.0, 0.0, 1.0, 0.0, 0.0])
    command, rounded = invert_mode(t, ramp, F, ZETA, 0.01)
    y = mode_response(t, command)
    plain = mode_response(t, ramp)
    # through the mode the command gives the rounded path; left: the finite differences of r''
    assert np.max(np.abs(y - rounded)) < 1e-4 * np.max(np.abs(plain - ramp))  # 1e-5 of the naive ringing
    assert np.max(np.abs(plain - ramp)) > 1e-3


def test_moving_average_rounds_a_corner_by_slope_change_times_window_over_8():
    t = np.arange(0.0, 1.0, 1e-3)
    corner = np.abs(t - 0.5)  # slope change 2 at t = 0.5
    window = 0.04
    rounded = smooth(t, corner, window)
    assert rounded[500] - corner[500] == pytest.approx(2.0 * window / 8.0, rel=1e-3)
    # away from the corners (also the held start at t = 0) unchanged
    assert np.max(np.abs(rounded[30:470] - corner[30:470])) < 1e-12


def test_creep_of_the_drive_is_compensated_with_the_time():
    # the drive's operator followed by creep (13 % more strain over 0.01 ... 0.1 s): the inverse with
    # the time (DynamicsInverse) keeps the ramp within 10 um RMS (measured 1.9 um); the program of
    # the creep-free operator on the same creeping drive is off by the creep (measured 1.8 mm RMS)
    def creeping(program=0.0) -> atcm.Mechanism:
        return lever(program, WithDynamics(paper_strain_preisach(), Creep([0.01, 0.1], [0.05, 0.08])))

    program, report = atcm.mechanism_feedforward(creeping(), "lever.end_y", T_WANTED, Y_WANTED)
    plain, _ = atcm.mechanism_feedforward(lever(), "lever.end_y", T_WANTED, Y_WANTED)
    errors = {}
    for name, p in (("creep", program), ("plain", plain)):
        result = atcm.simulate(creeping(p), float(T_WANTED[-1]), step=STEP)
        error = result["lever.end_y"] - np.interp(result["time"], T_WANTED, Y_WANTED)
        errors[name] = float(np.sqrt(np.mean(error**2)))
    assert errors["creep"] <= 10e-6
    assert errors["plain"] > 100.0 * errors["creep"]
    # the static map is the fully crept one: reachable up to (1 + 0.13) x the creep-free strain's output
    assert report.reachable[1] > 1.1 * 0.0284


def pid_from_model(k0: float, w: float, zeta: float, kp_fraction=0.5, zeta_target=0.7) -> tuple[float, float, float]:
    """The case's tuning rule, written out again: kp stiffens to w_c, kd damps to zeta_target at w_c, ki at a
    quarter of the closed-loop cubic's Routh limit (a2 a1 / 4)."""
    kp = kp_fraction / k0
    wc = w * math.sqrt(1.0 + k0 * kp)
    kd = 2.0 * (zeta_target * wc - zeta * w) / (k0 * w * w)
    return kp, 0.25 * (2.0 * zeta_target * wc) * wc * wc / (k0 * w * w), kd


def test_control_case_tracks_within_10_um_and_its_pid_is_stable():
    out = load_case(CASES / "control_lever.py").run()
    s = {k: (v[0] if isinstance(v, tuple) else v) for k, v in out.scalars.items()}
    assert s["rms_error_compensated"] <= 10e-6 and s["rms_error_pid_feedforward"] <= 10e-6
    assert s["rms_error_naive"] > 20.0 * s["rms_error_compensated"]
    assert s["map_error_polygon"] < 1e-9  # rigid chain on the free arc plus the lever: exact but for the solver
    # the linear model, built here from this file's own stage, about the case's operating voltage (the middle
    # output, 13 mm) on the ascending branch
    lin = atcm.linearise(lever(), voltage={"bender": s["operating_voltage"]}, outputs=["lever.end_y"])
    assert lin.operating_point["lever.end_y"] == pytest.approx(0.5 * (6e-3 + 20e-3), abs=1e-6)
    A, B, C = lin.A, lin.B, lin.C
    k0 = float(-(C @ np.linalg.solve(A, B))[0, 0])  # static gain of the state-space model [m/V]
    # the same gain from the static sweep's map (a difference over its 50 V spacing): measured 2.7e-4 apart
    assert k0 == pytest.approx(s["static_gain"], rel=1e-9) and k0 == pytest.approx(s["static_gain_map"], rel=2e-3)
    poles = np.linalg.eigvals(A)
    first = poles[poles.imag > 0.0][np.argmin(np.abs(poles[poles.imag > 0.0]))]
    w, zeta = abs(first), -first.real / abs(first)
    assert w / (2.0 * math.pi) == pytest.approx(s["first_frequency"], rel=1e-6)  # the eigenfrequency about 13 mm
    # the PID is the tuning rule applied to the model's K0, w and zeta
    kp, ki, kd = pid_from_model(k0, w, zeta)
    assert (s["kp"], s["ki"], s["kd"]) == pytest.approx((kp, ki, kd), rel=1e-6)
    # closed loop of the whole linear model (every mode) with the continuous PID u = -(kp y + ki int y + kd y'),
    # y' = C A x since C B = 0 (the output is a position): state [x, int y]
    assert np.allclose(C @ B, 0.0)
    n = A.shape[0]
    closed = np.block([[A - B @ (kp * C + kd * C @ A), -ki * B], [C, np.zeros((1, 1))]])
    assert np.max(np.linalg.eigvals(closed).real) < 0.0
    assert np.max(np.linalg.eigvals(closed).real) == pytest.approx(s["pid_closed_loop_max_real"], rel=1e-6)
    # and as the controller runs: sampled every Ts with a zero-order hold, v_k = kp e_k + ki Ts sum e_j
    # - kd (y_k - y_(k-1))/Ts (PIDController); state [x_k, sum_(j<k) e_j Ts, y_(k-1)], plant discretised exactly
    ts = 5e-4
    aug = expm(np.block([[A, B], [np.zeros((1, n + 1))]]) * ts)
    ad, bd = aug[:n, :n], aug[:n, n:]
    gain_x = -(kp + ki * ts + kd / ts) * C
    sampled = np.block([[ad + bd @ gain_x, ki * bd, kd / ts * bd],
                        [-ts * C, np.ones((1, 1)), np.zeros((1, 1))],
                        [C, np.zeros((1, 2))]])
    assert np.max(np.abs(np.linalg.eigvals(sampled))) < 1.0
    # the simulated PID loop (hysteresis in the step) is stable too: from 0 V at rest to 6 mm (an initial error
    # of 4.7 mm), the error stays bounded, never hits the voltage limits and settles after the ramp (measured
    # 2.0 mm at most during it, 59 um over the last 0.1 s: a reversal of the Preisach loop has a low slope)
    error = out.result["end_pid"] - out.result["wanted"]
    t = out.result["time"]
    assert np.max(np.abs(error)) < 5e-3
    assert out.notes["controller_pid"]["limited_samples"] == 0
    assert np.max(np.abs(error[t >= t[-1] - 0.1])) < 0.05 * np.max(np.abs(error))