"""Priors of the relay-grid fits for where the record says nothing, and their strength by cross-validation.

A record of major loops measures the Preisach density only along the edges of the triangle
(:mod:`exudyn_atcm.hysteresis.coverage`); the weights inside are set by the regularisation.
The default (``prior="smooth"``) penalises differences between neighbouring cells along
``α`` and along ``β``: a smooth fill-in with no physical reason.  ``prior="pi"`` adds a
penalty on the differences along the lines ``α − β = const`` (cell ``(i, j)`` against
``(i + 1, j + 1)``).  A Prandtl-Ishlinskii operator is a Preisach model whose density depends
on ``α − β`` only (the play of radius ``r`` is the relays on the line ``α − β = 2r``), so this
prior makes the interior follow the measured edges the way a PI model would, while the data
can still make the density depend on ``α + β`` where they show it.  With a strong prior the
fit tends to the best PI-structured Preisach density (at least as good as the PI fit on the
record), with none to the plain smooth fit.

The strength ``s`` (the prior's weight relative to the trace of the data's Gram matrix, as for
``smoothing``) is chosen by ``K``-fold cross-validation on the record itself: the fitted
samples are cut into ``K`` contiguous blocks; the relay states of every sample follow from the
input alone, so leaving a block out of the least squares is leaving its rows out of the Gram
matrix.  For each candidate strength the ``K`` fits predict their left-out blocks; the choice is
the *strongest* prior whose cross-validated mean squared error is within one standard error of
the smallest (the one-standard-error rule of Hastie, Tibshirani and Friedman, *The Elements of
Statistical Learning*, 2nd ed., 2009, Sect. 7.10): the data cannot tell it apart from the best,
and in the unmeasured interior it gives the most structure.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .nnls import nnls_gram

__all__ = ["PRIORS", "PRIOR_STRENGTHS", "along_lines_matrix", "cross_validate_strength", "solve_regularised"]

#: Priors of :meth:`DiscretePreisach.fit <exudyn_atcm.hysteresis.DiscretePreisach.fit>` and
#: :meth:`EverettPreisach.fit <exudyn_atcm.hysteresis.EverettPreisach.fit>`.
PRIORS = ("smooth", "pi")

#: Candidate strengths of the ``"pi"`` prior tried by cross-validation.
PRIOR_STRENGTHS = (1e-3, 1e-2, 1e-1, 1.0, 10.0)


def along_lines_matrix(index: np.ndarray, n_levels: int) -> Any:
    """Sparse differences between grid cells ``(i, j)`` and ``(i + 1, j + 1)`` (same ``α − β``)."""
    import scipy.sparse  # noqa: PLC0415 - lazy: scipy.sparse is slow to import
    position = -np.ones((n_levels, n_levels), dtype=int)
    position[index[:, 0], index[:, 1]] = np.arange(index.shape[0])
    ok = index[:, 0] + 1 < n_levels
    first = np.flatnonzero(ok)
    second = position[index[ok, 0] + 1, index[ok, 1] + 1]
    rows = np.arange(first.size)
    return scipy.sparse.csr_matrix(
        (np.r_[np.ones(first.size), -np.ones(first.size)], (np.r_[rows, rows], np.r_[first, second])),
        shape=(first.size, index.shape[0]))


def _centred(gram: np.ndarray, rhs: np.ndarray, colsum: np.ndarray, ysum: float, m: float) -> tuple:
    mean = colsum / m
    return gram - m * np.outer(mean, mean), rhs - mean * ysum, mean


def solve_regularised(gram_c: np.ndarray, rhs_c: np.ndarray, penalties: list, initial: Any = None) -> tuple:
    """``argmin_{w>=0} ½ wᵀ(G + Σ λ_k L_k + ridge)w − bᵀw`` with each ``λ_k = weight_k · tr(G)/tr(L_k)``.

    ``penalties``: ``(weight_k, L_k)`` pairs, ``L_k`` sparse.  Returns the weights, the
    ``λ_k`` and the :class:`~exudyn_atcm.hysteresis.nnls.NNLSInfo`.
    """
    matrix = gram_c.copy()
    trace = float(np.trace(gram_c))
    lams = []
    for weight, lap in penalties:
        lam = weight * trace / max(float(lap.diagonal().sum()), 1e-300)
        lams.append(lam)
        if lam:
            coo = lap.tocoo()
            np.add.at(matrix, (coo.row, coo.col), lam * coo.data)
    ridge = 1e-10 * max(float(np.trace(matrix)) / matrix.shape[0], 1e-300)
    matrix[np.diag_indices_from(matrix)] += ridge
    weights, info = nnls_gram(matrix, rhs_c, initial=initial)
    return weights, lams, info


def cross_validate_strength(folds: list, smooth_lap: Any, smoothing: float, prior_lap: Any,
                            strengths: tuple = PRIOR_STRENGTHS) -> tuple[float, list]:
    """Choose the prior's strength by ``K``-fold cross-validation (see the module).

    Parameters
    ----------
    folds : list of tuple
        Per block of samples: ``(gram, rhs, colsum, ysum, m, yy)``, the uncentred Gram matrix of
        its relay states, ``Sᵀy``, column sums, ``Σ y``, sample count and ``Σ y²``.
    smooth_lap, prior_lap : scipy.sparse matrix
        ``DᵀD`` of the smoothness and of the prior.
    smoothing : float
        Weight of the smoothness (as in the fit).
    strengths : tuple of float
        Candidates.

    Returns
    -------
    strength : float
        The strongest candidate within one standard error of the best.
    table : list of dict
        ``strength``, ``cv_rms`` (cross-validated RMS error of the scaled output) and
        ``cv_mse_se`` (standard error of its square over the blocks) per candidate.
    """
    total = [sum(f[k] for f in folds) for k in range(6)]
    table = []
    warm: list = [None] * len(folds)
    for strength in strengths:
        mse = []
        sse_total, m_total = 0.0, 0.0
        for k, (g_f, r_f, c_f, ys_f, m_f, yy_f) in enumerate(folds):
            g_t, r_t, c_t, ys_t, m_t = (total[0] - g_f, total[1] - r_f, total[2] - c_f, total[3] - ys_f, total[4] - m_f)
            gram_c, rhs_c, mean = _centred(g_t, r_t, c_t, ys_t, m_t)
            w, _, _ = solve_regularised(gram_c, rhs_c, [(smoothing, smooth_lap), (strength, prior_lap)], warm[k])
            warm[k] = w > 0.0
            c = ys_t / m_t - float(mean @ w)
            sse = float(w @ g_f @ w + 2 * c * (c_f @ w) - 2 * (r_f @ w) + m_f * c * c - 2 * c * ys_f + yy_f)
            sse = max(sse, 0.0)
            mse.append(sse / m_f)
            sse_total += sse
            m_total += m_f
        table.append({"strength": strength, "cv_mse": sse_total / m_total,
                      "cv_mse_se": float(np.std(mse, ddof=1) / math.sqrt(len(mse))) if len(mse) > 1 else 0.0})
    best = min(table, key=lambda row: row["cv_mse"])
    limit = best["cv_mse"] + best["cv_mse_se"]
    chosen = max(row["strength"] for row in table if row["cv_mse"] <= limit)
    for row in table:
        row["cv_rms"] = math.sqrt(row.pop("cv_mse"))
    return chosen, table
