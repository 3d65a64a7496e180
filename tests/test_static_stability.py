"""Stability of static equilibria (issue 29, finding 1): every cell kind follows the stable branch, and an
unstable or critical equilibrium warns.

Independent references:

* the elastica of a cantilever under an axial (compressive) dead tip load ``P`` above Euler's
  ``P_cr = pi^2 EI / (4 L^2)``, in closed form (Timoshenko & Gere, *Theory of Elastic Stability*,
  sec. 2.7): with ``k = sin(alpha/2)`` (``alpha`` the tip rotation), ``K(k) = L sqrt(P/EI)`` and the
  tip at ``x = L (2 E(k)/K(k) - 1)``, ``|y| = 2 k L / K(k)`` (complete elliptic integrals of the
  first and second kind); and by shooting on ``EI theta'' = Fx sin(theta) - Fy cos(theta)`` with
  the nudge included (scipy's ``solve_ivp`` and ``brentq``), which agrees with the closed form to
  5e-6 L (the 1 mN nudge against 126 N);
* a plain one-coordinate-at-a-time central difference of Exudyn's static residual, for the grouped
  differences of :class:`~exudyn_atcm.mbs.tangent.TangentPlan`;
* Euler's load itself: a straight cantilever below it is stable, above it unstable.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

import exudyn as exu
from exudyn_atcm import (AccuracyWarning, Bender, Layer, Mechanism, PiezoDrive, StabilityWarning, simulate,
                         solve_static, static_sweep)
from exudyn_atcm.mbs import builder as mb
from exudyn_atcm.mbs.stability import CRITICAL_MARGIN
from exudyn_atcm.mbs.tangent import TangentPlan, static_settings
from exudyn_atcm.solve.mechanism_static import equilibrium

CFC = Layer(0.2e-3, 70e9, 1550.0)
MFC = Layer(0.3e-3, 30.336e9, 5440.0)
W, L = 10e-3, 0.03
NUDGE = 1e-3  # N, transverse


def column(cell: str, n: int, factor: float, nudge: float = -NUDGE, voltage: float = 0.0) -> tuple[Mechanism, float]:
    """A cantilever along +x under ``factor`` times Euler's load (compressive, along -x) and a transverse nudge."""
    b = Bender("b", width=W, passive=CFC, active=MFC, length=L, n_cells=n, drive=PiezoDrive(voltage), cell=cell)
    ei = b.laminate.bending_stiffness
    p_cr = math.pi**2 * ei / (4.0 * L**2)
    m = Mechanism("column").add(b)
    m.ground(b.base)
    m.force(b.tip, (-factor * p_cr, nudge))
    return m, ei


def elastica_closed_form(ei: float, p: float) -> tuple[float, float, float]:
    """Tip (x, |y|) [m] of the first buckling mode under the axial dead load ``p`` > P_cr, and the clamp's
    curvature ``2 k sqrt(P/EI)`` [1/m] (Timoshenko & Gere)."""
    lam = math.sqrt(p / ei) * L
    m = brentq(lambda m: ellipk(m) - lam, 1e-12, 1.0 - 1e-16)
    k = math.sqrt(m)
    return L * (2.0 * ellipe(m) / ellipk(m) - 1.0), 2.0 * k * L / ellipk(m), 2.0 * k * math.sqrt(p / ei)


def elastica_shooting(ei: float, fx: float, fy: float, k0_guess: float) -> tuple[float, float]:
    """Tip (x, y) [m] of the clamped elastica under the dead tip force (fx, fy): shooting on the clamp curvature."""
    def rhs(s, z):
        return [z[1], (fx * math.sin(z[0]) - fy * math.cos(z[0])) / ei, math.cos(z[0]), math.sin(z[0])]

    def end(k0):
        return solve_ivp(rhs, (0.0, L), [0.0, k0, 0.0, 0.0], rtol=1e-12, atol=1e-15).y[:, -1]

    k0 = brentq(lambda c: end(c)[1], 1.02 * k0_guess, 0.98 * k0_guess, xtol=1e-14)
    tip = end(k0)
    return float(tip[2]), float(tip[3])


