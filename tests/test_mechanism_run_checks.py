"""Issue 9, sections 1-2, for mechanisms: the run checks of the actuator path on the mechanism path.

References: the clamped-free Euler-Bernoulli beam (beta1 L = 1.8751, Timoshenko 1925) with the
two-layer section's bending stiffness about its neutral axis, the MFC P1 rating
(-500 ... +1500 V), the step grid ``t_end / ceil(t_end / step)``, the measured cost constants
of :data:`exudyn_atcm.solve.run_checks.COST_PER_STEP`, and the uninterrupted / every-step run for the
interrupted / thinned one.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from exudyn_atcm import Bender, Layer, Link, Mechanism, MechanismError, PiezoDrive, simulate
from exudyn_atcm.solve import run_checks
from exudyn_atcm.model.control import Controller, PIDController
from exudyn_atcm.model.signals import Steps
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.solve.run_checks import SimulationInterrupted
from exudyn_atcm.model.signals import Triangle

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W = 28e-3


def bender(name, drive, length=0.087, n_cells=3):
    return Bender(name, width=W, passive=CFC, active=MFC, length=length, n_cells=n_cells, drive=drive, cell="rigid")


def cantilever(b):
    return Mechanism("cantilever").add(b).ground(b.base)


def two_benders(drive_a, drive_b, length_b=0.087):
    """Two cantilevers side by side (independent; one mechanism)."""
    a = bender("a", drive_a)
    b = Bender("b", width=W, passive=CFC, active=MFC, length=length_b, n_cells=3, drive=drive_b, base=(0.0, 0.05), cell="rigid")
    return Mechanism("pair").add(a, b).ground(a.base).ground(b.base)


def _messages(record):
    return [str(w.message) for w in record if issubclass(w.category, RuntimeWarning)]


def clamped_free_f1(length: float) -> float:
    """First bending frequency [Hz] of the CFC/MFC strip: neutral-axis EI, beta1 L = 1.8751."""
    layers = [(CFC.thickness, CFC.youngs_modulus), (MFC.thickness, MFC.youngs_modulus)]
    z = [CFC.thickness / 2, CFC.thickness + MFC.thickness / 2]
    zn = sum(E * t * zi for (t, E), zi in zip(layers, z)) / sum(E * t for t, E in layers)
    ei = sum(E * W * (t**3 / 12 + t * (zi - zn) ** 2) for (t, E), zi in zip(layers, z))
    mu = W * (CFC.thickness * CFC.density + MFC.thickness * MFC.density)
    return 1.8751040687**2 / (2 * math.pi * length**2) * math.sqrt(ei / mu)


# ----------------------------------------------------------------------------- step checks

def test_step_too_coarse_for_one_drive_is_refused_naming_the_drive():
    mech = two_benders(PiezoDrive(500.0), PiezoDrive(Triangle(500.0, 500.0, 0.02)))
    # the ramp of drive 'b' lasts 0.01 s: a step of 0.005 s gives 2 steps (< 4)
    with pytest.raises(ValueError, match=r"too coarse for the voltage program of drive 'b'.*lasts 0\.01 s, only 2 steps"):
        simulate(mech, 0.02, step=0.005)


def test_step_against_the_lowest_bender_frequency_names_the_bender():
    # bender 'b' is twice as long: f1 four times lower (f1 ~ 1/L^2), so it is the one named
    mech = two_benders(PiezoDrive(0.0), PiezoDrive(0.0), length_b=0.174)
    f1 = clamped_free_f1(0.174)
    step = 0.2 / f1  # 5 steps per period (< 10)
    with pytest.warns(RuntimeWarning) as record:
        simulate(mech, 10 * step, step=step)
    hits = [m for m in _messages(record) if "bending mode" in m]
    assert len(hits) == 1 and "bender 'b'" in hits[0]
    assert f"f1 = {f1:.4g} Hz" in hits[0]


def test_step_that_does_not_divide_t_end_is_recorded_and_warned():
    mech = cantilever(bender("a", PiezoDrive(300.0)))
    with pytest.warns(RuntimeWarning, match=r"does not divide t_end"):
        r = simulate(mech, 0.002, step=3e-4)
    n = math.ceil(0.002 / 3e-4)  # 7 steps of 0.002/7 s
    assert r.info["step [s]"] == pytest.approx(0.002 / n, rel=1e-12)
    assert r.info["step_requested [s]"] == 3e-4
    assert r.n_rows == n + 1 and r["time"][-1] == pytest.approx(0.002, abs=1e-15)


def test_quiet_on_a_sound_step():
    mech = cantilever(bender("a", PiezoDrive(Triangle(500.0, 500.0, 0.02))))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        simulate(mech, 0.002, step=1e-4)  # 100 steps per ramp, f1 period 0.028 s / 1e-4 s


# ----------------------------------------------------------------------------- long runs

def test_long_run_warning_counts_the_cells_and_links(monkeypatch):
    b = bender("a", PiezoDrive(0.0), n_cells=5)
    lever = Link("lever", {"A": (0.087, 0.0), "B": (0.1, 0.0)}, mass=1e-3, inertia=1e-8)
    mech = Mechanism("m").add(b, lever).ground(b.base).weld(b.tip, lever.point("A"))
    monkeypatch.setattr(run_checks, "LONG_RUN_SECONDS", 1e-6)
    a, bb, c = run_checks.COST_PER_STEP["rigid"]
    parts, steps = 6, 10  # five cells and one link
    expected = steps * (a + bb * parts + c * parts**2)
    with pytest.warns(RuntimeWarning, match=r"predicted to take") as record:
        simulate(mech, 1e-3, step=1e-4)
    msg = next(m for m in _messages(record) if "predicted" in m)
    assert "6 cells and bodies (rigid cells)" in msg
    assert f"~{expected / steps * 1e6:.3g} µs per step" in msg


@pytest.mark.filterwarnings("ignore:record_every = .* keeps only:RuntimeWarning")  # thinned on purpose
def test_record_every_thins_the_record_not_the_solution():
    mech = cantilever(bender("a", PiezoDrive(Triangle(500.0, 500.0, 0.02), hysteresis=paper_strain_preisach())))
    full = simulate(mech, 0.01, step=1e-4)
    thin = simulate(mech, 0.01, step=1e-4, record_every=7)
    # rows 0, 7, 14, ..., 98 and the last one (100)
    idx = list(range(0, 101, 7)) + [100]
    assert thin.n_rows == len(idx) and thin.info["recorded"] == "every 7 steps"
    for name in ("time", "a.voltage", "a.strain", "a.tip_y", "a.cell_angle_2"):
        np.testing.assert_array_equal(thin[name], full[name][idx])
    by_time = simulate(mech, 0.01, step=1e-4, record_every=0.002)
    np.testing.assert_allclose(by_time["time"], [0.0, 0.002, 0.004, 0.006, 0.008, 0.01], atol=1e-12)


def test_interrupt_keeps_the_partial_result_marked_partial():
    mech = cantilever(bender("a", PiezoDrive(Triangle(500.0, 500.0, 0.02), hysteresis=paper_strain_preisach())))
    full = simulate(mech, 0.01, step=1e-4)

    def progress(t, t_end):
        if t >= 0.004:
            raise KeyboardInterrupt

    with pytest.raises(SimulationInterrupted, match=r"interrupted at t = 0\.004") as info:
        simulate(mech, 0.01, step=1e-4, progress=progress)
    exc = info.value
    partial = exc.result
    assert partial.info["partial"] is True and partial.info["interrupted_at [s]"] == exc.time
    n = partial.n_rows
    assert n == round(exc.time / 1e-4) + 1 and partial["time"][-1] == exc.time
    for name in ("time", "a.voltage", "a.strain", "a.tip_y"):
        np.testing.assert_array_equal(partial[name], full[name][:n])


# ----------------------------------------------------------------------------- drive ranges

def test_voltage_beyond_the_rating_warns_once_naming_the_drive():
    mech = two_benders(PiezoDrive(400.0), PiezoDrive(Triangle(1000.0, 1000.0, 0.02)))
    with pytest.warns(RuntimeWarning) as record:
        simulate(mech, 0.01, step=1e-4)  # drive 'b' reaches 2000 V at t = 0.01 s
    hits = [m for m in _messages(record) if "rated range" in m]
    assert len(hits) == 1
    assert hits[0].startswith("drive 'b': the voltage program spans 0 ... 2000 V")
    assert "500 V above" in hits[0]


def test_implausible_strain_warns_naming_the_drive():
    # d33 U / t_IDE = 5.5e-8 * 100 / 0.5e-3 = 0.011 > 1e-2 (more than a piezo layer gives)
    drive = PiezoDrive(100.0, d33=5.5e-8)
    mech = cantilever(bender("a", drive, n_cells=8))
    with pytest.warns(RuntimeWarning, match=r"the free strain of drive 'a' reaches a free strain of 0\.011"):
        simulate(mech, 1e-3, step=1e-4)


# ----------------------------------------------------------------------------- controllers

class Recording(Controller):
    """A constant voltage that records what it observes."""

    def __init__(self, volts):
        self.volts = volts
        self.seen = []

    def voltage_at(self, t):
        return self.volts

    def observe(self, t, value):
        self.seen.append((t, value))

    def reset(self):
        self.seen = []


def test_controller_without_a_declared_measurement_is_refused():
    mech = cantilever(bender("crank", PiezoDrive(Recording(100.0))))
    with pytest.raises(MechanismError, match=r"drive 'crank'.*set by a controller.*feedback\('crank', "):
        simulate(mech, 1e-3, step=1e-4)


def test_unknown_measurement_is_refused_with_the_closest_column():
    mech = cantilever(bender("crank", PiezoDrive(Recording(100.0))))
    mech.feedback("crank", "crank.tipy")
    with pytest.raises(MechanismError, match=r"'crank.tipy' is not a result column.*did you mean 'crank.tip_y'"):
        simulate(mech, 1e-3, step=1e-4)
    with pytest.raises(MechanismError, match=r"feedback: unknown drive 'crnk'.*did you mean 'crank'"):
        mech.feedback("crnk", "crank.tip_y")


@pytest.mark.parametrize("column", ["crank.tip_y", "crank.tip_angle [rad]"])
def test_controller_observes_the_declared_column_of_every_accepted_step(column):
    ctrl = Recording(800.0)
    mech = cantilever(bender("crank", PiezoDrive(ctrl)))
    mech.feedback("crank", column)
    r = simulate(mech, 0.003, step=1e-4)
    times, values = np.array(ctrl.seen).T
    np.testing.assert_array_equal(times, r["time"])
    np.testing.assert_allclose(values, r[column.split(" [")[0]], rtol=0, atol=1e-15)
    assert r.info["controller"]["measurement"] == column


def test_pid_on_a_mechanism_reaches_its_setpoint():
    # Integral action removes the steady error of a reachable constant setpoint.  Static gain
    # of the plant ~1.1e-5 m/V, so ki = 3e5 V/(m s) gives a first-order approach with time
    # constant ~0.3 s, far below the first mode (36 Hz, 2 % damping): after 2 s ~e^-6 is left.
    target = 2e-3  # m
    pid = PIDController(0.0, 3e5, 0.0, sample_time=1e-3, setpoint=target, output_limits=(-500.0, 1500.0))
    mech = cantilever(bender("crank", PiezoDrive(pid)))
    mech.feedback("crank", "crank.tip_y")
    r = simulate(mech, 2.0, step=1e-3)
    assert r["crank.tip_y"][-1] == pytest.approx(target, rel=0.01)
    assert r.info["controller"]["samples"] == 2001


def test_warnings_point_at_the_callers_line():
    # a warning is attributed to the user's call of simulate / solve_static, not to package internals
    from exudyn_atcm import solve_static

    mech = two_benders(PiezoDrive(400.0), PiezoDrive(Triangle(1000.0, 1000.0, 0.02)), length_b=0.174)
    with pytest.warns(RuntimeWarning) as record:
        simulate(mech, 0.01, step=3e-3)  # does not divide, coarse for the program, beyond the rating
    assert len(record) == 3 and {w.filename for w in record} == {__file__}
    with pytest.warns(RuntimeWarning) as record:
        solve_static(mech, voltage={"a": 0.0, "b": 1800.0})
    assert {w.filename for w in record} == {__file__}


def test_actuator_warnings_point_at_the_callers_line_too():
    from exudyn_atcm import BendingActuator

    act = BendingActuator(3, 0.029, W, CFC, MFC, PiezoDrive(Triangle(1000.0, 1000.0, 0.02)), cell="six-bar")
    with pytest.warns(RuntimeWarning) as record:
        simulate(act, 0.01, step=3e-3)  # does not divide, coarse for the program, beyond the rating
    assert len(record) == 3 and {w.filename for w in record} == {__file__}


def test_segments_sharing_one_program_are_checked_once_naming_both():
    from exudyn_atcm import Segment

    drive = PiezoDrive(Triangle(500.0, 500.0, 0.02))
    s = Bender("s", width=W, passive=CFC, active=MFC, segments=[Segment(0.04, 2, drive), Segment(0.04, 2, drive)], cell="rigid")
    mech = Mechanism("m").add(s).ground(s.base)
    with pytest.warns(RuntimeWarning) as record:
        simulate(mech, 0.002, step=1e-3)  # 10 steps per 0.01 s ramp: a warning, once
    hits = [m for m in _messages(record) if "shortest feature" in m]
    assert len(hits) == 1 and "drives 's.1', 's.2'" in hits[0]


def test_measurement_declared_for_a_drive_without_controller_is_refused():
    mech = cantilever(bender("crank", PiezoDrive(300.0)))
    mech.feedback("crank", "crank.tip_y")
    with pytest.raises(MechanismError, match=r"declares the measurement 'crank.tip_y' for drive 'crank'.*not a controller"):
        simulate(mech, 1e-3, step=1e-4)


def test_a_long_program_is_cut_short_in_the_refusal():
    # a step program of 2000 switches: its repr is some 60,000 characters; the message names it in about 100
    times = np.linspace(0.0, 10.0, 2000)  # dwells of 5 ms: 50 steps each
    mech = cantilever(bender("crank", PiezoDrive(Steps(times, 300.0 * np.sin(times)))))
    mech.feedback("crank", "crank.tip_y")
    with pytest.raises(MechanismError, match=r"not a controller \(Steps\(times=\[.*\.\.\. \(Steps, \d+ characters\)\)") as info:
        simulate(mech, 1e-3, step=1e-4)
    assert len(str(info.value)) < 500


def test_range_check_sees_every_step_not_only_the_recorded_ones():
    # the triangle peaks at 2000 V at t = 0.01 s; records at 0, 7, 14, 20 ms see at most 1400 V
    mech = cantilever(bender("a", PiezoDrive(Triangle(1000.0, 1000.0, 0.02))))
    with pytest.warns(RuntimeWarning) as record:
        r = simulate(mech, 0.02, step=1e-4, record_every=0.007)
    assert r["a.voltage"].max() == pytest.approx(1400.0)
    hits = [m for m in _messages(record) if "rated range" in m]
    assert len(hits) == 1 and "spans 0 ... 2000 V" in hits[0]
