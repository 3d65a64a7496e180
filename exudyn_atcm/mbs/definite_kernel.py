"""The stability proof of :mod:`exudyn_atcm.mbs.definite` from Exudyn's Jacobian as one compiled call (numba).

:meth:`StabilityProbe.proved_in_solve <exudyn_atcm.mbs.stability.StabilityProbe.proved_in_solve>`
runs at every point of a static sweep.  In numpy its algebra (the cushion, the shift, the
penalty, the symmetrised penalised matrix and its Cholesky factorisation) is about fifteen small
array operations: 30 us on the README four-bar's 18 coordinates, more than the Jacobian itself.
:func:`shifted_penalised_cholesky` does the same arithmetic in loops, compiled: a few
microseconds.  A Cholesky factorisation that succeeds in floating point proves the positive
definiteness of the matrix it was given within about ``n u`` of its size whichever way its
operations are ordered (Golub & Van Loan, *Matrix Computations*, 4th ed., sec. 4.2), so this is the
same proof as :func:`~exudyn_atcm.mbs.definite.positive_definite_on_null_space`
(``tests/test_sweep_solve.py`` compares the two on random matrices and against the projected
eigenvalues).  Compiled on first use and cached on disk (numba's ``cache=True``), like the rod
cell's kernels.

Inside a static sweep's solve the whole check is one call, :func:`jacobian_penalised_cholesky`: it
takes the running solver's system Jacobian as Exudyn gives it, adds the revolute joints' lever
terms (:func:`add_lever_terms`, the arithmetic of
:class:`~exudyn_atcm.mbs.solver_jacobian.JointLevers`) and forms ``C_q^T C_q`` itself.  The
slicing, the lever terms and the Gram matrix in numpy cost about 25 us per point on a rigid-cell
actuator, three times the Exudyn calls that form the Jacobian (measured).

May import: numpy, numba, :mod:`exudyn_atcm.theory.cholesky_kernel`.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..theory.cholesky_kernel import cholesky_in_place

__all__ = ["add_lever_terms", "jacobian_penalised_cholesky", "shifted_penalised_cholesky"]


@numba.njit(cache=True)
def shifted_penalised_cholesky(k, metric, gram, sigma, cushion_per_size, scale):  # pragma: no cover - compiled
    """Whether ``(A + A^T)/2 + rho C_q^T C_q`` has a Cholesky factorisation, ``A = K - sigma M - c I``.

    ``c = cushion_per_size * max|K|``; ``rho = scale * max|A| / max_j (C_q^T C_q)_jj`` (0 without
    constraints), as :class:`~exudyn_atcm.mbs.definite.PenaltyProof` chooses it.  ``k`` (n x n),
    ``metric`` (``M``, n x n, or the identity), ``gram`` (``C_q^T C_q``, n x n; zeros without
    constraints).  ``True`` proves ``N^T A N`` positive definite on the null space ``N`` of ``C_q``;
    ``False`` proves nothing.
    """
    n = k.shape[0]
    k_size = 0.0
    for i in range(n):
        for j in range(n):
            v = abs(k[i, j])
            if v > k_size:
                k_size = v
    cushion = cushion_per_size * k_size
    a = np.empty((n, n))
    a_size = 0.0
    for i in range(n):
        for j in range(n):
            v = k[i, j] - sigma * metric[i, j]
            if i == j:
                v -= cushion
            a[i, j] = v
            if abs(v) > a_size:
                a_size = abs(v)
    gram_size = 0.0
    for j in range(n):
        if gram[j, j] > gram_size:
            gram_size = gram[j, j]
    rho = scale * a_size / gram_size if gram_size > 0.0 else 0.0
    p = np.empty((n, n))
    for i in range(n):
        for j in range(i + 1):
            v = 0.5 * (a[i, j] + a[j, i]) + rho * gram[i, j]
            if not math.isfinite(v):
                return False
            p[i, j] = v
    return cholesky_in_place(p)  # the lower triangle of p, in place


@numba.njit(cache=True)
def add_lever_terms(k, rows, signs, angles, local, ae, q, multipliers):  # pragma: no cover - compiled
    """Add the revolute joints' lever terms to the tangent ``k`` (in place), as
    :meth:`JointLevers.add_to <exudyn_atcm.mbs.solver_jacobian.JointLevers.add_to>` defines them:
    ``k[r, r] += s (lambda_0 (c p_x - s_theta p_y) + lambda_1 (s_theta p_x + c p_y))`` per lever, ``theta``
    the reference angle plus ``q[r]``, ``lambda`` the joint's multipliers (``ae``: their indices)."""
    for i in range(rows.shape[0]):
        r = rows[i]
        theta = angles[i] + q[r]
        c = math.cos(theta)
        s = math.sin(theta)
        px = local[i, 0]
        py = local[i, 1]
        k[r, r] += signs[i] * (multipliers[ae[i, 0]] * (c * px - s * py) + multipliers[ae[i, 1]] * (s * px + c * py))


@numba.njit(cache=True)
def jacobian_penalised_cholesky(jacobian, n2, metric, rows, signs, angles, local, ae, q, multipliers, sigma,
                                cushion_per_size, scale):  # pragma: no cover - compiled
    """:func:`shifted_penalised_cholesky` of the tangent in Exudyn's system Jacobian ``jacobian``.

    ``jacobian``: the static solver's system Jacobian (ODE2 rows and columns first, then the
    constraints' rows, ``n2`` ODE2 coordinates); ``K`` is its ODE2 block with the lever terms
    (:func:`add_lever_terms`; ``rows`` ... ``ae`` the levers' arrays of
    :class:`~exudyn_atcm.mbs.solver_jacobian.JointLevers`, ``q`` and ``multipliers`` the state's
    ODE2 and algebraic coordinates), ``C_q`` its constraint rows' first ``n2`` columns.
    """
    k = np.empty((n2, n2))
    for i in range(n2):
        for j in range(n2):
            k[i, j] = jacobian[i, j]
    add_lever_terms(k, rows, signs, angles, local, ae, q, multipliers)
    m = jacobian.shape[0] - n2
    gram = np.zeros((n2, n2))
    for r in range(m):
        for i in range(n2):
            v = jacobian[n2 + r, i]
            if v != 0.0:
                for j in range(n2):
                    gram[i, j] += v * jacobian[n2 + r, j]
    return shifted_penalised_cholesky(k, metric, gram, sigma, cushion_per_size, scale)
