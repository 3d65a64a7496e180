"""The interface shared by every rate-independent hysteresis operator."""

from __future__ import annotations

import abc
import copy
import math
import numbers
import warnings
from typing import Any

import numpy as np

from .model_files import SavableModel  # the save() method of every operator
from .._checks import finite_array, shown
from ..errors import InputRangeWarning
from ..io.units import SI_SCALE

#: Output units read as a length (a displacement or stroke), in SI and the usual sub-units.
LENGTH_UNITS = frozenset({"m", "mm", "um", "µm", "μm", "nm", "cm", "micron", "microns"})

#: What a fitted model's output may be (``output_quantity``): a free strain [-], a displacement
#: or a stroke (a length).
OUTPUT_QUANTITIES = ("strain", "displacement", "stroke")


def known_output_units() -> tuple[str, ...]:
    """Output units the package knows: the lengths (:data:`LENGTH_UNITS`) and the strains the record
    readers convert (:data:`~exudyn_atcm.io.units.SI_SCALE`), ``"-"`` and ``""`` (not stated)."""
    strains = [unit for unit, (_, si) in SI_SCALE.items() if si == "-"]
    return ("", *sorted(LENGTH_UNITS), *strains)


def quantity_from_unit(unit: str, quantity: str | None = None) -> str | None:
    """The output quantity a fit records: ``quantity`` if given, else read from ``unit``.

    A length unit (``"m"``, ``"mm"``, ``"um"``, ...) gives ``"displacement"``; any other unit,
    ``"-"`` or ``""`` gives ``None`` (not stated: a dimensionless output may be a strain or a
    normalised output).  A stated ``quantity`` must be one of :data:`OUTPUT_QUANTITIES`, and
    ``"strain"`` (a dimensionless quantity) is refused with a length unit.

    Raises
    ------
    ValueError
        For a ``quantity`` that is not ``None`` or one of :data:`OUTPUT_QUANTITIES`, or a strain in a
        length unit.
    """
    if not isinstance(unit, str):
        raise ValueError(f"output_unit must be a string such as 'm', '-' or '', got {shown(unit)}")
    length = unit.strip() in LENGTH_UNITS
    if quantity is None:
        return "displacement" if length else None
    if quantity not in OUTPUT_QUANTITIES:
        raise ValueError(f"output_quantity must be None or one of {', '.join(repr(q) for q in OUTPUT_QUANTITIES)}, "
                         f"got {shown(quantity)}")
    if quantity == "strain" and length:
        raise ValueError(f"output_quantity 'strain' is dimensionless, but output_unit is the length {unit!r}: a "
                         "displacement measured over a length is a strain only after dividing by that length")
    return quantity


def json_safe(value: Any) -> Any:
    """``value`` with numpy scalars and arrays as Python numbers and lists (for :attr:`fit_info`)."""
    if isinstance(value, dict):
        return {str(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, np.ndarray):
        return json_safe(value.tolist())
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, (np.floating, float)):
        v = float(value)
        return v if math.isfinite(v) else None
    return value


def check_input(u: Any) -> float:
    """Return the operator input ``u`` as a float; raise ``ValueError`` if it is not finite."""
    if isinstance(u, (bool, np.bool_)) or not isinstance(u, (numbers.Real, np.floating, np.integer)):
        raise ValueError(f"u must be a finite real number, got {shown(u)}")
    value = float(u)
    if not math.isfinite(value):
        raise ValueError(f"u must be a finite real number, got {shown(u)}")
    return value


