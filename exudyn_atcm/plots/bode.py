"""Bode plots of a linear model (:func:`plot_bode`): gain and phase over frequency."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .._checks import shown
from .style import axis_label
from .target import figure_axes, finish

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure

__all__ = ["plot_bode"]


def _pick(what: str, wanted: Sequence[str] | None, names: tuple[str, ...]) -> list[int]:
    if wanted is None:
        return list(range(len(names)))
    wanted = [wanted] if isinstance(wanted, str) else list(wanted)
    for name in wanted:
        if name not in names:
            raise ValueError(f"{what} must name the model's {what} ({', '.join(map(repr, names))}), got {shown(name)}")
    return [names.index(name) for name in wanted]


def plot_bode(linear_model: Any, *, outputs: Sequence[str] | None = None, inputs: Sequence[str] | None = None,
              frequencies_hz: Sequence[float] | None = None, ax: Any = None,
              path: str | os.PathLike | None = None) -> Figure:
    """Gain (top, log-log) and phase (bottom) of every chosen output per chosen input.

    Parameters
    ----------
    linear_model : LinearModel
        From :func:`exudyn_atcm.linearise`.
    outputs, inputs : list of str, optional
        The outputs and inputs drawn (default: all).
    frequencies_hz : array_like, optional
        Frequencies [Hz] (default: 400 points, log-spaced from a tenth of the lowest natural frequency to
        three times the highest of the lowest three).
    ax : sequence of two Axes, optional
        Gain and phase axes to draw into.
    path : str or path, optional
        Also write the figure as a PNG file.

    Returns
    -------
    matplotlib.figure.Figure
    """
    out_idx = _pick("outputs", outputs, linear_model.outputs)
    in_idx = _pick("inputs", inputs, linear_model.inputs)
    if frequencies_hz is None:
        natural = linear_model.natural_frequencies
        low = 0.1 * natural[0] if natural.size else 1.0
        high = 3.0 * natural[min(2, natural.size - 1)] if natural.size else 1e3
        frequencies_hz = np.logspace(np.log10(low), np.log10(high), 400)
    f = np.asarray(frequencies_hz, dtype=float)
    G = linear_model.frequency_response(f)
    fig, (gain_ax, phase_ax) = figure_axes(ax, 2, 1, sharex=True)
    for o in out_idx:
        for i in in_idx:
            label = f"{linear_model.outputs[o]} / {linear_model.inputs[i]}"
            g = G[:, o, i]
            gain_ax.loglog(f, np.abs(g), label=label)
            phase_ax.semilogx(f, np.degrees(np.unwrap(np.angle(g))), label=label)
    units = {f"{linear_model.output_units[o]}/{linear_model.input_units[i]}" for o in out_idx for i in in_idx}
    gain_ax.set_ylabel(axis_label("gain", ", ".join(sorted(units))))
    phase_ax.set_ylabel(axis_label("phase", "deg"))
    phase_ax.set_xlabel(axis_label("frequency", "Hz"))
    gain_ax.legend(fontsize="small")
    gain_ax.set_title(f"linear model about {linear_model.state} ({linear_model.branch} branch)", fontsize="medium")
    return finish(fig, path)
