"""A bound on cells and an announcement before the build (issue 29, finding 9).

``n_cells=10**5`` ran 21 s and took 1.2 GB with no announcement, ``10**7`` ran for minutes silently
(relay and play counts were bounded, cells were not).  Now a count above
:data:`~exudyn_atcm.physical_bounds.MAX_CELLS` (1e5) is refused where it is given, and every solve
(time integration, static solve and sweep, eigenfrequencies) and ``add_to`` estimates the build from
each cell kind's measured cost before building, announcing a long or large one with a
``RunCostWarning``.  The tests never build the large models: the Exudyn builder is replaced by one
that fails the test if it is reached, so the refusal and the announcement are shown to come first.
"""

from __future__ import annotations

import warnings

import exudyn as exu
import pytest

import exudyn_atcm as atcm
from exudyn_atcm import BendingActuator, Bender, Flexure, Layer, Mechanism, PiezoDrive, Segment
from exudyn_atcm.cells import CELL_KINDS
from exudyn_atcm.errors import RunCostWarning
from exudyn_atcm.mbs import builder, user_system
from exudyn_atcm.mechanism.build_cost import (LARGE_MODEL_BYTES, STATIC_CELLS_MEASURED, build_estimate,
                                              coordinates_at_least)
from exudyn_atcm.physical_bounds import MAX_CELLS
from exudyn_atcm.solve import run_checks

CFC = Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
MFC = Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)


def bender(n_cells: int, cell: str = "rigid") -> Bender:
    return Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.03, n_cells=n_cells, drive=PiezoDrive(500.0),
                  cell=cell)


def cantilever(n_cells: int, cell: str = "rigid") -> Mechanism:
    b = bender(n_cells, cell)
    return Mechanism("big").add(b).ground(b.base)


@pytest.fixture
def no_build(monkeypatch):
    """Building an Exudyn model fails the test: what is checked must come before it."""
    def refuse(*args, **kwargs):
        raise AssertionError("the model was built before the announcement")
    monkeypatch.setattr(builder, "build", refuse)
    monkeypatch.setattr(user_system, "add_mechanism", refuse)


@pytest.mark.parametrize("make", [
    lambda n: bender(n),
    lambda n: Bender("b", width=10e-3, passive=CFC, active=MFC, segments=[Segment(0.03, n)], cell="rigid"),
    lambda n: BendingActuator(n, 0.03 / n, 10e-3, CFC, MFC, PiezoDrive(0.0), cell="six-bar"),
    lambda n: Flexure("f", base=(0.0, 0.0), tip=(0.03, 0.0), width=5e-3, layer=Layer(0.2e-3, 70e9, 1550.0), model="cells", n_cells=n),
])
def test_more_cells_than_the_bound_are_refused_where_they_are_given(make):
    with pytest.raises(ValueError, match=r"n_cells = 10000000 is more than 100000 cells"):
        make(10**7)
    with pytest.raises(ValueError, match=f"n_cells = {MAX_CELLS + 1}"):
        make(MAX_CELLS + 1)


def test_segments_within_the_bound_that_sum_beyond_it_are_refused():
    half = MAX_CELLS // 2 + 1
    with pytest.raises(ValueError, match=r"bender 'b': n_cells \(all segments\) = 100002"):
        Bender("b", width=10e-3, passive=CFC, active=MFC, segments=[Segment(0.015, half), Segment(0.015, half)], cell="rigid")


@pytest.mark.parametrize("solve, words", [
    (lambda m: atcm.simulate(m, 0.1), r"this run is predicted to take about .*100000 rigid cells.*building the "
                                       r"Exudyn model: about .* and 810 MB"),
    (lambda m: atcm.solve_static(m), r"solve_static of 'big' \(100000 cells and bodies\) .* or more .*810 MB.*"
                                     r"1 static equilibrium"),
    (lambda m: atcm.static_sweep(m, [0.0, 500.0, 1000.0]), r"static_sweep of 'big' .*3 static equilibria"),
    (lambda m: atcm.eigenfrequencies(m), r"eigenfrequencies of 'big' .*at least 300000 coordinates"),
])
def test_a_hundred_thousand_cells_are_announced_before_the_build(no_build, solve, words):
    mech = cantilever(10**5)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RunCostWarning)  # the announcement stops the call: nothing is built
        with pytest.raises(RunCostWarning, match=words):
            solve(mech)


def test_a_hundred_thousand_cells_are_announced_by_add_to_before_they_are_added(no_build):
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    with warnings.catch_warnings():
        warnings.simplefilter("error", RunCostWarning)
        with pytest.raises(RunCostWarning, match=r"add_to of 'b' \(100000 cells and bodies\).*810 MB"):
            atcm.add_to(mbs, bender(10**5))
    assert mbs.systemData.NumberOfObjects() == 0  # nothing was added


def test_the_build_estimate_adds_the_measured_costs_of_every_part():
    # the estimate is the sum of the parts' measured costs: each segment by its kind, a link as one rigid body
    a, b, m, k = CELL_KINDS["rigid"].build_cost
    beam = CELL_KINDS["beam"].build_cost
    mech = Mechanism().add(bender(1000), Bender("c", width=10e-3, passive=CFC, active=MFC,
                                                segments=[Segment(0.01, 300), Segment(0.02, 500)], cell="beam",
                                                base=(0.03, 0.0)),
                           atcm.Link("L", {"A": (0.06, 0.0)}, mass=1e-4, inertia=1e-8))
    seconds, memory = build_estimate(mech)
    expected = (1000 * (a + b * 1000) + sum(n * (beam[0] + beam[1] * n) for n in (300, 500)) + (a + b),
                1000 * (m + k * 1000) + sum(n * (beam[2] + beam[3] * n) for n in (300, 500)) + (m + k))
    assert (seconds, memory) == pytest.approx(expected, rel=1e-12)
    assert coordinates_at_least(mech) == 3 * 1000 + 3 * 800 + 3


def test_small_models_stay_quiet_and_the_thresholds_are_documented():
    # the package's cases: tens of cells (any RunCostWarning is an error here, setup.cfg)
    mech = cantilever(40)
    atcm.solve_static(mech)
    atcm.static_sweep(mech, [0.0, 500.0])
    atcm.eigenfrequencies(mech)
    assert run_checks.LONG_RUN_SECONDS == 60.0  # the default limit of the build announcements
    assert build_estimate(cantilever(MAX_CELLS))[1] > LARGE_MODEL_BYTES > build_estimate(cantilever(10_000))[1]
    assert STATIC_CELLS_MEASURED < MAX_CELLS
