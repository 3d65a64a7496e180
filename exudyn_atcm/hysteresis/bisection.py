"""Inverse of a Preisach model by bisection on its input (see :mod:`exudyn_atcm.hysteresis.inverse`).

:class:`BisectionInverse` works for any operator whose output, from a fixed memory, does not
decrease as the input grows (a Preisach model with a non-negative density); every Preisach
model's :meth:`~exudyn_atcm.hysteresis.staircase.StaircasePreisach.inverse` returns one.
"""

from __future__ import annotations

import copy
import math
import warnings
from typing import Any

import numpy as np

from .._checks import finite_array, finite_float, shown
from ..errors import OutOfReachWarning
from .base import HysteresisOperator, check_input, forward_model

__all__ = ["BisectionInverse", "default_input_range"]


def default_input_range(model: Any) -> tuple[float, float]:
    """The input range an inverse of ``model`` searches when none is given: the range the model declares.

    Read from the operator contract (:class:`~exudyn_atcm.hysteresis.HysteresisOperator`), never
    from other attributes: its :attr:`~exudyn_atcm.hysteresis.HysteresisOperator.saturation_range`
    (the inputs over which the output changes; beyond them nothing more is reached) if it
    declares one, else its :attr:`~exudyn_atcm.hysteresis.HysteresisOperator.fitted_range` (a
    fitted model without saturation, e.g. a Prandtl-Ishlinskii or a Bouc-Wen fit).  If the
    output from the reset state already moves at the low end (a relay with ``alpha == beta`` at
    the lowest threshold is on there), the range starts just below it (by ``1e-6`` of the range),
    so the reset output is reachable.

    Raises
    ------
    ValueError
        If the model declares neither range (then give ``input_range``).
    """
    declared = getattr(model, "saturation_range", None)
    saturates = declared is not None
    if not saturates:
        declared = getattr(model, "fitted_range", None)
    if declared is None:
        raise ValueError(f"input_range must be given for a {type(model).__name__}: it declares neither a "
                         "saturation_range nor a fitted_range (the HysteresisOperator contract), so the inputs to "
                         "search are unknown")
    lo, hi = (float(v) for v in declared)
    if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
        raise ValueError(f"input_range: {type(model).__name__} declares the range {declared!r}; an inverse needs a "
                         "finite one with high > low (give input_range)")
    if saturates:  # the output is constant below the saturation range, unless a relay switches exactly at lo
        below = lo - 1e-6 * max(hi - lo, abs(lo), 1.0)
        probe = copy.deepcopy(model)
        probe.reset()
        if float(probe.evaluate(below)) != float(probe.evaluate(lo)):
            lo = below
    return lo, hi


