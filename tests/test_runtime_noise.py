"""Warnings only where the user can act, one meaning of ``record_every``, file errors that name the path
(issue 29, finding 11).

* The package's own feedforward program (a table of voltages at the controller's sample time, whose
  inverse-hysteresis voltages jump and hold between samples) counted every sample as a corner, so a
  recording interval of two samples gave "record_every keeps only 0.5 recorded instants across the
  shortest feature".  A sampled program is measured by its reversals, which the wanted output
  fixes: for a wanted ``sin(2 pi t / T)`` they lie at ``T/4 + k T/2``.
* ``record_every=0.0`` was refused in Python but documented as "every step" on the command line:
  zero means every step in both.
* ``to_csv("")`` said "it is a directory", a 300-character file name raised a raw ``OSError``: both
  are a :class:`~exudyn_atcm.errors.WriteError` (an ``OSError``) naming the path and the reason.
"""

from __future__ import annotations

import errno
import math
import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm import BendingActuator, Layer, PiezoDrive, Result, simulate
from exudyn_atcm.errors import AccuracyWarning, WriteError
from exudyn_atcm.io import atomic
from exudyn_atcm.model import PiecewiseLinear, SampledProgram, feedforward_program, linear_program
from exudyn_atcm.model import reference_preisach
from exudyn_atcm.model.recording import recording_schedule
from exudyn_atcm.model.sampled_program import reversal_times

CELL = 29e-3
SAMPLE = 1e-3  # the controller's sample time of cases/tip_tracking.py
PERIOD = 0.5


def wanted_strain(times: np.ndarray) -> np.ndarray:
    """A wanted free strain: a sine of period 0.5 s about 3e-4 (reversals at 0.125 + k 0.25 s)."""
    return 3e-4 + 2e-4 * np.sin(2.0 * math.pi * times / PERIOD)


def feedforward(duration: float = 1.0) -> SampledProgram:
    times = np.arange(0.0, duration + 0.5 * SAMPLE, SAMPLE)
    program, info = feedforward_program(reference_preisach(scale=1.0 / CELL), times, wanted_strain(times),
                                        (-500.0, 1500.0))
    assert info["clipped_samples"] == 0
    return program


def actuator(program) -> BendingActuator:
    return BendingActuator(3, CELL, 28e-3, Layer(0.2e-3, 70e9, 1550.0), Layer(0.3e-3, 30.336e9, 5440.0),
                           PiezoDrive(program, hysteresis=reference_preisach(scale=1.0 / CELL)), cell="rigid")


def test_the_feedforward_program_reverses_where_the_wanted_output_does():
    program = feedforward()
    assert isinstance(program, SampledProgram)
    # nearly every sample of the inverse of a relay model is a kink or a hold: as a PiecewiseLinear program
    # its shortest feature was one sample
    plain = PiecewiseLinear(program.times, program.values).shortest_feature(1.0)
    assert plain[0] == pytest.approx(SAMPLE)
    # the wanted sine turns at T/4 + k T/2: 0.125, 0.375, 0.625, 0.875 s (to the sample)
    turns = reversal_times(program.times, program.values)
    np.testing.assert_allclose(turns, [0.125, 0.375, 0.625, 0.875], atol=2 * SAMPLE)
    duration, description = program.shortest_feature(1.0)
    assert duration == pytest.approx(PERIOD / 4, abs=2 * SAMPLE)  # the first stretch, 0 ... 0.125 s
    assert "between reversals" in description


def test_a_hold_inside_a_rise_is_no_reversal():
    # rise, hold, rise, fall: one reversal, at the start of the fall (3 s)
    program = SampledProgram([0.0, 1.0, 2.0, 3.0, 4.0], [0.0, 1.0, 1.0, 2.0, 0.0])
    np.testing.assert_array_equal(reversal_times(program.times, program.values), [3.0])
    assert program.shortest_feature()[0] == 1.0  # 3 ... 4 s, after the only reversal
    assert SampledProgram([0.0, 1.0, 2.0], [5.0, 5.0, 5.0]).shortest_feature() is None


def test_the_package_feedforward_program_recorded_every_two_samples_gives_no_warning():
    # 2 ms records: 62 instants across the shortest stretch of 0.125 s (any AccuracyWarning is an error here)
    result = simulate(actuator(feedforward()), 0.3, step=2e-4, record_every=2 * SAMPLE)
    assert result.n_rows == 151
    # a record coarser than a tenth of the stretch is still warned about, naming the stretch
    with pytest.warns(AccuracyWarning, match=r"record_every = 0\.05 s keeps only 2\.5 recorded instants .*"
                                             r"a monotone stretch of 0\.125 s"):
        simulate(actuator(feedforward()), 0.3, step=2e-4, record_every=0.05)


def test_the_linear_inversion_is_a_sampled_program_too():
    times = np.arange(0.0, 1.0 + 0.5 * SAMPLE, SAMPLE)
    program, _ = linear_program(1e-6, 0.0, times, wanted_strain(times))
    assert isinstance(program, SampledProgram)
    assert program.shortest_feature(1.0)[0] == pytest.approx(PERIOD / 4, abs=2 * SAMPLE)


# ----------------------------------------------------------------------------- record_every

@pytest.mark.parametrize("zero", [0, 0.0, np.int64(0), np.float64(0.0)])
def test_record_every_zero_records_every_step_as_on_the_command_line(zero):
    schedule = recording_schedule(zero, 1e-4)
    assert schedule.every_step and schedule.describe() == "every step"
    act = actuator(0.0)
    every = simulate(act, 0.01, step=1e-4, record_every=zero)
    assert every.n_rows == 101  # 100 steps and the start
    np.testing.assert_array_equal(every["actuator.tip_y"], simulate(act, 0.01, step=1e-4)["actuator.tip_y"])
    assert every.info["recorded"] == "every step"


@pytest.mark.parametrize("bad", [-1, -1e-3, float("nan"), float("inf"), "0", True])
def test_record_every_below_zero_or_not_a_number_is_refused(bad):
    with pytest.raises(ValueError, match="record_every"):
        recording_schedule(bad, 1e-4)


# ----------------------------------------------------------------------------- file errors

def small_result() -> Result:
    return Result({"time": np.arange(3.0), "x": np.ones(3)}, {"time": "s", "x": "m"})


def test_an_empty_path_is_a_write_error_saying_so():
    with pytest.raises(WriteError, match=r"^cannot write '': the file name is empty") as info:
        small_result().to_csv("")
    assert isinstance(info.value, OSError) and info.value.filename == ""
    with pytest.raises(WriteError, match=r"cannot create the output directory '': the name is empty"):
        atomic.make_directory("")


def test_a_name_too_long_for_the_file_system_is_a_write_error_naming_it(tmp_path):
    name = "a" * 300 + ".csv"  # NAME_MAX is 255 bytes on the usual file systems
    path = tmp_path / name
    with pytest.raises(WriteError) as info:
        small_result().to_csv(path)
    assert str(info.value) == f"cannot write {str(path)!r}: the name is too long"
    assert info.value.errno == errno.ENAMETOOLONG and info.value.filename == str(path)
    assert list(tmp_path.iterdir()) == []  # nothing half-written


def test_a_directory_is_a_write_error_asking_for_a_file_name(tmp_path):
    with pytest.raises(WriteError, match=r"it is a directory \(give a file name in it\)"):
        small_result().to_csv(tmp_path)


def test_write_error_is_one_class_everywhere():
    assert atcm.WriteError is WriteError is atomic.WriteError
    assert issubclass(WriteError, OSError)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert str(WriteError("cannot write 'x': why")) == "cannot write 'x': why"
