"""Non-negative least squares from the normal equations, by block principal pivoting.

The relay-grid fits (:meth:`DiscretePreisach.fit <exudyn_atcm.hysteresis.DiscretePreisach.fit>`,
:meth:`EverettPreisach.fit <exudyn_atcm.hysteresis.EverettPreisach.fit>`) minimise

``f(w) = ½ wᵀ G w − bᵀ w``  subject to  ``w >= 0``

with ``G`` the (regularised) Gram matrix of the relay states, a few hundred to a few thousand
unknowns.  :func:`nnls_gram` solves it by the block principal pivoting method of Júdice and
Pires (1994), in the form of Kim and Park (2011) for NNLS: guess the set ``F`` of positive
weights, solve ``G_FF w_F = b_F`` with one Cholesky factorisation, and exchange *every* index
that violates the optimality (KKT) conditions ``w_F >= 0``, ``(G w − b)_i >= 0`` off ``F`` at
once; when an exchange does not reduce the number of violations for three rounds, only the
violating index with the largest number is exchanged (Murty's rule, which terminates).  A fit
needs about ten factorisations where the Lawson-Hanson method (SciPy's ``nnls``) adds one
index per iteration.  The result satisfies the KKT conditions to the stated tolerance, so it is
the same minimiser as any other exact NNLS method's (tested against SciPy's ``nnls``).

The dense linear algebra runs on one BLAS thread (``threadpoolctl``, when installed): for
matrices of this size a second thread gains little on an idle machine and, on a machine whose
cores are busy with other work, threads waiting for each other make a factorisation ten to
twenty times slower.

References
----------
Júdice, J. J., Pires, F. M. (1994).  A block principal pivoting algorithm for large-scale strictly
monotone linear complementarity problems.  *Computers & Operations Research* 21(5), 587-596.

Kim, J., Park, H. (2011).  Fast nonnegative matrix factorization: an active-set-like method and
comparisons.  *SIAM Journal on Scientific Computing* 33(6), 3261-3281.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, field
from typing import Any

import numpy as np

try:  # optional: limits BLAS threads (see the module docstring)
    from threadpoolctl import threadpool_limits
except ImportError:  # pragma: no cover - without it the BLAS runs with its default threads
    threadpool_limits = None

__all__ = ["NNLSInfo", "nnls_gram", "single_blas_thread"]


def single_blas_thread() -> Any:
    """Context manager running the BLAS/LAPACK calls inside on one thread (no-op without threadpoolctl)."""
    if threadpool_limits is None:
        return contextlib.nullcontext()
    return threadpool_limits(limits=1, user_api="blas")


@dataclass
class NNLSInfo:
    """How :func:`nnls_gram` went.

    Attributes
    ----------
    iterations : int
        Factorisations of a free block (exchanges of the guessed set ``F``).
    free_sizes : list of int
        Size of ``F`` at each iteration.
    kkt_violation : float
        Largest violation of the optimality conditions at the solution, relative to ``max |b|``
        (for the gradient) and ``max w`` (for the weights); ``<= tolerance``.
    """

    iterations: int = 0
    free_sizes: list = field(default_factory=list)
    kkt_violation: float = 0.0


def _solve_free(gram: np.ndarray, rhs: np.ndarray, idx: np.ndarray) -> np.ndarray:
    import scipy.linalg  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
    block = gram[np.ix_(idx, idx)]
    try:
        factor = scipy.linalg.cho_factor(block, lower=False, check_finite=False)
        return scipy.linalg.cho_solve(factor, rhs[idx], check_finite=False)
    except np.linalg.LinAlgError:
        # numerically semi-definite block: least-squares solution of the (consistent) system
        return scipy.linalg.lstsq(block, rhs[idx], check_finite=False, lapack_driver="gelsy")[0]


def nnls_gram(gram: Any, rhs: Any, *, initial: Any = None, tolerance: float = 1e-10,
              max_iterations: int | None = None) -> tuple[np.ndarray, NNLSInfo]:
    """``argmin_{w >= 0} ½ wᵀ G w − bᵀ w`` for a symmetric positive (semi-)definite ``G``.

    Parameters
    ----------
    gram : array_like
        ``G``, shape ``(n, n)``, symmetric positive definite (add a tiny ridge if it is only
        semi-definite).
    rhs : array_like
        ``b``, shape ``(n,)``.
    initial : array_like of bool, optional
        Guess of the set of positive weights (a warm start, e.g. from a fit of a similar
        problem).  Default: all weights free.
    tolerance : float, optional
        Relative tolerance of the optimality conditions: a free weight counts as negative below
        ``−tolerance·max(w)``, a zero weight's gradient as negative below ``−tolerance·max|b|``.
    max_iterations : int, optional
        Default ``10 n + 50``; Murty's single exchanges terminate within ``2ⁿ`` in theory and in
        a few ``n`` in practice.

    Returns
    -------
    weights : numpy.ndarray
        The minimiser, ``>= 0``.
    info : NNLSInfo

    Raises
    ------
    ValueError
        For shapes that do not match or non-finite entries.
    RuntimeError
        If the exchanges do not reach the optimality conditions within ``max_iterations``.
    """
    g = np.asarray(gram, dtype=float)
    b = np.asarray(rhs, dtype=float)
    n = b.size
    if g.shape != (n, n) or b.ndim != 1:
        raise ValueError(f"gram must have shape (n, n) for rhs of shape (n,), got {g.shape} and {b.shape}")
    if not (np.isfinite(g).all() and np.isfinite(b).all()):
        raise ValueError("gram and rhs must hold finite numbers only")
    if n == 0:
        return np.zeros(0), NNLSInfo()
    free = np.ones(n, dtype=bool) if initial is None else np.asarray(initial, dtype=bool).copy()
    if free.shape != (n,):
        raise ValueError(f"initial must have shape ({n},), got {free.shape}")
    limit = 10 * n + 50 if max_iterations is None else int(max_iterations)
    b_scale = max(float(np.abs(b).max()), 1e-300)
    info = NNLSInfo()
    w = np.zeros(n)
    best, chances = n + 1, 3
    with single_blas_thread():
        for _ in range(limit):
            w[:] = 0.0
            idx = np.flatnonzero(free)
            if idx.size:
                w[idx] = _solve_free(g, b, idx)
            gradient = g @ w - b
            w_scale = max(float(w.max()), 1e-300)
            negative_w = free & (w < -tolerance * w_scale)
            negative_g = ~free & (gradient < -tolerance * b_scale)
            bad = negative_w | negative_g
            info.iterations += 1
            info.free_sizes.append(int(idx.size))
            count = int(bad.sum())
            if count == 0:
                violation_w = float(np.max(-w[free], initial=0.0)) / w_scale
                violation_g = float(np.max(-gradient[~free], initial=0.0)) / b_scale
                info.kkt_violation = max(violation_w, violation_g, 0.0)
                return np.maximum(w, 0.0), info
            if count < best:
                best, chances = count, 3
                free ^= bad
            elif chances > 0:
                chances -= 1
                free ^= bad
            else:
                k = int(np.flatnonzero(bad)[-1])
                free[k] = not free[k]
    raise RuntimeError(f"nnls_gram: no optimum within {limit} exchanges ({best} optimality conditions still violated)")
