"""Inverse hysteresis operators: the input that makes a model produce a wanted output.

An inverse operator has the same interface as the forward ones (``evaluate``/``commit``/
``reset``/``apply``/``checkpoint``/``restore``), with input and output exchanged: its input is
the wanted output ``y`` of the forward model, its output the input ``u`` that produces it
*given the forward model's committed memory*.  Committing ``y`` commits that ``u`` to the
inverse's own copy of the forward model, so the two memories stay together.

* :class:`BisectionInverse`, for Preisach models (:class:`DiscretePreisach`,
  :class:`ContinuousPreisach`, :class:`EverettPreisach`, and any operator whose output, from a fixed memory, does not
  decrease with the input; true for non-negative Preisach densities): bisection on the input
  range.  For a discrete model the output is a staircase, so only its step values are reached
  exactly; the input returned is the one whose output lies nearest to ``y``.
* :func:`inverse_operator` picks the analytic inverse for :class:`PrandtlIshlinskii` (its
  :meth:`~PrandtlIshlinskii.inverse`, with the offset subtracted) and bisection otherwise.

Unreachable outputs (beyond what the input range can produce from the present memory) are
clipped to the nearest reachable output, with a ``RuntimeWarning`` saying by how much, when
they are committed; :attr:`BisectionInverse.clip_count` and ``largest_clip`` keep count.
"""

from __future__ import annotations

import copy
import math
import warnings
from typing import Any

from .._checks import finite_float
from .base import HysteresisOperator, check_input
from .continuous import ContinuousPreisach
from .discrete import DiscretePreisach
from .prandtl_ishlinskii import PrandtlIshlinskii
from ..errors import OutOfReachWarning

__all__ = ["BisectionInverse", "ShiftedPIInverse", "inverse_operator"]


def default_input_range(model: Any) -> tuple[float, float]:
    """Input range over which a Preisach model's output changes (beyond it, it saturates)."""
    edges = getattr(model, "edges", None)
    if edges is not None:  # EverettPreisach
        return float(edges[0]), float(edges[-1])
    if isinstance(model, DiscretePreisach):
        # just below the lowest switch-off threshold every relay is off (also one with alpha == beta)
        lo, hi = float(model.beta.min()), float(model.alpha.max())
        return lo - 1e-6 * max(hi - lo, abs(lo), 1.0), hi
    if isinstance(model, ContinuousPreisach):
        return model.u_min, model.u_max
    raise ValueError(
        f"input_range must be given for a {type(model).__name__}; the default is known for DiscretePreisach "
        "and ContinuousPreisach only"
    )


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
            raise ValueError(f"input_range must be a pair (u_lo, u_hi), got {input_range!r}") from None
        if not u_hi > u_lo:
            raise ValueError(f"input_range must have u_hi > u_lo, got {input_range!r}")
        self.u_lo, self.u_hi = u_lo, u_hi
        self.tolerance = 1e-9 * (u_hi - u_lo) if tolerance is None else finite_float("tolerance", tolerance)
        if self.tolerance <= 0.0:
            raise ValueError(f"tolerance must be > 0, got {tolerance!r}")
        self.reset()

    def reset(self) -> None:
        """Reset the forward model; clip counters to zero."""
        self.model.reset()
        self._u = math.nan
        self.clip_count = 0
        self.largest_clip = 0.0

    def checkpoint(self) -> tuple:
        """Snapshot of the forward memory and the last input."""
        return (self.model.checkpoint(), self._u)

    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint`."""
        memory, u = snapshot
        self.model.restore(memory)
        self._u = u

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
        if y >= y_hi:
            return hi, y - y_hi
        if y <= y_lo:
            return lo, y - y_lo
        # invariant: f(lo) < y <= f(hi)
        while hi - lo > self.tolerance:
            mid = 0.5 * (lo + hi)
            y_mid = float(f(mid))
            if y_mid < y:
                lo, y_lo = mid, y_mid
            else:
                hi, y_hi = mid, y_mid
        return (hi if y_hi - y <= y - y_lo else lo), 0.0

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
            self.largest_clip = max(self.largest_clip, abs(excess))
            warnings.warn(
                f"wanted output {y!r} is outside the range [{y_lo!r}, {y_hi!r}] reachable with inputs in "
                f"[{self.u_lo!r}, {self.u_hi!r}] from the present memory: clipped by {abs(excess):.6g} "
                f"(output units) to the input {u!r}",
                OutOfReachWarning,
                stacklevel=2,
            )
        self.model.commit(u)
        self._u = u
        return u

    def __repr__(self) -> str:
        return f"BisectionInverse({self.model!r}, input_range=({self.u_lo!r}, {self.u_hi!r}))"


class ShiftedPIInverse(HysteresisOperator):
    """Analytic inverse of ``y = offset + P[u]`` (``P`` a Prandtl-Ishlinskii operator): ``u = P⁻¹[y − offset]``,
    that is :meth:`PrandtlIshlinskii.inverse` with the bookkeeping of the other inverses (``clip_count``).

    Every output is reachable (a PI operator with ``p0 > 0`` is unbounded), so nothing is clipped.
    """

    def __init__(self, model: PrandtlIshlinskii) -> None:
        self.offset = model.offset
        self._inverse = model.inverse()
        self.clip_count = 0
        self.largest_clip = 0.0

    def evaluate(self, y: float) -> float:
        """Input producing ``y`` from the committed memory."""
        return self._inverse.evaluate(check_input(y))

    def commit(self, y: float) -> float:
        """Commit the input producing ``y``."""
        return self._inverse.commit(check_input(y))

    def reset(self) -> None:
        """Both the inverse and (implicitly) the forward plays at rest."""
        self._inverse.reset()

    def checkpoint(self) -> Any:
        """Snapshot of the inverse play states."""
        return self._inverse.checkpoint()

    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint`."""
        self._inverse.restore(snapshot)

    @property
    def output(self) -> float:
        """Input committed last."""
        return self._inverse.output

    def __repr__(self) -> str:
        return f"ShiftedPIInverse(offset={self.offset!r}, inverse={self._inverse!r})"


def inverse_operator(model: Any, input_range: tuple[float, float] | None = None) -> HysteresisOperator:
    """The inverse of a hysteresis model, with the operator interface (see the module).

    Parameters
    ----------
    model : PrandtlIshlinskii, DiscretePreisach, ContinuousPreisach or a monotone operator
        The forward model (input ``u`` to output ``y``).
    input_range : (float, float), optional
        Allowed inputs for the bisection inverse (ignored for Prandtl-Ishlinskii, whose inverse
        is analytic and unbounded).

    Returns
    -------
    HysteresisOperator
        Input ``y`` (wanted output), output ``u``; starting, like the forward model, from the
        reset state.
    """
    if isinstance(model, PrandtlIshlinskii):
        return ShiftedPIInverse(model)
    return BisectionInverse(model, input_range)
