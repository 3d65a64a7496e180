"""Identification of hysteresis operators from measured input-output records.

The public entry points are class methods of the operators (:meth:`DiscretePreisach.fit`,
:meth:`EverettPreisach.fit`, :meth:`PrandtlIshlinskii.fit`, :meth:`ContinuousPreisach.fit`;
:meth:`DiscretePreisach.from_loop` is in :mod:`exudyn_atcm.hysteresis.loop_identification`);
this module holds their least-squares bodies.  The operator classes are passed in, so nothing here imports them (no cycle).

Conventions shared by every fit
-------------------------------
* ``u``, ``y``: the record's input and output in time order; the first ``n_fit`` samples are
  fitted, the rest is held out and only predicted (the model runs over the whole record, so
  the held-out part is predicted with the memory the fitted part left behind).  Instead of
  ``n_fit`` a boolean ``fit_mask`` (one entry per sample) names the fitted samples, e.g.
  every other cycle of the record (:func:`~exudyn_atcm.hysteresis.identify` holds out
  interleaved cycles so that the held-out inputs lie inside the fitted range): the model
  still runs over the whole record, only the least-squares rows are the masked samples.
* The identified operator starts from its reset state at the first sample.  The real device's
  memory before the record is unknown, so the samples before the input has wiped that memory
  out are left out of the least squares and of the fitted-part errors (``fit_start`` in the
  :class:`~exudyn_atcm.hysteresis.fit_report.FitReport`): for the Preisach grid, until the
  input first comes down to the lowest threshold (half a cell above its minimum; for spread
  cells the lowest cell edge), from when every relay of the grid is off, whatever happened
  before; for the Prandtl-Ishlinskii plays see :mod:`exudyn_atcm.hysteresis.pi_fit` (a record
  that starts at its lowest input is fitted from its first sample).
* Every fitted model knows its :attr:`~exudyn_atcm.hysteresis.base.HysteresisOperator.fitted_range`
  (the input range of the fitted samples; applying it beyond warns), its output unit and
  quantity and a JSON-serialisable ``fit_info``.  An explicit ``input_range`` that cuts the
  fitted samples is refused.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from .._checks import finite_array, same_length, shown
from ..physical_bounds import check_element_count
from .base import quantity_from_unit
from .fit_cost import check_cost, continuous_fit_cost, finite_squares, grid_fit_cost
from .fit_report import FitReport, make_report
from .nnls import single_blas_thread
from .priors import PRIOR_STRENGTHS, PRIORS, along_lines_matrix, cross_validate_strength, solve_regularised
from .relay_gram import cell_gram, nnls_normal, refined_relays, relay_grid, relay_gram, smoothness_matrix

#: Fewest samples accepted by the least-squares fits.
MIN_SAMPLES = 10


# ------------------------------------------------------------------------------ checks

def check_record(u: Any, y: Any, n_fit: int | None = None, *, min_samples: int = MIN_SAMPLES) -> tuple:
    """Return ``u``, ``y`` as float arrays and ``n_fit``; ``ValueError`` for every bad input.

    Bad inputs: non-numeric or non-finite values, different lengths, fewer than
    ``min_samples`` samples (in the fitted part, too), an input or output that does not vary.
    """
    u_a = finite_array("u", u, min_length=0)
    y_a = finite_array("y", y, min_length=0)
    same_length(("u", "y"), (u_a, y_a))
    if u_a.size < min_samples:
        raise ValueError(f"u, y must hold at least {min_samples} samples to identify a model, got {u_a.size}")
    if n_fit is None:
        n_fit = u_a.size
    elif isinstance(n_fit, bool) or not isinstance(n_fit, (int, np.integer)) or not min_samples <= n_fit <= u_a.size:
        raise ValueError(
            f"n_fit (samples fitted, the rest held out) must be an integer in [{min_samples}, {u_a.size}], got {shown(n_fit)}"
        )
    n_fit = int(n_fit)
    finite_squares("u", u_a)
    finite_squares("y", y_a)
    span = float(np.ptp(u_a[:n_fit]))
    if span <= 0.0:
        raise ValueError(f"u must vary over the fitted samples, got a constant input {float(u_a[0])!r}")
    if float(np.ptp(y_a[:n_fit])) <= 0.0:
        raise ValueError(f"y must vary over the fitted samples, got a constant output {float(y_a[0])!r}")
    return u_a, y_a, n_fit


#: Largest ``n_levels`` of a relay-grid fit: ``n (n + 1) / 2`` relays and dense normal equations
#: of that size (100 levels: 5050 relays, about 1 GB of working memory and ~20 s).
MAX_FIT_LEVELS = 100


def fit_samples(u: Any, y: Any, n_fit: int | None = None, fit_mask: Any = None, *,
                min_samples: int = MIN_SAMPLES) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """``u``, ``y`` as arrays, the boolean mask of the fitted samples and ``stop`` (one past the last).

    ``n_fit`` (the first ``n_fit`` samples) or ``fit_mask`` (a boolean array, one entry per
    sample), not both; neither: every sample.  ``ValueError`` for every bad input (see
    :func:`check_record`; a mask of another length, not boolean, with fewer than ``min_samples``
    fitted samples, or a constant input or output over them).
    """
    if fit_mask is None:
        u_a, y_a, n_fit = check_record(u, y, n_fit, min_samples=min_samples)
        return u_a, y_a, np.arange(u_a.size) < n_fit, n_fit
    if n_fit is not None:
        raise ValueError(f"give n_fit or fit_mask, not both (got n_fit={n_fit!r} and a fit_mask)")
    u_a, y_a, _ = check_record(u, y, min_samples=min_samples)
    mask = np.asarray(fit_mask)
    if mask.dtype != bool or mask.shape != u_a.shape:
        raise ValueError(f"fit_mask must be a boolean array with one entry per sample ({u_a.size}), got "
                         f"dtype {mask.dtype} and shape {mask.shape}")
    count = int(np.count_nonzero(mask))
    if count < min_samples:
        raise ValueError(f"fit_mask must select at least {min_samples} samples, got {count}")
    if float(np.ptp(u_a[mask])) <= 0.0:
        raise ValueError(f"u must vary over the fitted samples, got a constant input {float(u_a[mask][0])!r}")
    if float(np.ptp(y_a[mask])) <= 0.0:
        raise ValueError(f"y must vary over the fitted samples, got a constant output {float(y_a[mask][0])!r}")
    return u_a, y_a, mask.copy(), int(np.flatnonzero(mask)[-1]) + 1


def grid_range(input_range: Any, u_fit: np.ndarray) -> tuple[float, float]:
    """The grid's input range: ``input_range`` (checked to hold every fitted input) or the fitted inputs'."""
    low, high = float(u_fit.min()), float(u_fit.max())
    if input_range is None:
        return low, high
    try:
        u_lo, u_hi = (float(v) for v in input_range)
    except (TypeError, ValueError):
        raise ValueError(f"input_range must be a pair (u_lo, u_hi) of numbers, got {shown(input_range)}") from None
    if not (math.isfinite(u_lo) and math.isfinite(u_hi) and u_hi > u_lo):
        raise ValueError(f"input_range must be finite with u_hi > u_lo, got {shown(input_range)}")
    slack = 1e-9 * (high - low)
    if u_lo > low + slack or u_hi < high - slack:
        raise ValueError(f"input_range ({u_lo:g}, {u_hi:g}) cuts the fitted samples, whose input spans {low:g} ... "
                         f"{high:g}: beyond the grid the model would saturate where the data go on; give a range "
                         "that holds every fitted input, or none (the fitted inputs' range)")
    return u_lo, u_hi


def sample_counts(mask: np.ndarray, start: int) -> dict[str, int]:
    """Sample counts of a fit for its ``fit_info``: record, fitted (least-squares rows), held out, first row."""
    after = np.arange(mask.size) >= start
    return {"record": int(mask.size), "fitted": int(np.count_nonzero(mask & after)),
            "held_out": int(np.count_nonzero(~mask & after)), "fit_start": int(start),
            "left_out_before_start": int(np.count_nonzero(mask & ~after))}


def record_fit(model: Any, report: FitReport, mask: np.ndarray, start: int, u_fit: np.ndarray, output_unit: str,
               output_quantity: str | None) -> None:
    """Set a fitted model's metadata (fitted range, unit, quantity, ``fit_info``) from its fit."""
    model.set_fit_metadata((float(u_fit.min()), float(u_fit.max())),
                           {"method": report.method, "settings": report.settings,
                            "samples": sample_counts(mask, start), "notes": list(report.notes)},
                           output_unit, output_quantity)


