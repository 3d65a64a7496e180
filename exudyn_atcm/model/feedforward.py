"""Feedforward compensation: a voltage program that makes the free strain follow a wanted trajectory.

The wanted strain samples are passed, in time order, through the inverse of the hysteresis
model (:func:`exudyn_atcm.hysteresis.inverse.inverse_operator`), whose memory follows the
history exactly as the drive's operator will in the simulation (both start from the reset
state).  The voltages are joined linearly in time: between two samples the voltage changes
monotonically, so a rate-independent operator sees the same extrema as the samples.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from .._checks import finite_array, same_length
from ..hysteresis.inverse import inverse_operator
from .sampled_program import SampledProgram
from ..errors import OutOfReachWarning

__all__ = ["feedforward_program", "linear_program"]


def feedforward_program(
    model: Any, times: Any, wanted: Any, input_range: tuple[float, float] | None = None
) -> tuple[SampledProgram, dict]:
    """Voltage program [V] whose response through ``model`` is the wanted output.

    Parameters
    ----------
    model : hysteresis operator
        Voltage [V] to free strain [-] (or any output) model of the drive.
    times : array_like
        Sample times [s], strictly increasing.
    wanted : array_like
        Wanted output at those times (strain [-] for a strain model).
    input_range : (float, float), optional
        Allowed voltages [V] (default: the range where the model's output changes).

    Returns
    -------
    (SampledProgram, dict)
        The program (linear between the samples; the run checks measure it by its reversals,
        not its sample spacing: :class:`~exudyn_atcm.model.sampled_program.SampledProgram`), and
        ``{"clipped_samples", "largest_clip", "samples"}``: how many wanted outputs were
        unreachable and by how much at most (output units).

    Warns
    -----
    RuntimeWarning
        Once, if some wanted outputs were unreachable (clipped), with the count and the
        largest amount.
    """
    t = finite_array("times", times, min_length=2)
    y = finite_array("wanted", wanted, min_length=2)
    same_length(("times", "wanted"), (t, y))
    inverse = inverse_operator(model, input_range)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        volts = np.array([inverse.commit(v) for v in y.tolist()])
    info = {"clipped_samples": int(getattr(inverse, "clip_count", 0)),
            "largest_clip": float(getattr(inverse, "largest_clip", 0.0)), "samples": int(y.size)}
    if info["clipped_samples"]:
        warnings.warn(
            f"feedforward: {info['clipped_samples']} of {y.size} wanted outputs are not reachable within the "
            f"input range; clipped by at most {info['largest_clip']:.6g} (output units)",
            OutOfReachWarning,
            stacklevel=2,
        )
    return SampledProgram(t, volts), info


def linear_program(slope: float, intercept: float, times: Any, wanted: Any,
                   input_range: tuple[float, float] | None = None) -> tuple[SampledProgram, dict]:
    """Voltage program of a linear model ``y = slope·u + intercept`` (no hysteresis), for comparison.

    Voltages outside ``input_range`` are clipped and counted as in :func:`feedforward_program`.
    """
    t = finite_array("times", times, min_length=2)
    y = finite_array("wanted", wanted, min_length=2)
    same_length(("times", "wanted"), (t, y))
    if slope == 0.0:
        raise ValueError("slope must be non-zero for a linear inversion, got 0")
    volts = (y - intercept) / slope
    info = {"clipped_samples": 0, "largest_clip": 0.0, "samples": int(y.size)}
    if input_range is not None:
        lo, hi = input_range
        clipped = np.clip(volts, lo, hi)
        moved = np.abs(clipped - volts) * abs(slope)
        info["clipped_samples"] = int((moved > 0).sum())
        info["largest_clip"] = float(moved.max())
        if info["clipped_samples"]:
            warnings.warn(
                f"linear inversion: {info['clipped_samples']} of {y.size} voltages outside {input_range} V; "
                f"clipped (output off by at most {info['largest_clip']:.6g})",
                OutOfReachWarning,
                stacklevel=2,
            )
        volts = clipped
    return SampledProgram(t, volts), info
