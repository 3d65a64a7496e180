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
:func:`make_report`), and :func:`identify` (every registered family fitted and ranked on
held-out data; a new family registers itself with :func:`register_family`,
:mod:`exudyn_atcm.hysteresis.families`);
inverses: ``inverse()`` of every operator, :func:`inverse_operator` (:mod:`exudyn_atcm.hysteresis.inverse`); rate families with
asymmetric loops: :func:`fit_rate_preisach` (an Everett operator, a creep law and a rate lag).  Feed-forward
programs and the synthetic reference record build on voltage programs and live in
:mod:`exudyn_atcm.model`.

Saved models: every operator and wrapper has ``save(path)`` (JSON), :func:`load_model` reads it
back (:mod:`exudyn_atcm.hysteresis.model_files`; the format:
:mod:`exudyn_atcm.hysteresis.model_format`; how a new family registers itself:
:mod:`exudyn_atcm.hysteresis.model_registry`).
"""

from .base import HysteresisOperator
# the families register themselves for identify() in this order (equal_gain, discrete, everett,
# prandtl_ishlinskii, continuous): the order identify fits them in and lists families it could not fit
from .discrete import DiscretePreisach
from .everett import EverettPreisach
from .prandtl_ishlinskii import PrandtlIshlinskii
from .continuous import ContinuousPreisach
from .model_choice import ModelChoice, identify
from .identify_options import IdentifyOptions
from .staircase import StaircasePreisach

from .fit_report import FitReport, error_measures, make_report
from .inverse import inverse_operator
from .families import register_family, registered_families
from . import model_kinds  # noqa: F401 - registers the package's model kinds for save/load_model
from .model_files import load_model, save_model
from .model_format import ModelFileError
from .model_registry import register_model_kind
from .rate_preisach import fit_rate_preisach

__all__ = [
    "HysteresisOperator",
    "StaircasePreisach",
    "ContinuousPreisach",
    "DiscretePreisach",
    "EverettPreisach",
    "PrandtlIshlinskii",
    "ModelChoice",
    "identify",
    "IdentifyOptions",
    "inverse_operator",
    "register_family",
    "registered_families",
    "fit_rate_preisach",
    "FitReport",
    "error_measures",
    "make_report",
    "load_model",
    "save_model",
    "ModelFileError",
    "register_model_kind",
]
