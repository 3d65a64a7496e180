"""A connection written outside the package: a rotational stop with a gap, through the one protocol.

The stop lives in this file only (no package file knows it): between two parts it gives no torque
while their relative rotation ``u`` stays inside the gap ``|u| <= g`` and a stiff torsional spring
``k (|u| - g)`` beyond it.  It is added with ``Mechanism.add_connection`` and must work in the static
solve, the dynamic run (its recorded column with its unit), ``parameters()``, a drawing and the
refusal checks, as the package's own springs and stops do.

Mechanism: a frame link welded to the ground and an arm link pinned to it at ``O`` with a weak pin
spring ``k_p``; a torque ``T`` on the arm.  Closed form (statics of one rotation): inside the gap
``phi = T / k_p`` with no stop torque; beyond it ``T = k_p phi + k (phi - g)``, so
``phi = (T + k g) / (k_p + k)`` and the stop torque is ``k (phi - g)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from exudyn_atcm import Link, Mechanism, simulate, solve_static  # noqa: E402
from exudyn_atcm.mechanism import MechanismError, PointRef  # noqa: E402
from exudyn_atcm.mechanism.connection import Connection, ConnectionBase, Readout  # noqa: E402
from exudyn_atcm.plots.mechanism import draw_mechanism  # noqa: E402

GAP = 0.05          # rad
K_STOP = 1.0        # N m/rad, the stop's spring beyond the gap
K_PIN = 0.01        # N m/rad, the pin's own spring (holds the arm inside the gap)
C_PIN = 3e-3        # N m s/rad, the pin's damper (the run settles)
ARM_LENGTH = 0.05   # m


@dataclass(frozen=True)
class RotationalStop(ConnectionBase):
    """No torque inside ``|u| <= gap``, ``stiffness (|u| - gap)`` against the rotation beyond it."""

    p: PointRef
    q: PointRef
    gap: float
    stiffness: float
    name: str = "stop"
    label: ClassVar[str] = "rotational stops"

    def law(self, u: float) -> float:
        excess = abs(u) - self.gap
        return float(np.sign(u)) * self.stiffness * excess if excess > 0.0 else 0.0

    def points(self) -> tuple[PointRef, ...]:
        return (self.p, self.q)

    def parameters(self) -> dict[str, Any]:
        return {f"{self.name}.gap [rad]": self.gap, f"{self.name}.stiffness [N m/rad]": self.stiffness}

    def readouts(self) -> tuple[Readout, ...]:
        return (Readout(f"{self.name}.torque", "N m"),)

    def realise(self, context: Any) -> None:
        item = context.add_rotational_spring(self.p, self.q, lambda u, rate: self.law(u))
        context.add_readout(self.readouts()[0], context.output(item, "Force"))

    def draw(self, canvas: Any) -> None:
        # two stroke marks at +-gap around the pin, on the arm's reference direction
        centre = canvas.position(self.p)
        r = 0.15 * canvas.size
        angles = np.linspace(-self.gap, self.gap, 9)
        arc = centre + r * np.column_stack([np.cos(angles), np.sin(angles)])
        canvas.line(arc, label=self.label, color="tab:red", lw=2.0)


def _mechanism(torque: Any) -> tuple[Mechanism, RotationalStop]:
    frame = Link("frame", {"O": (0.0, 0.0), "A": (-0.02, 0.0)}, mass=1e-3, inertia=1e-7)
    arm = Link("arm", {"O": (0.0, 0.0), "B": (ARM_LENGTH, 0.0)}, mass=1e-3, inertia=1e-6)
    mech = Mechanism("stopped").add(frame, arm).ground(frame.point("A"))
    mech.pin(frame.point("O"), arm.point("O"), stiffness=K_PIN, damping=C_PIN).torque("arm", torque)
    stop = RotationalStop(frame.point("O"), arm.point("O"), GAP, K_STOP)
    mech.add_connection(stop)
    return mech, stop


def _closed_form(torque: float) -> tuple[float, float]:
    """Arm angle [rad] and stop torque [N m] at a constant torque (module text)."""
    phi = torque / K_PIN
    if abs(phi) <= GAP:
        return phi, 0.0
    sign = float(np.sign(torque))  # the stop is symmetric: beyond -gap as beyond +gap
    phi = sign * (abs(torque) + K_STOP * GAP) / (K_PIN + K_STOP)
    return phi, sign * K_STOP * (abs(phi) - GAP)


def test_the_stop_follows_the_protocol_and_is_kept_in_the_one_list():
    mech, stop = _mechanism(0.0)
    assert isinstance(stop, Connection)
    assert mech.connections[-1] is stop
    # it is no joint and no spring of the package: the typed views leave it out
    assert stop not in mech.joints and stop not in mech.springs and stop not in mech.stops


@pytest.mark.parametrize("torque", [2e-4, 1e-2, -2e-2])
def test_static_solve_against_the_closed_form(torque):
    mech, _ = _mechanism(torque)
    result = solve_static(mech)
    phi, stop_torque = _closed_form(torque)
    assert result.unit("stop.torque") == "N m"
    # Newton's residual tolerance leaves about 1e-10 relative; 1e-7 is the margin
    assert result["arm.angle"][-1] == pytest.approx(phi, rel=1e-7, abs=1e-12)
    assert result["stop.torque"][-1] == pytest.approx(stop_torque, rel=1e-7, abs=1e-12)
    if torque == 2e-4:  # inside the gap: no contact (phi = 0.02 rad < 0.05 rad)
        assert abs(result["arm.angle"][-1]) < GAP and result["stop.torque"][-1] == 0.0
    else:  # beyond the gap: contact angle past the gap, torque of the spring beyond it
        assert abs(result["arm.angle"][-1]) > GAP


def test_simulate_records_the_stop_torque_with_its_unit():
    t_ramp, torque = 0.05, 1e-2

    def ramp(t: float) -> float:
        return torque * min(t / t_ramp, 1.0)

    mech, stop = _mechanism(ramp)
    result = simulate(mech, 0.2, step=2e-4)
    assert result.unit("stop.torque") == "N m"
    angle, recorded = result["arm.angle"], result["stop.torque"]
    # the recorded column is the stop's law at the recorded angle, every row (same state)
    expected = np.array([stop.law(u) for u in angle])
    assert np.max(np.abs(recorded - expected)) <= 1e-9 * K_STOP
    assert recorded[0] == 0.0 and np.any(recorded > 0.0)  # starts in the gap, then closes it
    # settled: damping ratio beyond the gap C_PIN / (2 sqrt(K I)) = 1.2 with I = 1.625e-6 kg m^2;
    # 0.15 s after the ramp the transient is below 1e-6 of the torque
    phi, stop_torque = _closed_form(torque)
    assert angle[-1] == pytest.approx(phi, rel=1e-5)
    assert recorded[-1] == pytest.approx(stop_torque, rel=1e-4)


def test_parameters_carry_the_stop():
    mech, _ = _mechanism(1e-3)
    params = mech.parameters()
    assert params["stop.gap [rad]"] == GAP and params["stop.stiffness [N m/rad]"] == K_STOP
    assert solve_static(mech).parameters["stop.gap [rad]"] == GAP


def test_a_drawing_plots_the_stop():
    mech, _ = _mechanism(1e-2)
    result = solve_static(mech)
    fig, ax = plt.subplots()
    try:
        draw_mechanism(ax, mech, result, -1)
        lines = [line for line in ax.get_lines() if line.get_label() == RotationalStop.label]
        assert len(lines) == 1
        xy = np.column_stack(lines[0].get_data()) / 1e3  # drawn in mm
        # the arc of radius 0.15 size around the pin O (at the origin, on the welded frame), +-gap wide
        radius = 0.15 * mech.size
        assert np.allclose(np.hypot(xy[:, 0], xy[:, 1]), radius, rtol=1e-12)
        assert np.arctan2(xy[[0, -1], 1], xy[[0, -1], 0]) == pytest.approx([-GAP, GAP], rel=1e-12)
        assert RotationalStop.label in [t.get_text() for t in ax.get_legend().get_texts()]
    finally:
        plt.close(fig)


def test_a_stop_naming_a_missing_part_is_refused():
    mech, _ = _mechanism(0.0)
    with pytest.raises(MechanismError, match=r"RotationalStop 'stop2'.*unknown component 'nowhere'"):
        mech.add_connection(RotationalStop(PointRef("frame", "O"), PointRef("nowhere", "O"), GAP, K_STOP, "stop2"))
    with pytest.raises(MechanismError, match=r"duplicate name 'stop'"):
        mech.add_connection(RotationalStop(PointRef("frame", "O"), PointRef("arm", "O"), GAP, K_STOP))
    with pytest.raises(MechanismError, match=r"does not implement the connection protocol \(missing: .*realise"):
        mech.add_connection(object())
    assert len([c for c in mech.connections if isinstance(c, RotationalStop)]) == 1


def test_a_connection_recording_other_columns_than_it_declares_is_refused():
    @dataclass(frozen=True)
    class Undeclared(RotationalStop):
        def readouts(self) -> tuple[Readout, ...]:
            return ()  # but realise records a column

        def realise(self, context: Any) -> None:
            item = context.add_rotational_spring(self.p, self.q, lambda u, rate: self.law(u))
            context.add_readout(Readout("stop.torque", "N m"), context.output(item, "Force"))

    frame = Link("frame", {"O": (0.0, 0.0), "A": (-0.02, 0.0)}, mass=1e-3, inertia=1e-7)
    arm = Link("arm", {"O": (0.0, 0.0), "B": (ARM_LENGTH, 0.0)}, mass=1e-3, inertia=1e-6)
    mech = Mechanism().add(frame, arm).ground(frame.point("A")).pin(frame.point("O"), arm.point("O"), stiffness=K_PIN)
    stop = Undeclared(frame.point("O"), arm.point("O"), GAP, K_STOP)
    mech.add_connection(stop)
    with pytest.raises(MechanismError, match=r"recorded the columns \[Readout\(column='stop.torque'.*declares \[\]"):
        solve_static(mech)


def test_add_to_records_the_stop_as_simulate_does():
    import exudyn as exu

    import exudyn_atcm as atcm
    from exudyn_atcm.mbs import solver_settings

    def ramp(t: float) -> float:  # the arm reaches the gap after about 0.02 s
        return 1e-2 * min(t / 0.005, 1.0)

    reference = simulate(_mechanism(ramp)[0], 0.05, step=1e-3)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    handle = atcm.add_to(mbs, _mechanism(ramp)[0])
    mbs.Assemble()
    mbs.SolveDynamic(solver_settings.dynamic_settings(0.05, 1e-3))
    result = handle.result()
    assert result.unit("stop.torque") == "N m"
    # the same system and solver settings: the same values to round-off
    np.testing.assert_allclose(result["stop.torque"], reference["stop.torque"], rtol=0, atol=1e-12)
    assert np.any(result["stop.torque"] > 0.0)


def test_joints_added_through_the_protocol_get_the_joint_checks():
    from exudyn_atcm.mechanism import Pin

    mech, stop = _mechanism(0.0)
    with pytest.raises(MechanismError, match=r"already joined by pin\(frame.O, arm.O\)"):
        mech.add_connection(Pin(PointRef("frame", "O"), PointRef("arm", "O")))
    with pytest.raises(MechanismError, match="holds=True, which is for joints"):
        mech.add_connection(type("Holding", (RotationalStop,), {"holds": True})(stop.p, stop.q, GAP, K_STOP, "h"))
