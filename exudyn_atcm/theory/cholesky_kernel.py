"""A small dense Cholesky factorisation, compiled (numba), for the package's other kernels.

The rod cell's step (:mod:`exudyn_atcm.theory.rod_kernels`) solves with it and the stability
proof (:mod:`exudyn_atcm.mbs.definite_kernel`) decides positive definiteness with it: for the
matrices of a few dozen rows they hold, loops compiled into the caller cost less than LAPACK's
call overhead.

May import: numba.
"""

from __future__ import annotations

import math

import numba

__all__ = ["cholesky_in_place"]


@numba.njit(cache=True)
def cholesky_in_place(a):  # pragma: no cover - compiled
    """Lower Cholesky factor of the symmetric ``a`` in its lower triangle (the upper one is not read); ``False``
    (``a`` partly overwritten) where a pivot is not positive, i.e. ``a`` is not positive definite."""
    size = a.shape[0]
    for j in range(size):
        d = a[j, j]
        for k in range(j):
            d -= a[j, k] * a[j, k]
        if not d > 0.0:
            return False
        d = math.sqrt(d)
        a[j, j] = d
        for i in range(j + 1, size):
            v = a[i, j]
            for k in range(j):
                v -= a[i, k] * a[j, k]
            a[i, j] = v / d
    return True
