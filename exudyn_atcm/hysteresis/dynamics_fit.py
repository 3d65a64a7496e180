"""Identification of creep from a step record and of a rate lag from records at several rates.

* :func:`creep_from_step`: after a step of the operator output by ``Δ`` from rest, a creep law
  gives ``y(t) − y_before = Δ (1 + Σ c_k (1 − e^{−t/τ_k}))``.  For given time constants this is
  linear in ``Δ`` and ``b_k = Δ c_k`` (non-negative least squares); with ``fit_tau`` the time
  constants are found by variable projection (a least-squares search over ``log τ`` with the
  linear part solved inside).
* :func:`fit_rate_lag`: records ``(t, u, y)`` at several rates of a Prandtl-Ishlinskii operator
  followed by an (optional, given) creep law and a first-order lag ``1/(1 + T s)``.  For a given
  ``T`` the output is linear in the play weights, so each ``T`` of a bounded scalar search over
  ``log T`` solves one non-negative least-squares problem on all records together.  The records
  at several rates separate the two: the operator's loop is the same at every rate, the lag's
  phase grows with the rate.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from .._checks import finite_array, finite_float, positive_int, shown
from .creep import Creep
from .dynamics import LagSum, RateLag, WithDynamics
from .prandtl_ishlinskii import PrandtlIshlinskii

__all__ = ["creep_from_step", "fit_rate_lag", "play_outputs"]


def _step_basis(t: np.ndarray, tau: np.ndarray) -> np.ndarray:
    return np.column_stack([np.ones_like(t), -np.expm1(-t[:, None] / tau)])


def _step_solve(t: np.ndarray, y: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(Δ and b_k with sign(Δ) b_k >= 0, residual) for given time constants."""
    from scipy.optimize import nnls  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    basis = _step_basis(t, tau)
    sign = 1.0 if float(np.mean(y)) >= 0.0 else -1.0
    x, _ = nnls(basis, sign * y)
    return sign * x, y - basis @ (sign * x)


