"""The settings of :func:`~exudyn_atcm.hysteresis.identify`'s fits and of its choice, as one object.

::

    identify(record, families=("everett", "prandtl_ishlinskii"), options=IdentifyOptions(n_levels=12))

The flat keywords of earlier releases (``identify(record, n_levels=12)``) still work for one
release, with an :class:`~exudyn_atcm.AtcmDeprecationWarning`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import shown
from ..physical_bounds import MAX_OPERATOR_ELEMENTS
from .identification import MAX_FIT_LEVELS
from .loop_identification import LEVEL_RULES
from .priors import PRIORS

__all__ = ["IdentifyOptions"]


@dataclass(frozen=True)
class IdentifyOptions:
    """How :func:`~exudyn_atcm.hysteresis.identify` fits each family and chooses among them.

    Parameters
    ----------
    n_levels : int
        Grid levels of the ``discrete`` and ``everett`` fits (default 30).
    n_plays : int
        Plays of the ``prandtl_ishlinskii`` fit (default 20).
    n_relays : int
        Relays of the ``equal_gain`` model (default 20).
    smoothing : float
        Regularisation of the grid fits (default 1e-3).
    prior : {"pi", "smooth"}
        Prior of the grid fits where the record says nothing (default ``"pi"``, its strength
        cross-validated on the fitted part: see :mod:`exudyn_atcm.hysteresis.priors`).
    reversal_tolerance : float
        Of the ``equal_gain`` construction (fraction of the input range; see ``from_loop``).
    levels : {"paper", "centred"}
        Level rule of the ``equal_gain`` construction.
    relays_per_cell : int
        Of the ``discrete`` fit: ``k > 1`` fits the weights as spread cells and realises each
        cell as ``k × k`` relays (the parameter count is the fitted weights'; default 1).
    simpler_margin : float
        A model with more parameters is chosen only if its held-out RMS error is below
        ``1 + simpler_margin`` times that of every simpler one within reach (default 0.1).
    linear_margin : float
        Warn unless the best linear model's held-out RMS error is at least ``1 + linear_margin``
        times the chosen model's (default 1: twice).
    """

    n_levels: int = 30
    n_plays: int = 20
    n_relays: int = 20
    smoothing: float = 1e-3
    prior: str = "pi"
    reversal_tolerance: float = 0.02
    levels: str = "paper"
    relays_per_cell: int = 1
    simpler_margin: float = 0.1
    linear_margin: float = 1.0


    def check(self) -> "IdentifyOptions":
        """Refuse options no family could be fitted with (``ValueError`` naming the option, the value
        and what is allowed: the limits the fits enforce), so that :func:`identify` does not turn a
        typo into "not fitted" notes; returns the options."""
        def integer(name: str, low: int, high: int) -> int:
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= value <= high:
                bound = f"<= {high}" if isinstance(value, (int, np.integer)) and value > high else f">= {low}"
                raise ValueError(f"IdentifyOptions.{name} must be an integer {bound}, got {shown(value)} (allowed: "
                                 f"{low} ... {high})")
            return int(value)

        def number(name: str, high: float = math.inf) -> None:
            value = getattr(self, name)
            ok = isinstance(value, (int, float, np.floating)) and not isinstance(value, bool)
            if not (ok and math.isfinite(value) and 0.0 <= value < high):
                allowed = "a finite number >= 0" if high == math.inf else f"a number in [0, {high:g})"
                raise ValueError(f"IdentifyOptions.{name} must be {allowed}, got {shown(value)}")

        def choice(name: str, allowed: Any) -> None:
            if getattr(self, name) not in allowed:
                raise ValueError(f"IdentifyOptions.{name} must be one of {', '.join(repr(a) for a in allowed)}, "
                                 f"got {getattr(self, name)!r}")

        n_levels = integer("n_levels", 2, MAX_FIT_LEVELS)
        integer("n_plays", 2, MAX_OPERATOR_ELEMENTS)
        integer("n_relays", 1, MAX_OPERATOR_ELEMENTS)
        per_cell = integer("relays_per_cell", 1, MAX_OPERATOR_ELEMENTS)
        relays = n_levels * per_cell * (n_levels * per_cell + 1) // 2
        if relays > MAX_OPERATOR_ELEMENTS:
            raise ValueError(f"IdentifyOptions.relays_per_cell = {per_cell} with n_levels = {n_levels} gives {relays} "
                             f"relays; at most {MAX_OPERATOR_ELEMENTS} are allowed (use fewer relays per cell)")
        number("smoothing")
        number("reversal_tolerance")
        number("simpler_margin", 10.0)
        number("linear_margin", 100.0)
        choice("prior", PRIORS)
        choice("levels", tuple(LEVEL_RULES))
        return self
