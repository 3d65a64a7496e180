"""Which samples of a record :func:`~exudyn_atcm.hysteresis.identify` fits and which it holds out.

A hysteresis model predicts the held-out part of a record only where the fitted part showed
it the input: beyond the fitted input range a Preisach grid saturates and a play operator
extrapolates.  A record whose amplitude grows cycle by cycle (the usual identification
excitation: triangles from the lowest voltage with rising peaks) has its largest inputs at
its end, so the classic split (fit the first 60 %, hold out the rest) asks the model to
predict inputs it has never seen.  The rules here:

``split="auto"`` (the default)
    The time split at 60 % of the record if its held-out input lies inside the fitted input
    range (within 1 % of that range); otherwise interleaved cycles (below); otherwise the time
    split, with an :class:`~exudyn_atcm.errors.AccuracyWarning` naming the uncovered range.
``split="cycles"``
    Interleaved cycles.  The record is cut into cycles at the input's reversal minima (a
    reversal counts once the input has moved back by more than 2 % of its range); about 40 %
    of the samples, in whole cycles spread evenly over the record, are held out, never the
    first cycle, and every held-out cycle whose input leaves the range of the fitted cycles is
    fitted instead.  The model still runs over the whole record (each held-out cycle is
    predicted with the memory the cycles before it left); only the least-squares rows are the
    fitted cycles' (the fits' ``fit_mask``).  ``ValueError`` if the record has fewer than three
    cycles or no cycle can be held out inside the fitted range.
``split=<fraction>``, ``n_fit=<sample>``, ``fit_mask=<booleans>``
    As given (the first ``fraction`` of the duration, the first ``n_fit`` samples, the masked
    samples); an :class:`~exudyn_atcm.errors.AccuracyWarning` names the held-out inputs beyond
    the fitted range, if any.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from .._checks import shown
from ..errors import AccuracyWarning
from .identification import MIN_SAMPLES
from .loop_identification import monotone_segments

__all__ = ["AUTO_FRACTION", "COVER_TOLERANCE", "SPLITS", "cycle_bounds", "interleaved_cycles", "uncovered",
           "choose_split"]

#: Fraction of the record the ``"auto"`` split fits first (the rest is held out).
AUTO_FRACTION = 0.6
#: Held-out inputs within this fraction of the fitted input range beyond it count as inside.
COVER_TOLERANCE = 0.01
#: Named splits of :func:`choose_split`.
SPLITS = ("auto", "cycles")
#: A reversal of the input, for cutting cycles: a move back by more than this fraction of its range.
CYCLE_REVERSAL = 0.02


def cycle_bounds(u: np.ndarray) -> list[tuple[int, int]]:
    """``(first, stop)`` sample ranges of the cycles of ``u``: cut where each rising segment starts."""
    u = np.asarray(u, dtype=float)
    starts = [first for first, _, rising in monotone_segments(u, CYCLE_REVERSAL * float(np.ptp(u))) if rising]
    starts = sorted(set(s for s in starts if s > 0))
    edges = [0, *starts, u.size]
    return [(a, b) for a, b in zip(edges[:-1], edges[1:]) if b > a]


def uncovered(u: np.ndarray, fit_rows: np.ndarray, held_rows: np.ndarray) -> list[tuple[float, float]]:
    """Input intervals of the held-out samples beyond the fitted samples' range (more than
    :data:`COVER_TOLERANCE` of it): ``[(low, high), ...]``, empty when covered."""
    if not held_rows.any() or not fit_rows.any():
        return []
    lo, hi = float(u[fit_rows].min()), float(u[fit_rows].max())
    slack = COVER_TOLERANCE * (hi - lo)
    h_lo, h_hi = float(u[held_rows].min()), float(u[held_rows].max())
    out = []
    if h_lo < lo - slack:
        out.append((h_lo, lo))
    if h_hi > hi + slack:
        out.append((hi, h_hi))
    return out


def interleaved_cycles(u: np.ndarray, held_fraction: float = 1.0 - AUTO_FRACTION) -> np.ndarray | None:
    """Fit mask holding out whole cycles spread over the record inside the fitted range (see the module).

    Returns ``None`` when the record has fewer than three cycles or none can be held out.
    """
    u = np.asarray(u, dtype=float)
    bounds = cycle_bounds(u)
    if len(bounds) < 3:
        return None
    held = np.zeros(len(bounds), dtype=bool)
    total = float(u.size)
    share = 0.0
    for i, (a, b) in enumerate(bounds[1:], start=1):  # spread evenly: hold out while behind the target share
        done = bounds[i - 1][1] / total
        if share < held_fraction * done:
            held[i] = True
            share += (b - a) / total
    changed = True
    while changed:  # a held-out cycle beyond the fitted cycles' range is fitted instead
        fit_lo = min(float(u[a:b].min()) for (a, b), h in zip(bounds, held) if not h)
        fit_hi = max(float(u[a:b].max()) for (a, b), h in zip(bounds, held) if not h)
        slack = COVER_TOLERANCE * (fit_hi - fit_lo)
        changed = False
        for i, (a, b) in enumerate(bounds):
            if held[i] and (float(u[a:b].min()) < fit_lo - slack or float(u[a:b].max()) > fit_hi + slack):
                held[i] = False
                changed = True
    if not held.any():
        return None
    mask = np.ones(u.size, dtype=bool)
    for (a, b), h in zip(bounds, held):
        if h:
            mask[a:b] = False
    return mask


def _interval_text(intervals: list[tuple[float, float]]) -> str:
    return " and ".join(f"{lo:g} ... {hi:g}" for lo, hi in intervals)


def _check_fitted(mask: np.ndarray, how: str) -> None:
    """Refuse a split that fits fewer samples than a fit needs (once, before any family is fitted)."""
    fitted = int(mask.sum())
    if fitted < MIN_SAMPLES:
        raise ValueError(
            f"u, y: the record has {mask.size} samples and the split ({how}) fits {fitted} of them, but every family "
            f"needs at least {MIN_SAMPLES} fitted samples (and some held out): give a longer record (at least "
            f"{MIN_SAMPLES + 1} samples), a larger split fraction or n_fit")


def choose_split(u: np.ndarray, t: Any, split: Any, n_fit: Any, fit_mask: Any, *, stacklevel: int = 3) -> tuple:
    """The fitted samples of :func:`identify`: ``(mask, description)`` (see the module).

    ``t``: the record's times (``None`` for arrays: the fraction is of the samples).
    """
    size = u.size
    given = [name for name, value in (("n_fit", n_fit), ("fit_mask", fit_mask)) if value is not None]
    if len(given) > 1:
        raise ValueError("give at most one of n_fit and fit_mask, got both")
    how = ""
    if fit_mask is not None:
        mask = np.asarray(fit_mask)
        if mask.dtype != bool or mask.shape != (size,):
            raise ValueError(f"fit_mask must be a boolean array with one entry per sample ({size}), got dtype "
                             f"{mask.dtype} and shape {mask.shape}")
        if not 10 <= int(mask.sum()) < size:
            raise ValueError(f"fit_mask must select at least 10 samples and leave some held out, got {int(mask.sum())} "
                             f"of {size}")
        mask, how = mask.copy(), "fit_mask (as given)"
    elif n_fit is None:
        if isinstance(split, str):
            if split not in SPLITS:
                raise ValueError(f"split must be a fraction in (0, 1) (the rest is held out), 'auto' or 'cycles', got {shown(split)}")
            fraction = AUTO_FRACTION
        elif isinstance(split, (int, float)) and not isinstance(split, bool) and 0.0 < split < 1.0:
            fraction = float(split)
        else:
            raise ValueError(f"split must be a fraction in (0, 1) (the rest is held out), 'auto' or 'cycles', got {shown(split)}")
        if t is not None:
            n_fit = int(np.searchsorted(t, t[0] + fraction * (t[-1] - t[0]), side="left"))
        else:
            n_fit = int(round(fraction * size))
        how = f"the first {100 * fraction:g} % of the {'duration' if t is not None else 'samples'}"
        if split in SPLITS:
            by_time = np.arange(size) < n_fit
            covered = not uncovered(u, by_time, ~by_time)
            cycles = None if (split == "auto" and covered) else interleaved_cycles(u)
            if cycles is not None:
                _check_fitted(cycles, "interleaved cycles")
                return cycles, (f"interleaved cycles ({int((~cycles).sum())} samples in whole cycles held out "
                                "inside the fitted input range)")
            if split == "cycles":
                raise ValueError("split='cycles': the record has fewer than three cycles (cut at its reversal minima) "
                                 "or none can be held out inside the fitted range; give split as a fraction or n_fit")
    if not how:
        if isinstance(n_fit, bool) or not isinstance(n_fit, (int, np.integer)) or not 10 <= n_fit < size:
            raise ValueError(f"n_fit must be an integer in [10, {size - 1}] (a held-out part is needed), got {shown(n_fit)}")
        how = f"the first {int(n_fit)} samples"
    if fit_mask is None:
        mask = np.arange(size) < int(n_fit)
    _check_fitted(mask, how)
    outside = uncovered(u, mask, ~mask)
    if outside:
        warnings.warn(
            f"identify: the held-out inputs reach {_interval_text(outside)}, outside the fitted input range "
            f"{float(u[mask].min()):g} ... {float(u[mask].max()):g} ({how} fitted): there every model extrapolates "
            "or saturates, so the held-out errors do not measure how well it predicts; use split='cycles' (interleaved "
            "cycles) or a record whose fitted part covers the range",
            AccuracyWarning, stacklevel=stacklevel)
    return mask, how
