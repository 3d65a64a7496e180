"""The one calling convention of the plot functions: ``plot_x(thing, *, ax=None, path=None) -> Figure``.

``ax`` draws into the caller's axes (one :class:`~matplotlib.axes.Axes`, or a sequence of as many
axes as the plot has panels) instead of a new figure; ``path`` also writes the figure as a PNG
file, atomically (:func:`~exudyn_atcm.plots.style.save_figure`).  Either way the function returns
the :class:`~matplotlib.figure.Figure` it drew on.  The earlier forms that took the output path
positionally keep working for one release with an :class:`~exudyn_atcm.AtcmDeprecationWarning`
(and return what they returned then: the path written).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from .._checks import shown
from ..errors import AtcmDeprecationWarning
from .style import new_figure, save_figure

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure

__all__ = ["figure_axes", "finish", "is_path", "warn_path_form", "legacy_path"]


def figure_axes(ax: Any, n_rows: int = 1, n_cols: int = 1, **layout: Any) -> tuple[Figure, list]:
    """The figure and the ``n_rows * n_cols`` axes to draw on: the caller's ``ax`` or a new figure.

    Raises
    ------
    ValueError
        For an ``ax`` that is not an Axes (one panel) or a sequence of ``n_rows * n_cols`` Axes.
    """
    n = n_rows * n_cols
    if ax is None:
        return new_figure(n_rows, n_cols, **layout)
    from matplotlib.axes import Axes  # noqa: PLC0415 - lazy: a caller's axes means matplotlib is loaded already

    axes = [ax] if isinstance(ax, Axes) else list(ax) if isinstance(ax, Sequence) else None
    if axes is None or len(axes) != n or not all(isinstance(a, Axes) for a in axes):
        allowed = "a matplotlib Axes" if n == 1 else f"a sequence of {n} matplotlib Axes (one per panel)"
        raise ValueError(f"ax must be {allowed}, got {shown(ax)}")
    return axes[0].figure, axes


def finish(fig: Figure, path: str | os.PathLike | None) -> Figure:
    """Write ``fig`` atomically to ``path`` when one is given; return ``fig``."""
    if path is not None:
        save_figure(fig, path)
    return fig


def is_path(value: Any) -> bool:
    """Whether ``value`` is an output path (the first argument of the earlier plot signatures)."""
    return isinstance(value, (str, os.PathLike))


def warn_path_form(function: str, stacklevel: int = 3) -> None:
    """Warn that ``function`` was called with its output path in the earlier position."""
    warnings.warn(f"{function}(): pass the output file as path=... (keyword; the function returns the Figure); "
                  "the positional output path goes away in the next release", AtcmDeprecationWarning,
                  stacklevel=stacklevel)


def legacy_path(function: str, legacy: tuple, path: Any, extra: int = 0) -> tuple[Any, tuple]:
    """The output path of an earlier call ``plot_x(thing, path[, ...])`` and the up to ``extra`` values after it.

    Warns :class:`~exudyn_atcm.AtcmDeprecationWarning` (pointing at the caller of ``function``).

    Raises
    ------
    TypeError
        For more positional values than the earlier signature had, or a path given both ways.
    """
    if len(legacy) > 1 + extra:
        raise TypeError(f"{function}() takes its data positionally and everything else by keyword (ax=, path=, ...); "
                        f"got {len(legacy)} extra positional arguments")
    if path is not None:
        raise TypeError(f"{function}() got multiple values for argument 'path'")
    warn_path_form(function, stacklevel=4)
    return legacy[0], tuple(legacy[1:])
