"""A cheap proof that a matrix is positive definite on the null space of a constraint Jacobian.

The stability of a constrained equilibrium asks whether ``N^T A N`` is positive definite, with
``N`` a basis of the null space of the constraint Jacobian ``C_q`` (:mod:`exudyn_atcm.mbs.stability`).
Computing ``N`` (a pivoted QR of ``C_q^T``) and the projection costs more than the test itself.
Finsler's lemma gives a test without ``N``: if the *penalised* matrix

    A_s + rho C_q^T C_q,   A_s = (A + A^T) / 2,   rho >= 0,

is positive definite, then for every ``x != 0`` with ``C_q x = 0``,
``x^T A x = x^T (A_s + rho C_q^T C_q) x > 0``: ``N^T A N`` (its symmetric part) is positive
definite, whatever ``rho``.  A Cholesky factorisation that succeeds proves it (Golub & Van Loan,
*Matrix Computations*, 4th ed., sec. 4.2).  The converse holds only for ``rho`` large enough
(Finsler: for some ``rho``), so a failure proves nothing and the caller falls back to the
eigenvalue solution; :class:`PenaltyProof` raises ``rho`` after such a failure when the
fallback found the state stable, so that the next state of a sweep passes.

Round-off: a Cholesky factorisation that succeeds in floating point proves the positive
definiteness of a matrix within about ``n u`` times the penalised matrix's size of the one
given (``u`` the unit round-off, ``n`` its order); with ``rho C_q^T C_q`` scaled to at most
``1e5`` times ``A`` that is about ``1e-9`` of ``A`` for 100 coordinates, below the ``1e-8`` the
grouped differences of the tangent leave (:mod:`exudyn_atcm.mbs.tangent`).

For an unsymmetric ``A`` (a follower load's tangent) the same proof bounds every eigenvalue
``lambda`` of ``N^T A N v = lambda N^T M N v`` (``M`` symmetric positive definite) when applied to
``A - sigma M``: ``Re(v^* (A - sigma M) v) > 0`` gives ``Re(lambda) > sigma``.
"""

from __future__ import annotations

import numpy as np
from .._checks import shown

__all__ = ["PenaltyProof", "positive_definite_on_null_space"]

#: largest penalty relative to ``max|A| / max|C_q^T C_q|`` (keeps the round-off bound above)
MAX_RELATIVE_PENALTY = 1e5
#: the compiled kernels, imported at their first use
_KERNELS: dict = {}


def positive_definite_on_null_space(a: np.ndarray, cq: np.ndarray, rho: float) -> bool:
    """Whether a Cholesky factorisation of ``(a + a^T)/2 + rho cq^T cq`` succeeds (then ``N^T a N`` is positive definite).

    Parameters
    ----------
    a : numpy.ndarray
        Square matrix (n x n), e.g. ``K_T - sigma M`` [N/m ...].
    cq : numpy.ndarray
        Constraint Jacobian (m x n); ``m`` may be 0.
    rho : float
        Penalty ``>= 0`` [units of ``a`` over those of ``cq^T cq``].

    Returns
    -------
    bool
        ``True`` is a proof; ``False`` proves nothing.
    """
    if not rho >= 0.0:
        raise ValueError(f"rho: expected a penalty >= 0, got {shown(rho)}")
    return _penalised_cholesky(a, cq.T @ cq if cq.shape[0] else None, rho)


def _penalised_cholesky(a: np.ndarray, gram: np.ndarray | None, rho: float) -> bool:
    """:func:`positive_definite_on_null_space` with ``gram = cq^T cq`` given (``None`` without constraints)."""
    from scipy.linalg.lapack import dpotrf  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
    penalised = a + a.T
    penalised *= 0.5
    if gram is not None:
        penalised += rho * gram
    if not np.isfinite(penalised.sum()):  # a nan or inf entry (or a sum that overflows): no proof
        return False
    # LAPACK's Cholesky factorisation directly (numpy's wrapper costs about 10 us more on matrices of a few
    # dozen rows, a fifth of a static sweep point's check): info > 0 when a leading minor is not positive
    _, info = dpotrf(penalised, lower=1, clean=0, overwrite_a=1)
    return info == 0


