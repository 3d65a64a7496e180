"""Labelled drawings of the two simulation cells, generated from an actuator's numbers.

The six-bar cell (the paper's Fig. 2) and a chain of rigid cells (the ``cell="rigid"``
model, a Fig. 11 chain) are drawn with the geometry and spring constants of a
:class:`~exudyn_atcm.mechanism.actuator.BendingActuator`, labelled with the paper's symbols
(``L_j``, ``h1``, ``h2``, ``e``, ``k_theta``, ``k1``, ``x_a``).  The layers of a real
bender are a few tenths of a millimetre thick on cells of some centimetres, so every
height is drawn exaggerated by a stated factor; the y tick labels stay in true millimetres.

Coordinates are the model's (see :mod:`exudyn_atcm.mechanism.actuator`): ``x`` along the cell from
its left interface, the passive layer's mid-plane on ``y = 0``, the active layer's on
``y = -e``.

Examples
--------
>>> from exudyn_atcm.plots.cells import cell_figure
>>> fig = cell_figure()          # the paper's actuator; fig.savefig(...) or save_cell_drawing
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._checks import shown
from ..mechanism.actuator import BendingActuator
from ..model.drive import PiezoDrive
from ..model.materials import Layer
from .style import COLORS, new_figure, save_figure

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.figure import Figure
    from matplotlib.path import Path as Path_

__all__ = ["paper_actuator", "height_exaggeration", "draw_six_bar_cell", "draw_rigid_chain", "cell_figure",
           "save_cell_drawing"]

_PASSIVE = COLORS[0]
_ACTIVE = COLORS[1]
_SPRING = COLORS[2]
_GREY = "0.35"


def paper_actuator(cell: str = "six-bar") -> BendingActuator:
    """The paper's actuator (Figs. 11, 12), unpowered: 3 cells of 29 mm, 28 mm wide.

    Passive layer CFC 0.2 mm, 70 GPa, 1550 kg/m³; active layer MFC 0.3 mm, 30.336 GPa,
    5440 kg/m³ (see the theory page of the documentation).
    """
    return BendingActuator(
        n_cells=3, cell_length=29e-3, width=28e-3,
        passive=Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0),
        active=Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0),
        drive=PiezoDrive(0.0), cell=cell)


def height_exaggeration(actuator: BendingActuator, drawn_offset: float = 0.3) -> float:
    """Factor by which heights are drawn: the layer offset ``e`` appears as ``drawn_offset * L_j``.

    Parameters
    ----------
    actuator : BendingActuator
        Source of ``e`` and ``L_j``.
    drawn_offset : float, optional
        Drawn ``e`` as a fraction of the cell length [-], > 0.

    Returns
    -------
    float
        The exaggeration factor [-] (1 if the cell is already that thick or thicker).
    """
    if not drawn_offset > 0.0:
        raise ValueError(f"drawn_offset must be > 0 (a fraction of the cell length), got {shown(drawn_offset)}")
    return max(1.0, drawn_offset * actuator.cell_length / actuator.layer_offset)


def _mm(value: float) -> float:
    return value * 1e3


def _si(value: float, unit: str) -> str:
    """A value with an SI prefix, 3 significant digits: 5.33e6 N/m -> '5.33 MN/m'."""
    for factor, prefix in ((1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m")):
        if abs(value) >= factor:
            return f"{value / factor:.3g} {prefix}{unit}"
    return f"{value:.3g} {unit}"


def _dimension(ax, p0, p1, text, *, offset=(0.0, 0.0), color=_GREY, text_offset=(0.0, 0.0), **text_kw):
    """A two-headed dimension arrow from p0 to p1 (drawing units) with a label at its middle."""
    from matplotlib import patches  # noqa: PLC0415 - lazy: matplotlib is slow to import

    a = (p0[0] + offset[0], p0[1] + offset[1])
    b = (p1[0] + offset[0], p1[1] + offset[1])
    ax.add_patch(patches.FancyArrowPatch(a, b, arrowstyle="<->", mutation_scale=9, color=color, lw=0.9,
                                         shrinkA=0, shrinkB=0))
    mid = (0.5 * (a[0] + b[0]) + text_offset[0], 0.5 * (a[1] + b[1]) + text_offset[1])
    kw = {"ha": "center", "va": "center", "color": color, "fontsize": 9}
    kw.update(text_kw)
    ax.text(mid[0], mid[1], text, **kw)


def _spring(ax, x0, x1, y, height, turns=5, color=_SPRING):
    """A zig-zag axial spring between x0 and x1 at height y."""
    n = 2 * turns
    xs = np.linspace(x0, x1, n + 4)
    ys = np.full(xs.size, y)
    ys[2:-2] = y + height * 0.5 * np.array([(-1) ** k for k in range(n)])
    ax.plot(xs, ys, color=color, lw=1.2, solid_joinstyle="miter")


def _spiral_marker() -> Path_:
    """A spiral as a marker path (drawn in points, so it stays round on stretched axes)."""
    from matplotlib import path as mpath  # noqa: PLC0415 - lazy: matplotlib is slow to import

    phi = np.linspace(0.0, 3.2 * np.pi, 120)
    r = 0.45 + 0.55 * phi / phi[-1]
    return mpath.Path(np.column_stack([r * np.cos(phi), r * np.sin(phi)]))


def _joint(ax, x, y, spring=True):
    """A revolute joint at (x, y), with a torsion spring (spiral) if ``spring``."""
    if spring:
        ax.plot([x], [y], linestyle="none", marker=_spiral_marker(), markersize=24, markerfacecolor="none",
                markeredgecolor=_SPRING, markeredgewidth=0.9, zorder=4)
    ax.plot([x], [y], linestyle="none", marker="o", markersize=7, markerfacecolor="white",
            markeredgecolor="black", markeredgewidth=1.1, zorder=5)


def _clamp(ax, x, y_low, y_high, width):
    """Hatched ground left of x between y_low and y_high."""
    from matplotlib import patches  # noqa: PLC0415 - lazy: matplotlib is slow to import

    ax.add_patch(patches.Rectangle((x - width, y_low), width, y_high - y_low, facecolor="0.85", edgecolor="black",
                                   hatch="////", lw=0.8, zorder=1))


def _true_mm_ticks(ax, scale: float) -> None:
    from matplotlib import ticker  # noqa: PLC0415 - lazy: matplotlib is slow to import

    ax.yaxis.set_major_locator(ticker.MultipleLocator(0.2 * scale))  # every 0.2 mm of true height
    ax.yaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _pos: f"{v / scale:.1f}"))


def draw_six_bar_cell(ax, actuator: BendingActuator | None = None, *, exaggeration: float | None = None) -> float:
    """Draw one six-bar cell (the paper's Fig. 2) on ``ax``, labelled, in millimetres.

    The cell: interface elements ``I_j`` and ``I_j+1`` at both ends (height ``e``), the
    passive layer (CFC) as one bar pinned at their points on ``y = 0``, the active layer
    (MFC) as three bodies A1-A2-A3 on ``y = -e`` pinned at their other points; four revolute
    joints with torsion springs (``k_theta1 = 2 E1 I1 / L_j`` on the passive layer,
    ``k_theta2 = 2 E2 I2 / L_j`` on the active layer); the prismatic joint A1-A2 is the linear
    motor (stroke ``x_a``), the prismatic joint A2-A3 carries the axial spring ``k1``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Target axes.
    actuator : BendingActuator, optional
        Source of the geometry and spring constants (default: :func:`paper_actuator`).
    exaggeration : float, optional
        Height exaggeration factor [-] (default: :func:`height_exaggeration`).

    Returns
    -------
    float
        The height exaggeration factor used.
    """
    from matplotlib import patches  # noqa: PLC0415 - lazy: matplotlib is slow to import

    act = paper_actuator() if actuator is None else actuator
    s = height_exaggeration(act) if exaggeration is None else float(exaggeration)
    lc = _mm(act.cell_length)
    e = _mm(act.layer_offset) * s
    h1 = _mm(act.passive.thickness) * s
    h2 = _mm(act.active.thickness) * s
    # true layer cross-sections, faint, behind the bars
    ax.add_patch(patches.Rectangle((0.0, -0.5 * h1), lc, h1, facecolor=_PASSIVE, alpha=0.12, lw=0))
    ax.add_patch(patches.Rectangle((0.0, -0.5 * h1 - h2), lc, h2, facecolor=_ACTIVE, alpha=0.12, lw=0))
    # interface elements
    over = 0.25 * e
    for x, name in ((0.0, r"$I_j$"), (lc, r"$I_{j+1}$")):
        ax.plot([x, x], [over, -e - over], color="black", lw=5, solid_capstyle="butt", zorder=3)
        ax.text(x, over + 0.06 * e, name, ha="center", va="bottom", fontsize=9)
    # passive bar
    ax.plot([0.0, lc], [0.0, 0.0], color=_PASSIVE, lw=3, zorder=4)
    ax.text(0.5 * lc, 0.5 * h1 + 0.04 * e, "passive layer (CFC)", ha="center", va="bottom", color=_PASSIVE,
            fontsize=9)
    # active bodies A1, A2, A3 with the motor and the spring in the gaps
    third = lc / 3.0
    gap = 0.16 * third
    for k in range(3):
        x0 = k * third + (0.0 if k == 0 else 0.5 * gap)
        x1 = (k + 1) * third - (0.0 if k == 2 else 0.5 * gap)
        ax.plot([x0, x1], [-e, -e], color=_ACTIVE, lw=3, zorder=4)
        ax.text(0.5 * (x0 + x1), -e - 0.5 * h2 - 0.05 * e, f"A{k + 1}", ha="center", va="top", color=_ACTIVE,
                fontsize=9)
    ax.text(0.5 * lc, -e - 0.5 * h2 - 0.42 * e, "active layer (MFC)", ha="center", va="top", color=_ACTIVE,
            fontsize=9)
    # motor A1-A2: a box with the stroke arrow
    xm = third
    box_h = 0.5 * e
    ax.add_patch(patches.Rectangle((xm - 0.5 * gap, -e - 0.5 * box_h), gap, box_h, facecolor="white", edgecolor="black",
                                   lw=1.0, zorder=5))
    ax.text(xm, -e, "M", ha="center", va="center", fontsize=8, zorder=6)
    ax.add_patch(patches.FancyArrowPatch((xm - 0.5 * gap, -e + 0.45 * e), (xm + 0.9 * gap, -e + 0.45 * e),
                                         arrowstyle="->", mutation_scale=9, color="black", lw=0.9))
    ax.text(xm + 0.2 * gap, -e + 0.5 * e, r"$x_a = \Lambda L_j$", ha="center", va="bottom", fontsize=9)
    # axial spring A2-A3
    xs = 2.0 * third
    _spring(ax, xs - 0.5 * gap, xs + 0.5 * gap, -e, 0.35 * e)
    ax.text(xs, -e + 0.3 * e, r"$k_1$", ha="center", va="bottom", color=_SPRING, fontsize=10)
    ax.text(xs, -e + 0.55 * e, _si(act.axial_spring_stiffness, "N/m"), ha="center", va="bottom", color=_SPRING,
            fontsize=7.5)
    # revolute joints with torsion springs
    for x in (0.0, lc):
        _joint(ax, x, 0.0)
        _joint(ax, x, -e)
    ax.text(0.06 * lc, 0.5 * h1 + 0.04 * e, r"$k_{\theta 1}$", ha="left", va="bottom", color=_SPRING, fontsize=10)
    ax.text(0.94 * lc, 0.5 * h1 + 0.04 * e, r"$k_{\theta 1}$", ha="right", va="bottom", color=_SPRING, fontsize=10)
    ax.text(0.06 * lc, -e - 0.5 * h2 - 0.05 * e, r"$k_{\theta 2}$", ha="left", va="top", color=_SPRING, fontsize=10)
    ax.text(0.94 * lc, -e - 0.5 * h2 - 0.05 * e, r"$k_{\theta 2}$", ha="right", va="top", color=_SPRING,
            fontsize=10)
    # dimensions: L_j above, e on the left, h1 and h2 on the right
    _dimension(ax, (0.0, 0.0), (lc, 0.0), r"$L_j$ = " + f"{lc:.3g} mm", offset=(0.0, over + 0.45 * e),
               text_offset=(0.0, 0.09 * e))
    _dimension(ax, (0.0, 0.0), (0.0, -e), r"$e$", offset=(-0.07 * lc, 0.0), text_offset=(-0.03 * lc, 0.0))
    xr = lc + 0.06 * lc
    _dimension(ax, (xr, 0.5 * h1), (xr, -0.5 * h1), r"$h_1$", color=_PASSIVE, text_offset=(0.035 * lc, 0.0))
    _dimension(ax, (xr, -0.5 * h1), (xr, -0.5 * h1 - h2), r"$h_2$", color=_ACTIVE, text_offset=(0.035 * lc, 0.0))
    legend = (
        rf"$k_{{\theta 1}} = 2E_1I_1/L_j$ = {_si(act.torsion_stiffness_passive, 'N m/rad')}" "\n"
        rf"$k_{{\theta 2}} = 2E_2I_2/L_j$ = {_si(act.torsion_stiffness_active, 'N m/rad')}" "\n"
        rf"$k_1$ ({act.stiffness}) = {_si(act.axial_spring_stiffness, 'N/m')}" "\n"
        rf"$h_1$ = {_mm(act.passive.thickness):.3g} mm, $h_2$ = {_mm(act.active.thickness):.3g} mm, "
        rf"$e = (h_1+h_2)/2$ = {_mm(act.layer_offset):.3g} mm"
    )
    ax.text(0.01, 0.02, legend, transform=ax.transAxes, ha="left", va="bottom", fontsize=7.5,
            bbox={"facecolor": "white", "edgecolor": "0.7", "alpha": 0.9})
    ax.set_xlim(-0.17 * lc, 1.2 * lc)
    ax.set_ylim(-e - 2.9 * e, over + 1.0 * e)
    ax.set_xlabel("x along the cell [mm]")
    ax.set_ylabel(f"y [mm] (heights ×{s:.0f})")
    ax.set_title("Six-bar cell (paper, Fig. 2): 4 revolute + 2 prismatic joints")
    ax.grid(False)
    _true_mm_ticks(ax, s)
    return s


def draw_rigid_chain(ax, actuator: BendingActuator | None = None, *, n_cells: int = 2,
                     exaggeration: float | None = None) -> float:
    """Draw ``n_cells`` rigid cells from the clamp (the ``cell="rigid"`` model), labelled, in mm.

    Each cell is one rigid body on the passive layer's mid-plane carrying both layers;
    revolute joints at the cell boundaries carry torsion springs ``2 EI / L_j`` at the
    clamp and ``EI / L_j`` between cells, whose rest angles are the free rotation
    ``kappa L_j / 2`` (clamp, half a cell) and ``kappa L_j`` (inside) of the cells they stand
    for; ``kappa`` follows the free strain ``Lambda``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Target axes.
    actuator : BendingActuator, optional
        Source of the geometry and spring constants (default: :func:`paper_actuator`).
    n_cells : int, optional
        Cells drawn, >= 1.
    exaggeration : float, optional
        Height exaggeration factor [-] (default: :func:`height_exaggeration`).

    Returns
    -------
    float
        The height exaggeration factor used.
    """
    from matplotlib import patches  # noqa: PLC0415 - lazy: matplotlib is slow to import

    if isinstance(n_cells, bool) or not isinstance(n_cells, int) or n_cells < 1:
        raise ValueError(f"n_cells must be an integer >= 1, got {shown(n_cells)}")
    act = paper_actuator("rigid") if actuator is None else actuator
    s = height_exaggeration(act) if exaggeration is None else float(exaggeration)
    lc = _mm(act.cell_length)
    e = _mm(act.layer_offset) * s
    h1 = _mm(act.passive.thickness) * s
    h2 = _mm(act.active.thickness) * s
    total = n_cells * lc
    _clamp(ax, 0.0, -e - 0.8 * e, 0.8 * e, 0.06 * lc)
    ax.text(-0.03 * lc, 0.9 * e, "clamp", ha="center", va="bottom", fontsize=9)
    for j in range(n_cells):
        x0 = j * lc
        ax.add_patch(patches.Rectangle((x0 + 0.02 * lc, -0.5 * h1), lc - 0.04 * lc, h1, facecolor=_PASSIVE,
                                       alpha=0.25, lw=0))
        ax.add_patch(patches.Rectangle((x0 + 0.02 * lc, -0.5 * h1 - h2), lc - 0.04 * lc, h2, facecolor=_ACTIVE,
                                       alpha=0.25, lw=0))
        ax.plot([x0, x0 + lc], [0.0, 0.0], color="black", lw=2.5, zorder=4)
        ax.text(x0 + 0.5 * lc, -0.5 * h1 - h2 - 0.1 * e, f"rigid cell {j + 1}\n(both layers' mass)", ha="center",
                va="top", fontsize=8.5)
        _dimension(ax, (x0, 0.0), (x0 + lc, 0.0), r"$L_j$", offset=(0.0, 1.25 * e), text_offset=(0.0, 0.12 * e))
    for j in range(n_cells + 1):
        x = j * lc
        _joint(ax, x, 0.0, spring=j < n_cells)
    ax.text(0.02 * lc, 0.42 * e, r"$k_\theta = 2EI/L_j$" "\n" r"$\theta_0 = \kappa(\Lambda) L_j/2$", ha="left",
            va="bottom", color=_SPRING, fontsize=8.5)
    for j in range(1, n_cells):
        ax.text(j * lc + 0.02 * lc, 0.42 * e, r"$k_\theta = EI/L_j$" "\n" r"$\theta_0 = \kappa(\Lambda) L_j$",
                ha="left", va="bottom", color=_SPRING, fontsize=8.5)
    ax.text(total - 0.03 * lc, 0.12 * e, "tip", ha="right", va="bottom", fontsize=9)
    _dimension(ax, (total + 0.06 * lc, 0.5 * h1), (total + 0.06 * lc, -0.5 * h1), r"$h_1$", color=_PASSIVE,
               text_offset=(0.035 * lc, 0.0))
    _dimension(ax, (total + 0.06 * lc, -0.5 * h1), (total + 0.06 * lc, -0.5 * h1 - h2), r"$h_2$", color=_ACTIVE,
               text_offset=(0.035 * lc, 0.0))
    legend = (
        rf"$EI$ ({act.stiffness}) = {_si(act.bending_stiffness, 'N m²')}" "\n"
        rf"$EI/L_j$ = {_si(act.joint_stiffness_inside, 'N m/rad')}, "
        rf"$2EI/L_j$ = {_si(act.joint_stiffness_end, 'N m/rad')}" "\n"
        rf"$\kappa/\Lambda$ = {act.curvature_per_strain:.4g} 1/m"
    )
    ax.text(0.99, 0.02, legend, transform=ax.transAxes, ha="right", va="bottom", fontsize=7.5,
            bbox={"facecolor": "white", "edgecolor": "0.7", "alpha": 0.9})
    ax.set_xlim(-0.12 * lc, total + 0.2 * lc)
    ax.set_ylim(-e - 2.6 * e, 2.1 * e)
    ax.set_xlabel("x along the actuator [mm]")
    ax.set_ylabel(f"y [mm] (heights ×{s:.0f})")
    ax.set_title(f"Rigid cells: {n_cells} of the chain, torsion springs at the joints")
    ax.grid(False)
    _true_mm_ticks(ax, s)
    return s


def cell_figure(actuator: BendingActuator | None = None, *, rigid_cells: int = 2) -> Figure:
    """Both cells, one above the other: the six-bar cell and a chain of ``rigid_cells`` rigid cells.

    Parameters
    ----------
    actuator : BendingActuator, optional
        Source of geometry and spring constants (default: :func:`paper_actuator`); its
        ``stiffness`` calibration sets the spring values shown.
    rigid_cells : int, optional
        Rigid cells drawn, >= 1.

    Returns
    -------
    matplotlib.figure.Figure
        A figure on the Agg canvas (no display needed).
    """
    act = paper_actuator() if actuator is None else actuator
    fig, (top, bottom) = new_figure(2, 1, width=7.5, height=8.4)
    s = height_exaggeration(act)
    draw_six_bar_cell(top, act, exaggeration=s)
    draw_rigid_chain(bottom, act, n_cells=rigid_cells, exaggeration=s)
    return fig


def save_cell_drawing(path: str | os.PathLike, actuator: BendingActuator | None = None, *,
                      rigid_cells: int = 2) -> Path:
    """Write :func:`cell_figure` as a PNG file (atomically) and return its path."""
    return save_figure(cell_figure(actuator, rigid_cells=rigid_cells), path)
