"""The case convention and the paper cases (checked against the paper's and the theory page's numbers)."""

from __future__ import annotations

import warnings

import json
import math

import exudyn
import numpy as np
import pytest

from exudyn_atcm.casework import Case, CaseError, CaseOutput, Parameter, case_dirs, find_case, load_case
from exudyn_atcm.io import read_csv

from _cli_helpers import CASES, cli, run

# Paper / docs/theory.rst numbers (independent of the code)
R1, R2 = 1.459432, 1.874469
LOOP_AREA_EXACT = 21605.0e-6  # m V  (21605.0 µm·V)
LOOP_AREA_ROUNDED = 23466.7e-6  # m V
STROKE_MAX, STROKE_MIN = 40e-6, -4e-6  # m
HYSTERESIS_CASES = ["paper_hysteresis_loop", "paper_stroke_table", "paper_discrete_preisach"]


# ----------------------------------------------------------------------------- standalone scripts
@pytest.mark.parametrize("name", HYSTERESIS_CASES)
def test_case_script_runs_standalone_with_defaults(tmp_path, name):
    proc = run([str(CASES / f"{name}.py"), "--out", "out"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "warning" not in proc.stderr.lower(), proc.stderr  # a case must not warn on its defaults
    out = tmp_path / "out"
    assert (out / f"{name}.csv").is_file()
    pngs = sorted(out.glob(f"{name}_*.png"))
    assert pngs, "plots expected"
    assert all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in pngs)
    record = json.loads((out / f"{name}.json").read_text())
    assert record["case"] == name
    assert record["versions"]["exudyn"] == exudyn.__version__
    assert record["wall_time [s]"] >= 0.0 and record["steps"] >= 2
    assert record["scalars"] and record["parameters"]
    assert not list(out.glob(".tmp_*")), "temporary files left behind"
    data = read_csv(out / f"{name}.csv")
    assert data.parameters["case"] == name
    assert data.n_rows == record["steps"]


@pytest.mark.parametrize("name", ["paper_bending_actuator", "stiffness_comparison"])
def test_case_is_quiet_on_its_defaults(name):
    """A case must not warn on its defaults (the other cases are checked where their tests run them)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        out = load_case(CASES / f"{name}.py").run({"animation": False} if name == "paper_bending_actuator" else None)
    assert out.scalars


# ----------------------------------------------------------------------------- paper numbers
def test_hysteresis_loop_reproduces_paper_numbers():
    out = load_case(CASES / "paper_hysteresis_loop.py").run()
    s = out.scalars
    assert s["r1"] == pytest.approx(R1, abs=5e-7)
    assert s["r2"] == pytest.approx(R2, abs=5e-7)
    assert (s["r1_rounded"], s["r2_rounded"]) == (1.5, 2.0)
    assert s["loop_area"] == pytest.approx(LOOP_AREA_EXACT, abs=5e-8)
    assert s["loop_area_rounded"] == pytest.approx(LOOP_AREA_ROUNDED, abs=5e-8)
    assert s["loop_area_series"] == pytest.approx(LOOP_AREA_EXACT, rel=1e-4)
    assert s["stroke_max"] == pytest.approx(STROKE_MAX, abs=1e-12)
    assert s["stroke_min"] == pytest.approx(STROKE_MIN, abs=1e-12)
    assert s["ascending_at_u_m"] == pytest.approx(12e-6, abs=1e-12)
    assert s["descending_at_u_m"] == pytest.approx(28e-6, abs=1e-12)
    assert s["ascending_rounded_at_u_m"] == pytest.approx(11.556e-6, abs=5e-10)
    assert s["descending_rounded_at_u_m"] == pytest.approx(29.000e-6, abs=5e-10)
    r = out.result
    assert r.unit("stroke") == "m" and r.unit("voltage") == "V" and r.unit("time") == "s"
    # Eq. 11: U_min at t = 0, U_max at T/2
    assert r["voltage"][0] == -500.0
    assert r["voltage"][np.argmin(abs(r["time"] - 0.5))] == pytest.approx(1500.0)


def test_stroke_table_is_the_motor_table():
    out = load_case(CASES / "paper_stroke_table.py").run()
    r = out.result
    assert r.names == ["time", "voltage", "stroke"]
    assert r.n_rows == 21
    np.testing.assert_allclose(np.diff(r["time"]), 0.05)
    assert r["stroke"][0] == pytest.approx(STROKE_MIN, abs=1e-12)
    assert r["stroke"][10] == pytest.approx(STROKE_MAX, abs=1e-12)  # t = T/2, U = 1500 V
    assert r["stroke"][-1] == pytest.approx(STROKE_MIN, abs=1e-12)
    # rounded exponents (default): x(t) on the rising half = x_min + Δx ((U - U_min)/ΔU)^1.5
    u = r["voltage"][:11]
    expected = STROKE_MIN + 44e-6 * ((u + 500.0) / 2000.0) ** 1.5
    np.testing.assert_allclose(r["stroke"][:11], expected, atol=1e-15)
    assert out.scalars["stroke_linear_law"] == pytest.approx(40.02e-6, abs=5e-9)  # docs/theory.rst
    assert 0.0 < out.scalars["table_max_interpolation_error"] < 1e-6


def test_stroke_table_more_points_are_more_accurate():
    case = load_case(CASES / "paper_stroke_table.py")
    coarse = case.run({"points_per_period": 10}).scalars["table_max_interpolation_error"]
    fine = case.run({"points_per_period": 40}).scalars["table_max_interpolation_error"]
    assert fine < coarse / 3.0


def test_discrete_preisach_identifies_relays_by_eq12():
    out = load_case(CASES / "paper_discrete_preisach.py").run()
    relays = out.tables["relays"]
    assert relays.n_rows == 6
    gain = (STROKE_MAX - STROKE_MIN) / 6
    np.testing.assert_allclose(relays["gain"], gain, rtol=1e-12)
    # switch-on: where the exact ascending branch reaches level i*gain above x_min (docs/theory.rst)
    levels = np.arange(1, 7) / 6.0
    alpha = -500.0 + 2000.0 * levels ** (1.0 / R1)
    beta = 1500.0 - 2000.0 * (1.0 - levels) ** (1.0 / R2)
    np.testing.assert_allclose(relays["switch_on"], alpha, atol=1.0)  # identified from 2000 samples
    np.testing.assert_allclose(relays["switch_off"], beta, atol=1.0)
    # the equal-gain discrete model stays within one gain step of the continuous one
    assert out.scalars["max_difference"] <= gain * (1 + 1e-9)
    assert out.scalars["loop_area_continuous"] == pytest.approx(LOOP_AREA_EXACT, abs=5e-8)
    # the input reverses inside the range
    u = out.result["voltage"]
    reversals = np.flatnonzero(np.diff(np.sign(np.diff(u))) != 0)
    inner = [u[i + 1] for i in reversals if -500.0 < u[i + 1] < 1500.0]
    assert len(inner) >= 3


def test_stiffness_comparison_against_model_md():
    pytest.importorskip("exudyn_atcm.mechanism.actuator")
    out = load_case(CASES / "stiffness_comparison.py").run({"n_voltages": 2})
    s = out.scalars
    assert s["EI_theory_composite"] == pytest.approx(1.28699e-2, rel=1e-5)  # the paper's actuator, docs/theory.rst
    assert s["tip_angle_composite"] == pytest.approx(4.13984 * 0.087, rel=1e-5)
    assert s["f1_theory_composite"] == pytest.approx(35.97, abs=0.005)
    assert s["EI_ratio_paper_to_composite"] == pytest.approx(1.49, abs=0.005)  # docs/theory.rst
    assert s["curvature_ratio_paper_to_composite"] == pytest.approx(1.11, abs=0.005)
    assert s["compliance_composite"] == pytest.approx(17.055e-3 * (1 + 1 / 18), rel=2e-4)


@pytest.mark.parametrize("cell, factor", [("beam", 1 - 1 / 36), ("ancf", 1.0)])
def test_stiffness_comparison_with_beam_elements(cell, factor):
    """cell="beam"/"ancf": the compliance reference is that of the element, not the six-bar chain's.

    Three linear shear-rigid elements: L^3/(3EI) (1 - 1/(4 N^2)) exactly (trapezoidal rule over
    the node rotations); cubic ANCF elements: the cubic deflection itself.  Tolerance 1e-4:
    the elements' axis is stiff but not rigid in extension and shear (penalty of the element).
    """
    s = load_case(CASES / "stiffness_comparison.py").run({"n_voltages": 2, "cell": cell}).scalars
    assert s["compliance_chain_theory_composite"] == pytest.approx(17.055e-3 * factor, rel=1e-4)
    assert s["compliance_composite"] == pytest.approx(s["compliance_chain_theory_composite"], rel=1e-4)
    assert s["tip_angle_composite"] == pytest.approx(4.13984 * 0.087, rel=1e-5)  # exact under actuation alone


def test_fig12_case_draws_layers_joints_and_motors_with_the_scale(tmp_path, monkeypatch):
    """The Fig. 12 shape plot and GIF are mechanism drawings: both layers, cell joints, motors, scale stated.

    Short run (one 0.2 s period, beam cells: the drawing does not depend on the cell model).
    """
    from exudyn_atcm.plots import target

    case = load_case(CASES / "paper_bending_actuator.py")
    figures = []
    save = target.save_figure

    def keep_shapes(fig, path):  # every plot function writes through plots.target; keep the shape plot's figure
        if str(path).endswith("_shapes.png"):
            figures.append(fig)
        return save(fig, path)
    monkeypatch.setattr(target, "save_figure", keep_shapes)
    out = case.run({"cell": "beam", "period": 0.2, "cycles": 1, "step": 1e-4}, out_dir=tmp_path, plot=True)
    names = {f.name for f in out.files}
    assert {"paper_bending_actuator_shapes.png", "paper_bending_actuator_animation.gif"} <= names
    (ax,) = figures[0].axes
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    # a beam-cell actuator's joints are its beam nodes (the kind's joint_label; before issue 30 the drawing's
    # own conversion made every actuator a rigid chain, labelled "cell joints")
    assert "passive layer" in labels and "beam nodes" in labels and "motor, drive actuator" in labels
    assert any(label.startswith("active layer") for label in labels)
    assert "(true scale)" in ax.get_title() and "3 beam cells" in ax.get_title()
    assert ax.get_xlabel() == "x [mm]" and ax.get_ylabel() == "y [mm]"
    # the drawn tip (passive layer's last point) is the simulated largest deflection; the polyline
    # is built from the recorded cell angles (a beam element's: the mean of its node rotations, so
    # its chord differs from the element's arc by O(rotation difference^2) ~ 1e-6 relative)
    tip = max(line.get_ydata()[-1] for line in ax.get_lines() if line.get_label() == "passive layer")
    assert tip == pytest.approx(1e3 * np.max(np.abs(out.result["actuator.tip_y"])), rel=1e-5)
    from PIL import Image

    with Image.open(tmp_path / "paper_bending_actuator_animation.gif") as gif:
        assert gif.n_frames >= 30


# ----------------------------------------------------------------------------- parameters
def test_cli_run_with_set_overrides(tmp_path):
    proc = cli(["run", "paper_hysteresis_loop", "--set", "period=2", "--set", "cycles=1", "--out", "o", "--no-plot"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    record = json.loads((tmp_path / "o" / "paper_hysteresis_loop.json").read_text())
    assert record["parameters"]["period"] == {"value": 2.0, "unit": "s"}
    assert record["parameters"]["cycles"]["value"] == 1
    data = read_csv(tmp_path / "o" / "paper_hysteresis_loop.csv")
    assert data["time"][-1] == pytest.approx(2.0)
    assert data.parameters["period [s]"] == 2.0
    assert not list((tmp_path / "o").glob("*.png"))
    assert record["scalars"]["r1"]["value"] == pytest.approx(R1, abs=5e-7)


@pytest.mark.parametrize(
    "assignment, words",
    [
        ("periode=2", "unknown parameter 'periode'"),
        ("period=fast", "must be a finite real number"),
        ("cycles=2.5", "must be an integer"),
        ("period", "NAME=VALUE"),
    ],
)
def test_bad_parameters_are_refused_with_the_list(assignment, words):
    case = load_case(CASES / "paper_hysteresis_loop.py")
    with pytest.raises(CaseError) as info:
        case.resolve([assignment])
    message = str(info.value)
    assert words in message
    for p in case.parameters:  # the list of valid parameters
        assert p.name in message
    assert "\n" not in message


def test_parameter_types():
    p_float = Parameter("x", 1.0, "m")
    assert p_float.parse("2") == 2.0 and isinstance(p_float.parse("2"), float)
    with pytest.raises(ValueError, match="finite"):
        p_float.parse("nan")
    p_int = Parameter("n", 3)
    assert p_int.parse("7") == 7
    with pytest.raises(ValueError):
        p_int.parse("7.0")
    p_bool = Parameter("flag", False)
    assert p_bool.parse("yes") is True and p_bool.parse("0") is False
    with pytest.raises(ValueError):
        p_bool.parse("maybe")
    p_list = Parameter("u", (0.0, 1.0), "V")
    assert p_list.parse("-500, 1500,0") == (-500.0, 1500.0, 0.0)
    with pytest.raises(ValueError, match="u must be comma-separated finite real numbers"):
        p_list.parse("")  # a list with a non-empty default needs at least one number
    with pytest.raises(ValueError):
        p_list.check(())
    # a list whose default is empty accepts an explicit empty value (= its default), by text or value
    p_optional = Parameter("points", (), "m", "empty: from the reference design")
    assert p_optional.parse("") == () and p_optional.check(()) == () and p_optional.check([]) == ()
    assert p_optional.parse("1e-3, 2e-3") == (1e-3, 2e-3)
    with pytest.raises(ValueError, match=r"points must be comma-separated finite real numbers \[m\], or empty"):
        p_optional.parse("1, nan")
    p_choice = Parameter("cell", "rigid", choices=("rigid", "six-bar"))
    with pytest.raises(ValueError, match="one of rigid, six-bar"):
        p_choice.parse("flexible")
    with pytest.raises(ValueError, match="identifier"):
        Parameter("bad name", 1.0)
    with pytest.raises(ValueError, match="default"):
        Parameter("x", None)


@pytest.mark.parametrize(
    "bounds, good, bad, message",
    [
        ({"exclusive_minimum": 0.0}, [1e-9, 5.0], [0.0, -1.0], r"x must be > 0 \[m\], got"),
        ({"minimum": 0.0}, [0.0, 2.0], [-1e-12], r"x must be >= 0 \[m\], got -1e-12"),
        ({"exclusive_minimum": 0.0, "maximum": 1.0}, [1.0, 0.5], [0.0, 1.0000001], r"x must be > 0 and <= 1 \[m\]"),
        ({"minimum": 0.0, "exclusive_maximum": 1.0}, [0.0, 0.999], [1.0], r"x must be >= 0 and < 1 \[m\], got 1.0"),
    ],
)
def test_declared_bounds_refuse_values_outside_them(bounds, good, bad, message):
    p = Parameter("x", 0.5, "m", **bounds)
    for value in good:
        assert p.check(value) == value and p.parse(repr(value)) == value
    for value in bad:
        with pytest.raises(ValueError, match=message):
            p.check(value)
        with pytest.raises(ValueError, match=message):
            p.parse(repr(value))


def test_bounds_of_ints_and_lists_and_their_declaration():
    n = Parameter("n", 3, "-", minimum=1)
    assert n.parse("1") == 1
    with pytest.raises(ValueError, match=r"^n must be >= 1, got 0$"):  # no unit for "-"
        n.parse("0")
    f = Parameter("f", (0.25, 0.75), "Hz", exclusive_minimum=0.0)
    assert f.parse("1, 2") == (1.0, 2.0)
    with pytest.raises(ValueError, match=r"f must be > 0 \[Hz\] \(every item\), got \(0.25, -1.0\)"):
        f.parse("0.25, -1")
    assert "step = 0.0001 [s] (float, > 0): time step" == Parameter("step", 1e-4, "s", "time step",
                                                                    exclusive_minimum=0.0).describe()
    with pytest.raises(ValueError, match="default of 'x' must be > 0, got -1.0"):
        Parameter("x", -1.0, "m", exclusive_minimum=0.0)
    with pytest.raises(ValueError, match="bounds need a number parameter"):
        Parameter("cell", "rigid", minimum=0.0)
    with pytest.raises(ValueError, match="minimum of 'x' must be a number, got '0'"):
        Parameter("x", 1.0, minimum="0")


def test_a_case_refuses_a_value_outside_its_declared_range_before_it_runs():
    # the four-bar's step is used only after its static sweep: the bound refuses it when it is read
    case = load_case(CASES / "compliant_four_bar.py")
    with pytest.raises(CaseError, match=r"case compliant_four_bar: step must be >= 0 \[s\], got -1.0; valid parameters"):
        case.resolve(["step=-1"])
    with pytest.raises(CaseError, match=r"dynamic_period must be >= 0 \[s\], got -0.5"):  # 0: none; < 0 was a silent none
        case.resolve({"dynamic_period": -0.5})
    identify = load_case(CASES / "identify_and_predict.py")
    with pytest.raises(CaseError, match=r"trim_start must be >= 0 \[s\], got -1.0"):  # was ignored when negative
        identify.resolve(["trim_start=-1"])


def test_python_values_are_checked_too():
    case = load_case(CASES / "paper_stroke_table.py")
    assert case.resolve({"period": 2}).period == 2.0
    with pytest.raises(CaseError, match="must be an integer"):
        case.resolve({"cycles": 1.5})
    with pytest.raises(CaseError, match="unknown parameter"):
        case.resolve({"nope": 1})


def test_run_must_return_case_output():
    bad = Case("bad", "Bad.", [], lambda p, ctx: 42)
    with pytest.raises(CaseError, match="CaseOutput"):
        bad.run()


# ----------------------------------------------------------------------------- finding cases
def _copied_case(directory, new_name="my_table"):
    directory.mkdir(parents=True, exist_ok=True)
    text = (CASES / "paper_stroke_table.py").read_text()
    text = text.replace('Case("paper_stroke_table"', f'Case("{new_name}"').replace('Parameter("period", 1.0', 'Parameter("period", 4.0')
    path = directory / f"{new_name}.py"
    path.write_text(text)
    return path


def test_copy_a_case_and_find_it_by_env_cwd_and_path(tmp_path, monkeypatch):
    extra = tmp_path / "extra"
    path = _copied_case(extra)
    monkeypatch.delenv("EXUDYN_ATCM_CASES", raising=False)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(CaseError, match="no case named 'my_table'"):
        find_case("my_table")
    assert find_case(str(path)) == path.resolve()  # (1) by path
    assert find_case("my_table", cases_dir=extra) == path.resolve()  # --cases-dir
    monkeypatch.setenv("EXUDYN_ATCM_CASES", str(extra))
    assert find_case("my_table") == path.resolve()  # $EXUDYN_ATCM_CASES
    monkeypatch.delenv("EXUDYN_ATCM_CASES")
    local = _copied_case(tmp_path / "cases", "local_case")
    # issue 17: ./cases is searched only when asked (--cases-dir cases, or a path)
    with pytest.raises(CaseError, match="the current directory is searched only when asked"):
        find_case("local_case")
    assert find_case("local_case", cases_dir="cases") == local.resolve()
    assert find_case("cases/local_case.py") == local.resolve()
    assert CASES.resolve() in case_dirs()  # the checkout's cases/
    out = load_case("my_table", cases_dir=extra).run()
    assert out.result["time"][-1] == pytest.approx(4.0)  # the changed default


def test_cli_runs_a_case_file_by_path_and_by_env(tmp_path):
    path = _copied_case(tmp_path / "extra")
    proc = cli(["run", str(path), "--out", "a", "--no-plot"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "a" / "my_table.csv").is_file()
    proc = cli(["run", "my_table", "--out", "b", "--no-plot"], tmp_path, EXUDYN_ATCM_CASES=str(tmp_path / "extra"))
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "b" / "my_table.json").is_file()


def test_load_case_refuses_a_file_without_case(tmp_path):
    plain = tmp_path / "plain_script.py"
    marker = tmp_path / "ran"
    plain.write_text(f"open({str(marker)!r}, 'w').write('x')\n")
    with pytest.raises(CaseError, match="does not follow the case convention"):
        load_case(plain)
    assert not marker.exists(), "a plain script must not be executed"
    wrong = tmp_path / "wrong.py"
    wrong.write_text("import exudyn_atcm.casework.case\nCASE = 1\n")
    with pytest.raises(CaseError, match="defines no CASE"):
        load_case(wrong)
    broken = tmp_path / "broken.py"
    broken.write_text("from exudyn_atcm.casework import Case\nimport no_such_module_xyz\nCASE = None\n")
    with pytest.raises(CaseError, match="import failed"):
        load_case(broken)


def test_case_output_scalars_and_units():
    from exudyn_atcm.io.result import Result

    r = Result({"time": [0.0, 1.0]}, {"time": "s"})
    out = CaseOutput(r, {"a": 1, "b": (2.5, "m")})
    assert out.scalars == {"a": 1.0, "b": 2.5}
    assert out.scalar_units == {"a": "-", "b": "m"}
    assert out.steps == 2
    assert math.isnan(out.wall_time)
    with pytest.raises(ValueError, match="Result"):
        CaseOutput({"time": [0.0]})
