"""A known rate-dependent actuator with asymmetric loops and the records of it at several rates.

No measured rate family ships with the package, so the rate fits
(:func:`~exudyn_atcm.hysteresis.rate_preisach.fit_rate_preisach`,
:func:`~exudyn_atcm.hysteresis.dynamics_fit.fit_rate_lag`) are tested and benchmarked on records
whose truth is known: :func:`rate_family_truth` (a Preisach density that depends on ``α + β`` as
well as on ``α − β``, so its loops are not point-symmetric and no Prandtl-Ishlinskii operator
follows them; then a creep law and a first-order lag) driven by :func:`growing_cycles` (cycles
from the lowest voltage whose peaks grow, the usual identification excitation) at a few
frequencies, sampled at 10 kHz, plus Gaussian noise (:func:`rate_family_records`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._checks import finite_array, positive_float
from ..hysteresis.creep import Creep
from ..hysteresis.dynamics import RateLag, WithDynamics
from ..hysteresis.everett import EverettPreisach
from ..hysteresis.relay_gram import relay_grid

__all__ = ["RATE_FAMILY", "rate_family_truth", "growing_cycles", "rate_family_records"]

#: Settings of the known family (SI units: volts in, strain out).
RATE_FAMILY = {
    "u_min [V]": -500.0,
    "u_max [V]": 1500.0,
    "grid_levels": 40,
    "strain_range [-]": 1.2e-3,
    "strain_min [-]": -1.5e-4,
    "lag T [s]": 1.5e-3,
    "creep tau [s]": (0.02, 0.2),
    "creep c [-]": (0.03, 0.04),
    "peaks [-]": (0.3, 0.5, 0.7, 0.85, 1.0, 1.0),
    "sample_rate [Hz]": 10e3,
    "rates [Hz]": (20.0, 40.0, 100.0),
    "noise [share of range]": 1e-3,
    "seed": 20280605,
}


def rate_family_truth(lag: bool = True, creep: bool = True) -> WithDynamics | EverettPreisach:
    """The known model: an asymmetric Everett operator, then the creep law, then the lag.

    Density over the Preisach triangle (``α >= β``, volts), on a 40-level grid over
    -500 ... 1500 V, each cell's weight spread over the cell::

        μ(α, β) = exp(−((α − β) − 300)² / (2·350²)) · (1 + 0.7 (α + β − 1000)/2000)
                  + on the diagonal: 0.6 (1 + 0.7 (α + β − 1000)/2000) per cell,

    scaled so that the major loop spans ``RATE_FAMILY["strain_range [-]"]`` from
    ``RATE_FAMILY["strain_min [-]"]``.  The factor in ``α + β`` makes the density grow towards
    high voltages: the ascending and descending branches are not point-symmetric.  Creep
    ``Creep((0.02, 0.2) s, (0.03, 0.04))``, lag ``T = 1.5 ms``.

    Parameters
    ----------
    lag, creep : bool, optional
        Include the lag / the creep law (without both, the Everett operator itself is returned).
    """
    lo, hi, n = RATE_FAMILY["u_min [V]"], RATE_FAMILY["u_max [V]"], RATE_FAMILY["grid_levels"]
    alpha, beta, index = relay_grid(lo, hi, n)
    tilt = 1.0 + 0.7 * (alpha + beta - (lo + hi)) / (2.0 * (hi - lo))
    weights = np.exp(-((alpha - beta) - 300.0) ** 2 / (2.0 * 350.0**2)) * tilt
    diagonal = index[:, 0] == index[:, 1]
    weights[diagonal] = 0.6 * tilt[diagonal]
    edges = np.linspace(lo, hi, n + 1)
    unit = EverettPreisach(edges, alpha, beta, weights)
    span = float(unit.apply([lo, hi])[-1])
    operator = EverettPreisach(edges, alpha, beta, weights * RATE_FAMILY["strain_range [-]"] / span,
                               offset=RATE_FAMILY["strain_min [-]"]).with_output_quantity("strain")
    creep_law = Creep(RATE_FAMILY["creep tau [s]"], RATE_FAMILY["creep c [-]"]) if creep else None
    rate_lag = RateLag(RATE_FAMILY["lag T [s]"]) if lag else None
    if creep_law is None and rate_lag is None:
        return operator
    return WithDynamics(operator, creep_law, rate_lag)


def growing_cycles(frequency: float, peaks: Any = None,
                   sample_rate: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Raised-cosine cycles from the lowest voltage, one per peak, at ``frequency`` [Hz].

    Cycle ``i`` runs ``u = u_min + p_i (u_max − u_min)(1 − cos 2π f t)/2`` over one period, so the
    input starts at rest at ``u_min`` (every relay off) and returns there after each cycle.

    Parameters
    ----------
    frequency : float
        Cycles per second [Hz].
    peaks : array_like, optional
        Peak of each cycle as a share of the range, in ``(0, 1]``; default ``RATE_FAMILY["peaks [-]"]``.
    sample_rate : float, optional
        [Hz]; default ``RATE_FAMILY["sample_rate [Hz]"]``.

    Returns
    -------
    (t, u)
        Times [s] and voltages [V].
    """
    f = positive_float("frequency", frequency)
    rate = positive_float("sample_rate", RATE_FAMILY["sample_rate [Hz]"] if sample_rate is None else sample_rate)
    p = finite_array("peaks", RATE_FAMILY["peaks [-]"] if peaks is None else peaks)
    if (p <= 0.0).any() or (p > 1.0).any():
        raise ValueError(f"peaks must lie in (0, 1], got {p.tolist()!r}")
    n = int(round(p.size * rate / f))
    t = np.arange(n + 1) / rate
    cycle = np.minimum((t * f).astype(int), p.size - 1)
    lo, hi = RATE_FAMILY["u_min [V]"], RATE_FAMILY["u_max [V]"]
    return t, lo + p[cycle] * (hi - lo) * 0.5 * (1.0 - np.cos(2.0 * np.pi * f * t))


def rate_family_records(rates: Any = None, *, noise: float | None = None, seed: int | None = None,
                        truth: Any = None) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Records ``(t, u, y_noisy, y_clean)`` of the known model at each rate [Hz].

    Parameters
    ----------
    rates : array_like, optional
        Cycle frequencies [Hz]; default ``RATE_FAMILY["rates [Hz]"]`` (20, 40, 100 Hz).
    noise : float, optional
        Standard deviation of the added noise as a share of the slowest record's output range;
        default ``RATE_FAMILY["noise [share of range]"]`` (0.1 %).
    seed : int, optional
        Of the noise; default ``RATE_FAMILY["seed"]``.
    truth : WithDynamics, optional
        The model; default :func:`rate_family_truth`.
    """
    model = rate_family_truth() if truth is None else truth
    freqs = finite_array("rates", RATE_FAMILY["rates [Hz]"] if rates is None else rates)
    share = RATE_FAMILY["noise [share of range]"] if noise is None else float(noise)
    rng = np.random.default_rng(RATE_FAMILY["seed"] if seed is None else seed)
    clean = []
    for f in freqs.tolist():
        t, u = growing_cycles(f)
        clean.append((t, u, model.apply(u, t) if getattr(model, "time_dependent", False) else model.apply(u)))
    sigma = share * float(np.ptp(clean[int(np.argmin(freqs))][2]))
    return [(t, u, y + sigma * rng.standard_normal(y.size), y) for t, u, y in clean]
