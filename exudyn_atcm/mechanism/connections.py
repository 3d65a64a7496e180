"""Connections (joints) and loads of a mechanism, all of one protocol
(:mod:`exudyn_atcm.mechanism.connection`): the joints (:mod:`.joints`) and loads (:mod:`.loads`)
in one import place.
"""

from __future__ import annotations

from .connection import Connection, ConnectionBase, Readout
from .joints import Joint, JointBase, Pin, Slider, Weld, joint_label
from .loads import Force, ForceValue, Spring, Stop, Torque, TorqueValue

__all__ = ["Connection", "ConnectionBase", "Readout", "Joint", "JointBase", "Weld", "Pin", "Slider",
           "joint_label", "Force", "Torque", "Spring", "Stop", "ForceValue", "TorqueValue"]
