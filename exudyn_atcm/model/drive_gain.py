"""The small-signal gain of a drive: its free strain's local slope ``d eps / d U`` on a hysteresis branch.

A linear model of a hysteretic actuator is valid for small signals about one state of the
operator's memory, and its voltage gain is the slope of the branch the state is on.  Three
states are offered (:data:`BRANCHES`), each a history of the input from the operator's reset
state:

``"ascending"``
    The voltage rose from the lowest input ``U_lo`` to ``U``; the signal continues upwards:
    ``(eps(U + dU) - eps(U)) / dU`` on the ascending branch through ``U``.
``"descending"``
    The voltage fell from the highest input ``U_hi`` to ``U``; the signal continues downwards:
    ``(eps(U) - eps(U - dU)) / dU`` on the descending branch.
``"reversal"``
    The ascending state, after which the voltage turns down: the slope right after a reversal.  For a
    Preisach operator with a bounded density it starts at zero and grows with the amplitude (the
    minor loop's height grows with the square of its amplitude, Madelung's rules); for a
    Prandtl-Ishlinskii operator it is the weight ``p0`` of the input itself.

``U_lo``/``U_hi`` are the operator's :attr:`input_range` (its saturation or fitted range), else the
drive's ``rated_range``.  ``dU`` (``voltage_step``) is the signal amplitude the slope is taken over:
for a discrete operator (relays) the slope is a secant over the relays the step crosses, which is
what a signal of that size sees.  Without hysteresis every branch has the slope ``d33 / t_IDE``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
from .._checks import shown
from ..errors import AccuracyWarning

__all__ = ["BRANCHES", "DriveGain", "drive_gain", "check_branch"]

#: The branch names of :func:`drive_gain`.
BRANCHES = ("ascending", "descending", "reversal")


@dataclass(frozen=True)
class DriveGain:
    """A drive's state and small-signal gain at a voltage.

    Attributes
    ----------
    voltage : float
        The operating voltage [V].
    strain : float
        The free strain at that state [-] (on the branch's history).
    gain : float
        ``d eps / d U`` [1/V] for a small signal of size ``voltage_step`` about the state.
    branch : str
        One of :data:`BRANCHES`.
    """

    voltage: float
    strain: float
    gain: float
    branch: str


def check_branch(branch: Any) -> str:
    """``branch`` if it is one of :data:`BRANCHES`, else a ``ValueError`` naming the allowed ones."""
    if not isinstance(branch, str) or branch not in BRANCHES:
        raise ValueError(f"branch must be one of {', '.join(map(repr, BRANCHES))}, got {shown(branch)}")
    return branch


def _input_limits(drive: Any, name: str) -> tuple[float, float]:
    limits = getattr(drive.hysteresis, "input_range", None)
    if limits is None:
        limits = drive.rated_range
    if limits is None:
        raise ValueError(f"drive {name!r}: its hysteresis operator declares no input_range and the drive has no "
                         "rated_range, so the ascending and descending branches have no start; give the PiezoDrive "
                         "a rated_range=(U_min, U_max)")
    return float(limits[0]), float(limits[1])


def drive_gain(drive: Any, voltage: float, branch: str = "ascending", *, voltage_step: float = 1.0,
               name: str = "drive", stacklevel: int = 2) -> DriveGain:
    """The drive's free strain and its small-signal gain ``d eps/d U`` [1/V] at ``voltage`` [V] on ``branch``.

    Parameters
    ----------
    drive : PiezoDrive
    voltage : float
        Operating voltage [V].
    branch : str, optional
        ``"ascending"`` (default), ``"descending"`` or ``"reversal"`` (module docstring).
    voltage_step : float, optional
        Signal amplitude [V] the slope is taken over (> 0; default 1 V).
    name : str, optional
        The drive's name in messages.

    Raises
    ------
    ValueError
        For an unknown branch, a non-positive step, a voltage outside the branch's input limits, or an
        operator with creep or rate dynamics (its small-signal gain depends on the frequency).
    """
    branch = check_branch(branch)
    voltage, step = float(voltage), float(voltage_step)
    if not (math.isfinite(step) and step > 0.0):
        raise ValueError(f"voltage_step must be a finite voltage > 0 [V], got {shown(voltage_step)}")
    op = drive.hysteresis
    if op is None:
        slope = drive.d33 / drive.electrode_spacing
        return DriveGain(voltage, drive.linear_strain(voltage), slope, branch)
    if callable(getattr(op, "static_output", None)):
        raise ValueError(f"drive {name!r}: its operator {type(op).__name__} has creep or rate dynamics, whose "
                         "small-signal gain depends on the frequency; a linear model takes a rate-independent "
                         "operator (the operator without its dynamics part)")
    low, high = _input_limits(drive, name)
    if branch == "ascending":
        if not (low <= voltage and voltage + step <= high):
            raise ValueError(f"voltage {voltage!r} V plus voltage_step {step!r} V must lie in the input range "
                             f"[{low!r}, {high!r}] V of drive {name!r} for the ascending branch")
        y = np.asarray(op.apply([low, voltage, voltage + step]), dtype=float)
        return _flat_warned(DriveGain(voltage, float(y[1]), float((y[2] - y[1]) / step), branch), y, step, name,
                            stacklevel + 1)
    if not (low <= voltage - step and voltage <= high):
        raise ValueError(f"voltage {voltage!r} V minus voltage_step {step!r} V must lie in the input range "
                         f"[{low!r}, {high!r}] V of drive {name!r} for the {branch} branch")
    history = [high, voltage, voltage - step] if branch == "descending" else [low, voltage, voltage - step]
    y = np.asarray(op.apply(history), dtype=float)
    return _flat_warned(DriveGain(voltage, float(y[1]), float((y[1] - y[2]) / step), branch), y, step, name,
                        stacklevel + 1)


def _flat_warned(gain: DriveGain, y: np.ndarray, step: float, name: str, stacklevel: int) -> DriveGain:
    """``gain``, with an :class:`~exudyn_atcm.AccuracyWarning` when it is zero (to round-off of the outputs ``y``):
    a Preisach operator leaves a reversal horizontally until its first relays switch back, so a small
    ``voltage_step`` there gives a linear model without this input."""
    if abs(gain.gain) * step <= 1e-12 * float(np.max(np.abs(y))):
        warnings.warn(f"drive {name!r}: its small-signal gain on the {gain.branch} branch at {gain.voltage:g} V over "
                      f"voltage_step {step:g} V is 0: the hysteresis operator is flat there (it leaves a reversal "
                      "horizontally until its relays switch back), so a linear model has no input from this drive. "
                      "Take a larger voltage_step (the slope grows with the amplitude) or another branch",
                      AccuracyWarning, stacklevel=stacklevel)
    return gain
