"""The electrical drive of the active layer: voltage program and voltage-to-strain law."""

from __future__ import annotations

import math
import numbers
import warnings
from typing import Any, Callable, Union

import numpy as np

from .._checks import finite_float, positive_float, shown
from ..physical_bounds import KV_SUSPECT_FRACTION, MFC_P1_RATED_RANGE, PLAUSIBLE_STRAIN, check_physical
from ..errors import InputRangeWarning, SetupWarning, annotate
from ..io.units import is_length

VoltageProgram = Union[float, Callable[[float], float]]

_OPERATOR_METHODS = ("evaluate", "commit", "reset", "apply", "checkpoint", "restore")





def _is_controller(value: Any) -> bool:
    """A controller of :mod:`exudyn_atcm.model.control`'s protocol (duck-typed)."""
    return all(callable(getattr(value, m, None)) for m in ("voltage_at", "observe", "reset"))


class PiezoDrive:
    """Voltage program of the MFC layer and its map to the free actuation strain.

    Parameters
    ----------
    voltage : float, callable or controller
        Applied voltage ``U`` [V]: a constant number, a callable of time ``t`` [s] returning
        volts (every object of :mod:`exudyn_atcm.model.signals` qualifies), or a controller (an
        object with ``voltage_at(t)``, ``observe(t, tip_deflection)`` and ``reset()``, e.g.
        :class:`exudyn_atcm.model.control.PIDController`; see :mod:`exudyn_atcm.model.control` for the
        protocol) that sets the voltage from the simulated tip deflection during the run.
    d33 : float, optional
        Piezoelectric constant [m/V] (= C/N), > 0 and at most 1e-7 (no material comes near:
        :data:`~exudyn_atcm.physical_bounds.PHYSICAL_LIMITS`).  Default 460e-12 (MFC P1, high field).
        Used only without ``hysteresis``.
    electrode_spacing : float, optional
        Spacing of the interdigitated electrodes ``t_IDE`` [m], > 0.  Default 0.5e-3.
        Used only without ``hysteresis``.
    hysteresis : hysteresis operator, optional
        Operator mapping voltage [V] to free strain [-] (e.g.
        :func:`exudyn_atcm.model.parameter_sets.paper_strain_preisach`).  It must provide
        ``evaluate``, ``commit``, ``reset``, ``apply``, ``checkpoint`` and ``restore``.
        Without it, the free strain is linear: ``d33 U / electrode_spacing`` (Eq. 3).
        The operator's output must be the free strain: an operator whose
        ``output_quantity`` is set to anything but ``"strain"`` (e.g. the paper's stroke
        model :func:`~exudyn_atcm.model.parameter_sets.paper_stroke_preisach`, ``"stroke"``, or
        a model fitted on a displacement, ``"displacement"``), or whose ``output_unit`` is a
        length, is refused with how to convert it
        (:func:`~exudyn_atcm.model.strain_conversion.model_to_strain`); ``None`` (not stated)
        is accepted, with a :class:`~exudyn_atcm.errors.SetupWarning` for a fitted operator
        (``fit_info`` set) whose output unit is unknown.
    rated_range : (float, float) or None, optional
        Rated voltage range of the MFC [V]; default ``(-500, 1500)``, the MFC P1 type.
        Voltages outside it, or outside the operator's ``input_range`` (where its output
        saturates, or for a fitted operator the range it was fitted on, beyond which it
        extrapolates), give one ``InputRangeWarning`` per run; so does a non-zero program whose
        peak ``|U|`` stays below :data:`KV_SUSPECT_FRACTION` of the rating's largest magnitude
        (3 V for the default: a program written in kV).  ``None``: no rating check.

    Notes
    -----
    Each cell's motor stroke is the free strain times the cell length (Eq. 2), so one
    strain-valued operator serves cells of any length.  The simulation resets the operator
    at its start and commits it only on accepted solver steps.
    """

    def __init__(
        self,
        voltage: VoltageProgram,
        d33: float = 460e-12,
        electrode_spacing: float = 0.5e-3,
        hysteresis: Any = None,
        rated_range: tuple[float, float] | None = MFC_P1_RATED_RANGE,
    ) -> None:
        self.voltage = voltage
        self.d33 = check_physical("d33", positive_float("d33", d33), "PiezoDrive")
        self.electrode_spacing = check_physical("electrode_spacing", positive_float("electrode_spacing", electrode_spacing),
                                                "PiezoDrive")
        if hysteresis is not None:
            missing = [m for m in _OPERATOR_METHODS if not callable(getattr(hysteresis, m, None))]
            if missing:
                raise ValueError(
                    f"hysteresis must be a hysteresis operator with methods {', '.join(_OPERATOR_METHODS)}; "
                    f"got {type(hysteresis).__name__!s} lacking {', '.join(missing)}"
                )
            _check_output_quantity(hysteresis)
            _check_strain_magnitude(_output_bound(hysteresis), "the hysteresis operator's output range", stacklevel=4)
        self.hysteresis = hysteresis
        if rated_range is None:
            self.rated_range = None
        else:
            try:
                low, high = rated_range
            except (TypeError, ValueError):
                raise ValueError(f"rated_range must be None or a pair (U_min, U_max) [V], got {shown(rated_range)}") from None
            low, high = finite_float("rated_range[0]", low), finite_float("rated_range[1]", high)
            if not low < high:
                raise ValueError(f"rated_range must have U_min < U_max, got {shown(rated_range)}")
            self.rated_range = (low, high)

    @property
    def voltage(self) -> VoltageProgram:
        """The voltage program [V]: a number, a callable of time ``t`` [s] (a signal of
        :mod:`exudyn_atcm.model.signals`, a function) or a controller.  It may be set again after
        construction (checked as at construction; the runs and the step choice all read it)."""
        return self._voltage

    @voltage.setter
    def voltage(self, voltage: VoltageProgram) -> None:
        if _is_controller(voltage):
            controller, function = voltage, voltage.voltage_at
        elif callable(voltage):
            controller, function = None, voltage
        elif isinstance(voltage, numbers.Real) and not isinstance(voltage, bool):
            if not math.isfinite(float(voltage)):
                raise ValueError(f"voltage must be a finite number [V] or a callable of time, got {shown(voltage)}")
            controller, function = None, None
        else:
            raise ValueError(
                f"voltage must be a finite number [V] or a callable of time t [s], got {shown(voltage)}"
            )
        # until 2026-11-29 ``voltage`` was a plain attribute and ``voltage_at`` kept the program given at
        # construction: a program set afterwards reached the step choice's stand-in but not the run
        self._voltage, self._voltage_fn, self.controller = voltage, function, controller

    def voltage_at(self, t: float) -> float:
        """Voltage [V] at time ``t`` [s] from the program (or the controller).

        Raises
        ------
        ValueError
            If the program returns anything but a finite real number (``None``, a string such as
            ``"5"``, a bool, an array of several values, NaN): the message names the program, the
            value and ``t``.
        Exception
            Whatever the program itself raises, as it is (its type and message), with a note
            naming the program and ``t`` (:func:`~exudyn_atcm.errors.annotate`).
        """
        if self._voltage_fn is None:
            return float(self.voltage)
        try:
            raw = self._voltage_fn(t)
        except Exception as exc:  # the user's code: its own error, with where it came from
            annotate(exc, f"raised by {self.program_name()} at t = {t:.9g} s")
            raise
        if isinstance(raw, float):  # the usual case first (numpy floats included)
            value = float(raw)
        else:
            value = self._number(raw, t)
        if not math.isfinite(value):
            raise ValueError(f"{self.program_name()} returned {value!r} at t = {t!r} s; it must return finite volts [V]")
        return value

    def _number(self, raw: Any, t: float) -> float:
        """``raw`` as volts if it is a real number (or a 0-d numeric array), else a ``ValueError`` naming the program."""
        if isinstance(raw, numbers.Real) and not isinstance(raw, (bool, np.bool_)):
            return float(raw)
        if isinstance(raw, np.ndarray) and raw.ndim == 0 and raw.dtype.kind in "iuf":
            return float(raw)
        raise ValueError(
            f"{self.program_name()} returned {raw!r} ({type(raw).__name__}) at t = {t!r} s; a voltage program must "
            "return a finite number of volts [V] (a float), as PiezoDrive(voltage=...) takes one: a string such as "
            "'5', None or a bool is not taken as a voltage")

    def program_name(self) -> str:
        """The voltage program in messages: ``"the voltage program 'ramp'"``, ``"the controller PIDController"``."""
        if self.controller is not None:
            return f"the controller {type(self.controller).__name__}"
        program = self.voltage
        if not callable(program):
            return f"the constant voltage {program!r} V"
        name = getattr(program, "__qualname__", None)  # functions and methods; not objects with __call__
        if isinstance(name, str):
            return f"the voltage program {name!r}"
        return f"the voltage program {type(program).__name__}"

    def linear_strain(self, voltage: float) -> float:
        """Free strain without hysteresis, ``d33 U / t_IDE`` (Eq. 3) [-]."""
        return self.d33 * voltage / self.electrode_spacing

    def static_strain(self, voltage: float) -> float:
        """Free strain [-] reached at ``voltage`` [V] by a monotone ramp from the operator's reset state.

        Without hysteresis this is :meth:`linear_strain`.  A rate-independent operator
        gives the same output for any monotone path from the reset state to ``voltage``,
        so the ramp is applied as one input.  An operator with creep or a rate lag
        (``static_output``, :class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`) gives the fully
        crept strain: the voltage held for ever.
        """
        if self.hysteresis is None:
            return self.linear_strain(voltage)
        static = getattr(self.hysteresis, "static_output", None)
        if callable(static):
            return float(static(float(voltage)))
        return float(self.hysteresis.apply([float(voltage)])[-1])

    def check_voltage_range(self, u_low: float, u_high: float, *, what: str | None = None,
                            stacklevel: int = 4) -> None:
        """Warn once if voltages in ``[u_low, u_high]`` [V] leave the operator's input range or the rating.

        Outside the hysteresis operator's ``input_range`` its output saturates (5000 V gives
        the 1500 V answer) or, for a fitted operator (its ``fitted_range``), extrapolates beyond
        the data it was fitted on; outside :attr:`rated_range` the MFC is driven beyond its rating.
        One ``RuntimeWarning`` lists each range and how far the voltages go beyond it; ``what``
        (e.g. ``"drive 'crank'"``) names the drive in it.  A second ``RuntimeWarning`` is given
        when a non-zero program peaks below :data:`KV_SUSPECT_FRACTION` of the rating's largest
        magnitude (below 3 V for the MFC P1: most likely written in kV).
        """
        problems = []
        op_range = getattr(self.hysteresis, "input_range", None) if self.hysteresis is not None else None
        if op_range is not None:
            text = _outside(u_low, u_high, op_range)
            if text:
                fitted = getattr(self.hysteresis, "operator", self.hysteresis)  # the operator of a WithDynamics
                if getattr(fitted, "fitted_range", None) is not None:
                    problems.append(
                        f"{text} the range {op_range[0]:g} ... {op_range[1]:g} V the hysteresis operator was fitted "
                        "on, beyond which it extrapolates from data it never saw (saturates or goes on linearly, "
                        "not as the actuator does); measure the wider range and fit again"
                    )
                else:
                    problems.append(
                        f"{text} the hysteresis operator's input range {op_range[0]:g} ... {op_range[1]:g} V, "
                        "where its output saturates (voltages beyond it give the strain at its limit)"
                    )
        if self.rated_range is not None:
            text = _outside(u_low, u_high, self.rated_range)
            if text:
                problems.append(
                    f"{text} the MFC's rated range {self.rated_range[0]:g} ... {self.rated_range[1]:g} V "
                    "(rated_range of the PiezoDrive)"
                )
        if problems:
            warnings.warn(
                (f"{what}: " if what else "") + f"the voltage program spans {u_low:g} ... {u_high:g} V: "
                + "; ".join(problems),
                InputRangeWarning,
                stacklevel=stacklevel,
            )
        self._check_tiny_program(u_low, u_high, what, stacklevel + 1)

    def _check_tiny_program(self, u_low: float, u_high: float, what: str | None, stacklevel: int) -> None:
        """Warn when a non-zero program peaks below :data:`KV_SUSPECT_FRACTION` of the rating (kV?).

        Not for a drive set by a controller (its voltage is computed, not written by the user)
        nor without a rated range; a program that is zero throughout stays silent.
        """
        if self.rated_range is None or self.controller is not None:
            return
        peak = max(abs(u_low), abs(u_high))
        rated = max(abs(self.rated_range[0]), abs(self.rated_range[1]))
        limit = KV_SUSPECT_FRACTION * rated
        if 0.0 < peak < limit:
            warnings.warn(
                (f"{what}: " if what else "")
                + f"the voltage program peaks at |U| = {peak:.4g} V, below {limit:.3g} V "
                f"({100 * KV_SUSPECT_FRACTION:g} % of the largest rated voltage; rated range "
                f"{self.rated_range[0]:g} ... {self.rated_range[1]:g} V), so its response is about "
                f"{peak / rated:.2g} of that at the rating. The drive takes volts: if the program is in kV, "
                "multiply it by 1000",
                InputRangeWarning,
                stacklevel=stacklevel,
            )

    def check_strain(self, strain_low: float, strain_high: float, *, what: str | None = None,
                     stacklevel: int = 5) -> None:
        """Warn if free strains in ``[strain_low, strain_high]`` exceed :data:`PLAUSIBLE_STRAIN` in magnitude.

        ``what`` (e.g. ``"drive 'crank'"``) names the drive in the warning.
        """
        _check_strain_magnitude(max(abs(strain_low), abs(strain_high)),
                                f"the free strain of {what}" if what else "the free strain of the run", stacklevel=stacklevel)

    def __repr__(self) -> str:
        hyst = "None" if self.hysteresis is None else type(self.hysteresis).__name__
        return (
            f"PiezoDrive(voltage={self.voltage!r}, d33={self.d33!r}, "
            f"electrode_spacing={self.electrode_spacing!r}, hysteresis={hyst})"
        )