# the tolerance of each kind at 10 P_cr, where the clamp's curvature is kappa_0 = 2 k sqrt(P/EI) = 331 1/m:
# rigid chain: its joints lie on the inscribed polygon, a tip error of about L (kappa_0 L_c)^2 / 24 at most
# (4e-3 L at 32 cells; measured 5.7e-4 L, 1.4e-4 L at 64: order 2);
# beam and ANCF elements stretch under the 126 N (P/EA = 5.5e-4, the elastica does not), plus order-2
# discretisation: 1.5e-3 L (measured 4.8e-4 L and 4.1e-4 L);
# six-bar cells: measured 2.8e-2 L at 16 cells and 6.3e-3 L at 32 (order 2.1): 1e-2 L;
# rod: exponential in the modes (6: 2.5e-4 L, 8: 5.8e-6 L, 12: 8.5e-9 L): 8 modes within 5e-5 L.
KINDS = [("rigid", 32, 4e-3), ("six-bar", 32, 1e-2), ("beam", 32, 1.5e-3), ("ancf", 32, 1.5e-3), ("rod", 8, 5e-5)]


@pytest.mark.parametrize("cell, n, tolerance", KINDS)
def test_buckled_cantilever_follows_the_stable_branch_on_the_nudge_side(cell, n, tolerance):
    # on main: beam elements returned the tip 5 mm up (against the nudge), rod and ANCF the straight pose
    mech, ei = column(cell, n, 10.0)
    p = 10.0 * math.pi**2 * ei / (4.0 * L**2)
    x_cf, y_cf, kappa0 = elastica_closed_form(ei, p)
    x_ref, y_ref = elastica_shooting(ei, -p, -NUDGE, -kappa0)
    assert math.hypot(x_ref - x_cf, -y_ref - y_cf) < 1e-5 * L  # the two references (the nudge's effect)
    result = solve_static(mech)
    x, y = result["b.tip_x"][-1], result["b.tip_y"][-1]
    assert y < -0.3 * L  # buckled, downwards as nudged
    assert math.hypot(x - x_ref, y - y_ref) < tolerance * L
    assert result.info["stability"] == "stable"


def test_the_opposite_nudge_buckles_the_other_way():
    mech, ei = column("beam", 32, 10.0, nudge=+NUDGE)
    p = 10.0 * math.pi**2 * ei / (4.0 * L**2)
    x_cf, y_cf, _ = elastica_closed_form(ei, p)
    result = solve_static(mech)
    assert math.hypot(result["b.tip_x"][-1] - x_cf, result["b.tip_y"][-1] - y_cf) < 1.5e-3 * L


@pytest.mark.parametrize("cell, n", [("rigid", 16), ("six-bar", 16), ("beam", 16), ("ancf", 16), ("rod", 6)])
def test_a_perfect_column_above_its_buckling_load_warns_unstable(cell, n):
    # no nudge: nothing decides a side, the straight state is the only equilibrium the path reaches
    mech, _ = column(cell, n, 1.5, nudge=0.0)
    with pytest.warns(StabilityWarning, match=r"load factor 1 .* is UNSTABLE.*imperfection") as record:
        result = solve_static(mech)
    assert result.info["stability"] == "unstable"
    assert abs(result["b.tip_y"][-1]) < 1e-9 and result["b.tip_x"][-1] > 0.999 * L  # straight, not folded
    assert issubclass(record[0].category, AccuracyWarning)  # filters for accuracy notes catch it
    # Euler's load is reached at load factor 1/1.5; the chains' own first buckling loads are within 1e-2 of
    # Euler's at 16 cells (order 1/N^2; measured: rigid 8e-4, six-bar 8e-3, beam 1.6e-3, ANCF 6e-5, rod 4e-11)
    factor = float(re.search(r"lost its stability at about load factor ([0-9.e+-]+)", str(record[0].message))[1])
    assert factor == pytest.approx(1 / 1.5, rel=1e-2)


