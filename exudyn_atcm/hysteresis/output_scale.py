"""A hysteresis operator with its output multiplied by a factor: the same family, the same memory rules.

Every operator family of the package is linear in the scale of its output, so a model fitted
on a displacement becomes the model of a strain by scaling its output parameters:

* :class:`~exudyn_atcm.hysteresis.DiscretePreisach`, :class:`~exudyn_atcm.hysteresis.EverettPreisach`:
  the relay weights and the offset;
* :class:`~exudyn_atcm.hysteresis.PrandtlIshlinskii`: the play weights, ``p0`` and the offset
  (the radii and ``input_offset`` are inputs and stay);
* :class:`~exudyn_atcm.hysteresis.ContinuousPreisach`: ``y_min`` and ``y_max`` (the exponents are
  shape, not scale);
* :class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`,
  :class:`~exudyn_atcm.hysteresis.creep.CreepHysteresis`: their inner operator (the creep and lag
  blocks are linear, unit gain per unit of their input).

The output of the scaled operator is ``factor`` times the original's for every input history
(tested against the original in ``tests/test_strain_conversion.py``).  What the operator knows
about itself (``output_quantity``, ``output_unit``, ``fitted_range``, ``fit_info``, its input
range, anything else set on it after it was made) is carried over; the scaling is added to
``fit_info`` when the model has one.  The new operator starts from its reset state.
"""

from __future__ import annotations

import copy
import warnings
from typing import Any

import numpy as np

from .._checks import positive_float, shown
from ..errors import InputRangeWarning
from ..physical_bounds import PLAUSIBLE_STRAIN
from .continuous import ContinuousPreisach
from .creep import CreepHysteresis
from .discrete import DiscretePreisach
from .dynamics import WithDynamics
from .everett import EverettPreisach
from .prandtl_ishlinskii import PrandtlIshlinskii

__all__ = ["SCALABLE", "scaled_output"]

#: The operator classes whose output :func:`scaled_output` scales (exact classes).
SCALABLE = (DiscretePreisach, EverettPreisach, PrandtlIshlinskii, ContinuousPreisach, WithDynamics, CreepHysteresis)


def _scaled(model: Any, f: float) -> Any:
    kind = type(model)
    if kind is DiscretePreisach:
        return DiscretePreisach(model.alpha, model.beta, model.weights * f, model.offset * f)
    if kind is EverettPreisach:
        return EverettPreisach(model.edges, model.alpha, model.beta, model.weights * f, model.offset * f)
    if kind is PrandtlIshlinskii:
        return PrandtlIshlinskii(model.radii, model.weights * f, model.p0 * f, offset=model.offset * f,
                                 input_offset=model.input_offset)
    if kind is ContinuousPreisach:
        return ContinuousPreisach(model.u_min, model.u_max, model.y_min * f, model.y_max * f, model.r1, model.r2)
    if kind is WithDynamics:
        return WithDynamics(scaled_output(model.operator, f), model.creep, model.lag)
    if kind is CreepHysteresis:
        return CreepHysteresis(scaled_output(model.hysteresis, f), model.creep)
    known = ", ".join(k.__name__ for k in SCALABLE)
    raise ValueError(
        f"model: cannot scale the output of a {kind.__name__}; scaled_output knows {known} (these exact classes: a "
        "subclass or another operator may hold output parameters it does not know). Convert the record's output "
        "instead and identify the model again"
    )


def scaled_output(model: Any, factor: float, *, quantity: str | None = None, unit: str | None = None,
                  note: str | None = None) -> Any:
    """A new operator of ``model``'s class whose output is ``factor`` times ``model``'s, for every input history.

    Parameters
    ----------
    model : operator
        One of :data:`SCALABLE`.
    factor : float
        Output scale, ``> 0`` (a negative scale would turn the loops upside down; negate the
        record instead).
    quantity, unit : str, optional
        The new ``output_quantity`` and ``output_unit`` (default: kept).
    note : str, optional
        How the factor came about, added to ``fit_info`` (when the model has a ``fit_info`` dict)
        under ``"output_scale"`` with the factor.

    Returns
    -------
    operator
        Same class, reset state; metadata carried over (see the module).

    Raises
    ------
    ValueError
        For a factor that is not finite and positive, or an operator class not in :data:`SCALABLE`.
    """
    factor = positive_float("factor", factor)
    new = _scaled(model, factor)
    mine = vars(new)
    for name, value in vars(model).items():
        if name not in mine:
            setattr(new, name, copy.deepcopy(value))
    if quantity is not None:
        if not isinstance(quantity, str) or not quantity.strip():
            raise ValueError(f"quantity must be None or a non-empty string such as 'strain', got {shown(quantity)}")
        new.output_quantity = quantity
    if unit is not None:
        if not isinstance(unit, str):
            raise ValueError(f"unit must be None or a unit string such as '-', got {shown(unit)}")
        new.output_unit = unit
    info = getattr(model, "fit_info", None)
    if isinstance(info, dict):
        new.fit_info = {**copy.deepcopy(info), "output_scale": {
            "factor": factor, "from_unit": getattr(model, "output_unit", ""), "to_unit": getattr(new, "output_unit", ""),
            "note": note or ""}}
    if quantity == "strain":
        _warn_implausible_strain(new, note)
    return new


def _warn_implausible_strain(model: Any, note: str | None) -> None:
    """Warn (:class:`~exudyn_atcm.errors.InputRangeWarning`) when a model scaled to a strain reaches,
    over a major loop of its input range, more than the drive's plausible free strain
    (:data:`~exudyn_atcm.physical_bounds.PLAUSIBLE_STRAIN`): a displacement in µm declared as m, say."""
    bounds = getattr(model, "input_range", None)
    if bounds is None or getattr(model, "time_dependent", False):  # a lag's output needs the time: not checked
        return
    ramp = np.linspace(float(bounds[0]), float(bounds[1]), 101)
    largest = float(np.max(np.abs(model.apply(np.concatenate([ramp, ramp[::-1]]), check_range=False))))
    if largest > PLAUSIBLE_STRAIN:
        warnings.warn(
            f"the model converted to a free strain ({note or 'scaled output'}) reaches a strain of {largest:.3g} "
            f"over its input range {float(bounds[0]):g} ... {float(bounds[1]):g}, more than {PLAUSIBLE_STRAIN:g} "
            "(1 %); an MFC reaches about 1e-3 (the paper's: 1.38e-3 at 1500 V). Check the output unit (a displacement "
            "in µm declared as m?) and the length it is divided by", InputRangeWarning, stacklevel=3)
