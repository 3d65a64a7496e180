"""Inverse hysteresis operators: the input that makes a model produce a wanted output.

An inverse operator has the same interface as the forward ones (``evaluate``/``commit``/
``reset``/``apply``/``checkpoint``/``restore``), with input and output exchanged: its input is
the wanted output ``y`` of the forward model, its output the input ``u`` that produces it
*given the forward model's committed memory*.  Committing ``y`` commits that ``u`` to the
inverse's own copy of the forward model, so the two memories stay together.

One convention: every operator class has ``inverse(input_range=None)``, which returns such an
operator (:meth:`~exudyn_atcm.hysteresis.HysteresisOperator.inverse`), and ``inverse()`` of an
inverse returns the forward model again.  :func:`inverse_operator` is the same as a function:

* Preisach models (:class:`DiscretePreisach`, :class:`ContinuousPreisach`,
  :class:`EverettPreisach`): :class:`BisectionInverse`, bisection on the input range.  For a
  discrete model the output is a staircase, so only its step values are reached exactly; the
  input returned is the one whose output lies nearest to ``y``.
* :class:`PrandtlIshlinskii`: the analytic inverse, a :class:`ShiftedPIInverse` (itself a
  Prandtl-Ishlinskii operator; with an ``input_range``, bisection on that range);
* :class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`: a
  :class:`~exudyn_atcm.hysteresis.dynamics_inverse.DynamicsInverse` (the lags' exact step
  inverse, then the operator's inverse), with the time like the forward model;
* any other operator whose output, from a fixed memory, does not decrease with the input (e.g.
  a family defined outside the package without its own ``inverse``): :class:`BisectionInverse`.

Without ``input_range`` the inverse searches the range the operator *declares*
(:func:`~exudyn_atcm.hysteresis.bisection.default_input_range`: its ``saturation_range``, else
its ``fitted_range``); an operator that declares neither needs ``input_range``.

Unreachable outputs (beyond what the input range can produce from the present memory) are
clipped to the nearest reachable output, with an :class:`~exudyn_atcm.errors.OutOfReachWarning` saying by how much, when
they are committed; :attr:`BisectionInverse.clip_count` and ``largest_clip`` keep count.
"""

from __future__ import annotations

from typing import Any

from .base import HysteresisOperator
from .bisection import BisectionInverse, default_input_range
from .prandtl_ishlinskii import ShiftedPIInverse

__all__ = ["BisectionInverse", "ShiftedPIInverse", "inverse_operator", "default_input_range"]


def inverse_operator(model: Any, input_range: tuple[float, float] | None = None) -> HysteresisOperator:
    """The inverse of a hysteresis model, with the operator interface (see the module).

    Parameters
    ----------
    model : hysteresis operator
        The forward model (input ``u`` to output ``y``).
    input_range : (float, float), optional
        Inputs the inverse may return (e.g. a drive's voltage limits [V]); default: the range
        the model declares (its ``saturation_range``, else its ``fitted_range``; the analytic
        Prandtl-Ishlinskii inverse is unbounded).

    Returns
    -------
    HysteresisOperator
        ``model.inverse(input_range)`` when the model's class implements
        :meth:`~exudyn_atcm.hysteresis.HysteresisOperator.inverse`, else a
        :class:`BisectionInverse`; input ``y`` (wanted output), output ``u``; starting, like the
        forward model, from the reset state.

    Raises
    ------
    ValueError
        If no ``input_range`` is given and the model declares none (for a bisection inverse).
    """
    own = getattr(type(model), "inverse", None)
    if callable(own) and own is not HysteresisOperator.inverse:
        return model.inverse(input_range)
    return BisectionInverse(model, input_range)
