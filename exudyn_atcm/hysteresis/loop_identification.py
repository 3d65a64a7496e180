"""Equal-gain relays (the paper's Eq. 12) from measured loops: the body of :meth:`DiscretePreisach.from_loop`.

The rule (branches averaged per direction by isotonic regression, unreached levels and
noise-level crossings handled and said) is documented on
:meth:`DiscretePreisach.from_loop <exudyn_atcm.hysteresis.DiscretePreisach.from_loop>`.
"""

from __future__ import annotations

import time
import warnings
from typing import Any

import numpy as np

from .._checks import finite_array, positive_int, same_length, shown
from ..physical_bounds import check_element_count
from .fit_cost import check_cost, finite_squares, loop_fit_cost
from .fit_report import make_report
from .base import quantity_from_unit
from .identification import nonnegative_float, record_fit
from ..errors import AccuracyWarning


def isotonic(values: np.ndarray) -> np.ndarray:
    """Least-squares non-decreasing fit of ``values`` (``scipy.optimize.isotonic_regression``)."""
    from scipy.optimize import isotonic_regression  # noqa: PLC0415 - lazy: scipy.optimize is slow to import
    return isotonic_regression(np.asarray(values, dtype=float)).x


def monotone_segments(u: np.ndarray, tolerance: float) -> list[tuple[int, int, bool]]:
    """Split ``u`` at its reversals into ``(first, last, rising)`` index ranges (inclusive).

    A reversal is recognised once the input has moved back by more than ``tolerance`` from
    its running extremum; the segment boundary is that extremum (it belongs to both segments).
    """
    segments = []
    first = 0
    extreme = 0
    rising: bool | None = None
    for k in range(1, u.size):
        v = u[k]
        if rising is None:
            if v > u[0] + tolerance or (tolerance == 0.0 and v > u[0]):
                rising = True
            elif v < u[0] - tolerance or (tolerance == 0.0 and v < u[0]):
                rising = False
            if rising is not None:
                extreme = int(np.argmax(u[: k + 1])) if rising else int(np.argmin(u[: k + 1]))
                first = int(np.argmin(u[: extreme + 1])) if rising else int(np.argmax(u[: extreme + 1]))
            continue
        if rising:
            if v >= u[extreme]:
                extreme = k
            elif v < u[extreme] - tolerance or (tolerance == 0.0 and v < u[extreme]):
                segments.append((first, extreme, True))
                first, rising = extreme, False
                extreme = k
        else:
            if v <= u[extreme]:
                extreme = k
            elif v > u[extreme] + tolerance or (tolerance == 0.0 and v > u[extreme]):
                segments.append((first, extreme, False))
                first, rising = extreme, True
                extreme = k
    if rising is not None:
        segments.append((first, extreme, rising))
    return segments


def _branch(u: np.ndarray, y: np.ndarray, segments: list, rising: bool) -> tuple[np.ndarray, np.ndarray]:
    idx = np.concatenate([np.arange(a, b + 1) for a, b, r in segments if r == rising])
    order = np.argsort(u[idx], kind="stable")
    u_b = u[idx][order]
    return u_b, isotonic(y[idx][order])


def _crossings(u: np.ndarray, y: np.ndarray, levels: np.ndarray, *, ascending: bool,
               tolerance: float = 0.0) -> tuple[np.ndarray, list]:
    """Input where a monotone branch first reaches each level walking in its direction; unreached levels listed.

    A level counts as reached within ``tolerance`` (the round-off of the branch averaging: a
    staircase's flat top, averaged over several segments, may fall short of its level by a few
    ulps).
    """
    if not ascending:  # walk the descending branch from u_max downwards
        u, y = u[::-1], y[::-1]
    result = np.empty(levels.size)
    unreached = []
    for j, level in enumerate(levels.tolist()):
        reached = y >= level - tolerance if ascending else y <= level + tolerance
        if not reached.any():
            result[j] = u[-1]
            unreached.append(j)
            continue
        k = int(np.argmax(reached))
        if k == 0 or y[k] == y[k - 1]:
            result[j] = u[k]
        else:
            s = (level - y[k - 1]) / (y[k] - y[k - 1])
            result[j] = u[k - 1] + s * (u[k] - u[k - 1])
    return result, unreached


#: Where ``from_loop`` puts the switching level of relay ``i = 1 … n`` (gain ``Δy``), in steps
#: above ``y_min``: the paper's top of each step, or its middle.
LEVEL_RULES = {"paper": 0.0, "centred": 0.5}


