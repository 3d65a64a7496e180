"""The linear basis of a Preisach operator followed by linear lags, along records at several rates.

An :class:`~exudyn_atcm.hysteresis.everett.EverettPreisach` operator's output is
``offset + Σ_c w_c F_c(t)``, ``F_c`` the share of grid cell ``c``'s spread relays that is on
(:class:`~exudyn_atcm.hysteresis.relay_gram.CellFractions`).  A linear block after it
(:class:`~exudyn_atcm.hysteresis.dynamics.LagSum`: a creep law and/or a rate lag) acts on each
term on its own, so the model output is ``Σ_c w_c L[F_c] + offset · L[1]``: for a given block
the output is linear in the cell weights, and the block applied to every basis column
(:func:`lagged_columns`) is the design matrix of a least-squares fit.

:func:`check_records` checks records ``(t, u, y)`` the way the rate fits take them.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from .._checks import finite_array
from .dynamics import LagSum
from .relay_gram import CellFractions

__all__ = ["cell_fraction_columns", "lagged_columns", "check_records", "record_rates"]

#: Sample spacings equal to this relative tolerance count as uniform (the fast filter path).
UNIFORM_SPACING = 1e-9


def cell_fraction_columns(u: Any, edges: Any, index: Any) -> np.ndarray:
    """Cell fractions ``F`` (one column per grid cell of ``index``) along ``u`` from all relays off.

    Parameters
    ----------
    u : array_like
        Inputs [input units], in time order.
    edges : array_like
        Cell edges of the input grid, ``n + 1`` values, strictly increasing.
    index : array_like of int
        ``(i, j)`` grid indices of the cells, shape ``(n_cells, 2)`` (as from
        :func:`~exudyn_atcm.hysteresis.relay_gram.relay_grid`).

    Returns
    -------
    numpy.ndarray
        Shape ``(len(u), n_cells)``: ``EverettPreisach(...).apply(u) = offset + F @ weights``.
    """
    u_a = finite_array("u", u)
    fractions = CellFractions(np.asarray(edges, dtype=float), np.asarray(index, dtype=int))
    return np.array([fractions.commit(v) for v in u_a.tolist()], dtype=float)


def lagged_columns(columns: np.ndarray, t: np.ndarray, lags: LagSum, rest: np.ndarray) -> np.ndarray:
    """:meth:`LagSum.response <exudyn_atcm.hysteresis.dynamics.LagSum.response>` of every column at once.

    Each column ``h`` (one per basis function, sampled at times ``t`` [s]) is passed through the
    block with its lag states at rest at ``rest`` (one value per column) and no time passing
    before the first sample, exactly as :class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`
    steps its states (first-order hold, :func:`~exudyn_atcm.hysteresis.dynamics.lag_step`).  For
    uniform sample spacing each lag is a recursive filter with constant coefficients
    (``z_k = a z_{k-1} + (1 − ρ) h_k + (ρ − a) h_{k-1}``, ``a = e^{−Δt/τ}``,
    ``ρ = (1 − a) τ/Δt``), run by :func:`scipy.signal.lfilter`; otherwise step by step.

    Returns
    -------
    numpy.ndarray
        Same shape as ``columns``.
    """
    from scipy.signal import lfilter  # noqa: PLC0415 - lazy: scipy.signal is slow to import
    columns = np.asarray(columns, dtype=float)
    out = lags.d * columns
    if lags.tau.size == 0 or columns.shape[0] == 0:
        return out
    dt = np.diff(t)
    uniform = dt.size == 0 or float(np.ptp(dt)) <= UNIFORM_SPACING * float(dt.mean())
    if uniform:
        step = float(dt.mean()) if dt.size else 1.0
        for tau, g in zip(lags.tau.tolist(), lags.g.tolist()):
            x = step / tau
            one_minus_a = -np.expm1(-x)
            a, ramp = 1.0 - one_minus_a, one_minus_a / x
            b0, b1 = 1.0 - ramp, ramp - a
            z = np.empty_like(columns)
            z[0] = rest
            if columns.shape[0] > 1:
                zi = (b1 * columns[0] + a * rest)[None, :]
                z[1:], _ = lfilter([b0, b1], [1.0, -a], columns[1:], axis=0, zi=zi)
            out += g * z
        return out
    z = np.repeat(rest[None, :], lags.tau.size, axis=0)
    out[0] += lags.g @ z
    for k in range(1, t.size):
        x = (t[k] - t[k - 1]) / lags.tau[:, None]
        one_minus_a = -np.expm1(-x)
        ramp = one_minus_a / x
        z = z + (columns[k - 1] - z) * one_minus_a + (columns[k] - columns[k - 1]) * (1.0 - ramp)
        out[k] += lags.g @ z
    return out


def check_records(records: Any, *, minimum: int = 1) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Records ``(t, u, y)`` as float arrays; ``ValueError`` naming the record for every bad one.

    Bad: not a sequence of at least ``minimum`` triples, non-finite values, ``t``, ``u``, ``y`` of
    different lengths, fewer than 3 samples, times not strictly increasing, a constant input.
    """
    if isinstance(records, (str, bytes)) or not isinstance(records, Sequence) or len(records) < minimum:
        count = len(records) if isinstance(records, Sequence) else "no"
        raise ValueError(f"records must be a sequence of at least {minimum} (t, u, y) record(s), got {count} "
                         f"({type(records).__name__})")
    checked = []
    for i, rec in enumerate(records):
        try:
            t, u, y = rec
        except (TypeError, ValueError):
            raise ValueError(f"records[{i}] must be a (t, u, y) triple, got {type(rec).__name__}") from None
        t_a, u_a, y_a = (finite_array(f"records[{i}].{n}", v) for n, v in (("t", t), ("u", u), ("y", y)))
        if not t_a.size == u_a.size == y_a.size:
            raise ValueError(f"records[{i}]: t, u and y must have the same length, got {t_a.size}, {u_a.size} and "
                             f"{y_a.size} samples")
        if t_a.size < 3:
            raise ValueError(f"records[{i}] must hold at least 3 samples, got {t_a.size}")
        if np.any(np.diff(t_a) <= 0.0):
            k = int(np.argmax(np.diff(t_a) <= 0.0)) + 1
            raise ValueError(f"records[{i}].t must be strictly increasing, got t[{k}] = {float(t_a[k])!r} after "
                             f"{float(t_a[k - 1])!r}")
        if float(np.ptp(u_a)) == 0.0:
            raise ValueError(f"records[{i}].u must vary, got a constant input {float(u_a[0])!r}")
        checked.append((t_a, u_a, y_a))
    return checked


def record_rates(records: list[tuple[np.ndarray, np.ndarray, np.ndarray]]) -> np.ndarray:
    """Each record's rate [1/s]: its mean ``|du/dt|`` over twice its input range.

    For cycles over the whole range this is the cycle frequency (a sine or triangle of
    frequency ``f`` sweeps ``2·range`` per period); for cycles of smaller amplitude it is that
    frequency times the mean amplitude's share of the range.  Records made from one program at
    different speeds keep the ratio of their speeds.
    """
    rates = []
    for t, u, _ in records:
        rates.append(float(np.sum(np.abs(np.diff(u)))) / (2.0 * float(np.ptp(u)) * float(t[-1] - t[0])))
    return np.asarray(rates)
