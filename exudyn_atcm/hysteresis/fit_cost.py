"""What an identification will cost, said before it starts: estimates, limits, refusals.

Every fit of :mod:`exudyn_atcm.hysteresis.identification` (and
:meth:`DiscretePreisach.from_loop <exudyn_atcm.hysteresis.DiscretePreisach.from_loop>`)
estimates its working memory and run time from the record length and the model size before
doing any work, and

* refuses with a ``ValueError`` when the memory would exceed ``LIMITS["bytes"]`` (1 GiB) or
  the time ``LIMITS["refuse_seconds"]`` (10 minutes),
* warns (``RuntimeWarning``) when the time would exceed ``LIMITS["seconds"]`` (one minute),

each message giving the estimate and what to change (fewer levels or plays, a decimated
record).  The time estimates are calibrated on a 2-core machine shared with other work
(single-thread BLAS at about ``FLOP_RATE``), so they are upper figures on a quiet machine; the
memory estimates count the large arrays the fit holds at once.  Raise the limits in
``LIMITS`` for a deliberate large fit.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import RunCostWarning

__all__ = ["LIMITS", "FLOP_RATE", "CostEstimate", "check_cost", "grid_fit_cost", "play_fit_cost",
           "continuous_fit_cost", "loop_fit_cost", "finite_squares"]

#: Work a fit may start without being asked: run time [s] (``"seconds"``: a warning beyond it;
#: ``"refuse_seconds"``: a refusal beyond it) and working memory [bytes] (a refusal beyond it).
LIMITS = {"seconds": 60.0, "refuse_seconds": 600.0, "bytes": float(2**30)}

#: Dense floating-point operations per second assumed for the estimates (one BLAS thread on a
#: busy machine; a quiet modern core does two to four times more).
FLOP_RATE = 5e9

#: Largest magnitude of a record value whose square, summed over a record, stays finite in float64.
MAX_MAGNITUDE = 1e150


@dataclass(frozen=True)
class CostEstimate:
    """Estimated run time [s] and working memory [bytes] of one fit, with what they count."""

    seconds: float
    bytes: float
    detail: str

    def text(self) -> str:
        """E.g. ``"about 12 s and 0.31 GiB (detail)"``."""
        return f"about {self.seconds:.3g} s and {self.bytes / 2**30:.3g} GiB ({self.detail})"


def check_cost(method: str, estimate: CostEstimate, advice: str) -> None:
    """Refuse (``ValueError``) or warn (``RuntimeWarning``) per :data:`LIMITS` before a fit starts.

    Parameters
    ----------
    method : str
        The fit's name for the message (e.g. ``"PrandtlIshlinskii.fit"``).
    estimate : CostEstimate
        Its estimated cost.
    advice : str
        What the user can change (appended to the message).
    """
    limit_s, limit_b = LIMITS["seconds"], LIMITS["bytes"]
    if estimate.bytes > limit_b:
        raise ValueError(
            f"{method} refused before starting: it would need {estimate.text()}, more than the "
            f"{limit_b / 2**30:.3g} GiB allowed (exudyn_atcm.hysteresis.fit_cost.LIMITS); {advice}")
    if estimate.seconds > LIMITS["refuse_seconds"]:
        raise ValueError(
            f"{method} refused before starting: it would take {estimate.text()}, more than "
            f"{LIMITS['refuse_seconds']:.3g} s (exudyn_atcm.hysteresis.fit_cost.LIMITS); {advice}")
    if estimate.seconds > limit_s:
        warnings.warn(f"{method} will take {estimate.text()}, more than {limit_s:.3g} s; {advice}",
                      RunCostWarning, stacklevel=4)


def grid_fit_cost(n_levels: int, n_samples: int, basis: str = "relays",
                  distinct_rows: int | None = None, cv_folds: int = 0,
                  cv_strengths: int = 5) -> CostEstimate:
    """Cost of a relay-grid fit (:meth:`DiscretePreisach.fit`, :meth:`EverettPreisach.fit`).

    ``R = n_levels (n_levels + 1) / 2`` unknowns.  Memory: three ``R × R`` float arrays (Gram
    matrix, regularised copy, factor of the free block) plus the relay states.  Time: the state
    sweep over the samples, the Gram matrix (``2 m R²`` flops for spread cells; for relays the
    distinct states, at most ``distinct_rows``, default the samples) and about ``R³`` flops of
    Cholesky factorisations in the block-pivoting NNLS (measured: ten factorisations of
    shrinking free sets add up to 0.9 ``R³``); with ``cv_folds`` (the ``"pi"`` prior's
    cross-validation over ``cv_strengths`` candidates) a Gram matrix per block and
    ``cv_folds × cv_strengths`` warm-started fits of about half a fit's factorisations each.
    """
    relays = n_levels * (n_levels + 1) // 2
    m = max(int(n_samples), 1)
    memory = 3.0 * relays**2 * 8.0
    if basis == "relays":
        memory += m * relays / 8.0 + 2048.0 * relays * 16.0
        sweep = m * (1e-5 + 3e-9 * relays)
        rows = m if distinct_rows is None else min(m, max(int(distinct_rows), 1))
        gram_flops = 2.0 * rows * relays**2
    else:
        memory += 2048.0 * relays * 16.0
        sweep = m * (7e-5 + 5e-8 * relays)
        gram_flops = 2.0 * m * relays**2
    seconds = sweep + (gram_flops + relays**3) / FLOP_RATE
    cv_fits = cv_folds * cv_strengths
    if cv_fits:
        memory += (cv_folds + 1) * relays**2 * 8.0
        seconds += cv_folds * sweep + cv_fits * 0.5 * relays**3 / FLOP_RATE
    return CostEstimate(seconds, memory, f"{relays} relays, {m} samples"
                        + (f", {cv_fits} cross-validation fits" if cv_fits else ""))


def play_fit_cost(n_plays: int, n_samples: int) -> CostEstimate:
    """Cost of :meth:`PrandtlIshlinskii.fit`: a dense ``m × n`` play matrix (three copies) and
    SciPy's NNLS on it, about ``m (3e-5 + 5e-9 n) + 2e-10 m² n`` s (measured: 36 s for 500
    plays on 20 000 samples, 2 s for 3000 plays on 2000, 1.3 s for 20 plays on 20 000; an upper
    figure, NNLS stops early when few plays carry weight)."""
    m = max(int(n_samples), 1)
    n = max(int(n_plays), 1)
    memory = 3.0 * m * n * 8.0
    seconds = m * (3e-5 + 5e-9 * n) + 2e-10 * m * m * n
    return CostEstimate(seconds, memory, f"{n} plays, {m} samples")


def continuous_fit_cost(n_samples: int) -> CostEstimate:
    """Cost of :meth:`ContinuousPreisach.fit`: about 100 runs of the operator over the record
    (2 µs per sample), a few arrays of the record's length."""
    m = max(int(n_samples), 1)
    return CostEstimate(100 * m * 2e-6, 10.0 * m * 8.0, f"about 100 runs over {m} samples")


