"""How well an identified hysteresis model predicts a record: :class:`FitReport`.

Every fit of :mod:`exudyn_atcm.hysteresis.identification` runs the identified operator over
the *whole* record from its reset state (so the held-out part is predicted with the memory
the fitted part left behind) and compares with the measured output on

* the fitted part: samples ``fit_start ... n_fit - 1`` (before ``fit_start`` the model's
  memory depends on the unknown history before the record; see the fit's documentation),
* the held-out part: samples ``n_fit ... n_samples - 1`` (empty without a split),

(or, for a fit with a ``fit_mask``, the masked and the other samples from ``fit_start`` on) by
the RMS and the largest absolute error, in output units and in % of the measured output range
of the *whole* record (one reference for both parts and for every model fitted to the same
record).  The same numbers for the best linear model ``y = a·u + b`` (least squares on the
fitted part) show what the hysteresis model gains.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import shown
from ..io.atomic import write_json
from .base import HysteresisOperator
from .coverage import TriangleCoverage, runs

__all__ = ["FitReport", "error_measures", "make_report"]


def _no_nan(value: Any) -> Any:
    """``value`` with every NaN float replaced by ``None`` (strict JSON has no NaN)."""
    if isinstance(value, dict):
        return {k: _no_nan(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_no_nan(v) for v in value]
    if isinstance(value, float) and math.isnan(value):
        return None
    return value


def error_measures(measured: np.ndarray, predicted: np.ndarray, output_range: float) -> dict[str, float]:
    """RMS and largest absolute error, absolute and in % of ``output_range``; NaN for no samples."""
    if measured.size == 0:
        nan = math.nan
        return {"rms": nan, "max": nan, "rms_percent": nan, "max_percent": nan, "samples": 0}
    error = np.asarray(predicted, dtype=float) - np.asarray(measured, dtype=float)
    rms = float(np.sqrt(np.mean(error**2)))
    peak = float(np.max(np.abs(error)))
    return {
        "rms": rms,
        "max": peak,
        "rms_percent": 100.0 * rms / output_range,
        "max_percent": 100.0 * peak / output_range,
        "samples": int(measured.size),
    }


@dataclass
class FitReport:
    """Errors of an identified model and of the best linear model on the fitted and held-out parts.

    Attributes
    ----------
    model : str
        ``repr`` of the identified operator.
    method : str
        How it was identified (e.g. ``"DiscretePreisach.fit"``).
    n_samples, n_fit, fit_start : int
        Record length, first held-out sample (``n_samples`` without a held-out part; for a fit
        with a ``fit_mask``, ``n_samples``) and first sample compared on the fitted part.
    output_range : float
        Measured output range of the whole record (output units); the ``%`` figures refer to it.
    model_errors, linear_errors : dict
        ``{"fit": {...}, "held_out": {...}}`` each with ``rms``, ``max`` (output units),
        ``rms_percent``, ``max_percent`` and ``samples``.
    linear_model : dict
        Slope ``a`` (output per input unit) and intercept ``b`` of the best linear model.
    output_unit : str
        Unit of the output (for printing; ``""`` if unknown).
    settings : dict
        The fit's settings (levels, regularisation, ...).
    notes : list of str
        What the identification had to decide (unreached levels, excluded samples, ...).
    predicted : numpy.ndarray
        The model's output over the whole record (not written to JSON).
    coverage : dict
        How much of the Preisach triangle the fitted input showed the model
        (:meth:`TriangleCoverage.to_dict <exudyn_atcm.hysteresis.coverage.TriangleCoverage.to_dict>`),
        and ``held_out_unseen``: the share of the held-out input's reversal-curve cells outside it.
    triangle : TriangleCoverage or None
        The coverage itself, for :meth:`check_use` (not written to JSON).
    fit_mask : numpy.ndarray or None
        The fitted samples of a fit with a ``fit_mask`` (``None``: samples ``fit_start … n_fit − 1``);
        in JSON as the counts of fitted and held-out samples.
    """

    model: str
    method: str
    n_samples: int
    n_fit: int
    fit_start: int
    output_range: float
    model_errors: dict
    linear_errors: dict
    linear_model: dict
    output_unit: str = ""
    settings: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    fit_time: float = math.nan
    predicted: np.ndarray = field(default_factory=lambda: np.empty(0), repr=False)
    coverage: dict = field(default_factory=dict)
    triangle: Any = field(default=None, repr=False)
    fit_mask: Any = field(default=None, repr=False)

    def check_use(self, u: Any, threshold: float = 0.1) -> float:
        """Share of the reversal-curve cells of input ``u`` that the fitted record never crossed.

        Warns (``AccuracyWarning``) above ``threshold``: the model would be used on minor loops
        it never saw, where its output rests on the fit's prior, or beyond the fitted input range,
        where it extrapolates (those cells count as unseen; see
        :mod:`exudyn_atcm.hysteresis.coverage`).
        """
        if self.triangle is None:
            raise ValueError("this report has no coverage (made without the fitted input)")
        return self.triangle.check(u, threshold)

    def improvement_over_linear(self, part: str = "held_out") -> float:
        """Linear model's RMS error divided by the model's, on ``part`` (``"fit"`` or ``"held_out"``)."""
        if part not in ("fit", "held_out"):
            raise ValueError(f"part must be 'fit' or 'held_out', got {shown(part)}")
        model, linear = self.model_errors[part]["rms"], self.linear_errors[part]["rms"]
        if not (model > 0.0) or math.isnan(linear):
            return math.nan if math.isnan(linear) or math.isnan(model) else math.inf
        return linear / model

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable contents (without the predicted series); NaN (no held-out part) as ``None``."""
        return _no_nan({
            "method": self.method,
            "model": self.model,
            "n_samples": self.n_samples,
            "n_fit": self.n_fit,
            "fit_start": self.fit_start,
            "fitted_samples": self.model_errors["fit"]["samples"],
            "held_out_samples": self.model_errors["held_out"]["samples"],
            "split": "fit_mask" if self.fit_mask is not None else "n_fit",
            "output_range": self.output_range,
            "output_range_of": "whole record",
            "output_unit": self.output_unit,
            "model_errors": self.model_errors,
            "linear_errors": self.linear_errors,
            "linear_model": self.linear_model,
            "improvement_over_linear": {
                "fit": self.improvement_over_linear("fit"),
                "held_out": self.improvement_over_linear("held_out"),
            },
            "settings": self.settings,
            "notes": list(self.notes),
            "fit_time [s]": self.fit_time,
            "coverage": self.coverage,
        })

    def write_json(self, path: str | Path) -> Path:
        """Write :meth:`to_dict` as JSON (atomically) and return the path."""
        return write_json(path, self.to_dict())

    def table(self) -> str:
        """The errors as a fixed-width text table."""
        unit = f" [{self.output_unit}]" if self.output_unit else ""
        if self.fit_mask is None:
            parts = f"fitted {self.fit_start}..{self.n_fit - 1}, held out {self.n_fit}..{self.n_samples - 1}"
        else:
            parts = (f"fitted {self.model_errors['fit']['samples']} and held out {self.model_errors['held_out']['samples']} "
                     f"samples from {self.fit_start} on, interleaved (fit_mask)")
        lines = [
            f"{self.method}: {self.model}",
            f"samples: {self.n_samples} ({parts}), "
            f"[%] of the whole record's output range {self.output_range:.4g}{unit}",
            f"{'model':<12}{'part':<10}{'RMS' + unit:>16}{'RMS [%]':>10}{'max' + unit:>16}{'max [%]':>10}",
        ]
        for name, errors in (("hysteresis", self.model_errors), ("linear", self.linear_errors)):
            for part in ("fit", "held_out"):
                e = errors[part]
                lines.append(
                    f"{name:<12}{part:<10}{e['rms']:>16.4g}{e['rms_percent']:>10.3f}{e['max']:>16.4g}{e['max_percent']:>10.3f}"
                )
        lines.append(
            f"linear RMS / model RMS: fit {self.improvement_over_linear('fit'):.3g}, "
            f"held out {self.improvement_over_linear('held_out'):.3g}"
        )
        lines.extend(f"note: {n}" for n in self.notes)
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.table()