def _outside(u_low: float, u_high: float, bounds: tuple[float, float]) -> str:
    """``"reach 5000 V, 3500 V above"``-style text, or ``""`` when inside ``bounds``."""
    parts = []
    if u_high > bounds[1]:
        parts.append(f"reach {u_high:g} V, {u_high - bounds[1]:g} V above")
    if u_low < bounds[0]:
        parts.append(f"reach {u_low:g} V, {bounds[0] - u_low:g} V below")
    return " and ".join(parts) and "they " + " and ".join(parts)


#: How to turn a displacement-valued model into the strain a drive takes (named in the refusal).
CONVERSION_HINT = (
    "convert it with exudyn_atcm.model.strain_conversion.model_to_strain(model, gauge_length=l0) (a free patch's "
    "elongation measured over l0 [m]; a paper-style cell stroke: l0 = the cell length) or model_to_strain(model, "
    "laminate=actuator.laminate, length=s) (a free bender's deflection at arc length s [m]), or convert the record "
    "with record_to_strain(record, ...) and identify the model again"
)


def _check_output_quantity(operator: Any) -> None:
    """Refuse an operator that states a non-strain output or a length unit; warn about a fitted one of unknown unit."""
    quantity = getattr(operator, "output_quantity", None)
    unit = getattr(operator, "output_unit", "") or ""
    if quantity is not None and quantity != "strain":
        raise ValueError(
            f"hysteresis must give the free strain [-] of the active layer, got an operator whose output is "
            f"{quantity!r}" + (f" [{unit}]" if unit else "") + ". The drive turns strain into each cell's stroke "
            "itself (stroke = strain x cell length); use a strain-valued operator (e.g. "
            "exudyn_atcm.model.parameter_sets.paper_strain_preisach() instead of paper_stroke_preisach()), or "
            + CONVERSION_HINT
        )
    if quantity is None and is_length(unit):
        raise ValueError(
            f"hysteresis must give the free strain [-] of the active layer, got an operator whose output unit is "
            f"{unit!r}, a length: it was identified on a displacement; " + CONVERSION_HINT
        )
    if quantity is None and not unit and getattr(operator, "fit_info", None) is not None:
        warnings.warn(
            "the hysteresis operator was fitted on a record whose output unit is unknown; the drive takes its output "
            "as the free strain [-]. If the record was a strain, say so (operator.with_output_quantity('strain')); "
            "if it was a displacement, give its unit (read_record(..., units={'output': 'um'})) and "
            + CONVERSION_HINT,
            SetupWarning,
            stacklevel=3,
        )


def _output_bound(operator: Any) -> float:
    """Largest output magnitude an operator states (``y_min``/``y_max`` or ``output_range``), else 0."""
    bounds = getattr(operator, "output_range", None)
    if bounds is None:
        low, high = getattr(operator, "y_min", None), getattr(operator, "y_max", None)
        if low is None or high is None:
            return 0.0
        bounds = (low, high)
    try:
        return max(abs(float(bounds[0])), abs(float(bounds[1])))
    except (TypeError, ValueError, IndexError):
        return 0.0


def _check_strain_magnitude(value: float, what: str, stacklevel: int) -> None:
    if value > PLAUSIBLE_STRAIN:
        warnings.warn(
            f"{what} reaches a free strain of {value:.3g}, more than {PLAUSIBLE_STRAIN:g} (1 %); piezo "
            "layers reach about 1e-3 (the paper's MFC: 1.38e-3 at 1500 V). Check the units: the drive "
            "expects strain [-], not a stroke in micrometres or a strain in percent",
            InputRangeWarning,
            stacklevel=stacklevel,
        )
