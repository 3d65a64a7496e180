"""The electrical drive of the active layer: voltage program and voltage-to-strain law."""

from __future__ import annotations

import math
import numbers
from typing import Any, Callable, Union

from ._checks import positive_float

VoltageProgram = Union[float, Callable[[float], float]]

_OPERATOR_METHODS = ("evaluate", "commit", "reset", "apply", "checkpoint", "restore")


def _is_controller(value: Any) -> bool:
    """A controller of :mod:`exudyn_atcm.control`'s protocol (duck-typed)."""
    return all(callable(getattr(value, m, None)) for m in ("voltage_at", "observe", "reset"))


class PiezoDrive:
    """Voltage program of the MFC layer and its map to the free actuation strain.

    Parameters
    ----------
    voltage : float, callable or controller
        Applied voltage ``U`` [V]: a constant number, a callable of time ``t`` [s] returning
        volts (every object of :mod:`exudyn_atcm.signals` qualifies), or a controller (an
        object with ``voltage_at(t)``, ``observe(t, tip_deflection)`` and ``reset()``, e.g.
        :class:`exudyn_atcm.control.PIDController`; see :mod:`exudyn_atcm.control` for the
        protocol) that sets the voltage from the simulated tip deflection during the run.
    d33 : float, optional
        Piezoelectric constant [m/V] (= C/N), > 0.  Default 460e-12 (MFC P1, high field).
        Used only without ``hysteresis``.
    electrode_spacing : float, optional
        Spacing of the interdigitated electrodes ``t_IDE`` [m], > 0.  Default 0.5e-3.
        Used only without ``hysteresis``.
    hysteresis : hysteresis operator, optional
        Operator mapping voltage [V] to free strain [-] (e.g.
        :func:`exudyn_atcm.parameter_sets.paper_strain_preisach`).  It must provide
        ``evaluate``, ``commit``, ``reset``, ``apply``, ``checkpoint`` and ``restore``.
        Without it, the free strain is linear: ``d33 U / electrode_spacing`` (Eq. 3).

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
    ) -> None:
        self.controller = None
        if _is_controller(voltage):
            self.controller = voltage
            self._voltage_fn = voltage.voltage_at
        elif callable(voltage):
            self._voltage_fn = voltage
        elif isinstance(voltage, numbers.Real) and not isinstance(voltage, bool):
            value = float(voltage)
            if not math.isfinite(value):
                raise ValueError(f"voltage must be a finite number [V] or a callable of time, got {voltage!r}")
            self._voltage_fn = None
        else:
            raise ValueError(
                f"voltage must be a finite number [V] or a callable of time t [s], got {voltage!r}"
            )
        self.voltage = voltage
        self.d33 = positive_float("d33", d33)
        self.electrode_spacing = positive_float("electrode_spacing", electrode_spacing)
        if hysteresis is not None:
            missing = [m for m in _OPERATOR_METHODS if not callable(getattr(hysteresis, m, None))]
            if missing:
                raise ValueError(
                    f"hysteresis must be a hysteresis operator with methods {', '.join(_OPERATOR_METHODS)}; "
                    f"got {type(hysteresis).__name__!s} lacking {', '.join(missing)}"
                )
        self.hysteresis = hysteresis

    def voltage_at(self, t: float) -> float:
        """Voltage [V] at time ``t`` [s]; raises ``ValueError`` if the program returns a non-finite value."""
        if self._voltage_fn is None:
            return float(self.voltage)
        value = float(self._voltage_fn(t))
        if not math.isfinite(value):
            raise ValueError(f"voltage program returned {value!r} at t = {t!r} s; it must return finite volts")
        return value

    def linear_strain(self, voltage: float) -> float:
        """Free strain without hysteresis, ``d33 U / t_IDE`` (Eq. 3) [-]."""
        return self.d33 * voltage / self.electrode_spacing

    def static_strain(self, voltage: float) -> float:
        """Free strain [-] reached at ``voltage`` [V] by a monotone ramp from the operator's reset state.

        Without hysteresis this is :meth:`linear_strain`.  A rate-independent operator
        gives the same output for any monotone path from the reset state to ``voltage``,
        so the ramp is applied as one input.
        """
        if self.hysteresis is None:
            return self.linear_strain(voltage)
        return float(self.hysteresis.apply([float(voltage)])[-1])

    def __repr__(self) -> str:
        hyst = "None" if self.hysteresis is None else type(self.hysteresis).__name__
        return (
            f"PiezoDrive(voltage={self.voltage!r}, d33={self.d33!r}, "
            f"electrode_spacing={self.electrode_spacing!r}, hysteresis={hyst})"
        )
