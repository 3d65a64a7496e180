"""The actuator animation (GIF) and the shape reconstruction it draws."""

import os

import numpy as np
import pytest

from exudyn_atcm.plots.result import animate_actuator, chain_shape
from exudyn_atcm.io.result import Result


def bent_result():
    t = np.linspace(0, 1, 21)
    kappa = 4.0 * t  # uniform curvature growing in time [1/m]
    length, n = 29e-3, 3
    series = {"time": t, "actuator.voltage": 1500 * t, "actuator.tip_x": np.zeros_like(t),
              "actuator.tip_y": np.zeros_like(t)}
    for j in range(n):  # cell j of a circular arc turns by kappa * L * (j + 1/2)
        series[f"actuator.cell_angle_{j + 1}"] = kappa * length * (j + 0.5)
    units = {name: ("s" if name == "time" else "V" if name.endswith("voltage") else "rad" if "angle" in name else "m")
             for name in series}
    return Result(series, units, parameters={"cell_length [m]": length})


def test_chain_shape_is_the_regular_polygon_of_the_bent_chain():
    r = bent_result()
    x, y = chain_shape(r, 20)
    kappa, length = 4.0, 29e-3
    s = np.arange(4) * length
    # sides of length L turning by κL each: a regular polygon inscribed in the circle of
    # radius L / (2 sin(κL/2)) tangent to the x axis at the clamp
    radius = length / (2 * np.sin(kappa * length / 2))
    np.testing.assert_allclose(x, radius * np.sin(kappa * s), atol=1e-12)
    np.testing.assert_allclose(y, radius * (1 - np.cos(kappa * s)), atol=1e-12)


def test_gif_is_written_atomically(tmp_path):
    path = tmp_path / "anim.gif"
    animate_actuator(bent_result(), path, frames=5, fps=5)
    assert path.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert [p.name for p in tmp_path.iterdir()] == ["anim.gif"]
    assert os.stat(path).st_mode & 0o044  # readable by others, unlike mkstemp's 0600


@pytest.mark.parametrize("kwargs, pattern", [({"frames": 1}, "frames must be an integer >= 2, got 1"), ({"fps": 0}, "fps must be an integer >= 1, got 0")])
def test_bad_arguments(tmp_path, kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        animate_actuator(bent_result(), tmp_path / "a.gif", **kwargs)


def test_blitted_frames_are_the_whole_drawings_of_each_frame(tmp_path):
    # save_gif draws the first frame whole and then only what draw(k) returns, on a copy of the rest:
    # every frame must be what drawing the whole figure in that state gives (the same quantizer)
    from PIL import Image, ImageSequence

    from exudyn_atcm.plots.gif import save_gif
    from exudyn_atcm.plots.style import new_figure

    fig, (ax,) = new_figure(1, 1, width=4, height=3)
    ax.grid(True, alpha=0.3)
    ax.plot([0, 1], [0, 1], color="0.5", ls="--", zorder=1)  # a static artist below the moving ones
    ax.set_xlim(0, 1)
    ax.set_ylim(-1, 1)
    ax.set_xlabel("x [m]")
    (moving,) = ax.plot([], [], "o-", color="tab:blue", zorder=3)
    x = np.linspace(0, 1, 30)

    def state(k):
        moving.set_data(x, np.sin(2 * np.pi * (x + 0.1 * k)))
        ax.set_title(f"frame {k}")
        return moving, ax.title

    save_gif(fig, state, 6, tmp_path / "b.gif", fps=5, colors=256)
    with Image.open(tmp_path / "b.gif") as image:
        frames = [np.asarray(f.convert("RGB")) for f in ImageSequence.Iterator(image)]
    assert len(frames) == 6
    for k in (5, 1, 3):  # whole drawings, in another order than the animation's
        state(k)
        fig.canvas.draw()
        whole = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy())
        expected = np.asarray(whole.quantize(256, method=Image.Quantize.MAXCOVERAGE).convert("RGB"))
        assert np.array_equal(frames[k], expected), k
    assert not np.array_equal(frames[1], frames[2])


def test_a_legend_kept_above_the_moving_artists_is_the_whole_drawing_in_every_frame(tmp_path):
    # a static legend above a marker that is far from it in some frames and crosses it in others: its pixels
    # are put back where nothing moving came near, drawn again where something did; every frame must be
    # what drawing the whole figure gives
    from PIL import Image, ImageSequence

    from exudyn_atcm.plots.gif import save_gif
    from exudyn_atcm.plots.style import new_figure

    fig, (ax,) = new_figure(1, 1, width=4, height=3)
    ax.grid(True, alpha=0.3)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.plot([0.1, 0.2], [0.1, 0.2], color="0.5", label="still")
    (moving,) = ax.plot([], [], "o-", color="tab:red", ms=8, lw=3, zorder=3, label="moving")
    legend = ax.legend(loc="upper right")
    spots = [(0.1, 0.1), (0.2, 0.2), (0.5, 0.3), (0.8, 0.85), (0.9, 0.9), (0.15, 0.2)]  # frames 3, 4 in the legend

    def state(k):
        x, y = spots[k]
        moving.set_data([x - 0.05, x], [y - 0.05, y])
        ax.set_title(f"frame {k}")
        return moving, ax.title

    drawn = []
    real_draw_artist = fig.draw_artist
    fig.draw_artist = lambda a: (drawn.append(a), real_draw_artist(a))[1]
    save_gif(fig, state, len(spots), tmp_path / "l.gif", fps=5, colors=256, above=[legend])
    fig.draw_artist = real_draw_artist
    assert 2 <= sum(a is legend for a in drawn) <= 4  # once for its pixels, then in the frames it is crossed
    with Image.open(tmp_path / "l.gif") as image:
        frames = [np.asarray(f.convert("RGB")) for f in ImageSequence.Iterator(image)]
    for k in (4, 2, 3, 5, 1):
        state(k)
        fig.canvas.draw()
        whole = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy())
        expected = np.asarray(whole.quantize(256, method=Image.Quantize.MAXCOVERAGE).convert("RGB"))
        assert np.array_equal(frames[k], expected), k
