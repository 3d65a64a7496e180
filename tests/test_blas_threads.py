"""The package's dense algebra on one BLAS thread (:mod:`exudyn_atcm.mbs.blas_threads`).

A threaded OpenBLAS leaves its workers spinning about 0.1 s of CPU after each threaded call; the
package's matrices are small, so its algebra runs on one thread.  Measured before the change: 0.20 s
of another thread's CPU after building the micro gripper with 24 rigid cells (the redundancy check's
SVD in scipy's own OpenBLAS, which the limit missed when numpy's was found first).
"""

from __future__ import annotations

import sys

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm.mbs import blas_threads, builder

from _spinning_threads import HAS_PROC, ticks_after

threadpoolctl = pytest.importorskip("threadpoolctl")


def blas_threads_now() -> list[int]:
    return [lib["num_threads"] for lib in threadpoolctl.threadpool_info() if lib["user_api"] == "blas"]


def test_inside_every_blas_library_runs_one_thread_and_the_counts_come_back():
    import scipy.linalg  # noqa: F401 - its own BLAS loaded (the limit must reach it too)
    before = blas_threads_now()
    with blas_threads.one_blas_thread():
        assert blas_threads_now() and all(n == 1 for n in blas_threads_now())
        with blas_threads.one_blas_thread():  # nested: still one, and the outer block's counts kept
            assert all(n == 1 for n in blas_threads_now())
        assert all(n == 1 for n in blas_threads_now())
    assert blas_threads_now() == before


def test_libraries_loaded_after_the_first_use_are_found(monkeypatch):
    import scipy.linalg  # noqa: F401
    # the libraries as found before any other import: none (a stale list whose module count no longer matches)
    monkeypatch.setattr(blas_threads, "_BLAS", [[], len(sys.modules) - 1])
    with blas_threads.one_blas_thread():
        assert all(n == 1 for n in blas_threads_now())


def cantilever_chain(n_cells: int) -> atcm.Mechanism:
    layer = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
    mfc = atcm.Layer(thickness=0.3e-3, youngs_modulus=30e9, density=5440.0)
    a = atcm.Bender("a", width=5e-3, passive=layer, active=mfc, length=0.03, n_cells=n_cells, cell="rigid",
                    drive=atcm.PiezoDrive(500.0))
    b = atcm.Bender("b", width=5e-3, passive=layer, active=mfc, length=0.03, n_cells=n_cells, cell="rigid",
                    drive=atcm.PiezoDrive(500.0), base=(0.0, 0.01))
    link = atcm.Link("tip", {"A": (0.03, 0.0), "B": (0.03, 0.01)}, mass=1e-4, inertia=1e-9)
    m = atcm.Mechanism("guide").add(a, b, link).ground(a.base).ground(b.base)
    return m.weld(a.tip, link.point("A")).pin(b.tip, link.point("B"))


@pytest.mark.skipif(not HAS_PROC, reason="reads the threads' CPU time from Linux's /proc")
def test_a_build_and_an_eigenvalue_analysis_leave_no_blas_worker_spinning():
    if all(n <= 1 for n in blas_threads_now()):
        pytest.skip("a single-threaded BLAS: nothing can spin")
    mech = cantilever_chain(48)  # 2 x 48 rigid cells: a constraint Jacobian of about 290 x 300
    for analysis in (lambda: builder.build(mech), lambda: atcm.eigenfrequencies(mech, n=2)):
        assert ticks_after(analysis) <= 2  # clock ticks of 10 ms: what other threads may take by chance
    assert np.all(np.isfinite(atcm.eigenfrequencies(mech, n=2)))
