"""Settings of a static sweep's continuation steps (issue 31, part 2): dense for small systems, made once per sweep.

The equilibria are unchanged by the linear solver (``test_static_sweep_continuation.py`` compares the
continuation with the point-by-point sweep, which keeps the sparse solver, to 1e-9 m).
"""

from __future__ import annotations

import exudyn as exu
import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm.mbs import builder as mb
from exudyn_atcm.mbs import blas_threads, stability
from exudyn_atcm.mbs.continuation_settings import DENSE_SIZE, continuation_settings
from exudyn_atcm.solve import sweep_continuation

from test_one_stepping import four_bar, lone


def unknowns(model) -> int:
    sd = model.mbs.systemData
    return len(sd.GetODE2Coordinates()) + len(sd.GetAECoordinates())


def test_a_small_system_steps_densely_and_a_large_one_sparsely():
    small = mb.build(four_bar(atcm.PiezoDrive(0.0)))
    b = atcm.Bender("b", width=10e-3, passive=atcm.Layer(0.2e-3, 70e9, 1550.0),
                    active=atcm.Layer(0.3e-3, 30.336e9, 5440.0), length=0.03, n_cells=16, drive=atcm.PiezoDrive(0.0),
                    cell="six-bar")
    large = mb.build(atcm.Mechanism("m").add(b).ground(b.base))
    assert unknowns(small) <= DENSE_SIZE < unknowns(large)
    assert continuation_settings(small).linearSolver.solverType == exu.LinearSolverType.EXUdense
    assert continuation_settings(large).linearSolver.solverType == exu.LinearSolverType.EigenSparse
    for model in (small, large):
        s = continuation_settings(model)
        assert not s.staticSolver.useLoadFactor and s.staticSolver.numberOfLoadSteps == 1


def test_a_smooth_sweep_continues_in_one_static_solve(monkeypatch):
    """The points after the first are the load steps of one Exudyn static solve (one set of settings, one
    solver set-up), not one solve per point."""
    calls = []
    original = sweep_continuation.solve_points

    def spy(model, strains, first, on_point, **kwargs):
        calls.append(first)
        return original(model, strains, first, on_point, **kwargs)

    monkeypatch.setattr(sweep_continuation, "solve_points", spy)
    r = atcm.static_sweep(lone(atcm.PiezoDrive(0.0)), np.linspace(0.0, 1000.0, 5))
    assert calls == [1] and r.info["continued_points"] == 4


def test_one_blas_thread_inside_and_the_counts_restored_after():
    with stability.one_blas_thread():  # still importable from stability; it lives in mbs.blas_threads
        libraries = blas_threads._BLAS[0]
        assert all(lib.get_num_threads() == 1 for lib in libraries)
    outside = [lib.get_num_threads() for lib in libraries]
    with stability.one_blas_thread():
        pass
    assert [lib.get_num_threads() for lib in libraries] == outside
