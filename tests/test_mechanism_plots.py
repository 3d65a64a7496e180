"""Drawing and animating a mechanism: geometry from synthetic results (no solver), files, errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm import Layer, PiezoDrive, Result
from exudyn_atcm.mechanism import Bender, Flexure, Link, Mechanism
from exudyn_atcm.plots.mechanism import (
    actuator_as_mechanism,
    animate_mechanism,
    mechanism_shape,
    plot_mechanism,
    plot_point_paths,
)

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
L, N = 0.03, 4
LC = L / N


def _mechanism() -> Mechanism:
    crank = Bender("crank", width=1e-2, passive=CFC, active=MFC, length=L, n_cells=N,
                   drive=PiezoDrive(500.0), angle=math.pi / 2, cell="rigid")
    coupler = Link("coupler", {"A": (0.0, L), "B": (0.04, L), "P": (0.02, 0.05)}, mass=1e-3, inertia=1e-7)
    hinge = Flexure("hinge", base=(0.04, L), tip=(0.04, 0.0), width=5e-3, layer=Layer(0.2e-3, 70e9, 1550.0), gamma=0.5, k_theta=2.0)
    mech = Mechanism("test").add(crank, coupler, hinge)
    mech.ground(crank.base).weld(crank.tip, coupler.point("A")).weld(coupler.point("B"), hinge.base)
    mech.ground(hinge.tip).spring(coupler.point("P"), crank.base, 10.0)
    return mech


def _synthetic_result(kappas: np.ndarray) -> Result:
    """Columns of a mechanism run: the crank bent uniformly (exact rigid-chain polygon, absolute
    cell angles), the coupler translated with the crank tip, the flexure's base segment turned."""
    series: dict[str, np.ndarray] = {"time": np.linspace(0.0, 1.0, kappas.size), "crank.voltage": 500 * kappas}
    cells = np.pi / 2 + (np.arange(N) + 0.5)[None, :] * kappas[:, None] * LC  # absolute angles
    tip_x = np.sum(LC * np.cos(cells), axis=1)
    tip_y = np.sum(LC * np.sin(cells), axis=1)
    series.update({"crank.base_x": 0 * kappas, "crank.base_y": 0 * kappas, "crank.tip_x": tip_x, "crank.tip_y": tip_y})
    for j in range(N):
        series[f"crank.cell_angle_{j + 1}"] = cells[:, j]
    dx, dy = tip_x - 0.0, tip_y - L
    for name, (x0, y0) in {"A": (0.0, L), "B": (0.04, L), "P": (0.02, 0.05)}.items():
        series[f"coupler.{name}_x"] = x0 + dx
        series[f"coupler.{name}_y"] = y0 + dy
    series.update({"hinge.base_x": 0.04 + dx, "hinge.base_y": L + dy, "hinge.tip_x": 0 * dx + 0.04,
                   "hinge.tip_y": 0 * dx, "hinge.base_angle": -np.pi / 2 + 0.1 * kappas})
    units = {n: ("s" if n == "time" else "V" if n.endswith("voltage") else "rad" if "angle" in n else "m")
             for n in series}
    return Result(series, units)


KAPPAS = np.linspace(0.0, 4.0, 9)


def test_bender_shape_ends_at_the_recorded_tip_with_the_active_layer_on_its_right():
    mech, result = _mechanism(), _synthetic_result(KAPPAS)
    for row in (0, 4, 8):
        shape = mechanism_shape(mech, result, row)
        crank = shape.benders[0]
        np.testing.assert_allclose(crank.passive[-1], [result["crank.tip_x"][row], result["crank.tip_y"][row]],
                                   atol=1e-15)
        np.testing.assert_allclose(crank.passive[0], [0.0, 0.0], atol=1e-15)
        # cell lengths kept
        np.testing.assert_allclose(np.linalg.norm(np.diff(crank.passive, axis=0), axis=1), LC, rtol=1e-12)
        # active layer: offset e = (h1 + h2)/2 to the right of base -> tip
        e = 0.25e-3
        for j in range(N):
            start = crank.active[j, 0] - crank.passive[j]
            axis = crank.passive[j + 1] - crank.passive[j]
            assert np.linalg.norm(start) == pytest.approx(e, rel=1e-12)
            assert float(axis[0] * start[1] - axis[1] * start[0]) < 0.0  # right of the axis
        assert crank.drives == ["crank"] * N


