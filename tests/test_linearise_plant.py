"""``linearise`` warns when its equilibrium is no plant to design for (the audit of 2026-11-30).

* A column above its buckling load (Euler's ``P_cr = pi^2 EI / (4 L^2)`` for a clamped-free column, with the
  laminate's ``EI`` computed here): the model had a pole at +479 1/s, ``natural_frequencies`` (oscillating
  modes only) did not show it and ``dc_gain`` had the wrong sign, silently; ``solve_static`` warned.  Below
  the load: silent.
* A link on a free pin at the bender's tip: a "mode" at 2e-5 Hz and a static gain of round-off, silently.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import exudyn_atcm as atcm

CFC = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
L, W = 0.04, 10e-3


def bending_stiffness() -> float:
    """EI [N m^2] of the two-layer strip about its neutral axis (by hand: transformed section)."""
    layers = [(CFC.thickness, CFC.youngs_modulus), (MFC.thickness, MFC.youngs_modulus)]
    z, bottom, ea, first = [], 0.0, 0.0, 0.0
    for t, e in layers:
        z.append(bottom + t / 2)
        ea += e * t
        first += e * t * (bottom + t / 2)
        bottom += t
    neutral = first / ea
    return W * sum(e * (t**3 / 12 + t * (zc - neutral) ** 2) for (t, e), zc in zip(layers, z))


def column() -> atcm.Mechanism:
    b = atcm.Bender("b", width=W, passive=CFC, active=MFC, length=L, n_cells=4, drive=atcm.PiezoDrive(0.0),
                    angle=math.pi / 2)
    return atcm.Mechanism("col").add(b).ground(b.base)


def test_a_column_beyond_its_buckling_load_is_warned_and_silent_below():
    p_cr = math.pi**2 * bending_stiffness() / (4 * L**2)
    with pytest.warns(atcm.StabilityWarning, match=r"at voltage 0 V is UNSTABLE"):
        lin = atcm.linearise(column(), voltage=0.0, loads={"b.tip": (0.0, -1.2 * p_cr)}, outputs=["b.tip_x"])
    assert lin.poles.real.max() > 100.0  # the divergence the warning is about
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        lin = atcm.linearise(column(), voltage=0.0, loads={"b.tip": (0.0, -0.9 * p_cr)}, outputs=["b.tip_x"])
    assert lin.poles.real.max() < 0.0


def test_a_link_on_a_free_pin_has_no_static_gain_and_says_so():
    b = atcm.Bender("b", width=W, passive=CFC, active=MFC, length=L, n_cells=4, drive=atcm.PiezoDrive(0.0))
    lever = atcm.Link("lev", {"O": (L, 0.0), "E": (0.07, 0.0)}, mass=1e-3, inertia=1e-7)
    m = atcm.Mechanism("free").add(b, lever).ground(b.base).pin(b.tip, "lev.O")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        atcm.linearise(m, voltage=0.0, outputs=["lev.E_y"])
    messages = [str(w.message) for w in caught if issubclass(w.category, atcm.StabilityWarning)]
    assert len(messages) == 1 and "motion without stiffness" in messages[0] and "moving most: lev" in messages[0]
    assert "no static gain" in messages[0] and "UNSTABLE" not in messages[0]