def creep_from_step(t: Any, y: Any, *, y_before: float = 0.0, n_lags: int = 2, tau: Any = None,
                    fit_tau: bool = True) -> tuple[Creep, float, dict]:
    """Creep law and step height from the record after one step, the lags at rest before it.

    Parameters
    ----------
    t : array_like
        Times since the step [s], ``>= 0``, strictly increasing (at least ``2 n_lags + 3`` samples).
    y : array_like
        Output after the step [output units].
    y_before : float, optional
        Output at rest before the step (subtracted from ``y``).
    n_lags : int, optional
        Number of time constants (used when ``tau`` is not given), ``>= 1``.
    tau : array_like, optional
        Time constants [s]: the start of the search with ``fit_tau``, else fixed.  Default:
        ``n_lags`` spread evenly in ``log τ`` from twice the first sample spacing to a third of
        the record.
    fit_tau : bool, optional
        Fit the time constants too (default) or keep them.

    Returns
    -------
    (Creep, float, dict)
        The creep law (time constants ascending), the step height ``Δ`` of the operator output
        (the jump at the step, before any creep) and ``{"rms": ..., "tau_start": ...}``.

    Raises
    ------
    ValueError
        For records of different lengths, non-finite values, negative or non-increasing
        times, too few samples, ``n_lags < 1`` or a step height of zero; and for a record
        that relaxes after its step (jumps, then settles below the jump): a creep law only
        adds to the step, so its fit would report a wrong step height.  The message gives the
        fit with coefficients of either sign (step, time constants, coefficients) and the
        reason.  A record counts as relaxing when that fit leaves less than
        :data:`RELAXATION_RATIO` of the creep fit's RMS residual, the creep fit misses by more
        than 1 % of the step, and the signed coefficients sum below zero.

    Notes
    -----
    Time constants much shorter than the first sample or longer than the record are not
    identifiable from it (their lag is a jump or a straight line); the search keeps each
    ``τ`` between a tenth of the first sample spacing and ten times the record length.
    """
    from scipy.optimize import least_squares  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    t_a = finite_array("t", t)
    y_a = finite_array("y", y) - finite_float("y_before", y_before)
    if y_a.size != t_a.size:
        raise ValueError(f"t and y must have the same length, got {t_a.size} and {y_a.size}")
    if t_a[0] < 0.0 or (t_a.size > 1 and np.any(np.diff(t_a) <= 0.0)):
        raise ValueError(f"t must be times since the step, >= 0 s and strictly increasing, got t[0] = {float(t_a[0])!r}")
    if tau is None:
        n = positive_int("n_lags", n_lags)
        if t_a.size < 2 * n + 3:
            raise ValueError(f"y: {t_a.size} samples are too few for {n} time constants (at least {2 * n + 3})")
        span = float(t_a[-1])
        tau_a = np.geomspace(2.0 * float(t_a[1] - t_a[0]), span / 3.0, n)
    else:
        tau_a = np.sort(finite_array("tau", tau))
        if (tau_a <= 0).any():
            raise ValueError(f"tau must be > 0 s, got {tau_a.tolist()!r}")
    start = tau_a.copy()
    if fit_tau:
        low = 0.1 * float(t_a[1] - t_a[0])
        high = 10.0 * float(t_a[-1])
        x0 = np.clip(np.log(tau_a), np.log(low) + 1e-9, np.log(high) - 1e-9)
        sol = least_squares(lambda lt: _step_solve(t_a, y_a, np.exp(lt))[1], x0,
                            bounds=(np.log(low), np.log(high)), x_scale=1.0)
        tau_a = np.sort(np.exp(sol.x))
    x, res = _step_solve(t_a, y_a, tau_a)
    step = float(x[0])
    if step == 0.0:
        raise ValueError("y: the record shows no step (the fitted step height is 0)")
    rms = float(np.sqrt(np.mean(res ** 2)))
    _refuse_relaxation(t_a, y_a, start, fit_tau, rms)
    info = {"rms": rms, "tau_start": start}
    return Creep(tau_a, x[1:] / step), step, info


#: A record relaxes when a fit with coefficients of either sign leaves less than this share of the
#: creep fit's RMS residual (and the creep fit misses by more than 1 % of the step).
RELAXATION_RATIO = 0.3


