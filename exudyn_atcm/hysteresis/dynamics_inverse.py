"""The inverse of an operator with creep and/or a rate lag (:class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`).

:class:`DynamicsInverse` is what :meth:`WithDynamics.inverse()
<exudyn_atcm.hysteresis.dynamics.WithDynamics.inverse>` returns: an operator with the time,
``evaluate(y, t)`` / ``commit(y, t)``, whose input is the wanted output ``y`` at time ``t`` [s]
and whose output is the input ``u`` that gives it.  Each step inverts the lag block's exact
discretised step (:meth:`WithDynamics.operator_output_for
<exudyn_atcm.hysteresis.dynamics.WithDynamics.operator_output_for>`: the operator output ``h``
that gives ``y`` from the committed lag states, ``h`` linear in time over the step), then the
rate-independent operator's inverse (:func:`~exudyn_atcm.hysteresis.inverse.inverse_operator`)
gives ``u``; the wanted ``h`` advances the lag states of the inverse's own copy of the forward
model (:meth:`WithDynamics.advance_lags <exudyn_atcm.hysteresis.dynamics.WithDynamics.advance_lags>`),
so a sequence of wanted outputs is inverted as by the block's exact inverse
(:meth:`LagSum.inverse_response <exudyn_atcm.hysteresis.dynamics.LagSum.inverse_response>`).  The first commit after a reset passes no time; through a
lag (no feed-through) the output cannot jump then, and a wanted output other than the rest output
warns (:class:`~exudyn_atcm.errors.OutOfReachWarning`).
"""

from __future__ import annotations

import copy
import math
import warnings
from typing import Any

import numpy as np

from .._checks import finite_array, sample_times
from ..errors import OutOfReachWarning
from .base import HysteresisOperator, check_input, forward_model
from .inverse import inverse_operator

__all__ = ["DynamicsInverse"]


class DynamicsInverse(HysteresisOperator):
    """Inverse of a :class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics` (see the module).

    Parameters
    ----------
    model : WithDynamics
        The forward model (copied and reset).
    input_range : (float, float), optional
        Inputs the operator's inverse may return (default: the range the operator declares).
    """

    #: ``evaluate``/``commit``/``apply`` take the time [s] as well.
    time_dependent = True

    def __init__(self, model: Any, input_range: tuple[float, float] | None = None) -> None:
        if not callable(getattr(model, "operator_output_for", None)):
            raise ValueError(f"model must be a WithDynamics (an operator with creep or a lag), got {type(model).__name__}")
        self.model = copy.deepcopy(model)
        self.operator_inverse = inverse_operator(self.model.operator, input_range)
        #: the ``input_range`` asked for (``None``: the operator's declared range), what :meth:`save` writes
        self.requested_range = None if input_range is None else tuple(float(v) for v in input_range)
        self.reset()

    def reset(self) -> None:
        """Both the forward copy and the operator's inverse at their reset state."""
        self.model.reset()
        self.operator_inverse.reset()
        self._u = math.nan

    def checkpoint(self) -> tuple:
        """Snapshot of the lag states, the operator inverse and the last input."""
        return (self.model.checkpoint(), self.operator_inverse.checkpoint(), self._u)

    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint`."""
        forward, inner, u = snapshot
        self.model.restore(forward)
        self.operator_inverse.restore(inner)
        self._u = u

    @property
    def output(self) -> float:
        """Input ``u`` committed last (``nan`` after a reset)."""
        return self._u

    @property
    def clip_count(self) -> int:
        """Wanted operator outputs the operator's inverse had to clip (0 for an analytic inverse)."""
        return int(getattr(self.operator_inverse, "clip_count", 0))

    @property
    def largest_clip(self) -> float:
        """Largest such clip (operator output units)."""
        return float(getattr(self.operator_inverse, "largest_clip", 0.0))

    def evaluate(self, y: float, t: float | None = None) -> float:
        """Input that gives ``y`` at time ``t`` [s] from the committed state; nothing is changed."""
        return float(self.operator_inverse.evaluate(self.model.operator_output_for(check_input(y), t)))

    def commit(self, y: float, t: float | None = None) -> float:
        """Commit the input that gives ``y`` at time ``t`` [s] (to the forward copy as well) and return it."""
        y_f = check_input(y)
        h = self.model.operator_output_for(y_f, t)
        at_rest = self.model.lags.d == 0.0 and self.model.committed_time in (None, t)
        if at_rest and abs(y_f - self.model.output) > 1e-12 * max(abs(y_f), abs(self.model.output), 1e-300):
            warnings.warn(f"wanted output {y_f!r} at t = {t!r} s: with a lag (no feed-through) the output cannot jump "
                          f"when no time passes; it stays {self.model.output!r}", OutOfReachWarning, stacklevel=2)
        u = float(self.operator_inverse.commit(h))
        self.model.advance_lags(h, t)  # the lags integrate the operator output asked for, as the exact block inverse
        self._u = u
        return u

    def apply(self, y_series: Any, t: Any = None) -> np.ndarray:
        """Inputs for the wanted outputs ``y_series`` at times ``t`` [s] (increasing), from the reset state; memory kept."""
        y_a = finite_array("y_series", y_series, min_length=0)
        if t is None:
            raise ValueError(f"t is required: {type(self).__name__}.apply(y_series, t) needs the sample times [s]")
        t_a = sample_times("t", t, y_a.size) if y_a.size else np.zeros(0)
        saved = self.checkpoint()
        try:
            self.reset()
            return np.array([self.commit(y, tk) for y, tk in zip(y_a.tolist(), t_a.tolist())], dtype=float)
        finally:
            self.restore(saved)

    def inverse(self, input_range: tuple[float, float] | None = None) -> HysteresisOperator:
        """The forward model (a copy at its reset state).

        Raises
        ------
        ValueError
            If ``input_range`` is given (the forward model takes any input).
        """
        return forward_model(self.model, input_range)

    def __repr__(self) -> str:
        return f"DynamicsInverse({self.model!r})"
