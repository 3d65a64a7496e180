"""Connections (joints) and loads of a mechanism, all of one protocol
(:mod:`exudyn_atcm.mechanism.connection`): the joints (:mod:`.joints`) and loads (:mod:`.loads`)
in one import place.
"""

from __future__ import annotations

from .connection import Connection, ConnectionBase, Readout
from .joints import Joint, JointBase, Pin, Slider, Weld, joint_label
from .loads import Force, ForceValue, Spring, Stop, Torque, TorqueValue

# the documented names; Joint, JointBase, joint_label, ForceValue and TorqueValue import from here too
__all__ = ["Connection", "ConnectionBase", "Readout", "Weld", "Pin", "Slider", "Force", "Torque", "Spring", "Stop"]
