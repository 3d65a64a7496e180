"""Which hysteresis model a record supports: every family fitted and compared on held-out data.

:func:`identify` fits every registered family (:mod:`exudyn_atcm.hysteresis.families`: each
family registers itself, with its fit, parameter count and kind of inverse, in the module that
defines its operator) on the same fitted part of a record and predicts the same held-out part
with each (the model runs over the whole record from its reset state, so the held-out part
starts from the memory the fitted part left).  The package's families (equal-gain relays,
the relay grid, the spread-cell grid, Prandtl-Ishlinskii, the continuous power law) are listed
with their inverses on the :doc:`/identification` page.

Which samples are fitted and which held out: :mod:`exudyn_atcm.hysteresis.record_split` (by
default the held-out inputs lie inside the fitted input range: the first 60 % of the record
when that covers it, else interleaved cycles; a warning names an uncovered range).

The result, a :class:`ModelChoice`, ranks them by held-out RMS error (in % of the output range
of the whole record, one reference for every family and part), with parameter count, fit time and whether a continuous inverse exists
(:func:`exudyn_atcm.hysteresis.inverse.inverse_operator`: the staircase models reach only
their step values), and names the chosen model: the one with the fewest parameters among those
whose held-out RMS error is within ``1 + simpler_margin`` (default 1.1) of the best, so a model
with more parameters has to predict clearly better to be chosen.  A family that cannot be fitted
to the record (e.g. no full major-loop branch in the fitted part for ``equal_gain``) is listed
with the reason instead of an error.  When the chosen model's held-out RMS error is not below
the best linear model's by a clear margin (``linear_margin``: the linear model's error must be
at least ``1 + linear_margin`` times the chosen model's, default 2), an
:class:`~exudyn_atcm.errors.AccuracyWarning` says that the record shows no hysteresis the
models can use (pure noise, a time-reversed record, a nearly linear actuator).  Measured: the
shipped record (``cases/data/preisach_record.csv``) 12x, pure noise 1.0x, a growing-amplitude
record of an asymmetric Preisach density 37x forwards and 1.4x played backwards (the models
follow the curvature of the backwards loops, not their sense: below 2x).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import hide_keywords, option_values, options_from_keywords, shown
from ..io.atomic import write_json
from .families import FitRequest, family_named, registered_families
from .fit_report import FitReport
from .base import known_output_units, quantity_from_unit
from .identification import check_record
from .identify_options import IdentifyOptions
from .record_split import choose_split
from ..errors import AccuracyWarning, AtcmDeprecationWarning, SetupWarning

__all__ = ["Candidate", "ModelChoice", "identify"]


def __getattr__(name: str) -> Any:
    """``FAMILIES`` (deprecated in 0.3): the registered family names, read from the registry."""
    if name == "FAMILIES":
        warnings.warn("exudyn_atcm.hysteresis.model_choice.FAMILIES is deprecated: use "
                      "tuple(exudyn_atcm.hysteresis.families.registered_families()), which includes families "
                      "registered outside the package", AtcmDeprecationWarning, stacklevel=2)
        return tuple(registered_families())
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@dataclass
class Candidate:
    """One fitted family of a :class:`ModelChoice`.

    Attributes
    ----------
    family : str
        A registered family (:func:`~exudyn_atcm.hysteresis.families.registered_families`).
    label : str
        Family and size, e.g. ``"everett (30 levels)"``.
    held_out_rms_percent, fit_rms_percent : float
        RMS error on the held-out and the fitted part, % of the output range of the whole record
        (NaN if the family could not be fitted).
    parameters : int
        Identified numbers: weights or thresholds, gains, offset, input range as they apply.
    fit_time : float
        Wall time of the fit [s].
    invertible : bool
        Whether a continuous inverse exists (``inverse`` says which).
    inverse : str
        ``"analytic"``, ``"bisection"`` or ``"none (staircase)"``.
    model : HysteresisOperator or None
        The identified operator.
    report : FitReport or None
        Its errors on both parts.
    failure : str
        Why the family could not be fitted (``""`` if it was).
    notes : tuple of str
        The warnings its fit issued (``"Category: message"``).  Only the chosen family's are
        issued again by :func:`identify`; the others are kept here (a note about a model not
        chosen is nothing the user has to act on).
    """

    family: str
    label: str
    held_out_rms_percent: float
    fit_rms_percent: float
    parameters: int
    fit_time: float
    invertible: bool
    inverse: str
    model: Any = field(default=None, repr=False)
    report: FitReport | None = field(default=None, repr=False)
    failure: str = ""
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable summary (without the model and the predicted series)."""
        def number(v: float) -> float | None:
            return None if math.isnan(v) else float(v)

        return {"family": self.family, "label": self.label,
                "held_out_rms [% of range]": number(self.held_out_rms_percent),
                "fit_rms [% of range]": number(self.fit_rms_percent), "parameters": self.parameters,
                "fit_time [s]": number(self.fit_time), "invertible": self.invertible, "inverse": self.inverse,
                "failure": self.failure, "notes": list(self.notes)}


