"""Eigenfrequencies about a deformed equilibrium (issue 7, part 2).

References: the undeformed chains' frequencies from Exudyn's own eigenvalue routine (where it is
exact: no constraint force), the rigid chain against the six-bar chain, the clamped-free
Euler-Bernoulli beam under an axial tip load (Rayleigh quotient of its first mode), and the
pre-curved beam's frequency, which differs from the straight beam's at second order in kappa L.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from exudyn_atcm import theory as bt
from exudyn_atcm.errors import InputRangeWarning
from exudyn_atcm.mbs import builder
from exudyn_atcm.mbs.eigen import exudyn_eigenfrequencies
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.solve import eigenfrequencies
from exudyn_atcm.solve.as_mechanism import actuator_mechanism
from exudyn_atcm.solve.mechanism_static import equilibrium

from _actuator_geometries import REF_A

CELLS = ("rigid", "six-bar")


def ref_a(cell, n):
    return REF_A.actuator(PiezoDrive(0.0), n_cells=n, cell=cell)


def composite_EI():
    g = REF_A
    return bt.composite_bending_stiffness(g.E1, g.h1, g.E2, g.h2, g.width)


def kappa_L(voltage):
    g = REF_A
    return bt.free_curvature(g.E1, g.h1, g.E2, g.h2, g.width, bt.piezo_strain(voltage)) * g.length


@pytest.mark.parametrize("cell", CELLS)
def test_undeformed_frequencies_equal_exudyns_routine(cell):
    # no constraint force in the undeformed state: Exudyn's analytic-Jacobian routine is exact
    # there, and the numerically differentiated tangent must reproduce it (difference
    # quotients with step 1e-7: relative error ~1e-8)
    act = ref_a(cell, 4)
    ours = eigenfrequencies(act, n=3)
    model = builder.build(actuator_mechanism(act))
    np.testing.assert_allclose(ours, exudyn_eigenfrequencies(model.mbs, 3), rtol=1e-7)
    # and the beam limit of the existing tests is untouched: 35.97 Hz, chains below it
    f1 = bt.first_bending_frequency(composite_EI(), act.mass_per_length, REF_A.length)
    assert f1 == pytest.approx(35.97, abs=0.005)
    assert 0.85 * f1 < ours[0] < f1


def test_exudyns_routine_is_wrong_about_a_bent_six_bar_chain_and_ours_is_not():
    # the cause documented in exudyn_atcm.mbs.eigen: the joints of the bent six-bar chain carry the
    # layers' axial forces (~50 N at 1500 V) whose geometric stiffness Exudyn's routine leaves out
    act = REF_A.actuator(PiezoDrive(1500.0), n_cells=4, cell="six-bar")
    mech = actuator_mechanism(act)
    model = builder.build(mech)
    strains = np.array([act.drive.static_strain(1500.0)])
    equilibrium(mech, model, np.zeros(1), strains, True, None, "test")
    lam = np.asarray(model.mbs.systemData.GetAECoordinates())
    assert np.max(np.abs(lam)) > 10.0  # newtons: the constraint forces are large
    exudyn_f1 = exudyn_eigenfrequencies(model.mbs, 1)[0]
    ours = eigenfrequencies(act, n=1, voltage=1500.0)[0]
    straight = eigenfrequencies(ref_a("six-bar", 4), n=1)[0]
    assert abs(exudyn_f1 / straight - 1) > 0.5  # measured -67 %
    assert abs(ours / straight - 1) < 0.01      # second-order effect, see the next test


def test_bent_chains_agree_and_change_at_second_order_in_kappa_L():
    # A uniformly pre-curved cantilever (actuation alone, no load) has the straight beam's f1
    # to small-deflection order.  The change has two parts:
    # - even in kappa: O((kappa L)^2), from the arc's geometry (measured 0.021 (kappa L)^2);
    # - odd in kappa: O(kappa y_m), because the laminate's mass centre lies y_m = -m2 e/m
    #   = -0.21 mm off the passive layer's mid-plane, the chain's reference line (measured
    #   0.56 kappa |y_m|).
    # At 1500 V (kappa L = 0.36 rad) the total is +0.21 %.  Checks at 16 cells, +-1500 V and
    # +-750 V: the even part quarters and the odd part halves when the voltage halves (5 %: the
    # next terms are two orders higher), both are bounded as stated, and the rigid and six-bar
    # chains give the same changes (their O(1/N^2) discretisation error of the change, measured
    # 3e-5 at 16 cells).
    n = 16
    g = REF_A
    m1 = g.rho1 * g.h1
    m2 = g.rho2 * g.h2
    y_m = m2 * 0.5 * (g.h1 + g.h2) / (m1 + m2)
    parts = {}
    for cell in CELLS:
        act = ref_a(cell, n)
        f0 = eigenfrequencies(act, n=1)[0]
        d = {v: eigenfrequencies(act, n=1, voltage=v)[0] / f0 - 1 for v in (750.0, 1500.0)}
        for v in (-1500.0, -750.0):  # below the MFC's rated -500 V: warned about, and computed all the same
            with pytest.warns(InputRangeWarning, match="rated range"):
                d[v] = eigenfrequencies(act, n=1, voltage=v)[0] / f0 - 1
        even = [(d[v] + d[-v]) / 2 for v in (1500.0, 750.0)]
        odd = [(d[v] - d[-v]) / 2 for v in (1500.0, 750.0)]
        assert even[0] / even[1] == pytest.approx(4.0, rel=0.05)
        assert odd[0] / odd[1] == pytest.approx(2.0, rel=0.05)
        assert 0 < even[0] <= 0.05 * kappa_L(1500.0) ** 2
        assert abs(odd[0]) <= kappa_L(1500.0) / g.length * y_m
        parts[cell] = (even[0], odd[0], d[1500.0])
    np.testing.assert_allclose(parts["six-bar"], parts["rigid"], rtol=0, atol=1e-4)


@pytest.mark.parametrize("cell", CELLS + ("beam", "ancf"))
def test_axial_tip_load_shifts_f1_as_the_rayleigh_quotient_of_the_beam_mode(cell):
    # Clamped-free Euler-Bernoulli beam with an axial tip force P (tension > 0):
    # omega^2(P) = omega^2(0) (1 + c P L^2/EI) + O(P^2), c = int(phi'^2) / int(phi''^2) of the first
    # mode (x in [0, 1]).  The antisymmetric part of +-P removes the O(P^2) term; what remains
    # is the discretisations' O(1/N^2) error of c (measured at 16 cells: 0.003 % rigid, 0.1 %
    # six-bar): tolerance 0.5 %.  The chains' joints carry P: without their geometric stiffness
    # the shift would be zero; the beam elements carry it as an axial force of their own.
    b = bt.BETA1_L
    s = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))

    def d1(x):
        return b * (math.sinh(b * x) + math.sin(b * x) - s * (math.cosh(b * x) - math.cos(b * x)))

    def d2(x):
        return b * b * (math.cosh(b * x) + math.cos(b * x) - s * (math.sinh(b * x) + math.sin(b * x)))

    c = quad(lambda x: d1(x) ** 2, 0, 1)[0] / quad(lambda x: d2(x) ** 2, 0, 1)[0]
    assert c == pytest.approx(0.37596, abs=1e-5)
    act = ref_a(cell, 16)
    p = 0.1
    P = p * composite_EI() / REF_A.length**2
    f0 = eigenfrequencies(act, n=1)[0]
    f_t = eigenfrequencies(act, n=1, tip_force=(P, 0.0))[0]
    f_c = eigenfrequencies(act, n=1, tip_force=(-P, 0.0))[0]
    slope = ((f_t / f0) ** 2 - (f_c / f0) ** 2) / 2
    assert slope == pytest.approx(c * p, rel=5e-3)


def test_eigenfrequencies_reject_bad_operating_point():
    act = ref_a("rigid", 2)
    with pytest.raises(ValueError, match="voltage"):
        eigenfrequencies(act, n=1, voltage=float("nan"))
    with pytest.raises(ValueError, match="tip_force"):
        eigenfrequencies(act, n=1, tip_force=(0.0,))
    with pytest.raises(ValueError, match="degrees of freedom"):
        eigenfrequencies(act, n=50)
