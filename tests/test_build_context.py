"""The one public build context: cells and connections write through the same :class:`BuildContext`.

A connection's ``realise`` and a cell's realisation are handed one object, a plain
``exudyn_atcm.mbs.BuildContext`` (not the builder, no private model state).  The old connection-facing
names keep working for one release with an ``AtcmDeprecationWarning``: ``ConnectionContext`` (the
class), ``add_hinge(point, point, stiffness, damping, label)`` (now ``add_pin``), ``body(point)``
(now ``body_at(point).item``) and ``system`` (now ``mbs``).

Mechanism of the checks: a frame link welded to the ground and an arm link pinned to it at ``O``
with a pin spring ``k_p``; a constant torque ``T`` on the arm.  Closed form: the static arm
angle is ``phi = T / k_p`` (a linear torsion spring against a pure torque, exact at any angle).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import pytest

from exudyn_atcm import AtcmDeprecationWarning, Link, Mechanism, solve_static
from exudyn_atcm.mbs import BuildContext
from exudyn_atcm.mechanism.connection import ConnectionBase
from exudyn_atcm.mechanism.connections import Pin

K_PIN = 0.01     # N m/rad
TORQUE = 2e-4    # N m: phi = 0.02 rad


def _links() -> tuple[Link, Link]:
    frame = Link("frame", {"O": (0.0, 0.0), "A": (-0.02, 0.0)}, mass=1e-3, inertia=1e-7)
    arm = Link("arm", {"O": (0.0, 0.0), "B": (0.05, 0.0)}, mass=1e-3, inertia=1e-6)
    return frame, arm


def test_connections_and_cells_are_handed_the_one_public_context():
    seen: list[Any] = []

    @dataclass(frozen=True)
    class Spy(ConnectionBase):
        name: str = "spy"
        loads_points: ClassVar[bool] = False

        def realise(self, context: Any) -> None:
            seen.append(context)

    frame, arm = _links()
    mech = Mechanism("spied").add(frame, arm).ground(frame.point("A"))
    mech.pin(frame.point("O"), arm.point("O"), stiffness=K_PIN).torque("arm", TORQUE)
    mech.add_connection(Spy())
    result = solve_static(mech)
    assert result["arm.angle"][-1] == pytest.approx(TORQUE / K_PIN, rel=1e-7)  # the spy changes nothing
    (context,) = seen
    # exactly the public class (not the builder), with the cell-facing and the connection-facing methods
    assert type(context) is BuildContext
    for method in ("add_body", "set_cells", "add_hinge", "add_strain_writer", "add_pin", "add_slider",
                   "position_marker", "rotation_marker", "add_rotational_spring", "add_readout", "output"):
        assert callable(getattr(context, method)), method
    # no private state and no builder internals reachable from it
    assert not [name for name in vars(context) if name.startswith("_")]
    assert not hasattr(context, "build") and not hasattr(context, "_model")
    # the point look-ups agree with the body look-ups: O of the welded frame is on the ground
    assert context.body_at(frame.point("O")) is context.body("ground")
    assert context.is_fixed(frame.point("O")) and not context.is_fixed(arm.point("B"))


@pytest.mark.parametrize("module", ["exudyn_atcm.mbs", "exudyn_atcm.mbs.connection_context"])
def test_connection_context_is_a_deprecated_alias(module):
    import importlib

    with pytest.warns(AtcmDeprecationWarning, match=r"ConnectionContext is deprecated.*BuildContext"):
        alias = getattr(importlib.import_module(module), "ConnectionContext")
    assert alias is BuildContext


def test_a_connection_written_against_the_old_context_names_still_works():
    found: dict[str, Any] = {}

    @dataclass(frozen=True)
    class OldPin(Pin):
        def realise(self, context: Any) -> None:
            with pytest.warns(AtcmDeprecationWarning, match=r"add_hinge\(point, point, .*use add_pin"):
                context.add_hinge(self.p, self.q, self.stiffness, self.damping, self.describe())
            with pytest.warns(AtcmDeprecationWarning, match=r"body\(point\) is deprecated"):
                found["body"] = context.body(self.p)
            with pytest.warns(AtcmDeprecationWarning, match=r"system is deprecated"):
                found["system"] = context.system
            found["ground item"] = int(context.body_at(self.p).item)
            found["mbs"] = context.mbs

    frame, arm = _links()
    mech = Mechanism("old").add(frame, arm).ground(frame.point("A")).torque("arm", TORQUE)
    mech.add_connection(OldPin(frame.point("O"), arm.point("O"), stiffness=K_PIN))
    result = solve_static(mech)
    # the old pin is the new pin: phi = T / k_p (Newton's residual tolerance leaves ~1e-10 relative)
    assert result["arm.angle"][-1] == pytest.approx(TORQUE / K_PIN, rel=1e-7)
    assert isinstance(found["body"], int) and found["body"] == found["ground item"]
    assert found["system"] is found["mbs"]