@pytest.mark.parametrize("cell, n", [("beam", 16), ("rod", 6)])
def test_a_perfect_column_below_its_buckling_load_is_stable_and_quiet(cell, n):
    mech, _ = column(cell, n, 0.9, nudge=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = solve_static(mech)
    assert result.info["stability"] == "stable"


def test_a_column_at_its_buckling_load_is_critical():
    # 8 rod modes give Euler's load to 1e-9; at 0.9997 P_cr the straight column's lowest eigenvalue is about
    # 3e-4 of the unloaded one (1 - P/P_cr for the lowest mode, Galef's approximation), below CRITICAL_MARGIN
    mech, _ = column("rod", 8, 0.9997, nudge=0.0)
    with pytest.warns(StabilityWarning, match=r"is CRITICAL .*amplified about"):
        result = solve_static(mech)
    assert result.info["stability"] == "critical"
    assert CRITICAL_MARGIN == 1e-3


def test_sweep_points_are_checked_and_named():
    mech, _ = column("beam", 16, 1.5, nudge=0.0)
    with pytest.warns(StabilityWarning, match=r"sweep point 0 \(voltage 0 V\) \(and 2 more of 3\) is UNSTABLE"):
        result = static_sweep(mech, [0.0, 0.0, 0.0])
    assert result.info["unstable_points"] == "0,1,2"


def test_sweep_keeps_the_buckled_branch_its_actuation_chose():
    # the drive's curvature is the imperfection: at 1000 V the column buckles to the actuated side, and back at
    # 0 V it stays on that (stable) branch; the straight state at 0 V would be unstable.  Reference: the elastica
    # at 1.5 P_cr (closed form), tip y of the sign of the free curvature (up, active layer below)
    mech, ei = column("rod", 8, 1.5, nudge=0.0)
    p = 1.5 * math.pi**2 * ei / (4.0 * L**2)
    x_cf, y_cf, _ = elastica_closed_form(ei, p)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = static_sweep(mech, [1000.0, 0.0])
    assert result.info["unstable_points"] == ""
    sign = math.copysign(1.0, result["b.tip_y"][0])
    assert math.hypot(result["b.tip_x"][-1] - x_cf, result["b.tip_y"][-1] - sign * y_cf) < 5e-5 * L


def test_simulate_starts_from_the_stable_branch():
    mech, ei = column("rod", 8, 10.0)
    p = 10.0 * math.pi**2 * ei / (4.0 * L**2)
    x_cf, y_cf, _ = elastica_closed_form(ei, p)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AccuracyWarning)  # a short run; only the initial state matters here
        result = simulate(mech, 2e-4, step=1e-4)
    assert math.hypot(result["b.tip_x"][0] - x_cf, result["b.tip_y"][0] + y_cf) < 1e-4 * L


# ------------------------------------------------------------------------------ the grouped differences

def one_at_a_time(mbs, h_rel=1e-7):
    """Plain central differences of the static residual, one coordinate at a time (the reference)."""
    sd = mbs.systemData
    cur, ini = exu.ConfigurationType.Current, exu.ConfigurationType.Initial
    saved = sd.GetSystemState(configuration=ini)
    sd.SetSystemState(systemStateList=sd.GetSystemState(configuration=cur), configuration=ini)
    q0 = np.array(sd.GetODE2Coordinates(configuration=cur))
    settings = static_settings()
    solver = exu.MainSolverStatic()
    solver.InitializeSolver(mbs, settings)

    def residual(q):
        sd.SetODE2Coordinates(q, configuration=cur)
        solver.ComputeNewtonResidual(mbs, settings)
        return np.array(solver.GetSystemResidual())

    columns = []
    for i in range(q0.size):
        h = h_rel * (1.0 + abs(q0[i]))
        qp, qm = q0.copy(), q0.copy()
        qp[i] += h
        qm[i] -= h
        columns.append((residual(qp) - residual(qm)) / (2.0 * h))
    sd.SetODE2Coordinates(q0, configuration=cur)
    solver.FinalizeSolver(mbs, settings)
    sd.SetSystemState(systemStateList=saved, configuration=ini)
    return np.array(columns).T


@pytest.mark.parametrize("cell", ["rigid", "six-bar", "beam", "ancf", "rod"])
def test_grouped_differences_equal_one_coordinate_at_a_time(cell):
    mech, _ = column(cell, 6, 0.5, voltage=800.0)
    model = mb.build(mech)
    strain = mech.drives["b"].static_strain(800.0)
    equilibrium(mech, model, np.zeros(1), np.array([strain]), True, None, "test")
    model.before_linearisation()
    plan = TangentPlan(model.mbs)
    # a chain's coordinates share few items: fewer groups than coordinates (a rod's modes are all coupled)
    assert len(plan.groups) < model.coordinates().size or cell == "rod"
    grouped = plan.system()
    plain = one_at_a_time(model.mbs)
    n = model.coordinates().size
    np.testing.assert_array_equal(grouped["K"], -plain[:n])  # the same differences, to the bit
    np.testing.assert_array_equal(grouped["Cq"], plain[n:])