def identify_from_loop(cls: type, u: Any, y: Any, n: int, *, reversal_tolerance: float = 0.0,
                       coverage: float = 0.9, report: bool = False, output_unit: str = "",
                       levels: str = "paper", fit_mask: Any = None, output_quantity: str | None = None) -> Any:
    """Body of :meth:`DiscretePreisach.from_loop` (see there for the rule).

    With ``fit_mask`` (boolean, one entry per sample) only the monotone segments lying in the
    masked samples are branches, and the others are held out in the report.
    """
    started = time.perf_counter()
    quantity_from_unit(output_unit, output_quantity)
    if levels not in LEVEL_RULES:
        raise ValueError(f"levels must be one of {', '.join(repr(k) for k in LEVEL_RULES)}, got {shown(levels)}")
    u_a = finite_array("u", u, min_length=2)
    y_a = finite_array("y", y, min_length=2)
    same_length(("u", "y"), (u_a, y_a))
    n = check_element_count("n", positive_int("n", n), "relays")
    finite_squares("u", u_a)
    finite_squares("y", y_a)
    mask = np.ones(u_a.size, dtype=bool)
    if fit_mask is not None:
        mask = np.asarray(fit_mask)
        if mask.dtype != bool or mask.shape != u_a.shape or mask.sum() < 2:
            raise ValueError(f"fit_mask must be a boolean array with one entry per sample ({u_a.size}) selecting at "
                             f"least 2, got dtype {mask.dtype} and shape {mask.shape}")
    check_cost(f"{cls.__name__}.from_loop", loop_fit_cost(n, u_a.size),
               "use fewer relays (n; the error on the loop is below one gain step (y_max - y_min)/n)")
    reversal_tolerance = nonnegative_float("reversal_tolerance", reversal_tolerance)
    coverage = nonnegative_float("coverage", coverage)
    if coverage > 1.0:
        raise ValueError(f"coverage must lie in [0, 1], got {shown(coverage)}")
    span = float(np.ptp(u_a[mask]))
    segments = monotone_segments(u_a, reversal_tolerance * span)
    if fit_mask is not None:  # segments whose inner samples are all fitted (the ends are shared)
        segments = [s for s in segments if mask[s[0] + 1:s[1]].all() and (mask[s[0]] or mask[s[1]])]
    major = [s for s in segments if u_a[s[1]] != u_a[s[0]] and abs(u_a[s[1]] - u_a[s[0]]) >= coverage * span]
    for rising, missing in ((True, "ascending (rising u)"), (False, "descending (falling u)")):
        if not any(s[2] == rising for s in major):
            seen = sum(1 for s in segments if s[2] == rising)
            raise ValueError(
                f"u, y must describe a loop with both branches; the {missing} branch is missing"
                + (f" ({seen} such segment(s) span less than coverage = {coverage:g} of the input range)" if seen else "")
            )
    u_up, y_up = _branch(u_a, y_a, major, True)
    u_dn, y_dn = _branch(u_a, y_a, major, False)
    y_min = float(min(y_up.min(), y_dn.min()))
    y_max = float(max(y_up.max(), y_dn.max()))
    if y_max <= y_min:
        raise ValueError(f"y must vary over the loop, got a constant {y_min!r}")
    gain = (y_max - y_min) / n
    level_rule = levels
    levels = y_min + gain * (np.arange(1, n + 1) - LEVEL_RULES[level_rule])
    if level_rule == "paper":
        levels[-1] = y_max
    # levels reached within round-off of the averaging count as reached (1e-9 of a gain)
    alpha, up_missing = _crossings(u_up, y_up, levels, ascending=True, tolerance=1e-9 * gain)
    beta, down_missing = _crossings(u_dn, y_dn, levels, ascending=False, tolerance=1e-9 * gain)
    notes = []
    n_up = sum(1 for s in major if s[2])
    n_down = len(major) - n_up
    if n_up > 1 or n_down > 1:
        notes.append(f"branches averaged over {n_up} ascending and {n_down} descending segments (isotonic fit)")
    # Both branches of a major loop meet at its turning points, so an ascending branch that
    # falls short of the top level by less than half a gain does so by noise: the top relay
    # switches at the turning point, as the crossing rule gives; noted, not warned.
    for missing, branch_y, kind, where in ((up_missing, y_up, "ascending", "its highest input"),
                                           (down_missing, y_dn, "descending", "its lowest input")):
        if missing == [n - 1] and kind == "ascending" and y_max - float(branch_y.max()) < 0.5 * gain:
            notes.append(f"the ascending branch peaks at y = {float(branch_y.max()):.6g}, {y_max - float(branch_y.max()):.3g} "
                         f"below the loop's top y = {y_max:.6g} (less than half a relay gain, {gain:.3g}: noise at the "
                         "turning point); the top relay switches at the branch's highest input")
            continue
        if missing:
            text = (f"the {kind} branch never reaches the level(s) y = "
                    f"{', '.join(f'{levels[j]:.6g}' for j in missing)}; those relays switch at {where}")
            notes.append(text)
            warnings.warn(f"from_loop: {text}", AccuracyWarning, stacklevel=3)
    cross = alpha < beta
    if cross.any():
        allowed = reversal_tolerance * span
        depth = beta - alpha
        i = int(np.argmax(depth))
        if depth[i] > allowed:
            raise ValueError(
                f"u, y: the ascending branch lies above the descending one at level {float(levels[i])!r} "
                f"(ascending crossing u = {float(alpha[i])!r} < descending crossing u = {float(beta[i])!r}); "
                "not a hysteresis loop"
                + (f" (more than reversal_tolerance x input range = {allowed:.4g} apart)" if allowed > 0 else "")
            )
        mid = 0.5 * (alpha + beta)
        alpha = np.where(cross, mid, alpha)
        beta = np.where(cross, mid, beta)
        text = (f"{int(cross.sum())} level(s) where the averaged branches cross by at most {float(depth[i]):.4g} "
                "input units (noise): switch-on and -off put at their mean")
        notes.append(text)
        warnings.warn(f"from_loop: {text}", AccuracyWarning, stacklevel=3)
    model = cls(alpha, beta, np.full(n, gain), offset=y_min)
    fit_report = make_report(model, u_a, y_a, u_a.size, 0, f"{cls.__name__}.from_loop",
                             settings={"n": n, "reversal_tolerance": reversal_tolerance, "coverage": coverage,
                                       "levels": level_rule},
                             notes=notes, output_unit=output_unit, fit_time=time.perf_counter() - started,
                             fit_mask=fit_mask if fit_mask is None else mask)
    record_fit(model, fit_report, mask, 0, u_a[mask], output_unit, output_quantity)
    return (model, fit_report) if report else model