def loop_fit_cost(n_relays: int, n_samples: int) -> CostEstimate:
    """Cost of :meth:`DiscretePreisach.from_loop`: one search along each averaged branch per
    relay (measured: 1.1 s for 20 000 relays on 20 000 samples) and a dozen arrays of the
    relay count."""
    m = max(int(n_samples), 1)
    n = max(int(n_relays), 1)
    return CostEstimate(n * (5e-6 + 3e-9 * m) + 2e-6 * m, 12.0 * n * 8.0 + 10.0 * m * 8.0,
                        f"{n} relays, {m} samples")


def finite_squares(name: str, values: Any) -> None:
    """``ValueError`` naming ``name`` if a record value is so large that sums of squares overflow.

    The fits form squared errors and Gram matrices; a value beyond ``1e150`` in magnitude (or a
    range that overflows) makes them infinite and the result meaningless.
    """
    array = np.asarray(values, dtype=float)
    if array.size == 0:
        return
    peak = float(np.max(np.abs(array)))
    if not peak <= MAX_MAGNITUDE:
        index = int(np.argmax(np.abs(array)))
        raise ValueError(
            f"{name} holds a value too large to fit: {name}[{index}] = {float(array[index])!r}; the squared errors "
            f"overflow float64 beyond |{name}| = {MAX_MAGNITUDE:g}: rescale {name} (e.g. to SI base units)")
