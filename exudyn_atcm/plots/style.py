"""One plot style for the package: labelled axes with units, Agg only, atomic PNG files.

Figures are made with matplotlib's object-oriented API on the Agg canvas
(:class:`matplotlib.figure.Figure`), never through ``pyplot``: no display is needed, no
global figure state is kept, and plotting works in threads and on headless machines.

Examples
--------
>>> from exudyn_atcm.plots.style import new_figure, axis_label, save_figure
>>> fig, (ax,) = new_figure(1)
>>> _ = ax.plot([0, 1], [0, 1e-6])
>>> ax.set_xlabel(axis_label("time", "s"))
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._checks import shown
from ..io.atomic import write_atomic
from ..io.progress import count_task

if TYPE_CHECKING:  # annotations only: matplotlib is imported where a figure is made
    from matplotlib.figure import Figure

__all__ = ["STYLE", "AxisLabels", "new_figure", "axis_label", "display_scale", "save_figure"]

#: rcParams applied to every figure of the package.
STYLE: dict[str, object] = {
    "font.size": 10.0,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.titlesize": 10.0,
    "legend.fontsize": 8.5,
    "lines.linewidth": 1.5,
    "savefig.dpi": 130,
}

#: Colour cycle (colour-blind safe, Okabe-Ito).
COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"]

_PREFIXES = [(1e-9, "n"), (1e-6, "µ"), (1e-3, "m"), (1.0, "")]


def new_figure(
    n_rows: int = 1, n_cols: int = 1, *, width: float = 6.4, height: float | None = None, sharex: bool = False
) -> tuple[Figure, list]:
    """A figure on the Agg canvas with the package style and a flat list of axes.

    Parameters
    ----------
    n_rows, n_cols : int
        Grid of axes.
    width : float
        Figure width [inch].
    height : float, optional
        Figure height [inch]; default ``2.6 * n_rows + 0.6``.
    sharex : bool
        Share the x axis between the axes.
    """
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: PLC0415 - lazy: matplotlib is slow to import
    from matplotlib.figure import Figure  # noqa: PLC0415 - lazy: matplotlib is slow to import

    with matplotlib.rc_context(STYLE):
        fig = Figure(figsize=(width, height if height is not None else 2.6 * n_rows + 0.6), layout="constrained")
        FigureCanvasAgg(fig)
        axes = fig.subplots(n_rows, n_cols, sharex=sharex, squeeze=False)
        for ax in axes.flat:
            ax.set_prop_cycle(color=COLORS)
            ax.grid(True, alpha=0.3)
    return fig, list(axes.flat)


@dataclass(frozen=True)
class AxisLabels:
    """The input and output quantities of an input-output plot, each with its SI unit.

    Parameters
    ----------
    input_name, input_unit : str
        The input quantity and its unit (default ``voltage [V]``).
    output_name, output_unit : str
        The output quantity and its unit (default ``displacement [m]``); an output shown on a
        scaled unit (``µm``) is scaled from this one.
    """

    input_name: str = "voltage"
    input_unit: str = "V"
    output_name: str = "displacement"
    output_unit: str = "m"

    def __post_init__(self) -> None:
        for name in ("input_name", "input_unit", "output_name", "output_unit"):
            value = getattr(self, name)
            if not isinstance(value, str):
                raise TypeError(f"AxisLabels.{name} must be a str, got {shown(value)}")


def axis_label(quantity: str, unit: str) -> str:
    """Axis label ``"quantity [unit]"``; ``"-"`` is written as ``[-]``."""
    return f"{quantity} [{unit}]"


def display_scale(values: Sequence[float] | np.ndarray, unit: str) -> tuple[float, str]:
    """Factor and unit for readable tick labels of an SI quantity.

    For the base units ``m`` and ``m V`` (and ``N``), values are shown in µ, m or n of the
    unit when their magnitude is small, e.g. strokes of 4e-5 m as 40 µm.  Other units are
    left unchanged (factor 1).

    Returns
    -------
    (float, str)
        Multiply the values by the factor and label the axis with the unit.
    """
    if unit not in ("m", "N", "m V", "m·V"):
        return 1.0, unit
    array = np.asarray(values, dtype=float)
    finite = array[np.isfinite(array)]
    peak = float(np.max(np.abs(finite))) if finite.size else 0.0
    if peak == 0.0 or peak >= 1.0:
        return 1.0, unit
    for size, prefix in _PREFIXES:
        if peak < 1000.0 * size:
            return 1.0 / size, prefix + unit
    return 1.0, unit  # pragma: no cover


def save_figure(fig: Figure, path: str | os.PathLike) -> Path:
    """Save ``fig`` as PNG at ``path`` atomically and return the path.

    Counts the figure on the active progress display (``figures written: n``,
    :func:`~exudyn_atcm.io.progress.count_task`).
    """
    written = write_atomic(path, lambda handle: fig.savefig(handle, format="png", dpi=STYLE["savefig.dpi"]), binary=True)
    count_task("figures written")
    return written