class PenaltyProof:
    """:func:`positive_definite_on_null_space` with a penalty that adapts along a sequence of states.

    The penalty is ``scale * max|a| / max|cq^T cq|``; ``scale`` starts at 10 (measured: 1 was too small for the
    first point of the four-bar and the rod chain) and is raised ten-fold
    (:meth:`missed`) when a proof failed on a state that was positive definite after all, up to
    :data:`MAX_RELATIVE_PENALTY`.
    """

    def __init__(self) -> None:
        self.scale = 10.0
        #: proofs that succeeded and attempts (for the record)
        self.proved = 0
        self.attempts = 0

    def __call__(self, a: np.ndarray, cq: np.ndarray) -> bool:
        """Try the proof on ``a`` and ``cq`` (see :func:`positive_definite_on_null_space`)."""
        self.attempts += 1
        gram = cq.T @ cq if cq.shape[0] else None
        ok = _penalised_cholesky(a, gram, self._rho(a, gram))
        self.proved += ok
        return ok

    def prove_shifted(self, k: np.ndarray, metric: np.ndarray, cq: np.ndarray, sigma: float,
                      cushion_per_size: float) -> bool:
        """The proof on ``a = K - sigma M - c I`` (``c = cushion_per_size max|K|``) in one compiled call
        (:func:`~exudyn_atcm.mbs.definite_kernel.shifted_penalised_cholesky`; the same arithmetic as forming
        ``a`` and calling this object on it)."""
        from .definite_kernel import shifted_penalised_cholesky  # noqa: PLC0415 - lazy: numba is slow to import
        self.attempts += 1
        gram = cq.T @ cq if cq.shape[0] else np.zeros((k.shape[0], k.shape[0]))
        ok = bool(shifted_penalised_cholesky(np.ascontiguousarray(k), np.ascontiguousarray(metric),
                                             np.ascontiguousarray(gram), float(sigma), float(cushion_per_size),
                                             float(self.scale)))
        self.proved += ok
        return ok

    def prove_from_jacobian(self, jacobian: np.ndarray, n2: int, metric: np.ndarray, levers: tuple, q: np.ndarray,
                            multipliers: np.ndarray, sigma: float, cushion_per_size: float) -> bool:
        """:meth:`prove_shifted` on the tangent in a static solver's system Jacobian, in one compiled call
        (:func:`~exudyn_atcm.mbs.definite_kernel.jacobian_penalised_cholesky`: ``K`` its first ``n2`` rows and
        columns plus the revolute joints' lever terms ``levers``, the arrays of
        :attr:`JointLevers.arrays <exudyn_atcm.mbs.solver_jacobian.JointLevers.arrays>`, at coordinates ``q`` and
        multipliers ``multipliers``; ``C_q`` its remaining rows)."""
        kernel = _KERNELS.get("jacobian")
        if kernel is None:  # lazy: numba is slow to import; kept after the first use (a sweep proves every point)
            from .definite_kernel import jacobian_penalised_cholesky  # noqa: PLC0415
            kernel = _KERNELS["jacobian"] = jacobian_penalised_cholesky
        self.attempts += 1
        ok = bool(kernel(jacobian, n2, metric, *levers, q, multipliers, float(sigma), float(cushion_per_size),
                         float(self.scale)))
        self.proved += ok
        return ok

    def missed(self, a: np.ndarray | None = None, cq: np.ndarray | None = None) -> None:
        """The last failed proof was on a positive definite state: a larger penalty for the next.

        With that state's ``a`` and ``cq``: the penalty raised ten-fold until it proves that state (at
        most to :data:`MAX_RELATIVE_PENALTY`; a few Cholesky factorisations), so that the next state of a
        sweep, close to it, passes; without them, ten-fold once.
        """
        self.scale = min(10.0 * self.scale, MAX_RELATIVE_PENALTY)
        if a is None or cq is None:
            return
        gram = cq.T @ cq if cq.shape[0] else None
        while self.scale < MAX_RELATIVE_PENALTY and not _penalised_cholesky(a, gram, self._rho(a, gram)):
            self.scale = min(10.0 * self.scale, MAX_RELATIVE_PENALTY)

    def _rho(self, a: np.ndarray, gram: np.ndarray | None) -> float:
        """The penalty for ``a`` and ``gram = cq^T cq`` (``None`` without constraints)."""
        if gram is None:
            return 0.0
        largest = float(gram.diagonal().max())  # the largest diagonal entry of cq^T cq
        size = float(abs(a).max()) if a.size else 0.0
        return self.scale * size / largest if largest > 0.0 else 0.0
