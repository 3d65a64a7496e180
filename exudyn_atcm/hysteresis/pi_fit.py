"""Least-squares fit of a Prandtl-Ishlinskii operator to a record: the body of :meth:`PrandtlIshlinskii.fit`.

The play outputs along a record follow from the input and the plays' state at its start, so
``p0``, the weights and the offset are a linear least-squares problem once that state is known.
The state before the record is the device's history, which the record does not show; the fit
takes it from one of three rules (``initial``):

``"rest"``
    Every play at rest at the first input ``u0``: ``z_r = u0`` (the operator's reset state
    with ``input_offset = u0``).  The state of a PI operator started at ``u0`` (the usual
    initial condition of the PI literature), e.g. an actuator switched on at ``u0`` for the
    first time.
``"descended"``
    Every play as after a descent from far above to ``u0``: ``z_r = u0 + r``.  The state of a
    Preisach operator at negative saturation (all relays off), which is what a record that
    starts at its lowest input after larger cycles shows.  It is the reset state with
    ``input_offset = u0 + r_max`` (``r_max`` the largest radius): from ``z = 0`` the first
    input ``v = −r_max`` puts every play at ``z_r = r − r_max``, i.e. ``u0 + r`` in inputs.
``"covered"``
    Unknown: the samples before the input has come within half a play spacing of both its
    minimum and its maximum are left out.  Until then a play of radius ``r`` may still be
    anywhere in ``[u − r, u + r]``; once the input has swept ``2 r`` its state no longer
    depends on where it started, and the largest radius is below half the range.

``"auto"`` (the default): when the record starts at its lowest fitted input (within half a
play spacing), both ``"rest"`` and ``"descended"`` are fitted on every sample and the one with
the smaller least-squares residual is kept: the two are the two ends of what a history can
leave at a minimum (plays of radius up to ``d`` descended, the larger ones at rest, for a
history that came down by ``2 d``), a PI operator's own history usually starts at rest, a
Preisach operator's in its negative saturation, and the data tell them apart (a PI truth
started at rest is recovered exactly by ``"rest"``; the growing-amplitude record of an
asymmetric Preisach operator is followed better from ``"descended"``).  Otherwise ``"covered"``.
In every case the model applied from its reset state (:meth:`~HysteresisOperator.apply`)
reproduces the play states the fit used from ``fit_start`` on.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from .._checks import shown
from ..physical_bounds import check_element_count
from .base import quantity_from_unit
from .fit_cost import check_cost, play_fit_cost
from .fit_report import FitReport, make_report
from .identification import MIN_SAMPLES, first_near, fit_samples, levels_int, record_fit

__all__ = ["INITIAL_STATES", "play_states", "fit_prandtl_ishlinskii"]

#: Rules for the plays' state at the start of a record (see the module).
INITIAL_STATES = ("auto", "rest", "descended", "covered")


def play_states(v: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """Play outputs (one column per radius) along ``v``, from ``z = 0`` (the operator's reset state)."""
    z = np.zeros(radii.size)
    out = np.empty((v.size, radii.size))
    for k, value in enumerate(v.tolist()):
        z = np.maximum(value - radii, np.minimum(value + radii, z))
        out[k] = z
    return out


def _solve(v: np.ndarray, plays: np.ndarray, y: np.ndarray, rows: np.ndarray, span: float) -> tuple:
    """``p0 >= p0_min``, weights ``>= 0`` and the offset by NNLS on ``rows``; returns them and the RMS."""
    from scipy.optimize import nnls  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    design = np.column_stack([v, plays])[rows]
    target = y[rows]
    scale = float(np.ptp(target)) or 1.0
    # p0 > 0 keeps the operator strictly increasing, so that its analytic inverse exists
    p0_min = 1e-3 * scale / span
    target_shift = target / scale - (p0_min / scale) * design[:, 0]
    mean_d, mean_t = design.mean(axis=0), float(target_shift.mean())
    coef, _ = nnls(design - mean_d, target_shift - mean_t, maxiter=50 * design.shape[1])
    coef = coef * scale
    coef[0] += p0_min
    offset = float(np.mean(target - design @ coef))
    rms = float(np.sqrt(np.mean((design @ coef + offset - target) ** 2)))
    return coef, offset, rms


def fit_prandtl_ishlinskii(cls: type, u: Any, y: Any, n: int, *, n_fit: int | None = None, output_unit: str = "",
                           fit_mask: Any = None, output_quantity: str | None = None,
                           initial: str = "auto") -> tuple[Any, FitReport]:
    """Body of :meth:`PrandtlIshlinskii.fit` (see there and the module)."""
    started = time.perf_counter()
    if initial not in INITIAL_STATES:
        raise ValueError(f"initial must be one of {', '.join(repr(s) for s in INITIAL_STATES)}, got {shown(initial)}")
    quantity_from_unit(output_unit, output_quantity)
    u_a, y_a, mask, stop = fit_samples(u, y, n_fit, fit_mask)
    n = check_element_count("n", levels_int("n", n), "plays")
    check_cost(f"{cls.__name__}.fit", play_fit_cost(n, int(np.count_nonzero(mask))),
               "use fewer plays (n; 10 ... 40 resolve a measured loop) or decimate the record")
    u_fit = u_a[mask]
    low, high = float(u_fit.min()), float(u_fit.max())
    span = high - low
    radii = span * np.arange(1, n) / (2.0 * n)
    tolerance = 0.5 * span / n
    u0 = float(u_a[0])
    at_minimum = u0 <= low + tolerance
    rules = (("rest", "descended") if at_minimum else ("covered",)) if initial == "auto" else (initial,)
    if rules == ("covered",):
        start = max(first_near(u_a[:stop], low, tolerance), first_near(u_a[:stop], high, tolerance))
        offsets = {"covered": 0.0}
    else:
        start = 0
        at = {"rest": u0, "descended": u0 + float(radii[-1]) if radii.size else u0}
        offsets = {name: at[name] for name in rules}
    rows = np.flatnonzero(mask[start:stop]) + start
    if rows.size < MIN_SAMPLES:
        raise ValueError(
            f"u: only {rows.size} fitted samples remain after the input has reached both its minimum and its "
            f"maximum (sample {start}); at least {MIN_SAMPLES} are needed"
        )
    solutions = {}
    for name, input_offset in offsets.items():
        v = u_a[:stop] - input_offset
        solutions[name] = (input_offset, *_solve(v, play_states(v, radii), y_a[:stop], rows, span))
    chosen = min(solutions, key=lambda name: solutions[name][3])
    input_offset, coef, offset, _ = solutions[chosen]
    model = cls(radii, coef[1:], coef[0], offset=offset, input_offset=input_offset)
    notes = []
    if chosen == "covered":
        if start > 0:
            notes.append(f"samples 0..{start - 1} left out: the play states before the input has covered its range "
                         f"({low:g} ... {high:g}) depend on the unknown history; a record that starts at its lowest "
                         "input is fitted from its first sample")
    else:
        rms = ", ".join(f"{name} {solutions[name][3]:.4g}" for name in solutions)
        state = "at rest" if chosen == "rest" else "descended (as after a descent from far above)"
        notes.append(f"every sample fitted from the first: the plays start {state} at u = {u0:g} "
                     + ("(the record starts at its lowest input; chosen by the least-squares residual, RMS "
                        f"{rms}{' ' + output_unit if output_unit else ''})" if len(solutions) > 1 else "(initial state given)"))
    masked = None if fit_mask is None else mask
    settings = {"n": n, "radii": radii.tolist(), "initial": chosen, "input_offset": input_offset,
                "initial_rms": {name: solutions[name][3] for name in solutions}}
    report = make_report(model, u_a, y_a, stop if masked is None else u_a.size, start, f"{cls.__name__}.fit",
                         settings=settings, notes=notes, output_unit=output_unit,
                         fit_time=time.perf_counter() - started, fit_mask=masked)
    record_fit(model, report, mask, start, u_fit, output_unit, output_quantity)
    return model, report
