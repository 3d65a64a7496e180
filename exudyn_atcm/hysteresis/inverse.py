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
clipped to the nearest reachable output, with an :class:`~exudyn_atcm.errors.OutOfReachWarning` saying by how much, when
they are committed; :attr:`BisectionInverse.clip_count` and ``largest_clip`` keep count.
"""

from __future__ import annotations

import copy
from typing import Any

from .base import HysteresisOperator, check_input
from .bisection import BisectionInverse, default_input_range
from .prandtl_ishlinskii import PrandtlIshlinskii

__all__ = ["BisectionInverse", "ShiftedPIInverse", "inverse_operator", "default_input_range"]


class ShiftedPIInverse(HysteresisOperator):
    """Analytic inverse of ``y = offset + P[u]`` (``P`` a Prandtl-Ishlinskii operator): ``u = P⁻¹[y − offset]``,
    that is :meth:`PrandtlIshlinskii.inverse` with the bookkeeping of the other inverses (``clip_count``).

    Every output is reachable (a PI operator with ``p0 > 0`` is unbounded), so nothing is clipped.
    ``model`` is a copy of the forward model (what :meth:`save` writes; loading inverts it again).
    """

    def __init__(self, model: PrandtlIshlinskii) -> None:
        self.model = copy.deepcopy(model)  # the forward model, kept for save()
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