def test_exaggerated_shape_scales_displacements():
    mech, result = _mechanism(), _synthetic_result(KAPPAS)
    true = mechanism_shape(mech, result, 8)
    big = mechanism_shape(mech, result, 8, scale=3.0)
    ref = np.array(mech.components["coupler"].points["P"])
    np.testing.assert_allclose(big.link_points["coupler"]["P"] - ref, 3.0 * (true.link_points["coupler"]["P"] - ref),
                               rtol=1e-12)
    # the bender's drawn tip is the magnified tip displacement (welded parts stay attached),
    # its base stays, and its cells turn by about 3x their rotation (the chain's closure gap
    # to the magnified tip is spread along it)
    tip0 = np.array([0.0, L])
    tip = np.array([result["crank.tip_x"][8], result["crank.tip_y"][8]])
    np.testing.assert_allclose(big.benders[0].passive[-1], tip0 + 3.0 * (tip - tip0), rtol=1e-12)
    np.testing.assert_allclose(big.benders[0].passive[0], [0.0, 0.0], atol=1e-15)
    turn = np.arctan2(*np.diff(big.benders[0].passive, axis=0)[:, ::-1].T) - np.pi / 2
    np.testing.assert_allclose(turn, 3.0 * (np.arange(N) + 0.5) * KAPPAS[8] * LC, rtol=0.05)


def test_flexure_pivot_and_spring_geometry():
    mech, result = _mechanism(), _synthetic_result(KAPPAS)
    shape = mechanism_shape(mech, result, 5)
    base = np.array([result["hinge.base_x"][5], result["hinge.base_y"][5]])
    angle = result["hinge.base_angle"][5]
    np.testing.assert_allclose(shape.pivots["hinge"], base + 0.5 * L * np.array([math.cos(angle), math.sin(angle)]),
                               rtol=1e-12)
    (name, p, q), = shape.springs
    assert name == "spring_1"
    np.testing.assert_allclose(p, [result["coupler.P_x"][5], result["coupler.P_y"][5]])
    np.testing.assert_allclose(q, [0.0, 0.0], atol=1e-15)


def test_png_and_gif_are_written_atomically(tmp_path):
    from PIL import Image

    mech, result = _mechanism(), _synthetic_result(KAPPAS)
    png = tmp_path / "m.png"
    plot_mechanism(mech, result, path=png, scale=2.0, trace=["coupler.P"])
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    gif = animate_mechanism(mech, result, tmp_path / "m.gif", frames=5, fps=5, trace=["coupler.P"])
    assert gif.read_bytes()[:6] == b"GIF89a"
    with Image.open(gif) as image:
        assert image.n_frames == 5
    paths = tmp_path / "p.png"
    plot_point_paths(result, ["coupler.P"], path=paths,
                     others=[(np.array([0.0, 0.01]), np.array([0.05, 0.05]), "reference")])
    assert paths.is_file()
    assert not list(tmp_path.glob(".tmp_*"))


def test_bad_input_is_refused(tmp_path):
    mech, result = _mechanism(), _synthetic_result(KAPPAS)
    with pytest.raises(ValueError, match=r"row must be an integer in \[-9, 8\].*got 9"):
        mechanism_shape(mech, result, 9)
    short = Result({"time": [0.0]}, {"time": "s"})
    with pytest.raises(ValueError, match="no column 'crank.cell_angle_1'"):
        mechanism_shape(mech, short, 0)
    with pytest.raises(ValueError, match="scale must be"):
        plot_mechanism(mech, result, path=tmp_path / "x.png", scale=0.0)
    with pytest.raises(ValueError, match="frames must be an integer >= 2"):
        animate_mechanism(mech, result, tmp_path / "x.gif", frames=1)
    with pytest.raises(ValueError, match="existing directory"):
        animate_mechanism(mech, result, tmp_path / "missing" / "x.gif", frames=2)
    with pytest.raises(ValueError, match="trace point 'coupler.Q'"):
        plot_mechanism(mech, result, path=tmp_path / "x.png", trace=["coupler.Q"])
    assert not list(tmp_path.glob("*"))


