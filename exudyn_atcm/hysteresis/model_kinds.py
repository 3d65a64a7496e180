"""The model kinds the package saves and loads (:mod:`.model_format`), one registration per class.

============================  =================================================================  ==========================================================
kind                          class                                                              parameters
============================  =================================================================  ==========================================================
``continuous_preisach``       :class:`~exudyn_atcm.hysteresis.ContinuousPreisach`                u_min, u_max, y_min, y_max, r1, r2
``discrete_preisach``         :class:`~exudyn_atcm.hysteresis.DiscretePreisach`                  alpha, beta, weights, offset, max_table_entries
``everett_preisach``          :class:`~exudyn_atcm.hysteresis.EverettPreisach`                   edges, alpha, beta, weights, offset
``prandtl_ishlinskii``        :class:`~exudyn_atcm.hysteresis.PrandtlIshlinskii`                 radii, weights, p0, offset, input_offset
``creep``                     :class:`~exudyn_atcm.hysteresis.creep.Creep`                       tau, c
``rate_lag``                  :class:`~exudyn_atcm.hysteresis.dynamics.RateLag`                  T
``lag_sum``                   :class:`~exudyn_atcm.hysteresis.dynamics.LagSum`                   d, tau, g
``with_dynamics``             :class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`             operator (a model), creep, lag (or null)
``creep_hysteresis``          :class:`~exudyn_atcm.hysteresis.creep.CreepHysteresis`             hysteresis (a model), creep
``bisection_inverse``         :class:`~exudyn_atcm.hysteresis.bisection.BisectionInverse`        model (the forward model), input_range, tolerance
``shifted_pi_inverse``        :class:`~exudyn_atcm.hysteresis.inverse.ShiftedPIInverse`          model (the forward Prandtl-Ishlinskii model)
``dynamics_inverse``          :class:`~exudyn_atcm.hysteresis.dynamics_inverse.DynamicsInverse`  model (the forward WithDynamics), input_range (or null)
``creep_hysteresis_inverse``  :class:`~exudyn_atcm.hysteresis.creep.CreepHysteresisInverse`      model (the forward CreepHysteresis), input_range (or null)
============================  =================================================================  ==========================================================

The inverses are saved as the forward model they invert plus their own settings; loading
builds the inverse again from the forward model (bit for bit the same operator).
:class:`~exudyn_atcm.hysteresis.StaircasePreisach` is abstract and has no kind.
"""

from __future__ import annotations

from .bisection import BisectionInverse
from .continuous import ContinuousPreisach
from .creep import Creep, CreepHysteresis, CreepHysteresisInverse
from .discrete import DiscretePreisach
from .dynamics import LagSum, RateLag, WithDynamics
from .dynamics_inverse import DynamicsInverse
from .everett import EverettPreisach
from .inverse import ShiftedPIInverse
from .model_registry import FLOAT, FLOATS, INT, RANGE, ParameterType, nested, register_model_kind
from .prandtl_ishlinskii import PrandtlIshlinskii

__all__: list[str] = []

register_model_kind("continuous_preisach", ContinuousPreisach,
                    {"u_min": FLOAT, "u_max": FLOAT, "y_min": FLOAT, "y_max": FLOAT, "r1": FLOAT, "r2": FLOAT})
register_model_kind("discrete_preisach", DiscretePreisach,
                    {"alpha": FLOATS, "beta": FLOATS, "weights": FLOATS, "offset": FLOAT, "max_table_entries": INT})
register_model_kind("everett_preisach", EverettPreisach,
                    {"edges": FLOATS, "alpha": FLOATS, "beta": FLOATS, "weights": FLOATS, "offset": FLOAT})
register_model_kind("prandtl_ishlinskii", PrandtlIshlinskii,
                    {"radii": FLOATS, "weights": FLOATS, "p0": FLOAT, "offset": FLOAT, "input_offset": FLOAT})
register_model_kind("creep", Creep, {"tau": FLOATS, "c": FLOATS})
register_model_kind("rate_lag", RateLag, {"T": FLOAT})
register_model_kind("lag_sum", LagSum, {"d": FLOAT, "tau": FLOATS, "g": FLOATS})
register_model_kind("with_dynamics", WithDynamics,
                    {"operator": nested(), "creep": nested("creep", optional=True),
                     "lag": nested("rate_lag", optional=True)})
register_model_kind("creep_hysteresis", CreepHysteresis, {"hysteresis": nested(), "creep": nested("creep")})
register_model_kind("bisection_inverse", BisectionInverse,
                    {"model": nested(), "input_range": RANGE, "tolerance": FLOAT},
                    to_params=lambda inverse: {"model": inverse.model, "input_range": (inverse.u_lo, inverse.u_hi),
                                               "tolerance": inverse.tolerance})
register_model_kind("shifted_pi_inverse", ShiftedPIInverse, {"model": nested("prandtl_ishlinskii")})
register_model_kind("dynamics_inverse", DynamicsInverse,
                    {"model": nested("with_dynamics"), "input_range": ParameterType("range", optional=True)},
                    to_params=lambda inverse: {"model": inverse.model, "input_range": inverse.requested_range})
register_model_kind("creep_hysteresis_inverse", CreepHysteresisInverse,
                    {"model": nested("creep_hysteresis"), "input_range": ParameterType("range", optional=True)},
                    to_params=lambda inverse: {"model": inverse.model, "input_range": inverse.requested_range})
