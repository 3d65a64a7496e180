"""The settings of :func:`~exudyn_atcm.hysteresis.identify`'s fits and of its choice, as one object.

::

    identify(record, families=("everett", "prandtl_ishlinskii"), options=IdentifyOptions(n_levels=12))

The flat keywords of earlier releases (``identify(record, n_levels=12)``) still work for one
release, with an :class:`~exudyn_atcm.AtcmDeprecationWarning`.
"""

from __future__ import annotations

from dataclasses import dataclass

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
