"""Plots and drawings (matplotlib, headless Agg): results, hysteresis loops, identified models,
mechanisms and their animations, cell drawings, one plot style.

The face (``from exudyn_atcm.plots import plot_mechanism, new_figure``) exports what cases and users
draw with; ``plot_time_series`` is the general one of :mod:`~exudyn_atcm.plots.hysteresis` (groups of
series), the lone actuator's voltage/stroke/tip panel is ``plot_actuator_time_series``
(:func:`exudyn_atcm.plots.result.plot_time_series`).

May import every description and result layer; never solves anything itself.
"""

import importlib
from typing import TYPE_CHECKING, Any

# Submodules are imported on first use of one of their names (PEP 562): `import exudyn_atcm.plots.style`
# (which the cases use) then does not load every drawing module and matplotlib with it.
_LAZY = {
    'cell_figure': ('cells', 'cell_figure'),
    'draw_rigid_chain': ('cells', 'draw_rigid_chain'),
    'draw_six_bar_cell': ('cells', 'draw_six_bar_cell'),
    'height_exaggeration': ('cells', 'height_exaggeration'),
    'paper_actuator': ('cells', 'paper_actuator'),
    'save_cell_drawing': ('cells', 'save_cell_drawing'),
    'Curve': ('hysteresis', 'Curve'),
    'plot_loops': ('hysteresis', 'plot_loops'),
    'plot_relays': ('hysteresis', 'plot_relays'),
    'plot_time_series': ('hysteresis', 'plot_time_series'),
    'save_gif': ('gif', 'save_gif'),
    'plot_fit': ('identification', 'plot_fit'),
    'plot_fit_series': ('identification', 'plot_fit_series'),
    'plot_model_choice': ('identification', 'plot_model_choice'),
    'BenderShape': ('mechanism', 'BenderShape'),
    'MechanismShape': ('mechanism', 'MechanismShape'),
    'actuator_as_mechanism': ('mechanism', 'actuator_as_mechanism'),
    'animate_mechanism': ('mechanism', 'animate_mechanism'),
    'draw_mechanism': ('mechanism', 'draw_mechanism'),
    'mechanism_shape': ('mechanism', 'mechanism_shape'),
    'plot_mechanism': ('mechanism', 'plot_mechanism'),
    'plot_point_paths': ('mechanism', 'plot_point_paths'),
    'animate_actuator': ('result', 'animate_actuator'),
    'chain_shape': ('result', 'chain_shape'),
    'plot_result': ('result', 'plot_result'),
    'plot_shapes': ('result', 'plot_shapes'),
    'plot_tip_vs_voltage': ('result', 'plot_tip_vs_voltage'),
    'plot_actuator_time_series': ('result', 'plot_time_series'),
    'plot_modes': ('modes', 'plot_modes'),
    'plot_bode': ('bode', 'plot_bode'),
    'COLORS': ('style', 'COLORS'),
    'STYLE': ('style', 'STYLE'),
    'AxisLabels': ('style', 'AxisLabels'),
    'axis_label': ('style', 'axis_label'),
    'display_scale': ('style', 'display_scale'),
    'new_figure': ('style', 'new_figure'),
    'save_figure': ('style', 'save_figure'),
}


if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from .cells import cell_figure, draw_rigid_chain, draw_six_bar_cell, height_exaggeration, paper_actuator, save_cell_drawing
    from .hysteresis import Curve, plot_loops, plot_relays, plot_time_series
    from .gif import save_gif
    from .identification import plot_fit, plot_fit_series, plot_model_choice
    from .mechanism import (
        BenderShape,
        MechanismShape,
        actuator_as_mechanism,
        animate_mechanism,
        draw_mechanism,
        mechanism_shape,
        plot_mechanism,
        plot_point_paths,
    )
    from .result import animate_actuator, chain_shape, plot_result, plot_shapes, plot_tip_vs_voltage
    from .result import plot_time_series as plot_actuator_time_series
    from .modes import plot_modes
    from .bode import plot_bode
    from .style import COLORS, STYLE, AxisLabels, axis_label, display_scale, new_figure, save_figure

__all__ = [
    # style
    "STYLE", "COLORS", "AxisLabels", "new_figure", "axis_label", "display_scale", "save_figure",
    # curves and hysteresis loops
    "Curve", "plot_loops", "plot_time_series", "plot_relays", "plot_fit", "plot_fit_series", "plot_model_choice",
    # results of the lone actuator
    "plot_result", "plot_actuator_time_series", "plot_tip_vs_voltage", "plot_shapes", "chain_shape", "animate_actuator",
    "save_gif",
    # mechanisms
    "draw_mechanism", "plot_mechanism", "animate_mechanism", "plot_point_paths", "mechanism_shape", "MechanismShape",
    "BenderShape", "actuator_as_mechanism",
    # modes and linear models
    "plot_modes", "plot_bode",
    # cell drawings
    "cell_figure", "save_cell_drawing", "draw_six_bar_cell", "draw_rigid_chain", "paper_actuator", "height_exaggeration",
]


def __getattr__(name: str) -> Any:
    """Import the submodule that defines ``name`` on first use and cache the name here."""
    try:
        module, attr = _LAZY[name]
    except KeyError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    value = getattr(importlib.import_module(f".{module}", __name__), attr)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
