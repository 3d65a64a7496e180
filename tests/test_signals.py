"""Voltage programs of exudyn_atcm.model.signals."""

import math

import numpy as np
import pytest

from exudyn_atcm.model.signals import Constant, CsvSignal, PiecewiseLinear, Sine, Steps, Triangle


def eq_11(t, u_med, u_amp, period):
    """The paper's Eq. 11 as printed (int() truncation, valid for t >= 0)."""
    k = int(2 * t / period)
    return u_med + u_amp * (4 * t / period - 1 - 2 * k) * (-1) ** k


def test_triangle_is_eq_11():
    tri = Triangle(500, 1000, 0.4)
    for t in np.linspace(0, 1.3, 211):
        assert tri(t) == pytest.approx(eq_11(t, 500, 1000, 0.4), abs=1e-9)
    assert tri(0.0) == -500 and tri(0.2) == pytest.approx(1500) and tri(0.4) == pytest.approx(-500)


def test_scalar_in_float_out_array_in_array_out():
    tri = Triangle(0, 1, 1.0)
    assert isinstance(tri(0.1), float)
    out = tri(np.zeros((2, 3)))
    assert out.shape == (2, 3)


def test_sine_steps_piecewise_constant():
    assert Sine(1.0, 2.0, 4.0)(1.0) == pytest.approx(3.0)
    assert Sine(1.0, 2.0, 4.0, phase=-math.pi / 2)(0.0) == pytest.approx(-1.0)
    steps = Steps([0.0, 1.0, 2.0], [0.0, 100.0, -50.0])
    np.testing.assert_array_equal(steps([-1, 0, 0.5, 1.0, 1.9, 2.0, 5.0]), [0, 0, 0, 100, 100, -50, -50])
    ramp = PiecewiseLinear([0.0, 1.0, 3.0], [0.0, 1000.0, 0.0])
    np.testing.assert_allclose(ramp([-1, 0.5, 2.0, 4.0]), [0, 500, 500, 0])
    assert Constant(7.5)(np.arange(3)).tolist() == [7.5, 7.5, 7.5]


def test_a_step_switch_is_taken_at_the_step_whose_time_misses_it_by_round_off():
    """A solver's step times are sums of steps: 3000 steps of 1e-4 s end 1.7e-14 s before 0.3 s, 1000 end
    1.8e-15 s after 0.1 s.  Either way the switch is at that step (not one step later for one of them); a time
    a microsecond before the switch is still before it."""
    steps = Steps([0.0, 0.1, 0.3], [0.0, 100.0, -50.0])
    t = 0.0
    times = []
    for _ in range(3000):
        t += 1e-4
        times.append(t)
    assert times[999] > 0.1 and times[2999] < 0.3  # the round-off the program must not depend on
    assert steps(times[999]) == 100.0 and steps(times[2999]) == -50.0
    assert steps(np.array([times[998], times[999], times[2998], times[2999]])).tolist() == [0.0, 100.0, 100.0, -50.0]
    assert steps(0.3 - 1e-6) == 100.0 and steps(0.1 - 1e-6) == 0.0


def test_piecewise_linear_outside_error():
    ramp = PiecewiseLinear([0.0, 1.0], [0.0, 1.0], outside="error")
    with pytest.raises(ValueError, match=r"t = 1.5 s lies outside"):
        ramp(1.5)


def test_csv_signal_by_header_and_index(tmp_path):
    path = tmp_path / "u.csv"
    path.write_text("# measured\ntime [s],voltage [V],other [-]\n0,0,9\n1,100,9\n2,-100,9\n")
    sig = CsvSignal(path)
    assert sig(0.5) == pytest.approx(50.0)
    assert sig(1.5) == pytest.approx(0.0)
    headerless = tmp_path / "v.csv"
    headerless.write_text("0,1,10\n2,3,30\n")
    assert CsvSignal(headerless, value_column=2)(1.0) == pytest.approx(20.0)
    assert sig.parameters["signal"] == "CsvSignal"


