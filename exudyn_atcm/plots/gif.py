"""GIF animations: frames drawn on a figure's Agg canvas, written atomically with Pillow.

The one GIF writer of the package (:func:`~exudyn_atcm.plots.result.animate_actuator` and
:func:`~exudyn_atcm.plots.mechanism.animate_mechanism` both go through :func:`save_gif`).  The first
frame is a whole drawing of the figure; the others draw only the artists that ``draw(k)`` returns on
a copy of everything else (matplotlib's blitting): axes, ticks, grid and labels are drawn twice in
all, not once a frame, which was most of an animation's cost (about 0.1 s a frame on a mechanism).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._checks import shown
from ..io.atomic import atomic_path
from ..io.progress import report_task

if TYPE_CHECKING:  # matplotlib is imported where a figure is made (style.new_figure)
    from matplotlib.artist import Artist
    from matplotlib.figure import Figure

__all__ = ["save_gif"]


def save_gif(fig: Figure, draw: Callable[[int], Sequence[Artist] | None], n_frames: int, path: str | os.PathLike, *,
             fps: int, colors: int = 128, progress: Callable[[int, int], None] | None = None,
             above: Sequence[Artist] | Callable[[], Sequence[Artist]] = ()) -> Path:
    """Draw frames ``draw(0) ... draw(n_frames - 1)`` on ``fig`` and write them as a looping GIF.

    The layout of the first frame is kept for all frames (no jumping axes).  Each frame is
    reduced to an adaptive palette of ``colors`` colours (Pillow's maximum-coverage quantizer); the frame duration is
    ``round(1000 / fps)`` ms.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure on the Agg canvas (:func:`~exudyn_atcm.plots.style.new_figure`).
    draw : callable
        ``draw(k)`` updates the figure for frame ``k``.  If it returns the artists that differ between
        frames (changed, or added for this frame and removed by the next call) and any artist that
        must stay above them, only those are drawn after the first frame, in the order of their
        ``zorder``, on a copy of everything else, which must not change (fixed axis limits, ticks and
        labels).  If it returns ``None``, every frame is drawn whole.
    n_frames : int
        Number of frames, ``>= 1``.
    path : str or os.PathLike
        Target ``.gif`` in an existing directory (written through
        :func:`~exudyn_atcm.io.atomic.atomic_path`).
    fps : int
        Frames per second, ``>= 1``.
    colors : int, optional
        Palette size per frame, 2 to 256.
    above : sequence of Artist, or a callable returning them, optional
        Artists that stay the same in every frame but lie above the changing ones (a legend; a callable
        is called after the first frame, for artists that frame makes): with blitting, their pixels
        over the rest are kept and put back in a frame where no changing artist comes near them (its
        extent, grown by its line width and :data:`NEAR` pixels, against theirs grown by 4 pixels for
        their frame's line and antialiasing; no shadows); elsewhere they are drawn again, last.
    progress : callable, optional
        ``progress(done, total)`` after each frame.  Whether given or not, the frames are also
        reported to the active progress display as ``GIF frames done/total``
        (:func:`~exudyn_atcm.io.progress.report_task`), from ``0/total`` before the first frame to
        ``total/total`` after the last.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    from PIL import Image  # noqa: PLC0415 - Pillow comes with matplotlib; only GIFs need it

    if isinstance(n_frames, bool) or not isinstance(n_frames, int) or n_frames < 1:
        raise ValueError(f"n_frames must be an integer >= 1, got {shown(n_frames)}")
    if isinstance(fps, bool) or not isinstance(fps, int) or fps < 1:
        raise ValueError(f"fps must be an integer >= 1, got {shown(fps)}")
    if isinstance(colors, bool) or not isinstance(colors, int) or not 2 <= colors <= 256:
        raise ValueError(f"colors must be an integer in [2, 256], got {shown(colors)}")
    target = os.fspath(path)
    if not os.path.isdir(os.path.dirname(os.path.abspath(target))):
        raise ValueError(f"path must be in an existing directory, got {shown(target)}")
    images = []
    report_task("GIF frames", 0, n_frames)
    canvas = fig.canvas
    background = None
    on_top: list = []  # the artists of ``above``, known after the first frame
    kept: list = []  # per artist of ``above``: (its extent, its pixels over the background)
    for k in range(n_frames):
        changing = draw(k)
        if k == 0 or changing is None:
            canvas.draw()
            fig.set_layout_engine("none")
            background = None  # a frame drawn whole may have changed anything: the next blit copies anew
        else:
            if background is None:  # the figure without what changes, once (again after a frame drawn whole)
                on_top = _artists_above(above() if callable(above) else above)
                changing = [a for a in changing if not any(a is b for b in on_top)]
                background, kept = _background(fig, changing, on_top)
            else:
                changing = [a for a in changing if not any(a is b for b in on_top)]
            canvas.restore_region(background)
            for artist in sorted(changing, key=lambda a: a.get_zorder()):  # stable: equal zorders in order drawn
                fig.draw_artist(artist)
            if kept:
                extents = _extents(fig, changing)
                near = [any(extent.overlaps(e) for e in extents) for extent, _ in kept]
                for (_, pixels), drawn_over in zip(kept, near):
                    if not drawn_over:  # nothing changing came near it: its pixels as kept
                        canvas.restore_region(pixels)
                for artist, drawn_over in zip(on_top, near):
                    if drawn_over:
                        fig.draw_artist(artist)
        rgba = np.asarray(canvas.buffer_rgba())
        # maximum coverage: half the time of the median cut, at most 12 levels off where the median cut put
        # a few pixels 80 off (a mechanism's frames, 128 colours; the mean 0.2 levels instead of 0.04)
        images.append(Image.fromarray(rgba[..., :3].copy()).quantize(colors, method=Image.Quantize.MAXCOVERAGE))
        report_task("GIF frames", k + 1, n_frames)
        if progress is not None:
            progress(k + 1, n_frames)
    with atomic_path(target) as tmp:
        images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:],
                       duration=int(round(1000.0 / fps)), loop=0)
    return Path(target)


