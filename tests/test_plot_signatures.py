"""Every plot function is ``plot_x(thing, *, ax=None, path=None) -> Figure`` (issue 30, part 6).

For each: the signature (``ax`` and ``path`` keyword-only, default ``None``, annotated ``Figure``); a
call with ``ax`` draws into the caller's axes and returns their figure, writing nothing; a call with
``path`` writes a PNG and returns the figure; a failure while writing leaves no file and no temporary
(the write is atomic); the earlier positional output path still works, warns
``AtcmDeprecationWarning`` and returns the path, as it did.
"""

from __future__ import annotations

import inspect
from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.figure import Figure

from exudyn_atcm import AtcmDeprecationWarning
from exudyn_atcm.io.result import Result
from exudyn_atcm.plots import identification, style
from exudyn_atcm.plots import hysteresis as hp
from exudyn_atcm.plots import mechanism as mp
from exudyn_atcm.plots import result as rp
from test_mechanism_plots import KAPPAS, _mechanism, _synthetic_result

PNG = b"\x89PNG\r\n\x1a\n"
U = np.linspace(-500.0, 1500.0, 40)
T = np.linspace(0.0, 1.0, 40)


def _actuator_result() -> Result:
    angles = {f"actuator.cell_angle_{j}": (j + 0.5) / 3 * 0.3 * T for j in range(3)}
    series = {"time": T, "actuator.voltage": U, "actuator.stroke": 1e-6 * T, "actuator.tip_x": 0.087 - 1e-3 * T,
              "actuator.tip_y": 0.01 * T, **angles}
    units = {"time": "s", "actuator.voltage": "V", "actuator.stroke": "m", "actuator.tip_x": "m", "actuator.tip_y": "m",
             **{k: "rad" for k in angles}}
    return Result(series, units, parameters={"cell_length [m]": 0.029})


def _report():
    return SimpleNamespace(predicted=2e-8 * (U + 500.0) + 1e-7, linear_model={"a": 2e-8, "b": 1e-5}, n_fit=25,
                           model_errors={"fit": {"rms": 1e-7}, "held_out": {"rms": 2e-7}})


def _choice():
    candidates = [SimpleNamespace(label=name, family=name, failure="", held_out_rms_percent=pct, parameters=k,
                                  report=SimpleNamespace(predicted=2e-8 * (U + 500.0) * f))
                  for name, pct, k, f in (("everett", 0.5, 20, 1.0), ("pi", 1.5, 8, 1.02))]
    return SimpleNamespace(candidates=candidates, chosen=candidates[0], input=U, output=2e-8 * (U + 500.0), n_fit=25,
                           output_unit="m")


def _cases():
    """(name, function, data args, keyword args, panels, the earlier call's positional args given a path)."""
    curves = [hp.Curve(U, 2e-8 * (U + 500.0), "a")]
    series = Result({"time": T, "voltage": U, "stroke": 1e-6 * T}, {"time": "s", "voltage": "V", "stroke": "m"})
    groups = [["voltage"], ["stroke"]]
    act = _actuator_result()
    mech, mres = _mechanism(), _synthetic_result(KAPPAS)
    relay_kw = {"u_min": -500.0, "u_max": 1500.0}
    return [
        ("plot_loops", hp.plot_loops, (curves,), {}, 1, lambda p: (p, curves)),
        ("hysteresis.plot_time_series", hp.plot_time_series, (series, groups), {}, 2, lambda p: (p, series, groups)),
        ("plot_relays", hp.plot_relays, ([0.0, 500.0], [-300.0, 100.0]), relay_kw, 1,
         lambda p: (p, [0.0, 500.0], [-300.0, 100.0])),
        ("plot_fit", identification.plot_fit, (_report(), U, 2e-8 * (U + 500.0)), {}, 2, None),
        ("plot_fit_series", identification.plot_fit_series, (_report(), U, 2e-8 * (U + 500.0)), {}, 3, None),
        ("plot_model_choice", identification.plot_model_choice, (_choice(),), {}, 2, lambda p: (p, _choice())),
        ("plot_mechanism", mp.plot_mechanism, (mech, mres), {}, 1, lambda p: (mech, mres, p)),
        ("plot_point_paths", mp.plot_point_paths, (mres, ["coupler.P"]), {}, 1, lambda p: (mres, ["coupler.P"], p)),
        ("result.plot_time_series", rp.plot_time_series, (act,), {}, 3, lambda p: (act, p)),
        ("plot_tip_vs_voltage", rp.plot_tip_vs_voltage, (act,), {}, 1, lambda p: (act, p)),
        ("plot_shapes", rp.plot_shapes, (act,), {}, 1, lambda p: (act, p)),
    ]


