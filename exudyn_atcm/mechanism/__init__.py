"""Planar mechanisms of benders, links and flexures: the description (no Exudyn here).

Build one with :class:`Mechanism`; solve it with :func:`exudyn_atcm.simulate`,
:func:`exudyn_atcm.solve_static` or :func:`exudyn_atcm.static_sweep`, or add it to your own
Exudyn system with :func:`exudyn_atcm.add_to`.
"""

from .assembly import Mechanism
from .bender import Bender, Segment
from .connection import Connection, ConnectionBase, Readout
from .connections import Force, Pin, Slider, Spring, Stop, Torque, Weld
from .flexure import Flexure
from .link import Link
from .points import GROUND, MechanismError, PointRef

__all__ = ["Mechanism", "MechanismError", "Bender", "Segment", "Link", "Flexure", "PointRef", "GROUND",
           "Weld", "Pin", "Slider", "Force", "Torque", "Spring", "Stop", "Connection", "ConnectionBase", "Readout"]