def levels_int(name: str, value: Any, minimum: int = 2) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {shown(value)}")
    return int(value)


def nonnegative_float(name: str, value: Any) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number) or number < 0.0:
        raise ValueError(f"{name} must be a finite number >= 0, got {shown(value)}")
    return number


def first_near(u: np.ndarray, target: float, tolerance: float) -> int:
    hits = np.flatnonzero(np.abs(u - target) <= tolerance)
    return int(hits[0]) if hits.size else u.size


# ------------------------------------------------------------------------------ Preisach fit

def fit_discrete(cls: type, u: Any, y: Any, n_levels: int, *, smoothing: float = 1e-3, n_fit: int | None = None,
                 input_range: tuple[float, float] | None = None, output_unit: str = "",
                 basis: str = "relays", prior: str = "pi", prior_weight: float | None = None,
                 cv_folds: int = 5, relays_per_cell: int = 1, fit_mask: Any = None,
                 output_quantity: str | None = None) -> tuple[Any, FitReport]:
    """Body of :meth:`DiscretePreisach.fit` (``basis="relays"``) and :meth:`EverettPreisach.fit`
    (``basis="cells"``: each weight spread over its grid cell).  With ``relays_per_cell > 1``
    the relay fit identifies the spread cells' weights and realises them as the finer relay grid
    of :func:`~exudyn_atcm.hysteresis.relay_gram.refined_relays`."""
    if basis not in ("relays", "cells"):
        raise ValueError(f"basis must be 'relays' or 'cells', got {shown(basis)}")
    refine = levels_int("relays_per_cell", relays_per_cell, minimum=1)
    if basis == "cells" and refine != 1:
        raise ValueError(f"relays_per_cell applies to DiscretePreisach.fit only (EverettPreisach spreads each weight "
                         f"over its whole cell), got relays_per_cell={relays_per_cell!r}")
    spread = "cells" if basis == "cells" or refine > 1 else "relays"
    started = time.perf_counter()
    quantity_from_unit(output_unit, output_quantity)
    u_a, y_a, mask, stop = fit_samples(u, y, n_fit, fit_mask)
    masked = None if fit_mask is None else mask  # None: the contiguous rows start .. n_fit - 1
    n_levels = levels_int("n_levels", n_levels)
    if n_levels > MAX_FIT_LEVELS:
        relays = n_levels * (n_levels + 1) // 2
        raise ValueError(
            f"n_levels must be <= {MAX_FIT_LEVELS}, got {n_levels}: {relays} relays would need dense normal equations "
            f"of {relays}x{relays} floats ({relays**2 * 8 / 2**30:.3g} GiB); 10 ... 40 levels resolve a measured loop "
            "to about its noise level")
    check_element_count(f"n_levels={n_levels} x relays_per_cell={refine}", n_levels * refine * (n_levels * refine + 1) // 2,
                        "relays")
    smoothing = nonnegative_float("smoothing", smoothing)
    if prior not in PRIORS:
        raise ValueError(f"prior must be one of {', '.join(repr(p) for p in PRIORS)}, got {shown(prior)}")
    if prior_weight is not None:
        prior_weight = nonnegative_float("prior_weight", prior_weight)
    cross_validate = prior == "pi" and prior_weight is None
    if cross_validate and (isinstance(cv_folds, bool) or not isinstance(cv_folds, (int, np.integer)) or cv_folds < 2):
        raise ValueError(f"cv_folds must be an integer >= 2, got {shown(cv_folds)}")
    u_fit = u_a[mask]
    u_lo, u_hi = grid_range(input_range, u_fit)
    # distinct relay states: a state changes only at a sample whose input crossed a threshold
    thresholds = u_lo + (np.arange(n_levels) + 0.5) * (u_hi - u_lo) / n_levels
    crossed = (np.diff(np.searchsorted(thresholds, u_a[:stop], side="right")) != 0) | (
        np.diff(np.searchsorted(thresholds, u_a[:stop], side="left")) != 0)
    changes = 1 + int(np.count_nonzero(crossed))
    rows_total = int(np.count_nonzero(mask))
    check_cost(f"{cls.__name__}.fit", grid_fit_cost(n_levels, max(stop, rows_total), spread, distinct_rows=changes,
                                                    cv_folds=cv_folds if cross_validate else 0,
                                                    cv_strengths=len(PRIOR_STRENGTHS)),
               "use fewer levels (n_levels) or decimate the record (exudyn_atcm.io.measurements.preprocess)")
    alpha, beta, index = relay_grid(u_lo, u_hi, n_levels)
    edges = np.linspace(u_lo, u_hi, n_levels + 1)
    # all grid relays are off once the input is at or below the lowest threshold (for relays
    # spread over their cells: at or below the lowest cell edge)
    lowest = float(alpha.min()) if spread == "relays" else u_lo + 1e-12 * (u_hi - u_lo)
    low = np.flatnonzero(u_a[:stop] <= lowest)
    start = int(low[0]) if low.size else stop
    rows = np.flatnonzero(mask[start:stop]) + start
    notes = []
    if start > 0:
        notes.append(
            f"samples 0..{start - 1} left out: the memory before the input first reaches its minimum is unknown"
        )
    else:
        notes.append("every fitted sample used: the record starts at its lowest input, where every relay of the "
                     "grid is off whatever the history before it")
    if rows.size < MIN_SAMPLES:
        raise ValueError(
            f"u: only {rows.size} fitted samples remain after the input first reaches its minimum "
            f"(sample {start}); at least {MIN_SAMPLES} are needed. Start the record at the input minimum."
        )
    scale = float(np.ptp(y_a[rows])) or 1.0

    def gram_of(first: int, end: int, mask_rows: Any) -> tuple:
        if spread == "relays":
            return relay_gram(alpha, beta, u_a, y_a / scale, first, end, mask=mask_rows)
        return cell_gram(edges, index, u_a, y_a / scale, first, end, mask=mask_rows)

    with single_blas_thread():  # see exudyn_atcm.hysteresis.nnls
        gram, rhs, colsum, ysum, m = gram_of(start, stop, masked)
    mean_s = colsum / m
    gram_c = gram - m * np.outer(mean_s, mean_s)
    rhs_c = rhs - mean_s * ysum
    d = smoothness_matrix(index, n_levels)
    dtd = (d.T @ d).tocsr()
    lam = smoothing * float(np.trace(gram_c)) / max(float(dtd.diagonal().sum()), 1e-300)
    prior_settings: dict = {"prior": prior}
    if prior == "smooth":
        weights = nnls_normal(gram_c, rhs_c, lam * dtd)
    else:
        dp = along_lines_matrix(index, n_levels)
        ptp_lap = (dp.T @ dp).tocsr()
        strength = prior_weight
        if cross_validate:
            if rows.size < cv_folds * MIN_SAMPLES:
                raise ValueError(f"cv_folds = {cv_folds} blocks of at least {MIN_SAMPLES} samples need {cv_folds * MIN_SAMPLES} "
                                 f"fitted samples, got {rows.size}; give prior_weight, fewer folds or prior='smooth'")
            # contiguous blocks of the fitted rows (of the masked samples, in time order)
            if masked is None:
                bounds = np.linspace(start, stop, cv_folds + 1).round().astype(int)
                blocks = [(int(a), int(b), None, slice(a, b)) for a, b in zip(bounds[:-1], bounds[1:])]
            else:
                cuts = np.linspace(0, rows.size, cv_folds + 1).round().astype(int)
                blocks = []
                for a, b in zip(cuts[:-1], cuts[1:]):
                    fold = np.zeros(u_a.size, dtype=bool)
                    fold[rows[a:b]] = True
                    blocks.append((int(rows[a]), int(rows[b - 1]) + 1, fold, rows[a:b]))
            folds = []
            with single_blas_thread():
                for first, end, fold, picked in blocks:
                    stats = gram_of(first, end, fold)
                    folds.append((*stats, float(np.sum((y_a[picked] / scale) ** 2))))
                strength, cv_table = cross_validate_strength(folds, dtd, smoothing, ptp_lap)
            for row in cv_table:
                row["cv_rms"] *= scale
                row["cv_mse_se"] *= scale**2
            prior_settings["cross_validation"] = {"folds": cv_folds, "rule": "strongest within one standard error",
                                                  "table": cv_table}
            notes.append(f"prior 'pi' (smoothness along alpha - beta): strength {strength:g} chosen by {cv_folds}-fold "
                         "cross-validation (strongest within one standard error of the best)")
        with single_blas_thread():
            weights, lams, _ = solve_regularised(gram_c, rhs_c, [(smoothing, dtd), (strength, ptp_lap)])
        prior_settings.update({"prior_weight": strength, "prior_weight_absolute": lams[1]})
    offset = (ysum / m - float(mean_s @ weights)) * scale
    weights = weights * scale
    never = colsum == 0.0
    if never.any():
        notes.append(f"{int(never.sum())} of {alpha.size} grid relays never switch on in the fitted samples "
                     "(their weights come from the smoothing only)")
    if basis == "cells":
        model = cls(edges, alpha, beta, weights, offset=offset)
    elif refine > 1:
        model = cls(*refined_relays(u_lo, u_hi, n_levels, weights, refine), offset=offset)
        notes.append(f"cell weights realised as {model.n_relays} relays, {refine} x {refine} per grid cell "
                     f"({n_levels * refine} levels)")
    else:
        model = cls(alpha, beta, weights, offset=offset)
    elapsed = time.perf_counter() - started
    report = make_report(
        model, u_a, y_a, stop if masked is None else u_a.size, start, f"{cls.__name__}.fit",
        settings={"n_levels": n_levels, "n_relays": int(getattr(model, "n_relays", alpha.size)),
                  "relays_per_cell": refine, "smoothing": smoothing,
                  "smoothing_weight": lam, "input_range": [u_lo, u_hi], "basis": basis, **prior_settings},
        notes=notes, output_unit=output_unit, fit_time=elapsed, coverage_levels=n_levels, fit_mask=masked,
    )
    record_fit(model, report, mask, start, u_fit, output_unit, output_quantity)
    return model, report