CASES = _cases()
IDS = [c[0] for c in CASES]


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_signature_is_thing_then_keyword_ax_and_path_returning_a_figure(case):
    _, function, *_ = case
    params = inspect.signature(function).parameters
    for name in ("ax", "path"):
        assert params[name].kind is inspect.Parameter.KEYWORD_ONLY, name
        assert params[name].default is None, name
    assert inspect.signature(function).return_annotation in (Figure, "Figure")


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_ax_draws_into_the_callers_axes_and_writes_nothing(case, tmp_path, monkeypatch):
    _, function, args, kwargs, panels, _ = case
    monkeypatch.chdir(tmp_path)
    fig, axes = style.new_figure(panels, 1)
    ax = axes[0] if panels == 1 else axes
    out = function(*args, ax=ax, **kwargs)
    assert out is fig
    assert all(a.has_data() for a in axes if a.get_visible())
    assert list(tmp_path.iterdir()) == []
    if panels > 1:  # a multi-panel plot wants one axes per panel
        with pytest.raises(ValueError, match=f"ax must be a sequence of {panels} matplotlib Axes"):
            function(*args, ax=axes[0], **kwargs)


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_path_writes_a_png_and_returns_the_figure(case, tmp_path):
    _, function, args, kwargs, *_ = case
    out = function(*args, path=tmp_path / "a.png", **kwargs)
    assert isinstance(out, Figure)
    assert (tmp_path / "a.png").read_bytes()[:8] == PNG
    assert [p.name for p in tmp_path.iterdir()] == ["a.png"]


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_a_failed_write_leaves_no_file(case, tmp_path, monkeypatch):
    _, function, args, kwargs, *_ = case

    def broken(self, handle, **kw):
        handle.write(PNG + b"half a picture")  # a partial file, then the failure
        raise RuntimeError("disk full")

    monkeypatch.setattr(Figure, "savefig", broken)
    with pytest.raises(RuntimeError, match="disk full"):
        function(*args, path=tmp_path / "a.png", **kwargs)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("case", [c for c in CASES if c[5] is not None], ids=[c[0] for c in CASES if c[5]])
def test_the_earlier_positional_path_warns_and_returns_the_path(case, tmp_path):
    name, function, _, kwargs, _, earlier = case
    target = tmp_path / "old.png"
    with pytest.warns(AtcmDeprecationWarning, match=r"pass the output file as path="):
        out = function(*earlier(target), **kwargs)
    assert str(out) == str(target)
    assert target.read_bytes()[:8] == PNG


def test_the_earlier_plot_fit_writes_both_figures_and_warns(tmp_path):
    loop, series = tmp_path / "loop.png", tmp_path / "series.png"
    with pytest.warns(AtcmDeprecationWarning, match=r"plot_fit\(\): pass the output file as path="):
        out = identification.plot_fit(loop, series, _report(), U, 2e-8 * (U + 500.0), T)
    assert [str(p) for p in out] == [str(loop), str(series)]
    assert loop.read_bytes()[:8] == PNG and series.read_bytes()[:8] == PNG


def test_a_path_given_both_ways_is_refused(tmp_path):
    act = _actuator_result()
    with pytest.raises(TypeError, match="multiple values for argument 'path'"):
        rp.plot_tip_vs_voltage(act, tmp_path / "a.png", path=tmp_path / "b.png")
    with pytest.raises(TypeError, match="multiple values for argument 'path'"):
        hp.plot_loops(tmp_path / "a.png", [hp.Curve(U, U)], path=tmp_path / "b.png")
    assert list(tmp_path.iterdir()) == []
