"""Where an animation's legend goes (:func:`exudyn_atcm.plots.legend_place.place_legend`): the location of
matplotlib's ``loc="best"`` order that covers the fewest vertices and filled shapes of all frames."""

from __future__ import annotations

import numpy as np

from exudyn_atcm.plots.legend_place import LOCATIONS, place_legend
from exudyn_atcm.plots.style import new_figure


def _axes_with_legend():
    fig, (ax,) = new_figure(1, 1, width=4, height=3)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.plot([0.5], [0.5], "o", label="a point")
    legend = ax.legend()
    fig.canvas.draw()
    return fig, ax, legend


def test_with_nothing_drawn_the_first_location_of_best_wins():
    fig, ax, legend = _axes_with_legend()
    assert place_legend(fig, ax, legend, np.zeros((0, 2))) == LOCATIONS[0] == 1  # "upper right"


def test_the_legend_avoids_vertices_of_any_frame_and_filled_shapes():
    fig, ax, legend = _axes_with_legend()
    # vertices in the upper right corner (a later frame), a filled triangle over the upper left
    corner = np.array([[0.95, 0.95], [0.9, 0.92], [0.97, 0.9]])
    triangle = np.array([[0.0, 0.6], [0.4, 1.0], [0.0, 1.0]])
    code = place_legend(fig, ax, legend, corner, [triangle])
    assert code == 3  # "lower left": the first location of the order that covers nothing
    box = legend.get_window_extent(fig.canvas.get_renderer())
    lower_left = ax.transAxes.transform([0.0, 0.0])
    assert box.x0 < lower_left[0] + 30 and box.y0 < lower_left[1] + 30  # really there, in pixels
    # the same vertices taken as the only thing drawn: the triangle's corner is free again
    assert place_legend(fig, ax, legend, corner) == 2  # "upper left"
