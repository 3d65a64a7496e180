"""Rate-independent hysteresis operators with one interface.

Every operator has ``evaluate(u)`` (trial output from the committed memory, no side
effect), ``commit(u)`` (accept ``u``), ``reset()``, ``apply(u_series)`` and
``checkpoint()``/``restore(snapshot)``.

* :class:`ContinuousPreisach`: the paper's power-law loop (Eqs. 8-10), a true Preisach operator
  for every input history;
* :class:`DiscretePreisach`: non-ideal relays with gains (Eq. 12), ``O(log n)`` per step;
* :class:`EverettPreisach`: a relay grid with each weight spread over its cell (continuous
  output), e.g. from :meth:`EverettPreisach.fit`;
* :class:`PrandtlIshlinskii`: play operators with the analytic inverse.

Identification from records: :mod:`exudyn_atcm.hysteresis.identification` (fit reports:
:func:`make_report`); inverses: :func:`inverse_operator` (:mod:`exudyn_atcm.hysteresis.inverse`);
feed-forward voltage programs: :func:`feedforward_program`, :func:`linear_program`; the synthetic
reference record: :func:`reference_preisach`, :func:`write_reference_record`.
"""

from .base import HysteresisOperator
from .continuous import ContinuousPreisach
from .discrete import DiscretePreisach
from .everett import EverettPreisach
from .prandtl_ishlinskii import PrandtlIshlinskii
from .staircase import StaircasePreisach

# the operators above are bound first: feedforward and reference_record build voltage programs of
# exudyn_atcm.model.signals (model's face imports hysteresis.continuous, never this face)
from .feedforward import feedforward_program, linear_program
from .fit_report import FitReport, error_measures, make_report
from .inverse import inverse_operator
from .reference_record import (
    REFERENCE,
    reference_preisach,
    reference_program,
    reference_samples,
    write_reference_record,
)

__all__ = [
    "HysteresisOperator",
    "StaircasePreisach",
    "ContinuousPreisach",
    "DiscretePreisach",
    "EverettPreisach",
    "PrandtlIshlinskii",
    "inverse_operator",
    "feedforward_program",
    "linear_program",
    "FitReport",
    "error_measures",
    "make_report",
    "REFERENCE",
    "reference_preisach",
    "reference_program",
    "reference_samples",
    "write_reference_record",
]
