"""Issue 14, part 3: damping is a property of the material, not of the part.

References: the closed-form free decay of a single-degree-of-freedom oscillator (for the
logarithmic-decrement relation), a one-bender system's own first eigenfrequency (for the
decay measured in simulation), and the identity "two benders of one laminate welded end to
end = one bender of the summed length" (exact for the rigid and beam cells: the weld is the
long bender's inner joint, see tests/test_mechanism_solve.py and tests/test_mechanism_beam.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_atcm import (Bender, BendingActuator, Flexure, Layer, Link, Mechanism, PiezoDrive, RayleighDamping,
                         eigenfrequencies, simulate)
from exudyn_atcm.model.damping import damping_ratio_from_log_decrement, log_decrement_from_damping_ratio
from exudyn_atcm.model.signals import Steps

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W = 28e-3
LC = 0.01  # cell length [m] of the split tests


# ----------------------------------------------------------------------------- the decrement relation

def sdof_decrement(zeta: float) -> float:
    """ln(x_k / x_{k+1}) of the closed-form free decay x(t) = exp(-zeta w t) cos(w_d t) (w = 1 rad/s),
    from its numerically located maxima (dx/dt = 0 by bisection), independent of any closed form for delta."""
    wd = math.sqrt(1.0 - zeta * zeta)

    def v(t):
        return -math.exp(-zeta * t) * (zeta * math.cos(wd * t) + wd * math.sin(wd * t))

    peaks = []
    for k in (1, 2):  # the maxima lie within ((2k-1) pi/wd, 2k pi/wd]: v changes sign there
        lo, hi = (2 * k - 1) * math.pi / wd, 2 * k * math.pi / wd
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if v(mid) > 0.0 else (lo, mid)
        t = 0.5 * (lo + hi)
        peaks.append(math.exp(-zeta * t) * math.cos(wd * t))
    return math.log(peaks[0] / peaks[1])


@pytest.mark.parametrize("delta", [0.01, 0.2, 1.0, 3.0])
def test_damping_ratio_from_log_decrement_is_the_analytic_relation(delta):
    zeta = damping_ratio_from_log_decrement(delta)
    assert zeta == pytest.approx(delta / math.sqrt(4 * math.pi**2 + delta**2), rel=1e-15)
    # and it is what a free decay with that ratio shows
    assert sdof_decrement(zeta) == pytest.approx(delta, rel=1e-12)
    assert log_decrement_from_damping_ratio(zeta) == pytest.approx(delta, rel=1e-13)


def test_from_log_decrement_gives_the_ratio_at_the_measured_frequency():
    d = RayleighDamping.from_log_decrement(0.2, 30.0)
    zeta = 0.2 / math.sqrt(4 * math.pi**2 + 0.04)
    assert d.alpha == 0.0
    assert d.beta == pytest.approx(2 * zeta / (2 * math.pi * 30.0), rel=1e-15)
    assert d.damping_ratio(30.0) == pytest.approx(zeta, rel=1e-15)
    assert d.damping_ratio(60.0) == pytest.approx(2 * zeta, rel=1e-15)  # stiffness-proportional: grows with f
    assert RayleighDamping(alpha=3.0).damping_ratio(30.0) == pytest.approx(3.0 / (4 * math.pi * 30.0), rel=1e-15)


def free_decay_decrement(y: np.ndarray, t: np.ndarray, t_from: float) -> np.ndarray:
    """ln(x_k / x_{k+1}) of the positive maxima of ``y`` after ``t_from`` (parabolic peak values)."""
    i = np.flatnonzero((y[1:-1] > y[:-2]) & (y[1:-1] >= y[2:]) & (y[1:-1] > 0.0)) + 1
    i = i[t[i] > t_from]
    a, b, c = y[i - 1], y[i], y[i + 1]
    peak = b - 0.125 * (a - c) ** 2 / (a - 2 * b + c)
    return np.log(peak[:-1] / peak[1:])


# a release from the static state at 500 V: 0 V from t = 1 ms on, a free decay about y = 0
RELEASE = Steps([0.0, 1e-3], [500.0, 0.0])


@pytest.mark.parametrize("cell, n_cells, part, path", [
    ("rigid", 6, "beta", "mechanism"),
    ("beam", 4, "beta", "mechanism"),
    ("six-bar", 4, "beta", "actuator"),
    # alpha damps the higher modes less than the first (zeta_r = alpha / 2 w_r): a one-cell bender
    # (one degree of freedom for the rigid cell) gives a clean first-mode decay
    ("rigid", 1, "alpha", "mechanism"),
    ("rigid", 1, "alpha", "actuator"),
    ("six-bar", 1, "alpha", "mechanism"),
    ("six-bar", 1, "alpha", "actuator"),
])
def test_simulated_free_decay_shows_the_decrement_it_was_set_from(cell, n_cells, part, path):
    """A bender's damping set from a decrement of 0.2 at its own first frequency (the model's,
    from ``eigenfrequencies``) rings down with that decrement.  Measured 0.1998-0.1999 (peaks
    after two periods, step 1e-4 s, about 1/400 of a period): the tolerance 0.5 % covers the time
    integration and the peak interpolation."""
    delta = 0.2
    drive = PiezoDrive(RELEASE)
    probe = Bender("b", width=W, passive=CFC, active=MFC, length=0.1, n_cells=n_cells, drive=drive, cell=cell)
    f1 = eigenfrequencies(Mechanism().add(probe).ground(probe.base), n=1)[0]
    if part == "beta":
        damping = RayleighDamping.from_log_decrement(delta, f1)
    else:
        damping = RayleighDamping(alpha=2.0 * damping_ratio_from_log_decrement(delta) * 2 * math.pi * f1)
    if path == "mechanism":
        b = Bender("b", width=W, passive=CFC, active=MFC, length=0.1, n_cells=n_cells, drive=drive, cell=cell,
                   damping=damping)
        r = simulate(Mechanism().add(b).ground(b.base), round(6.5 / f1, 2), step=1e-4)
        y = r["b.tip_y"]
    else:
        r = simulate(BendingActuator(n_cells, 0.1 / n_cells, W, CFC, MFC, drive, cell=cell, damping=damping),
                     round(6.5 / f1, 2), step=1e-4)
        y = r["actuator.tip_y"]
    measured = free_decay_decrement(np.asarray(y), np.asarray(r["time"]), 1e-3 + 2.0 / f1)
    assert len(measured) >= 3
    np.testing.assert_allclose(measured, delta, rtol=5e-3)


def test_mass_damping_of_a_flexure_segment_welded_to_a_link_is_the_segments_own():
    """A pseudo-rigid-body flexure clamped at its base with a link welded to its tip is one rigid
    body on the characteristic pivot: J_p theta'' + c theta' + K theta = 0 exactly, with
    ``c = alpha J_seg`` (only the flexure's tip segment is laminate; the link is not damped) and
    J_p, J_seg about the pivot from the segment's and the link's own mass data.  The decay of the
    link's end after a released force shows delta(zeta), zeta = c / (2 sqrt(K J_p)): measured
    within 3e-5 (step 1e-5 s, 1/600 of a period); damping the link too would give 21x the decrement."""
    alpha = 1000.0
    f = Flexure("f", base=(0.0, 0.0), tip=(0.02, 0.0), width=10e-3, layer=Layer(0.3e-3, 70e9, 1550.0), damping=RayleighDamping(alpha=alpha))
    link = Link("lever", {"A": (0.02, 0.0), "E": (0.04, 0.0)}, mass=2e-4, inertia=1e-8)
    m = Mechanism().add(f, link).ground(f.base).weld(f.tip, link.point("A")).force(
        "lever.E", lambda t: (0.0, -0.01) if t < 1e-3 else (0.0, 0.0))
    pivot = np.array(f.pivot)
    m_seg, j_seg, c_seg = f.segment_masses()[1]
    j_seg_p = j_seg + m_seg * float((c_seg - pivot) @ (c_seg - pivot))
    c_link = np.array(link.center_of_mass)
    j_p = j_seg_p + link.inertia + link.mass * float((c_link - pivot) @ (c_link - pivot))
    k = f.torsion_stiffness
    f1 = math.sqrt(k / j_p) / (2 * math.pi)
    assert eigenfrequencies(m, n=1)[0] == pytest.approx(f1, rel=1e-12)  # the model is that oscillator
    zeta = alpha * j_seg_p / (2 * math.sqrt(k * j_p))
    r = simulate(m, 0.05, step=1e-5)
    measured = free_decay_decrement(np.asarray(r["lever.E_y"]), np.asarray(r["time"]), 1e-3 + 1.0 / f1)
    assert len(measured) >= 5
    np.testing.assert_allclose(measured, log_decrement_from_damping_ratio(zeta), rtol=1e-4)


# ----------------------------------------------------------------------------- split == unsplit

def bender(name, n, cell, damping, base=(0.0, 0.0)):
    drive = PiezoDrive(Steps([0.0, 1e-3], [0.0, 1000.0]))  # a voltage step at 1 ms: a damped ring-up
    return Bender(name, width=W, passive=CFC, active=MFC, length=n * LC, n_cells=n, drive=drive, base=base,
                  cell=cell, damping=damping)


def split_and_whole(cell, damping):
    """Tip paths [m] of one 100 mm bender and of 40 + 60 mm benders welded end to end (same laminate,
    same cells, a tip force), 0.1 s (about three periods of the first mode)."""
    whole = bender("one", 10, cell, damping)
    one = Mechanism("one").add(whole).ground(whole.base).force(whole.tip, (0.0, -0.02))
    a, b = bender("a", 4, cell, damping), bender("b", 6, cell, damping, base=(4 * LC, 0.0))
    two = Mechanism("two").add(a, b).ground(a.base).weld(a.tip, b.base).force(b.tip, (0.0, -0.02))
    r1, r2 = simulate(one, 0.1, step=1e-4), simulate(two, 0.1, step=1e-4)
    return (np.array([r1["one.tip_x"], r1["one.tip_y"]]), np.array([r2["b.tip_x"], r2["b.tip_y"]]))


@pytest.mark.parametrize("cell, damping", [
    ("rigid", RayleighDamping(beta=1.5e-4)),
    ("beam", RayleighDamping(beta=1.5e-4)),
    ("rigid", RayleighDamping(alpha=5.0, beta=1.5e-4)),
])
def test_two_benders_welded_end_to_end_equal_one_of_the_summed_length_in_damped_dynamics(cell, damping):
    """Material damping: one beta for every spring (series springs of one beta keep it), one alpha
    for every mass.  Measured: 7e-14 (rigid), 1.3e-11 (beam), 1.2e-13 (rigid with alpha) of the travel."""
    whole, split = split_and_whole(cell, damping)
    travel = np.ptp(whole[1])
    assert travel > 0.02  # it moved: about 25 mm
    assert np.max(np.abs(split - whole)) <= 1e-9 * travel


def test_a_damping_ratio_per_bender_depends_on_the_split():
    """The default (2 % of each bender's own first mode) gives the 40 and 60 mm parts other beta than
    the 100 mm bender: about 10 % of the travel apart (measured 0.102), which material damping removes."""
    whole, split = split_and_whole("rigid", 0.02)
    travel = np.ptp(whole[1])
    assert np.max(np.abs(split - whole)) > 0.05 * travel


# ----------------------------------------------------------------------------- the ratio form is unchanged

def test_a_damping_ratio_is_the_material_beta_at_the_benders_own_first_mode():
    b = bender("b", 10, "rigid", 0.02)
    omega1 = 2 * math.pi * b.laminate.first_frequency(b.length)
    assert b.stiffness_damping_factor == pytest.approx(2 * 0.02 / omega1, rel=1e-15)
    assert b.mass_damping_factor == 0.0
    same = bender("b", 10, "rigid", RayleighDamping(beta=b.stiffness_damping_factor))
    assert same.rayleigh_damping.damping_ratio(b.laminate.first_frequency(b.length)) == pytest.approx(0.02, rel=1e-15)
    r1 = simulate(Mechanism().add(b).ground(b.base), 0.02, step=1e-4)
    r2 = simulate(Mechanism().add(same).ground(same.base), 0.02, step=1e-4)
    np.testing.assert_array_equal(r1["b.tip_y"], r2["b.tip_y"])  # the same numbers go into the same model


def test_material_damping_is_the_laminates_and_independent_of_length():
    d = RayleighDamping(alpha=1.0, beta=2e-4)
    for length in (0.03, 0.1):
        b = Bender("b", width=W, passive=CFC, active=MFC, length=length, n_cells=3, drive=PiezoDrive(0.0), damping=d, cell="rigid")
        assert b.laminate.damping is d
        assert (b.mass_damping_factor, b.stiffness_damping_factor) == (1.0, 2e-4)
        act = BendingActuator(3, length / 3, W, CFC, MFC, PiezoDrive(0.0), cell="rigid", damping=d)
        assert act.rayleigh_damping is d
    f = Flexure("f", base=(0.0, 0.0), tip=(0.02, 0.0), width=W, layer=Layer(0.2e-3, 70e9, 1550.0), damping=d)
    assert f.stiffness_damping_factor == 2e-4 and f.as_bender().rayleigh_damping is d


def test_parameters_name_the_material_coefficients_with_units():
    p = bender("b", 3, "rigid", RayleighDamping(alpha=1.0, beta=2e-4)).parameters()
    assert p["b.damping.alpha [1/s]"] == 1.0 and p["b.damping.beta [s]"] == 2e-4
    assert "b.damping ratio [-]" not in p
    assert bender("b", 3, "rigid", 0.03).parameters()["b.damping ratio [-]"] == 0.03


# ----------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("kwargs, name", [({"alpha": -1.0}, "alpha"), ({"beta": float("nan")}, "beta"),
                                          ({"beta": "1e-4"}, "beta"), ({"alpha": True}, "alpha")])
def test_rayleigh_damping_rejects_bad_coefficients(kwargs, name):
    with pytest.raises(ValueError, match=name):
        RayleighDamping(**kwargs)


@pytest.mark.parametrize("delta, frequency", [(-0.1, 30.0), (0.2, 0.0), (0.2, float("inf"))])
def test_from_log_decrement_rejects_bad_input(delta, frequency):
    with pytest.raises(ValueError, match="delta" if delta < 0 else "frequency_hz"):
        RayleighDamping.from_log_decrement(delta, frequency)


def test_continuum_cells_refuse_mass_proportional_damping_naming_the_cell():
    d = RayleighDamping(alpha=2.0, beta=1e-4)
    with pytest.raises(ValueError, match="'beam' cell cannot realise"):
        bender("b", 3, "beam", d)
    for cell in ("beam", "ancf", "ritz"):
        with pytest.raises(ValueError, match=f"'{cell}' cell cannot realise"):
            BendingActuator(3, 0.03, W, CFC, MFC, PiezoDrive(0.0), cell=cell, damping=d)
    bender("b", 3, "beam", RayleighDamping(beta=1e-4))  # stiffness-proportional damping is fine


@pytest.mark.parametrize("bad", ["0.02", None, True, -0.01, float("inf")])
def test_damping_argument_must_be_a_ratio_or_rayleigh_damping(bad):
    with pytest.raises(ValueError, match="damping must be"):
        bender("b", 3, "rigid", bad)
