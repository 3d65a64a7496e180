"""One column schema (issue 30, part 1): a lone actuator's columns are named like any bender's.

The reference is the same bender built by hand with :class:`~exudyn_atcm.Bender` and
:class:`~exudyn_atcm.Mechanism` (bender ``actuator``): the actuator's result has that mechanism's
columns, plus ``actuator.stroke`` (strain times cell length, computed here from the strain).  The
names before 0.3.0 (``tip_y``, ``stroke``, ``cell_angle_j``, ...) still read for one release, each with
an ``AtcmDeprecationWarning`` naming the new name; a CSV file written before 0.3.0 reads back as written.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm import AtcmDeprecationWarning, Bender, BendingActuator, Layer, Mechanism, PiezoDrive, Result
from exudyn_atcm.plots.result import plot_result

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
N, CELL, W = 3, 0.029, 28e-3
OLD = {"voltage": "actuator.voltage", "strain": "actuator.strain", "stroke": "actuator.stroke",
       "tip_x": "actuator.tip_x", "tip_y": "actuator.tip_y", "tip_angle": "actuator.tip_angle",
       "cell_angle_1": "actuator.cell_angle_1", "cell_angle_3": "actuator.cell_angle_3"}


def _drive():
    return PiezoDrive(lambda t: 1500.0 * t / 0.01)


def _actuator():
    return BendingActuator(N, CELL, W, CFC, MFC, _drive(), cell="rigid")


def _by_hand():
    b = Bender("actuator", width=W, passive=CFC, active=MFC, length=N * CELL, n_cells=N, drive=_drive(), cell="rigid")
    return Mechanism("actuator").add(b).ground(b.base)


def _with_stroke(names):
    k = names.index("actuator.strain") + 1
    return names[:k] + ["actuator.stroke"] + names[k:]


@pytest.fixture(scope="module")
def run():
    return atcm.simulate(_actuator(), 0.01, step=1e-3, record_every=2)


def test_the_columns_are_the_one_bender_mechanisms_plus_the_stroke(run):
    ref = atcm.simulate(_by_hand(), 0.01, step=1e-3, record_every=2)
    assert run.names == _with_stroke(ref.names)
    assert run.every_step.names == _with_stroke(ref.every_step.names)
    for name in ref:
        assert run.unit(name) == ref.unit(name)
    assert run.unit("actuator.stroke") == "m"
    np.testing.assert_array_equal(run["actuator.stroke"], run["actuator.strain"] * CELL)
    assert not [n for n in run if not (n == "time" or n.startswith("actuator."))]
    static = atcm.solve_static(_actuator(), voltage=800.0)
    assert static.names == _with_stroke(atcm.solve_static(_by_hand(), voltage=800.0).names)
    sweep = atcm.static_sweep(_actuator(), [0.0, 800.0])
    assert sweep.names[0] == "point" and sweep.names[1:4] == ["actuator.voltage", "actuator.strain", "actuator.stroke"]


@pytest.mark.parametrize("old", sorted(OLD))
def test_an_old_name_reads_for_one_release_with_a_deprecation_warning(run, old):
    new = OLD[old]
    message = rf"series '{old}' is now named '{new}'"
    with pytest.warns(AtcmDeprecationWarning, match=message) as caught:
        values = run[old]
    assert caught[0].filename == __file__  # points at the reading line
    np.testing.assert_array_equal(values, run[new])
    with pytest.warns(AtcmDeprecationWarning, match=message):
        assert old in run
    with pytest.warns(AtcmDeprecationWarning, match=message):
        assert run.unit(old) == run.unit(new)
    with pytest.warns(AtcmDeprecationWarning, match=message):
        np.testing.assert_array_equal(run.get(old), run[new])
    assert old not in run.names and len(run) == len(run.names)  # not a second copy in files or iteration
    if not old.startswith("cell_angle_"):
        with pytest.warns(AtcmDeprecationWarning, match=message):
            np.testing.assert_array_equal(run.every_step[old], run.every_step[new])


def test_new_names_and_unknown_names_do_not_warn(run):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert "actuator.tip_y" in run and "time" in run
        assert "tip_z" not in run and "cell_angle_4" not in run
        with pytest.raises(KeyError, match="no series 'tip_z'"):
            run["tip_z"]
    assert run.old_names["tip_y"] == "actuator.tip_y" and run.old_names["cell_angle_2"] == "actuator.cell_angle_2"


def test_csv_files_carry_the_new_names(run, tmp_path):
    path = tmp_path / "run.csv"
    run.to_csv(path)
    header = [line for line in path.read_text().splitlines() if not line.startswith("#")][0]
    assert header.split(",")[:4] == ["time [s]", "actuator.voltage [V]", "actuator.strain [-]", "actuator.stroke [m]"]
    back = atcm.read_csv(path)
    assert back.names == run.names
    np.testing.assert_array_equal(back["actuator.tip_y"], run["actuator.tip_y"])


def test_a_file_written_before_0_3_keeps_its_columns_and_still_plots(tmp_path):
    t = np.linspace(0.0, 0.01, 6)
    kappa_l = 0.3 * t / 0.01  # a circular arc growing in time: cell j turns by kappa * CELL * (j + 1/2)
    series = {"time": t, "voltage": 1500.0 * t / 0.01, "strain": 1e-3 * t / 0.01, "stroke": CELL * 1e-3 * t / 0.01,
              "tip_x": N * CELL * np.cos(kappa_l), "tip_y": N * CELL * np.sin(kappa_l), "tip_angle": kappa_l,
              **{f"cell_angle_{j + 1}": kappa_l * (j + 0.5) / N for j in range(N)}}
    units = {n: "s" if n == "time" else "V" if n == "voltage" else "-" if n == "strain"
             else "rad" if "angle" in n else "m" for n in series}
    path = tmp_path / "old.csv"
    Result(series, units, parameters={"cell_length [m]": CELL}).to_csv(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        old = atcm.read_csv(path)  # kept as written: no renaming, no warning
        assert old.names == list(series)
        np.testing.assert_array_equal(old["tip_y"], series["tip_y"])
        written = plot_result(old, tmp_path / "plots")  # the actuator's three plots, as before
    assert sorted(p.rsplit("/", 1)[-1] for p in map(str, written)) == ["shapes.png", "time_series.png",
                                                                        "tip_vs_voltage.png"]


def test_old_names_must_name_series_of_the_result():
    series, units = {"time": [0.0], "b.tip_y": [1.0]}, {"time": "s", "b.tip_y": "m"}
    with pytest.raises(ValueError, match="old_names must map names that are not series"):
        Result(series, units, old_names={"tip_y": "b.tip_x"})
    with pytest.raises(ValueError, match="old_names must map names that are not series"):
        Result(series, units, old_names={"time": "b.tip_y"})


def test_step_error_takes_an_old_column_name_for_one_release():
    with pytest.warns(AtcmDeprecationWarning, match=r"columns: series 'tip_y' is now named 'actuator.tip_y'") as caught:
        report = atcm.step_error(_actuator(), 0.01, step=1e-3, check_order=False, columns=["tip_y"])
    assert caught[0].filename == __file__
    assert report.summary == ["actuator.tip_y"]