def test_actuator_run_drawn_as_a_one_bender_mechanism(tmp_path):
    from exudyn_atcm import BendingActuator, simulate

    act = BendingActuator(3, 29e-3, 28e-3, CFC, MFC, PiezoDrive(lambda t: 1500.0 * t / 0.01), cell="rigid")
    result = simulate(act, 0.01, step=1e-3)
    mech, drawn = actuator_as_mechanism(act, result)
    shape = mechanism_shape(mech, drawn, -1)
    # the drawn chain ends at the actuator's recorded tip (same cell angles and lengths)
    np.testing.assert_allclose(shape.benders[0].passive[-1], [result["actuator.tip_x"][-1], result["actuator.tip_y"][-1]], atol=1e-12)
    assert shape.benders[0].drives == ["actuator"] * 3
    gif = animate_mechanism(mech, drawn, tmp_path / "a.gif", frames=3, trace=["actuator.tip"])
    assert gif.read_bytes()[:6] == b"GIF89a"


def test_real_run_with_every_component_kind_is_drawn(tmp_path):
    from exudyn_atcm import static_sweep

    bender = Bender("b", width=1e-2, passive=CFC, active=MFC, length=0.04, n_cells=6, drive=PiezoDrive(0.0),
                    angle=0.3, active_side="left", cell="rigid")
    tip = bender.points["tip"]
    strip = Flexure("f", base=tip, tip=(tip[0] + 0.01, tip[1]), width=5e-3, layer=Layer(0.1e-3, 70e9, 1550.0), model="cells", n_cells=3)
    slide = Link("slide", {"A": (tip[0] + 0.01, tip[1]), "B": (tip[0] + 0.02, tip[1])}, mass=1e-3, inertia=1e-8)
    mech = Mechanism("kinds").add(bender, strip, slide).ground(bender.base).weld(bender.tip, strip.base)
    mech.weld(strip.tip, slide.point("A")).ground(slide.point("B"), joint="slider", axis=(1.0, 0.0))
    mech.stop("slide.A", position=(tip[0] + 0.012, tip[1]), normal=(-1.0, 0.0), stiffness=1e4)
    result = static_sweep(mech, [0.0, 1500.0])
    shape = mechanism_shape(mech, result, 1)
    for name, line in (("b", shape.benders[0].passive), ("f", shape.flexures["f"])):
        np.testing.assert_allclose(line[-1], [result[f"{name}.tip_x"][1], result[f"{name}.tip_y"][1]], atol=1e-12)
    # active layer on the left of base -> tip
    axis = shape.benders[0].passive[1] - shape.benders[0].passive[0]
    offset = shape.benders[0].active[0, 0] - shape.benders[0].passive[0]
    assert float(axis[0] * offset[1] - axis[1] * offset[0]) > 0.0
    plot_mechanism(mech, result, path=tmp_path / "kinds.png", scale=5.0)
    assert (tmp_path / "kinds.png").is_file()


def test_every_animation_frame_is_the_whole_drawing_of_its_state(tmp_path, monkeypatch):
    # animate_mechanism hands save_gif the artists that change (the mechanism, the traces, the title, the
    # legend above them); each blitted frame must equal a whole drawing of the figure in that frame's state
    from PIL import Image, ImageSequence

    from exudyn_atcm.plots import gif as gif_module
    from exudyn_atcm.plots import mechanism as mechanism_plots

    seen = {}

    def keep(fig, draw, n_frames, path, **kwargs):
        seen.update(fig=fig, draw=draw)
        return gif_module.save_gif(fig, draw, n_frames, path, colors=256, **{k: v for k, v in kwargs.items() if k != "colors"})

    monkeypatch.setattr(mechanism_plots, "save_gif", keep)
    mech, result = _mechanism(), _synthetic_result(KAPPAS)
    gif = animate_mechanism(mech, result, tmp_path / "m.gif", frames=6, fps=5, trace=["coupler.P"])
    with Image.open(gif) as image:
        frames = [np.asarray(f.convert("RGB")) for f in ImageSequence.Iterator(image)]
    fig, draw = seen["fig"], seen["draw"]
    for k in (4, 1, 5):
        draw(k)
        fig.canvas.draw()
        whole = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy())
        expected = np.asarray(whole.quantize(256, method=Image.Quantize.MAXCOVERAGE).convert("RGB"))
        assert np.array_equal(frames[k], expected), k
        assert (frames[k][:20] < 128).any()  # the title with the frame's time is drawn
