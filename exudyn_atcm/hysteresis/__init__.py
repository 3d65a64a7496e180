"""Rate-independent hysteresis operators with one interface.

Every operator has ``evaluate(u)`` (trial output from the committed memory, no side
effect), ``commit(u)`` (accept ``u``), ``reset()``, ``apply(u_series)`` and
``checkpoint()``/``restore(snapshot)``.

* :class:`ContinuousPreisach`: the paper's power-law loop (Eqs. 8-10), a true Preisach operator
  for every input history;
* :class:`DiscretePreisach`: non-ideal relays with gains (Eq. 12), ``O(log n)`` per step;
* :class:`PrandtlIshlinskii`: play operators with the analytic inverse.
"""

from .base import HysteresisOperator
from .continuous import ContinuousPreisach
from .discrete import DiscretePreisach
from .prandtl_ishlinskii import PrandtlIshlinskii
from .staircase import StaircasePreisach

__all__ = [
    "HysteresisOperator",
    "StaircasePreisach",
    "ContinuousPreisach",
    "DiscretePreisach",
    "PrandtlIshlinskii",
]