def _refuse_relaxation(t: np.ndarray, y: np.ndarray, tau_start: np.ndarray, fit_tau: bool, rms: float) -> None:
    """``ValueError`` with the reason and the signed fit when ``y`` relaxes after the step (see
    :func:`creep_from_step`): a creep law only adds to the step (``c_k >= 0``)."""
    from scipy.optimize import least_squares  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    def signed(tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        basis = _step_basis(t, tau)
        x, *_ = np.linalg.lstsq(basis, y, rcond=None)
        return x, y - basis @ x

    tau = tau_start
    if fit_tau:
        low, high = 0.1 * float(t[1] - t[0]), 10.0 * float(t[-1])
        x0 = np.clip(np.log(tau), np.log(low) + 1e-9, np.log(high) - 1e-9)
        tau = np.sort(np.exp(least_squares(lambda lt: signed(np.exp(lt))[1], x0,
                                           bounds=(np.log(low), np.log(high))).x))
    x, res = signed(tau)
    signed_rms = float(np.sqrt(np.mean(res ** 2)))
    step = float(x[0])
    if step == 0.0 or not (signed_rms < RELAXATION_RATIO * rms and rms > 0.01 * abs(step)):
        return
    c = x[1:] / step
    if not float(np.sum(c)) < 0.0:
        return
    raise ValueError(
        f"y relaxes after the step: it jumps by {step:.4g} and settles at {step * (1.0 + float(np.sum(c))):.4g} "
        f"(a least-squares fit with coefficients of either sign: tau = {np.round(tau, 6).tolist()} s, "
        f"c = {np.round(c, 4).tolist()}, RMS {signed_rms:.3g}); a creep law (c_k >= 0) only adds to the step, so "
        f"its best fit (RMS {rms:.3g}) would give a wrong step height. Creep cannot represent relaxation: check "
        "the record (drift, a force or a thermal effect after the step), or fit the creep from a record that "
        "creeps in the direction of the step"
    )


def play_outputs(u: Any, radii: Any) -> np.ndarray:
    """Play operator outputs (one column per radius [input units]) along ``u``, from rest at 0."""
    u_a = finite_array("u", u)
    r = finite_array("radii", radii, min_length=0)
    out = np.empty((u_a.size, r.size))
    z = np.zeros(r.size)
    for k, v in enumerate(u_a.tolist()):
        z = np.maximum(v - r, np.minimum(v + r, z))
        out[k] = z
    return out


def _lagged(columns: np.ndarray, t: np.ndarray, lags: LagSum, rest: np.ndarray) -> np.ndarray:
    """:meth:`LagSum.response` of every column at once (the lags at rest at ``rest``)."""
    z = np.repeat(rest[None, :], lags.tau.size, axis=0)
    out = np.empty_like(columns)
    out[0] = lags.d * columns[0] + lags.g @ z
    for k in range(1, t.size):
        x = (t[k] - t[k - 1]) / lags.tau[:, None]
        one_minus_a = -np.expm1(-x)
        ramp = one_minus_a / x
        z = z + (columns[k - 1] - z) * one_minus_a + (columns[k] - columns[k - 1]) * (1.0 - ramp)
        out[k] = lags.d * columns[k] + lags.g @ z
    return out


def _check_records(records: Any) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    if not isinstance(records, Sequence) or len(records) < 1:
        raise ValueError(f"records must be a non-empty sequence of (t, u, y) records, got {shown(records)}")
    checked = []
    for i, rec in enumerate(records):
        try:
            t, u, y = rec
        except (TypeError, ValueError):
            raise ValueError(f"records[{i}] must be a (t, u, y) triple, got {type(rec).__name__}") from None
        t_a, u_a, y_a = (finite_array(f"records[{i}].{n}", v) for n, v in (("t", t), ("u", u), ("y", y)))
        if not t_a.size == u_a.size == y_a.size:
            raise ValueError(f"records[{i}]: t, u and y must have the same length, got {t_a.size}, {u_a.size}, {y_a.size}")
        if t_a.size < 3 or np.any(np.diff(t_a) <= 0.0):
            raise ValueError(f"records[{i}].t must be strictly increasing with at least 3 samples")
        checked.append((t_a, u_a, y_a))
    return checked


def fit_rate_lag(records: Any, n_plays: int, *, creep: Creep | None = None,
                 T_bounds: tuple[float, float] | None = None) -> tuple[WithDynamics, dict]:
    """Prandtl-Ishlinskii operator and rate lag ``T`` (after a given creep law) from records at several rates.

    Parameters
    ----------
    records : sequence of (t, u, y)
        Records [s, input units, output units], each from the operator's reset state (plays at
        rest, the input starting at 0) with the lags at rest: e.g. sine or triangle cycles at a
        few frequencies, the slowest nearly rate-independent, the fastest with a phase lag.
    n_plays : int
        Plays including the radius-0 one, ``>= 2``; radii ``r_j = j Δu/(2 n_plays)``,
        ``Δu`` the input range over all records (as :meth:`PrandtlIshlinskii.fit`).
    creep : Creep, optional
        A creep law known beforehand (e.g. :func:`creep_from_step`), kept fixed.
    T_bounds : (float, float), optional
        Search range of ``T`` [s]; default from a tenth of the shortest sample spacing to the
        longest record.  ``T`` must differ from the creep's time constants.

    Returns
    -------
    (WithDynamics, dict)
        The model ``WithDynamics(PrandtlIshlinskii, creep, RateLag(T))`` and
        ``{"T": ..., "rms": [per record], "rms_rate_independent": [per record, T → lower bound]}``.

    Raises
    ------
    ValueError
        For malformed records, ``n_plays < 2``, bounds that are not ``0 < low < high`` or a
        constant input.

    Notes
    -----
    The weights are non-negative and ``p0 >= 10⁻³ Δy/Δu``, so the operator has its analytic
    inverse and the whole model is invertible (:meth:`WithDynamics.inverse`).  The search
    over ``log T`` is a bounded scalar minimisation (Brent): it finds the minimum of a cost that
    has one minimum over the range, which is the case for records whose rates span the lag.
    """
    from scipy.optimize import minimize_scalar, nnls  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    recs = _check_records(records)
    n = positive_int("n_plays", n_plays)
    if n < 2:
        raise ValueError(f"n_plays must be >= 2, got {shown(n_plays)}")
    if creep is not None and not isinstance(creep, Creep):
        raise ValueError(f"creep must be a Creep or None, got {type(creep).__name__}")
    u_all = np.concatenate([u for _, u, _ in recs])
    y_all = np.concatenate([y for _, _, y in recs])
    du, dy = float(np.ptp(u_all)), float(np.ptp(y_all))
    if du == 0.0 or dy == 0.0:
        raise ValueError("records: the input and the output must vary")
    radii = np.arange(1, n) * du / (2.0 * n)
    if T_bounds is None:
        low = 0.1 * min(float(np.min(np.diff(t))) for t, _, _ in recs)
        high = max(float(t[-1] - t[0]) for t, _, _ in recs)
    else:
        try:
            low, high = (finite_float("T_bounds[0]", T_bounds[0]), finite_float("T_bounds[1]", T_bounds[1]))
        except (TypeError, IndexError):
            raise ValueError(f"T_bounds must be a pair (low, high) [s], got {T_bounds!r}") from None
        if not 0.0 < low < high:
            raise ValueError(f"T_bounds must satisfy 0 < low < high, got {T_bounds!r}")
    p0_min = 1e-3 * dy / du
    # columns: u (p0), plays, +1, -1 (offset); rest values of the lags: 0, 0, 1, -1
    raw = [np.column_stack([u, play_outputs(u, radii), np.ones_like(u), -np.ones_like(u)]) for _, u, _ in recs]
    rest = np.concatenate([[0.0], np.zeros(radii.size), [1.0, -1.0]])

    def solve(T: float) -> tuple[np.ndarray, list[np.ndarray]]:
        lags = LagSum.series(creep, RateLag(T))
        design = [_lagged(cols, t, lags, rest) for cols, (t, _, _) in zip(raw, recs)]
        a = np.vstack(design)
        x, _ = nnls(a, y_all - p0_min * a[:, 0])
        x[0] += p0_min
        return x, [d @ x - y for d, (_, _, y) in zip(design, recs)]

    def cost(log_t: float) -> float:
        return float(sum(np.sum(r ** 2) for r in solve(float(np.exp(log_t)))[1]))

    best = minimize_scalar(cost, bounds=(np.log(low), np.log(high)), method="bounded",
                           options={"xatol": 1e-6})
    T = float(np.exp(best.x))
    x, residuals = solve(T)
    _, plain = solve(low)
    operator = PrandtlIshlinskii(radii, x[1:-2], float(x[0]), offset=float(x[-2] - x[-1]))
    info = {"T": T, "rms": [float(np.sqrt(np.mean(r ** 2))) for r in residuals],
            "rms_rate_independent": [float(np.sqrt(np.mean(r ** 2))) for r in plain]}
    operator.set_fit_metadata((float(u_all.min()), float(u_all.max())),
                              {"method": "fit_rate_lag", "settings": {"n_plays": n, "radii": radii, **info},
                               "samples": {"records": len(recs), "fitted": int(u_all.size)}})
    model = WithDynamics(operator, creep, RateLag(T))
    return model, info