# ------------------------------------------------------------------------------ continuous fit

def fit_continuous(cls: type, u: Any, y: Any, *, n_fit: int | None = None, output_unit: str = "",
                   fit_mask: Any = None, output_quantity: str | None = None) -> tuple[Any, FitReport]:
    """Body of :meth:`ContinuousPreisach.fit` (see there)."""
    from scipy.optimize import least_squares

    started = time.perf_counter()
    quantity_from_unit(output_unit, output_quantity)
    u_a, y_a, mask, stop = fit_samples(u, y, n_fit, fit_mask)
    check_cost(f"{cls.__name__}.fit", continuous_fit_cost(stop),
               "decimate the record (exudyn_atcm.io.measurements.preprocess)")
    u_fit = u_a[mask]
    u_min, u_max = float(u_fit.min()), float(u_fit.max())
    start = first_near(u_a[:stop], u_min, 1e-3 * (u_max - u_min))
    rows = np.flatnonzero(mask[start:stop]) + start
    if rows.size < MIN_SAMPLES:
        raise ValueError(f"u: only {rows.size} fitted samples remain after the input first reaches its minimum")
    y_rows = y_a[rows]
    scale = float(np.ptp(y_rows))
    y0 = float(y_rows.min())

    def model_of(x: np.ndarray) -> Any:
        low, span, r1, r2 = x
        return cls(u_min, u_max, y0 + scale * low, y0 + scale * (low + span), r1, r2)

    def residuals(x: np.ndarray) -> np.ndarray:
        return (model_of(x).apply(u_a[:stop])[rows] - y_rows) / scale

    result = least_squares(residuals, x0=[0.0, 1.0, 1.5, 1.5],
                           bounds=([-1.0, 1e-6, 1.0, 1.0], [1.0, 3.0, 50.0, 50.0]), x_scale=[0.1, 0.1, 0.5, 0.5])
    model = model_of(result.x)
    notes = [] if result.success else [f"least squares stopped without convergence: {result.message}"]
    if start > 0:
        notes.append(f"samples 0..{start - 1} left out: the memory before the input first reaches its minimum is unknown")
    masked = None if fit_mask is None else mask
    report = make_report(model, u_a, y_a, stop if masked is None else u_a.size, start, f"{cls.__name__}.fit",
                         settings={"u_min": u_min, "u_max": u_max, "evaluations": int(result.nfev)},
                         notes=notes, output_unit=output_unit, fit_time=time.perf_counter() - started, fit_mask=masked)
    record_fit(model, report, mask, start, u_fit, output_unit, output_quantity)
    return model, report
