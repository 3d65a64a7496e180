"""GIF animations: every frame drawn once on a figure's Agg canvas, written atomically with Pillow.

The one GIF writer of the package (:func:`~exudyn_atcm.plots.result.animate_actuator` and
:func:`~exudyn_atcm.plots.mechanism.animate_mechanism` both go through :func:`save_gif`).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ..io.atomic import atomic_path
from ..io.progress import report_task

__all__ = ["save_gif"]


def save_gif(fig: Figure, draw: Callable[[int], object], n_frames: int, path: str | os.PathLike, *, fps: int,
             colors: int = 128, progress: Callable[[int, int], None] | None = None) -> Path:
    """Draw frames ``draw(0) ... draw(n_frames - 1)`` on ``fig`` and write them as a looping GIF.

    The layout of the first frame is kept for all frames (no jumping axes).  Each frame is
    reduced to an adaptive palette of ``colors`` colours; the frame duration is
    ``round(1000 / fps)`` ms.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure on the Agg canvas (:func:`~exudyn_atcm.plots.style.new_figure`).
    draw : callable
        ``draw(k)`` updates the figure for frame ``k``.
    n_frames : int
        Number of frames, ``>= 1``.
    path : str or os.PathLike
        Target ``.gif`` in an existing directory (written through
        :func:`~exudyn_atcm.io.atomic.atomic_path`).
    fps : int
        Frames per second, ``>= 1``.
    colors : int, optional
        Palette size per frame, 2 to 256.
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
        raise ValueError(f"n_frames must be an integer >= 1, got {n_frames!r}")
    if isinstance(fps, bool) or not isinstance(fps, int) or fps < 1:
        raise ValueError(f"fps must be an integer >= 1, got {fps!r}")
    if isinstance(colors, bool) or not isinstance(colors, int) or not 2 <= colors <= 256:
        raise ValueError(f"colors must be an integer in [2, 256], got {colors!r}")
    target = os.fspath(path)
    if not os.path.isdir(os.path.dirname(os.path.abspath(target))):
        raise ValueError(f"path must be in an existing directory, got {target!r}")
    images = []
    report_task("GIF frames", 0, n_frames)
    for k in range(n_frames):
        draw(k)
        fig.canvas.draw()
        if k == 0:
            fig.set_layout_engine("none")
        rgba = np.asarray(fig.canvas.buffer_rgba())
        images.append(Image.fromarray(rgba[..., :3].copy()).convert("P", palette=Image.Palette.ADAPTIVE, colors=colors))
        report_task("GIF frames", k + 1, n_frames)
        if progress is not None:
            progress(k + 1, n_frames)
    with atomic_path(target) as tmp:
        images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:],
                       duration=int(round(1000.0 / fps)), loop=0)
    return Path(target)