class BisectionInverse(HysteresisOperator):
    """Inverse of a monotone hysteresis operator by bisection on the input.

    Parameters
    ----------
    model : hysteresis operator
        The forward model (copied: the original and its memory are not touched).  From any
        memory, its output must not decrease as the input grows (a Preisach model with
        non-negative weights).
    input_range : (float, float), optional
        Inputs allowed ``(u_lo, u_hi)`` (e.g. the drive's voltage limits).  Default: the range
        over which the model's output changes.
    tolerance : float, optional
        Bisection stops when the input bracket is this narrow (input units).  Default
        ``1e-9 × (u_hi − u_lo)``.

    Notes
    -----
    Initial state (after :meth:`reset`): the forward model reset.  :attr:`output` is the
    last committed input ``u`` (``nan`` after a reset).

    **A wanted output that holds keeps its input.**  Where the model's output is flat in the input
    (the paper's continuous Preisach loop leaves a reversal horizontally: after a rise to -149 V, its
    output stays within 1e-12 of its value down to -414 V), many inputs give the wanted output, and
    bisection picks an end of that stretch by the last bit of the output's rounding: a constant
    wanted output, committed three times, gave -149 V, -414 V, -149 V (a spurious 265 V pulse of one
    sample in a feedforward program, which a step chosen for accuracy then resolved with 22 steps per
    millisecond).  When the wanted output equals the one committed last (within ``1e-12`` of the
    reachable range) and that was reached, the last input is committed again: re-applying an input
    leaves a rate-independent memory as it was, so the output is the same.
    """

    def __init__(self, model: Any, input_range: tuple[float, float] | None = None, tolerance: float | None = None) -> None:
        for method in ("evaluate", "commit", "reset", "checkpoint", "restore"):
            if not callable(getattr(model, method, None)):
                raise ValueError(f"model must be a hysteresis operator with {method}(), got {type(model).__name__}")
        self.model = copy.deepcopy(model)
        if input_range is None:
            input_range = default_input_range(model)
        try:
            u_lo, u_hi = (finite_float("input_range", v) for v in input_range)
        except TypeError:
            raise ValueError(f"input_range must be a pair (u_lo, u_hi), got {shown(input_range)}") from None
        if not u_hi > u_lo:
            raise ValueError(f"input_range must have u_hi > u_lo, got {shown(input_range)}")
        self.u_lo, self.u_hi = u_lo, u_hi
        self.tolerance = 1e-9 * (u_hi - u_lo) if tolerance is None else finite_float("tolerance", tolerance)
        if self.tolerance <= 0.0:
            raise ValueError(f"tolerance must be > 0, got {shown(tolerance)}")
        self.reset()

    def reset(self) -> None:
        """Reset the forward model; clip counters to zero."""
        self.model.reset()
        self._u = math.nan
        self._y = math.nan  # the wanted output committed last, if it was reached (nan: none, or clipped)
        self.clip_count = 0
        self.largest_clip = 0.0
        self.worst_clip: tuple[float, float] | None = None  # (wanted output, input returned) of largest_clip
        self._quiet = False

    def checkpoint(self) -> tuple:
        """Snapshot of the forward memory, the last input and the last wanted output."""
        return (self.model.checkpoint(), self._u, self._y)

    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint`."""
        memory, u, y = snapshot
        self.model.restore(memory)
        self._u, self._y = u, y

    @property
    def output(self) -> float:
        """Input ``u`` [input units] committed last."""
        return self._u

    def reachable(self) -> tuple[float, float]:
        """Outputs reachable from the committed memory: ``(model(u_lo), model(u_hi))``."""
        return float(self.model.evaluate(self.u_lo)), float(self.model.evaluate(self.u_hi))

    def _solve(self, y: float) -> tuple[float, float]:
        """Input for the wanted output ``y``, and how far ``y`` lies outside the reachable range."""
        f = self.model.evaluate
        lo, hi = self.u_lo, self.u_hi
        y_lo, y_hi = float(f(lo)), float(f(hi))
        # an output beyond the reachable ones by rounding only (e.g. a saturated output returned by a
        # lag's inverse) is reached, not clipped
        rounding = 1e-12 * max(y_hi - y_lo, abs(y_hi), abs(y_lo))
        if abs(y - self._y) <= rounding:  # a hold: the last input again (see the class notes)
            return self._u, 0.0
        if y >= y_hi:
            return hi, (0.0 if y - y_hi <= rounding else y - y_hi)
        if y <= y_lo:
            return lo, (0.0 if y_lo - y <= rounding else y - y_lo)
        # invariant: f(lo) < y <= f(hi)
        exact = getattr(self.model, "input_for_output", None)
        if callable(exact):  # an operator that solves its own output exactly (piecewise linear: PI)
            return min(max(float(exact(y, lo, hi)), lo), hi), 0.0
        while hi - lo > self.tolerance:
            mid = 0.5 * (lo + hi)
            y_mid = float(f(mid))
            if y_mid < y:
                lo, y_lo = mid, y_mid
            else:
                hi, y_hi = mid, y_mid
        return (hi if y_hi - y <= y - y_lo else lo), 0.0

    def inverse(self, input_range: tuple[float, float] | None = None) -> HysteresisOperator:
        """The inverse of this inverse: a copy of the forward model, at its reset state.

        Raises
        ------
        ValueError
            If ``input_range`` is given (the forward model takes any input).
        """
        return forward_model(self.model, input_range)

    def evaluate(self, y: float) -> float:
        """Input that produces ``y`` from the committed memory (clipped silently: trial only)."""
        return self._solve(check_input(y))[0]

    def commit(self, y: float) -> float:
        """Commit the input producing ``y``; warn if ``y`` was unreachable and had to be clipped."""
        y = check_input(y)
        u, excess = self._solve(y)
        if excess != 0.0:
            y_lo, y_hi = self.reachable()
            self.clip_count += 1
            if abs(excess) > self.largest_clip:
                self.largest_clip, self.worst_clip = abs(excess), (y, u)
            if self._quiet:  # apply() says it once for the series
                self.model.commit(u)
                self._u, self._y = u, math.nan
                return u
            warnings.warn(
                f"wanted output {y!r} is outside the range [{y_lo!r}, {y_hi!r}] reachable with inputs in "
                f"[{self.u_lo!r}, {self.u_hi!r}] from the present memory: clipped by {abs(excess):.6g} "
                f"(output units) to the input {u!r}",
                OutOfReachWarning,
                stacklevel=2,
            )
        self.model.commit(u)
        self._u, self._y = u, (y if excess == 0.0 else math.nan)
        return u

    def apply(self, u_series: Any, *, check_range: bool = True) -> np.ndarray:
        """Inputs [input units] for a whole series of wanted outputs, starting from the reset state.

        As :meth:`HysteresisOperator.apply` (the memory is left as it was); unreachable wanted
        outputs are clipped as by :meth:`commit`, with one
        :class:`~exudyn_atcm.errors.OutOfReachWarning` for the series (how many were clipped, the
        largest amount and the wanted output it was for) instead of one per sample.  Afterwards
        :attr:`clip_count`, ``largest_clip`` and ``worst_clip`` are the series'.
        """
        wanted = finite_array("u_series", u_series, min_length=0)
        saved = self.checkpoint()
        try:
            self.reset()
            self._quiet = True
            inputs = np.array([self.commit(v) for v in wanted.tolist()], dtype=float)
        finally:
            self._quiet = False
            self.restore(saved)
        if self.clip_count:
            y, u = self.worst_clip
            warnings.warn(
                f"{self.clip_count} of {wanted.size} wanted outputs are outside the range reachable with inputs in "
                f"[{self.u_lo!r}, {self.u_hi!r}] and were clipped; the largest by {self.largest_clip:.6g} (output "
                f"units): the wanted output {y!r}, given the input {u!r}", OutOfReachWarning, stacklevel=2)
        return inputs

    def __repr__(self) -> str:
        return f"BisectionInverse({self.model!r}, input_range=({self.u_lo!r}, {self.u_hi!r}))"
