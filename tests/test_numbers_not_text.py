"""Numbers must be numbers: ``solve_static(mech, voltage="5")`` ran at 5 V, ``voltage=True`` at 1 V, because the
shared checks (:mod:`exudyn_atcm._checks`) converted with ``float()``.  Text and booleans are now refused with a
``ValueError`` naming the parameter and the value (issue 31, found in passing); real numbers of any numeric type
are still taken, exactly.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from exudyn_atcm import (Bender, BendingActuator, Layer, Mechanism, PiezoDrive, solve_static, static_sweep)
from exudyn_atcm._checks import finite_array, finite_float, positive_float, shown
from exudyn_atcm.model.signals import Constant

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)

NOT_NUMBERS = ["5", " 5 ", "1e-4", b"5", bytearray(b"5"), True, False, np.bool_(True), np.str_("5")]


@pytest.mark.parametrize("value", NOT_NUMBERS, ids=repr)
def test_finite_float_refuses_text_and_booleans(value):
    with pytest.raises(ValueError, match=r"^voltage must be a finite real number, got .* \((str|bytes|bytearray|bool|"
                                         r"bool_|str_); pass a float\)$") as info:
        finite_float("voltage", value)
    assert shown(value)[:20] in str(info.value)  # NumPy scalars as their Python values (True, '5')


@pytest.mark.parametrize("value", ["0.1", True])
def test_positive_float_refuses_text_and_booleans(value):
    with pytest.raises(ValueError, match=f"step must be a finite real number, got {value!r}"):
        positive_float("step", value)


@pytest.mark.parametrize("value, expected", [(5, 5.0), (-2.5, -2.5), (np.float32(0.5), 0.5), (np.int64(7), 7.0),
                                             (Fraction(1, 4), 0.25), (np.array(3.0), 3.0)])
def test_finite_float_still_takes_every_real_number(value, expected):
    # exact binary fractions: the conversion is exact, so equality is the right check
    assert finite_float("x", value) == expected


@pytest.mark.parametrize("values", [["1", "2"], [True, False], np.array([b"1", b"2"]), np.array([True, False])],
                         ids=["str", "bool", "bytes", "bool-array"])
def test_finite_array_refuses_text_and_booleans(values):
    with pytest.raises(ValueError, match="voltages must be a 1-D sequence of finite numbers"):
        finite_array("voltages", values)


def test_finite_array_still_takes_integers_and_floats():
    assert finite_array("u", [1, 2.5, np.int32(3)]).tolist() == [1.0, 2.5, 3.0]


def _cantilever() -> Mechanism:
    bender = Bender("b", width=28e-3, passive=CFC, active=MFC, length=0.087, n_cells=3,
                    drive=PiezoDrive(Constant(0.0)), cell="rigid")
    return Mechanism("cantilever").add(bender).ground(bender.base)


@pytest.mark.parametrize("voltage", ["5", True, {"b": "5"}], ids=["str", "bool", "mapping-str"])
def test_solve_static_of_a_mechanism_refuses_a_voltage_given_as_text(voltage):
    with pytest.raises(ValueError, match=r"voltage(\['b'\])? must be a finite real number, got ('5'|True)"):
        solve_static(_cantilever(), voltage=voltage)


def test_solve_static_of_an_actuator_and_static_sweep_refuse_text():
    actuator = BendingActuator(3, 29e-3, 28e-3, CFC, MFC, PiezoDrive(Constant(0.0)), cell="rigid")
    with pytest.raises(ValueError, match="voltage must be a finite real number, got '5'"):
        solve_static(actuator, voltage="5")
    with pytest.raises(ValueError, match="voltages must be a 1-D sequence of finite numbers, got \\['0', '5'\\]"):
        static_sweep(_cantilever(), ["0", "5"])


def test_layer_refuses_a_thickness_given_as_text():
    with pytest.raises(ValueError, match="thickness must be a finite real number, got '0.2e-3'"):
        Layer("0.2e-3", 70e9, 1550.0)