@pytest.mark.parametrize(
    "make, pattern",
    [
        (lambda: Triangle(0, 1, 0), r"period must be > 0, got 0"),
        (lambda: Triangle(0, -1, 1), r"u_amp must be >= 0, got -1"),
        (lambda: Sine(math.nan, 1, 1), r"u_med must be a finite real number, got nan"),
        (lambda: Steps([0, 0], [1, 2]), r"times must be strictly increasing, got times\[1\] = 0.0"),
        (lambda: PiecewiseLinear([0, 1], [1]), r"times and values must have the same length"),
        (lambda: PiecewiseLinear([0, 1], [1, 2], outside="clip"), r"outside must be 'hold' or 'error', got 'clip'"),
        (lambda: Triangle(0, 1, 1)(math.inf), r"t must be finite"),
    ],
)
def test_bad_input(make, pattern):
    with pytest.raises(ValueError, match=pattern):
        make()


def test_csv_signal_errors(tmp_path):
    with pytest.raises(ValueError, match=r"path must be an existing CSV file"):
        CsvSignal(tmp_path / "missing.csv")
    bad = tmp_path / "bad.csv"
    bad.write_text("time [s],voltage [V]\n0,1\n1,abc\n")
    with pytest.raises(ValueError, match=r"line 3 must hold numbers"):
        CsvSignal(bad)
    with pytest.raises(ValueError, match=r"value_column = 'volts' is not a column"):
        CsvSignal(bad, value_column="volts")


@pytest.mark.parametrize(
    "signal",
    [Triangle(500, 1000, 0.3), Sine(1, 2, 0.7, 0.3), Constant(3.0), Steps([0, 1], [1, 2]), PiecewiseLinear([0, 1], [0, 5])],
    ids=lambda s: type(s).__name__,
)
def test_scalar_fast_path_equals_array_path(signal):
    times = np.linspace(-1.0, 2.0, 97)
    np.testing.assert_allclose([signal(float(t)) for t in times], signal(times), rtol=1e-14, atol=1e-12)


def test_a_csv_program_in_ms_and_kv_is_read_in_seconds_and_volts(tmp_path):
    """The header's units were ignored: 50 ms read as 50 s and 1.5 kV as 1.5 V (the audit of 2026-11-30).
    Reference: the file's numbers times 1e-3 (ms) and 1e3 (kV)."""
    path = tmp_path / "rec.csv"
    path.write_text("time [ms],voltage [kV]\n0,0\n100,1.5\n200,0\n")
    sig = CsvSignal(path)
    assert sig(0.05) == pytest.approx(750.0)  # 50 ms: half way up to 1500 V
    assert sig(0.1) == pytest.approx(1500.0)
    mv = tmp_path / "mv.csv"
    mv.write_text("time [s],voltage [mV]\n0,0\n1,1500\n")
    assert CsvSignal(mv)(1.0) == pytest.approx(1.5)


def test_a_csv_program_in_an_unknown_or_wrong_unit_is_refused(tmp_path):
    path = tmp_path / "rec.csv"
    path.write_text("time [m],voltage [V]\n0,0\n1,1\n")
    with pytest.raises(ValueError, match=r"time_column: the column 'time \[m\]' of .* is in 'm', which is not a time unit"):
        CsvSignal(path)
    path.write_text("time [s],voltage [furlong]\n0,0\n1,1\n")
    with pytest.raises(ValueError, match=r"value_column: .* is in 'furlong', which is not a voltage unit"):
        CsvSignal(path)


def test_a_sine_phase_in_degrees_is_warned():
    from exudyn_atcm.errors import InputRangeWarning
    with pytest.warns(InputRangeWarning, match=r"Sine: phase = 90\.0 rad is outside the plausible range .* degrees"):
        Sine(0.0, 100.0, 1.0, phase=90.0)