class HysteresisOperator(SavableModel, abc.ABC):
    """A rate-independent hysteresis operator with an explicit, committed memory.

    The memory changes only in :meth:`commit`, so :meth:`evaluate` can be called any number
    of times for trial inputs (inside the Newton iterations of a solver step) and
    :meth:`commit` once the step is accepted.  Inputs and outputs are unit-free floats
    (volts in and strain out when the operator models a piezo layer).
    """

    #: What the output is: ``"strain"`` [-], ``"stroke"`` [m], ... or ``None`` when not stated.
    #: The parameter sets state it; :class:`~exudyn_atcm.model.drive.PiezoDrive` accepts ``"strain"``
    #: or ``None`` only.  Set it with :meth:`with_output_quantity`.
    output_quantity: str | None = None
    #: Unit of the output: ``"-"`` (strain), ``"m"`` (displacement), ``""`` (not stated).  Set by the fits.
    output_unit: str = ""
    #: ``(u_low, u_high)``: the input range of the samples a fitted model was fitted to (``None``
    #: for a model that was not fitted).  Beyond it a fitted model extrapolates.
    fitted_range: tuple[float, float] | None = None
    #: What the fit did (JSON-serialisable: method, settings, sample counts, fitted range,
    #: output unit and quantity); ``None`` for a model that was not fitted.
    fit_info: dict | None = None

    @property
    def saturation_range(self) -> tuple[float, float] | None:
        """``(u_low, u_high)``: beyond it the output saturates; ``None`` if the operator has no such range."""
        return None

    @property
    def input_range(self) -> tuple[float, float] | None:
        """Where the model is valid: :attr:`fitted_range` for a fitted model, else :attr:`saturation_range`.

        A fitted model extrapolates beyond its fitted range (:meth:`apply` warns); a model
        that was not fitted saturates beyond its own range (or has none: ``None``).
        """
        return self.fitted_range if self.fitted_range is not None else self.saturation_range

    def set_fit_metadata(self, fitted_range: tuple[float, float], fit_info: dict, output_unit: str = "",
                         output_quantity: str | None = None) -> "HysteresisOperator":
        """Record what a fit found (every fit calls it): the fitted input range, the output unit and
        quantity (:func:`quantity_from_unit`) and ``fit_info``; returns the operator."""
        low, high = (float(v) for v in fitted_range)
        if not (math.isfinite(low) and math.isfinite(high) and high >= low):
            raise ValueError(f"fitted_range must be finite with high >= low, got {shown(fitted_range)}")
        quantity = quantity_from_unit(output_unit, output_quantity)
        self.fitted_range = (low, high)
        self.output_unit = output_unit
        self.output_quantity = quantity
        self.fit_info = json_safe({**fit_info, "fitted_range": [low, high], "output_unit": output_unit,
                                   "output_quantity": quantity})
        return self

    def check_fitted_range(self, low: float, high: float, *, stacklevel: int = 3) -> None:
        """Warn (:class:`~exudyn_atcm.errors.InputRangeWarning`) if inputs in ``[low, high]`` leave
        the :attr:`fitted_range` of a fitted model (nothing for a model that was not fitted)."""
        fitted = self.fitted_range
        if fitted is None:
            return
        f_lo, f_hi = fitted
        slack = 1e-9 * max(f_hi - f_lo, abs(f_lo), abs(f_hi), 1e-300)
        beyond = []
        if high > f_hi + slack:
            beyond.append(f"up to {high:g}, {high - f_hi:g} above")
        if low < f_lo - slack:
            beyond.append(f"down to {low:g}, {f_lo - low:g} below")
        if beyond:
            warnings.warn(
                f"{type(self).__name__} was fitted on inputs {f_lo:g} ... {f_hi:g}; the inputs go "
                + " and ".join(beyond) + ": there the model extrapolates beyond the data it was fitted to "
                "(measure the wider range and fit again, or keep the input within the fitted range)",
                InputRangeWarning, stacklevel=stacklevel)

    def with_output_quantity(self, quantity: str | None) -> "HysteresisOperator":
        """Set :attr:`output_quantity` (e.g. ``"strain"`` or ``"stroke"``) and return the operator."""
        if quantity is not None and (not isinstance(quantity, str) or not quantity.strip()):
            raise ValueError(f"quantity must be None or a non-empty string such as 'strain', got {shown(quantity)}")
        self.output_quantity = quantity
        return self

    @abc.abstractmethod
    def evaluate(self, u: float) -> float:
        """Output for input ``u`` from the committed memory, without changing it."""

    @abc.abstractmethod
    def commit(self, u: float) -> float:
        """Accept input ``u``: update the memory and return the output."""

    @abc.abstractmethod
    def reset(self) -> None:
        """Return to the documented initial state of the model."""

    @abc.abstractmethod
    def checkpoint(self) -> Any:
        """Return an opaque snapshot of the memory, for :meth:`restore`."""

    @abc.abstractmethod
    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint` of this operator."""

    def inverse(self, input_range: tuple[float, float] | None = None) -> "HysteresisOperator":
        """The inverse operator: its input is a wanted output, its output the input that produces it.

        The one convention of every operator class of the package: an operator (this interface)
        starting, like this one after :meth:`reset`, from the reset state, whose memory follows
        this operator's for the inputs it returns.  ``input_range`` bounds the inputs it may
        return (outputs beyond reach are clipped with an
        :class:`~exudyn_atcm.errors.OutOfReachWarning` on commit); default: the range the operator
        declares (:func:`~exudyn_atcm.hysteresis.bisection.default_input_range`).

        This default raises ``NotImplementedError``; a class outside the package whose output
        does not decrease with the input gets a bisection inverse from
        :func:`~exudyn_atcm.hysteresis.inverse_operator` without implementing it.
        """
        raise NotImplementedError(f"{type(self).__name__} does not implement inverse(); for an operator whose output "
                                  "does not decrease with its input use exudyn_atcm.hysteresis.inverse_operator(model, "
                                  "input_range) (bisection)")

    @property
    @abc.abstractmethod
    def output(self) -> float:
        """Output for the last committed input (the initial output after :meth:`reset`)."""

    def apply(self, u_series: Any, *, check_range: bool = True) -> np.ndarray:
        """Outputs for a whole input series, starting from the reset state.

        The operator's own memory is left as it was: the series is run from a reset copy.
        A fitted model warns once (:class:`~exudyn_atcm.errors.InputRangeWarning`, with the
        range and the farthest input) when the series leaves its :attr:`fitted_range`; a
        model's own saturation is part of its definition and is not warned about here
        (:class:`~exudyn_atcm.model.drive.PiezoDrive` says it for a simulation).

        Parameters
        ----------
        u_series : array_like
            1-D sequence of finite inputs, in order.
        check_range : bool, optional
            ``False`` skips the fitted-range warning (for a caller that says it itself, as the
            fit reports do for their held-out part).

        Returns
        -------
        numpy.ndarray
            One output per input.
        """
        inputs = finite_array("u_series", u_series, min_length=0)
        if check_range and inputs.size and self.fitted_range is not None:
            self.check_fitted_range(float(inputs.min()), float(inputs.max()))
        saved = self.checkpoint()
        try:
            self.reset()
            commit = self.commit
            return np.array([commit(u) for u in inputs.tolist()], dtype=float)
        finally:
            self.restore(saved)


def forward_model(model: Any, input_range: tuple[float, float] | None, reset: bool = True) -> Any:
    """The inverse of an inverse: a copy of its forward ``model`` (at its reset state when ``reset``).

    Raises
    ------
    ValueError
        If ``input_range`` is given (the forward model takes any input).
    """
    if input_range is not None:
        raise ValueError(f"input_range must be None for the inverse of an inverse (the forward model), got "
                         f"{input_range!r}")
    forward = copy.deepcopy(model)
    if reset:
        forward.reset()
    return forward
