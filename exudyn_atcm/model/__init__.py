"""The physical description below any mechanism: layer materials, the laminate, the drive, voltage
programs, controllers, strain sources, recording schedules and literature parameter sets.

May import: numpy, scipy, :mod:`exudyn_atcm.hysteresis`, :mod:`exudyn_atcm.theory`,
:mod:`exudyn_atcm.io` and the package's argument checks; never Exudyn, solving or plotting.

The face (``from exudyn_atcm.model import Triangle, PAPER_LOOP``) exports all of these; the top level
re-exports the most used (``Layer``, ``PiezoDrive``, ``PIDController``, ``signals``).
"""

from .control import Controller, PIDController
from .damping import DEFAULT_DAMPING_RATIO, RayleighDamping, damping_ratio_from_log_decrement, log_decrement_from_damping_ratio
from .feedforward import feedforward_program, linear_program
from .drive import KV_SUSPECT_FRACTION, MFC_P1_RATED_RANGE, PLAUSIBLE_STRAIN, PiezoDrive
from .laminate import STIFFNESS_MODELS, Laminate
from .materials import PLAUSIBLE_RANGES, Layer
from .parameter_sets import (
    PAPER_CITATION,
    PAPER_D33,
    PAPER_ELECTRODE_SPACING,
    PAPER_LOOP,
    paper_strain_preisach,
    paper_stroke_preisach,
)
from .recording import RecordingSchedule, recording_schedule
from .reference_record import (
    REFERENCE,
    reference_preisach,
    reference_program,
    reference_samples,
    write_reference_record,
)
from .signals import Constant, CsvSignal, ForcProgram, PiecewiseLinear, Signal, Sine, Steps, Triangle
from .sampled_program import SampledProgram
from .strain_sources import InStepStrain, TableStrain
from .strain_conversion import model_to_strain, record_to_strain, strain_from_displacement, strain_from_tip_deflection

__all__ = [
    "Layer", "PLAUSIBLE_RANGES", "Laminate", "STIFFNESS_MODELS",
    "PiezoDrive", "MFC_P1_RATED_RANGE", "PLAUSIBLE_STRAIN", "KV_SUSPECT_FRACTION",
    "Signal", "Constant", "Triangle", "Sine", "Steps", "PiecewiseLinear", "CsvSignal", "ForcProgram",
    "SampledProgram",
    "Controller", "PIDController",
    "InStepStrain", "TableStrain",
    "strain_from_displacement", "strain_from_tip_deflection", "record_to_strain", "model_to_strain",
    "RecordingSchedule", "recording_schedule",
    "paper_stroke_preisach", "paper_strain_preisach", "PAPER_CITATION", "PAPER_LOOP", "PAPER_D33",
    "PAPER_ELECTRODE_SPACING",
    "RayleighDamping", "DEFAULT_DAMPING_RATIO", "damping_ratio_from_log_decrement", "log_decrement_from_damping_ratio",
    "feedforward_program", "linear_program",
    "REFERENCE", "reference_preisach", "reference_program", "reference_samples", "write_reference_record",
]
