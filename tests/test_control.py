"""Closed loop inside the simulation: a controller sets the drive voltage from the simulated tip deflection."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.mechanism.actuator import BendingActuator
from exudyn_atcm.model.control import PIDController
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.materials import Layer
from exudyn_atcm.model.parameter_sets import paper_strain_preisach
from exudyn_atcm.solve import TableStrain, run_actuator, simulate


def actuator(drive):
    return BendingActuator(
        n_cells=3, cell_length=29e-3, width=28e-3,
        passive=Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0),
        active=Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0),
        drive=drive, cell="rigid", damping=0.05,
    )


class Recording(PIDController):
    """A PID controller that keeps what it observed."""

    def reset(self):
        super().reset()
        self.seen = []

    def observe(self, t, tip_deflection):
        self.seen.append((t, tip_deflection))
        super().observe(t, tip_deflection)


def test_integral_action_brings_the_tip_to_the_setpoint_through_the_hysteresis():
    target = 6e-3  # m, inside the reachable range (about -1.6 ... 15.6 mm)
    pid = Recording(2e4, 2e6, sample_time=1e-3, setpoint=target, output_limits=(-500.0, 1500.0))
    act = actuator(PiezoDrive(pid, hysteresis=paper_strain_preisach()))
    result = simulate(act, 1.5, step=2e-4)
    # integral action: zero steady-state error on a constant setpoint
    assert result["actuator.tip_y"][-1] == pytest.approx(target, abs=2e-3 * target)
    # the controller saw exactly the recorded deflections of the accepted steps
    seen = np.array(pid.seen)
    np.testing.assert_allclose(seen[:, 0], result["time"])
    np.testing.assert_allclose(seen[:, 1], result["actuator.tip_y"], rtol=0, atol=1e-15)
    # zero-order hold at its own rate: the voltage changes only right after sample instants
    volts, t = result["actuator.voltage"], result["time"]
    changes = t[1:][np.abs(np.diff(volts)) > 0]
    # a step ending at t uses the feedback sampled at the last sample instant before t
    assert np.all(np.abs(changes - 2e-4 - np.round((changes - 2e-4) / 1e-3) * 1e-3) < 1e-9)
    info = result.info["controller"]
    assert info["samples"] == pytest.approx(1.5 / 1e-3 + 1, abs=1)
    assert info["limited_samples"] == 0


def test_output_limit_is_reported_not_silent():
    pid = PIDController(2e4, 2e6, sample_time=1e-3, setpoint=30e-3, output_limits=(-500.0, 1500.0))
    act = actuator(PiezoDrive(pid, hysteresis=paper_strain_preisach()))
    with pytest.warns(RuntimeWarning, match=r"at its limits \[-500.0, 1500.0\] V in \d+ of \d+ samples"):
        result = simulate(act, 0.3, step=2e-4)
    assert result["actuator.voltage"].max() == 1500.0
    assert result.info["controller"]["limited_samples"] > 0


def test_controller_needs_the_in_step_source():
    pid = PIDController(1.0, sample_time=1e-3, setpoint=0.0)
    act = actuator(PiezoDrive(pid))
    table = TableStrain(np.array([0.0, 1.0]), np.zeros(2), np.zeros(2))
    with pytest.raises(ValueError, match="needs the in-step strain source, got TableStrain"):
        run_actuator(act, 0.1, 1e-3, (0.0, 0.0), None, source=table)


@pytest.mark.parametrize(
    "kwargs, pattern",
    [
        ({"kp": 1.0, "sample_time": 0.0, "setpoint": 0.0}, "sample_time must be > 0"),
        ({"kp": float("nan"), "sample_time": 1e-3, "setpoint": 0.0}, "kp must be a finite real number"),
        ({"kp": 1.0, "sample_time": 1e-3, "setpoint": 0.0, "output_limits": (1, 0)}, "output_limits must have high > low"),
        ({"kp": 1.0, "ki": -5.0, "sample_time": 1e-3, "setpoint": 0.0}, r"kp, ki, kd must share one sign .*got kp=1.0, ki=-5.0, kd=0.0"),
        ({"kp": 0.0, "sample_time": 1e-3, "setpoint": 0.0}, "all 0 and there is no feedforward"),
    ],
)
def test_pid_rejects_bad_settings(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        PIDController(**kwargs)


def test_pid_arithmetic_by_hand():
    # kp = 2 V/m, ki = 10 V/(m s), kd = 0.5 V s/m, T_s = 0.1 s, setpoint 1 m, feedforward 0.25 V
    pid = PIDController(2.0, 10.0, 0.5, sample_time=0.1, setpoint=1.0, feedforward=0.25, output_limits=(-1.0, 2.0))
    assert pid.voltage_at(0.0) == 0.25  # no sample yet: feedforward only
    pid.observe(0.0, 0.0)  # e = 1: 2*1 + 10*(1*0.1) = 3 -> 3.25 V, limited to 2 V
    assert pid.voltage_at(0.05) == 2.0
    assert pid.limited_samples == 1 and pid.largest_excess == pytest.approx(1.25)
    pid.observe(0.05, 0.9)  # between samples: ignored (zero-order hold)
    assert pid.voltage_at(0.07) == 2.0
    # e = 0.5; the last sample was limited upwards and e > 0: no integration (integral stays 0.1)
    # v = 2*0.5 + 10*0.1 - 0.5*(0.5 - 0)/0.1 = 1 + 1 - 2.5 = -0.5 -> -0.25 V
    pid.observe(0.1, 0.5)
    assert pid.voltage_at(0.15) == pytest.approx(-0.25)
    # e = -0.2: integral 0.1 - 0.02 = 0.08; v = -0.4 + 0.8 - 0.5*(1.2 - 0.5)/0.1 = -3.1 -> -2.85, limited to -1
    pid.observe(0.2, 1.2)
    assert pid.voltage_at(0.25) == -1.0
    assert pid.samples == 3 and pid.limited_samples == 2


def test_sample_time_below_the_solver_step_warns():
    """T_s = 1e-4 s with a 2e-4 s solver step: samples come every step, 2 T_s apart, while the
    integral and derivative use T_s: their effective gains are off by 2 (warned, counted)."""
    pid = PIDController(2e4, 2e6, sample_time=1e-4, setpoint=1e-3, output_limits=(-500.0, 1500.0))
    act = actuator(PiezoDrive(pid, hysteresis=paper_strain_preisach()))
    with pytest.warns(RuntimeWarning, match=r"PID sample_time = 0.0001 s, but consecutive samples came 0.0002 s apart"):
        result = simulate(act, 0.01, step=2e-4)
    info = result.info["controller"]
    assert info["late_samples"] == info["samples"] - 1  # every interval after the first sample
    assert info["largest_sample_interval [s]"] == pytest.approx(2e-4, rel=1e-9)


def test_samples_on_time_are_quiet():
    import warnings

    pid = PIDController(2.0, sample_time=0.1, setpoint=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        for k in range(5):
            pid.observe(0.1 * k, 0.0)
    assert pid.late_samples == 0 and pid.largest_interval == pytest.approx(0.1)
    with pytest.warns(RuntimeWarning, match="came 0.3 s apart"):
        pid.observe(0.7, 0.0)  # a missed sample (0.5 and 0.6 never observed)


def test_a_loop_of_the_wrong_sign_is_named_as_such():
    """Gains of the wrong sign for the drive (here: negative where a positive voltage raises the tip) push the
    output away from the setpoint into a voltage limit; the warning said only "partly out of reach".  The
    setpoint, 6 mm, is reachable (the test above reaches it with the right sign)."""
    pid = PIDController(-2e4, -2e6, sample_time=1e-3, setpoint=6e-3, output_limits=(-500.0, 1500.0))
    act = actuator(PiezoDrive(pid, hysteresis=paper_strain_preisach()))
    with pytest.warns(RuntimeWarning, match=r"the output moved away from the setpoint \(\|error\| [\d.e-]+ -> [\d.e-]+ m\)"
                                            r", which a loop of the wrong sign does"):
        result = simulate(act, 0.3, step=2e-4)
    info = result.info["controller"]
    assert info["first_error [m]"] > 0.0 and info["last_output [m]"] < info["first_output [m]"]  # pushed down


def test_a_setpoint_out_of_reach_is_not_called_a_wrong_sign():
    pid = PIDController(2e4, 2e6, sample_time=1e-3, setpoint=30e-3, output_limits=(-500.0, 1500.0))
    act = actuator(PiezoDrive(pid, hysteresis=paper_strain_preisach()))
    with pytest.warns(RuntimeWarning, match=r"partly out of reach$"):
        simulate(act, 0.3, step=2e-4)