def make_report(
    operator: Any,
    u: np.ndarray,
    y: np.ndarray,
    n_fit: int,
    fit_start: int,
    method: str,
    *,
    settings: dict | None = None,
    notes: list | None = None,
    output_unit: str = "",
    fit_time: float = math.nan,
    coverage_levels: int = 20,
    fit_mask: Any = None,
) -> FitReport:
    """Run ``operator`` over the whole record and compare with the measured output (see module).

    ``coverage_levels``: grid of the :class:`~exudyn_atcm.hysteresis.coverage.TriangleCoverage`
    of the fitted samples (over their input range).  ``fit_mask`` (boolean, one entry per
    sample): the fitted samples, instead of ``fit_start … n_fit − 1`` (then ``n_fit`` is
    ``n_samples``); the others from ``fit_start`` on are held out.  Inputs of the held-out
    part beyond the fitted input range are said in a note (the prediction there extrapolates).
    """
    # the report says itself where the held-out input leaves the fitted range (a note below)
    predicted = operator.apply(u, check_range=False) if isinstance(operator, HysteresisOperator) else operator.apply(u)
    notes = list(notes or [])
    after = np.arange(u.size) >= fit_start
    if fit_mask is None:
        fit_rows = after & (np.arange(u.size) < n_fit)
        held_rows = np.arange(u.size) >= n_fit
    else:
        mask = np.asarray(fit_mask, dtype=bool)
        n_fit = int(u.size)
        fit_rows = mask & after
        held_rows = ~mask & after
    triangle = None
    coverage: dict = {}
    u_fit = u[fit_rows]
    if u_fit.size >= 2 and float(np.ptp(u_fit)) > 0.0:
        fit_runs = runs(u, fit_rows)
        held_runs = runs(u, held_rows, overlap=1)
        triangle = TriangleCoverage(fit_runs, float(u_fit.min()), float(u_fit.max()), coverage_levels)
        coverage = triangle.to_dict()
        coverage["held_out_unseen"] = triangle.unseen_fraction(held_runs) if held_runs else 0.0
        notes.append(f"the fitted input's reversal curves cross {100 * triangle.fraction:.1f} % of the Preisach "
                     f"triangle ({coverage['cells_crossed']} of {coverage['cells_total']} cells of a "
                     f"{coverage_levels}-level grid)"
                     + (f"; {100 * coverage['held_out_unseen']:.0f} % of the held-out input's lie outside, where the "
                        "model follows its prior or extrapolates" if coverage["held_out_unseen"] > 0.0 else ""))
        u_held = u[held_rows]
        lo, hi = float(u_fit.min()), float(u_fit.max())
        if u_held.size and (u_held.min() < lo or u_held.max() > hi):
            notes.append(f"the held-out input spans {float(u_held.min()):g} ... {float(u_held.max()):g}, beyond the "
                         f"fitted input range {lo:g} ... {hi:g}: the prediction there is an extrapolation")
    output_range = float(np.ptp(y)) or 1.0  # the whole record's: one reference for every part and model
    design = np.column_stack([u[fit_rows], np.ones(int(np.count_nonzero(fit_rows)))])
    (a, b), *_ = np.linalg.lstsq(design, y[fit_rows], rcond=None)
    linear = a * u + b
    return FitReport(
        model=repr(operator),
        method=method,
        n_samples=int(u.size),
        n_fit=int(n_fit),
        fit_start=int(fit_start),
        output_range=output_range,
        model_errors={"fit": error_measures(y[fit_rows], predicted[fit_rows], output_range),
                      "held_out": error_measures(y[held_rows], predicted[held_rows], output_range)},
        linear_errors={"fit": error_measures(y[fit_rows], linear[fit_rows], output_range),
                       "held_out": error_measures(y[held_rows], linear[held_rows], output_range)},
        linear_model={"a": float(a), "b": float(b)},
        output_unit=output_unit,
        settings=dict(settings or {}),
        notes=notes,
        fit_time=fit_time,
        predicted=predicted,
        coverage=coverage,
        triangle=triangle,
        fit_mask=None if fit_mask is None else np.asarray(fit_mask, dtype=bool).copy(),
    )