def _artists_above(artists: Sequence[Artist]) -> list:
    """``save_gif``'s ``above`` as a list, checked: artists that can be drawn and measured."""
    artists = list(artists)
    for artist in artists:
        if not (hasattr(artist, "draw") and hasattr(artist, "get_window_extent")):
            raise ValueError(f"above: expected matplotlib artists (a legend, ...), got {shown(artist)}")
    return artists


#: Pixels [px] by which a changing artist's extent is grown before it is tested against an ``above`` artist's.
NEAR = 3.0


def _background(fig: Figure, changing: list, above: list) -> tuple[Any, list]:
    """The figure drawn without the ``changing`` artists and without those ``above`` them, copied; and per
    artist of ``above`` its extent and its pixels over that background."""
    canvas = fig.canvas
    # animated artists are left out of a drawing (hidden ones would also leave the layout: an axes title
    # hidden so is moved off the figure)
    still = [a for a in changing + above if not a.get_animated()]
    for artist in still:
        artist.set_animated(True)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    kept = []
    renderer = canvas.get_renderer()
    for artist in above:
        fig.draw_artist(artist)
        extent = artist.get_window_extent(renderer).padded(4.0)  # its frame's line, antialiasing, whole pixels
        kept.append((extent, canvas.copy_from_bbox(extent)))
        canvas.restore_region(background)
    for artist in still:
        artist.set_animated(False)
    return background, kept


def _extents(fig: Figure, artists: list) -> list:
    """The window extents [px] of ``artists``, grown by their line widths and :data:`NEAR`."""
    renderer = fig.canvas.get_renderer()
    out = []
    for artist in artists:
        extent = artist.get_window_extent(renderer)
        width = artist.get_linewidth() if hasattr(artist, "get_linewidth") else 0.0
        width = float(np.max(width)) if np.size(width) else 0.0
        if not np.all(np.isfinite(extent.bounds)):  # no extent known (no data, or NaN in it): anywhere
            extent = fig.bbox
        out.append(extent.padded(NEAR + width * fig.dpi / 72.0))
    return out