@dataclass
class ModelChoice:
    """Families ranked by held-out error, and the chosen model (see the module).

    Attributes
    ----------
    candidates : list of Candidate
        Fitted families, best held-out RMS error first; families that failed at the end.
    chosen : Candidate
        The chosen one.
    n_samples, n_fit : int
        Record length and first held-out sample.
    output_range : float
        Output range of the whole record (output units): the one reference of every
        candidate's ``%`` figures (and of each :class:`FitReport`'s).
    output_unit : str
        Unit of the output.
    simpler_margin : float
        The choice rule's margin (see the module).
    input, output : numpy.ndarray
        The record (for plots; each candidate's ``report.predicted`` is its prediction).
    fit_mask : numpy.ndarray
        The fitted samples (the others are held out).
    split : str
        How the record was split (e.g. ``"interleaved cycles (...)"``).
    linear_held_out_rms_percent : float
        Held-out RMS error of the best linear model (least squares on the fitted samples), %.
    output_quantity : str or None
        What the output is (from the unit, or as given).
    """

    candidates: list
    chosen: Candidate
    n_samples: int
    n_fit: int
    output_range: float
    output_unit: str = ""
    simpler_margin: float = 0.1
    input: np.ndarray = field(default_factory=lambda: np.empty(0), repr=False)
    output: np.ndarray = field(default_factory=lambda: np.empty(0), repr=False)
    fit_mask: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=bool), repr=False)
    split: str = ""
    linear_held_out_rms_percent: float = math.nan
    output_quantity: str | None = None

    @property
    def model(self) -> Any:
        """The chosen operator."""
        return self.chosen.model

    def candidate(self, family: str) -> Candidate:
        """The candidate of ``family`` (``ValueError`` if it was not fitted)."""
        for c in self.candidates:
            if c.family == family:
                return c
        raise ValueError(f"family must be one of {[c.family for c in self.candidates]}, got {shown(family)}")

    def to_text(self) -> str:
        """The ranked table as fixed-width text."""
        unit = f" {self.output_unit}" if self.output_unit else ""
        if self.split.startswith("the first") or not self.split:
            parts = f"fitted samples 0..{self.n_fit - 1}, held out {self.n_fit}..{self.n_samples - 1}"
        else:
            parts = (f"fitted {int(self.fit_mask.sum())} samples, held out {int((~self.fit_mask).sum())}: "
                     f"{self.split}")
        lines = [
            f"model choice on held-out data: {parts}; [%] of the whole record's output range "
            f"{self.output_range:.4g}{unit}",
            f"{'rank':<5}{'model':<34}{'held-out RMS [%]':>17}{'fit RMS [%]':>12}{'parameters':>11}{'fit time [s]':>13}"
            f"  {'invertible':<22}",
        ]
        for k, c in enumerate(self.candidates, start=1):
            if c.failure:
                lines.append(f"{'-':<5}{c.label:<34}  not fitted: {c.failure}")
                continue
            mark = " *" if c is self.chosen else ""
            lines.append(f"{k:<5}{c.label + mark:<34}{c.held_out_rms_percent:>17.3f}{c.fit_rms_percent:>12.3f}"
                         f"{c.parameters:>11d}{c.fit_time:>13.3g}  {('yes, ' if c.invertible else 'no, ') + c.inverse:<22}")
        lines.append(f"* chosen: {self.chosen.label} (fewest parameters within {1 + self.simpler_margin:.3g}x "
                     "the best held-out RMS error)")
        if not math.isnan(self.linear_held_out_rms_percent):
            lines.append(f"best linear model: held-out RMS {self.linear_held_out_rms_percent:.3f} % "
                         f"({self.linear_held_out_rms_percent / self.chosen.held_out_rms_percent:.3g}x the chosen model's)")
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.to_text()

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable contents."""
        linear = self.linear_held_out_rms_percent
        return {"chosen": self.chosen.family, "chosen_label": self.chosen.label, "n_samples": self.n_samples,
                "n_fit": self.n_fit, "split": self.split, "fitted_samples": int(self.fit_mask.sum()),
                "output_range": self.output_range, "output_range_of": "whole record", "output_unit": self.output_unit,
                "output_quantity": self.output_quantity,
                "linear_held_out_rms [% of range]": None if math.isnan(linear) else float(linear),
                "simpler_margin": self.simpler_margin, "candidates": [c.to_dict() for c in self.candidates]}

    def write_json(self, path: str | Path) -> Path:
        """Write :meth:`to_dict` as JSON (atomically) and return the path."""
        return write_json(path, self.to_dict())


def _record_arrays(record: Any, y: Any) -> tuple[Any, Any, str, Any]:
    """``u``, ``y``, the output unit and the time (or None) from arrays or a measured record."""
    if y is None:
        if not all(hasattr(record, a) for a in ("input", "output", "time")):
            raise ValueError("identify needs u and y, or a measured record (exudyn_atcm.io.measurements.Record) "
                             f"as its first argument, got {type(record).__name__} and y=None")
        return record.input, record.output, getattr(record, "units", {}).get("output", ""), record.time
    return record, y, "", None


@hide_keywords
def identify(u: Any, y: Any = None, *, split: float | str = "auto", n_fit: int | None = None,
             fit_mask: Any = None, families: tuple[str, ...] | None = None, output_unit: str | None = None,
             output_quantity: str | None = None, options: IdentifyOptions | None = None, **legacy: Any) -> ModelChoice:
    """Fit every hysteresis family to a record and choose one by its held-out error.

    Parameters
    ----------
    u : array_like or Record
        Input samples in time order, or a measured record
        (:class:`exudyn_atcm.io.measurements.Record`; then ``y`` is left out, the fraction of
        ``split`` is of the duration and the output unit is the record's).
    y : array_like, optional
        Output samples (omit with a record).
    split : {"auto", "cycles"} or float, optional
        Which samples are held out (:mod:`exudyn_atcm.hysteresis.record_split`): ``"auto"``
        (default) the last 40 % when the first 60 % covers their inputs, else interleaved whole
        cycles inside the fitted range; ``"cycles"`` interleaved cycles; a fraction in
        ``(0, 1)``: that share of the record (of the duration for a record, of the samples for
        arrays) is fitted, the rest held out.  An :class:`~exudyn_atcm.errors.AccuracyWarning`
        names held-out inputs beyond the fitted range.
    n_fit : int, optional
        First held-out sample, instead of ``split``.
    fit_mask : array_like of bool, optional
        The fitted samples (one entry per sample), instead of ``split``.
    families : tuple of str, optional
        Which registered families to fit (default all of
        :func:`~exudyn_atcm.hysteresis.families.registered_families`, in their order).
    output_unit : str, optional
        Unit of ``y`` (default: the record's, or ``""``); every fitted model keeps it.
    output_quantity : str, optional
        What ``y`` is (``"strain"``, ``"displacement"``, ...); default from the unit (a length
        unit: ``"displacement"``).
    options : IdentifyOptions, optional
        How each family is fitted and how one is chosen
        (:class:`~exudyn_atcm.hysteresis.identify_options.IdentifyOptions`: ``n_levels``,
        ``n_plays``, ``n_relays``, ``smoothing``, ``prior``, ``reversal_tolerance``, ``levels``,
        ``relays_per_cell``, ``simpler_margin``, ``linear_margin``).  These names as flat keywords
        (the earlier signature) still work for one release, with an
        :class:`~exudyn_atcm.AtcmDeprecationWarning`.

    Returns
    -------
    ModelChoice

    Raises
    ------
    ValueError
        For a bad record (see :func:`~exudyn_atcm.hysteresis.identification.check_record`), no
        held-out part, an unknown family or split, or no family that could be fitted.
    """
    (options,) = options_from_keywords("identify", legacy, options=(IdentifyOptions, options))
    options.check()  # a bad option is refused here, not turned into "not fitted" for every family
    (n_levels, n_plays, n_relays, smoothing, prior, reversal_tolerance, levels, relays_per_cell, simpler_margin,
     linear_margin) = option_values(options)
    u_in, y_in, unit, t = _record_arrays(u, y)
    unit = unit if output_unit is None else output_unit
    quantity = quantity_from_unit(unit, output_quantity)
    if unit.strip() not in known_output_units():
        warnings.warn(f"identify: output_unit {unit!r} is not a unit the package knows "
                      f"({', '.join(repr(k) for k in known_output_units())}), so it cannot tell what the output is"
                      + ("" if output_quantity else " (output_quantity is left unstated: None)")
                      + "; give one of these units (SI: 'm' or '-')", SetupWarning, stacklevel=2)
    u_a, y_a, _ = check_record(u_in, y_in)
    known = registered_families()
    families = tuple(known) if families is None else families
    if isinstance(families, str) or not families or any(f not in known for f in families):
        raise ValueError(f"families must be a non-empty selection of the registered families {tuple(known)}, "
                         f"got {shown(families)}")
    mask, how = choose_split(u_a, t, split, n_fit, fit_mask)
    contiguous = how.startswith("the first")
    n_fit = int(np.argmin(mask)) if contiguous else int(u_a.size)
    request = FitRequest(u_a, y_a, mask, n_fit if contiguous else None, unit, quantity,
                         {"n_levels": n_levels, "n_plays": n_plays, "n_relays": n_relays, "smoothing": smoothing,
                          "prior": prior, "reversal_tolerance": reversal_tolerance, "levels": levels,
                          "relays_per_cell": relays_per_cell})

    output_range = float(np.ptp(y_a))  # the whole record's: one reference for every family's % figures
    candidates = []
    failed = []
    fit_warnings: dict[str, list] = {}
    for name in families:
        family = family_named(name)
        started = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:  # issued again below for the chosen family only
            warnings.simplefilter("always")
            try:
                fitted = family.fit(request)
            except ValueError as exc:
                failed.append(Candidate(name, name, math.nan, math.nan, 0, time.perf_counter() - started,
                                        family.invertible, family.inverse, failure=str(exc)))
                continue
        report = fitted.report
        candidates.append(Candidate(
            name, fitted.label, 100.0 * report.model_errors["held_out"]["rms"] / output_range,
            100.0 * report.model_errors["fit"]["rms"] / output_range,
            int(fitted.parameters), time.perf_counter() - started, family.invertible, family.inverse,
            model=fitted.model, report=report,
            notes=tuple(f"{w.category.__name__}: {w.message}" for w in caught)))
        fit_warnings[name] = [(w.message, w.category) for w in caught]
    if not candidates:
        raise ValueError("identify: no family could be fitted to the record: "
                         + "; ".join(f"{c.family}: {c.failure}" for c in failed))
    candidates.sort(key=lambda c: c.held_out_rms_percent)
    best = candidates[0].held_out_rms_percent
    within = [c for c in candidates if c.held_out_rms_percent <= (1.0 + simpler_margin) * best]
    chosen = min(within, key=lambda c: (c.parameters, c.held_out_rms_percent))
    for message, category in fit_warnings[chosen.family]:
        warnings.warn(f"identify ({chosen.label}, chosen): {message}", category, stacklevel=2)
    if failed:
        warnings.warn("identify: not fitted: " + "; ".join(f"{c.family} ({c.failure})" for c in failed),
                      SetupWarning, stacklevel=2)
    linear = 100.0 * chosen.report.linear_errors["held_out"]["rms"] / output_range
    if not linear >= (1.0 + linear_margin) * chosen.held_out_rms_percent:
        warnings.warn(
            f"identify: the chosen model ({chosen.label}) predicts the held-out part at {chosen.held_out_rms_percent:.3g} % "
            f"RMS of the output range, the best straight line y = a u + b at {linear:.3g} % ({linear / chosen.held_out_rms_percent:.3g}x, "
            f"less than the {1 + linear_margin:.3g}x asked by linear_margin): the record shows no hysteresis the models "
            "can use (noise, a time-reversed or mislabelled record, or a nearly linear actuator); check the channels "
            "and their order before using the model", AccuracyWarning, stacklevel=2)
    return ModelChoice(candidates + failed, chosen, int(u_a.size), n_fit, output_range, unit, float(simpler_margin),
                       input=u_a, output=y_a, fit_mask=mask, split=how, linear_held_out_rms_percent=linear,
                       output_quantity=quantity)
