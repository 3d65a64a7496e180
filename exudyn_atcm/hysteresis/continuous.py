"""The paper's continuous Preisach model (Eqs. 8-10), extended to arbitrary input histories."""

from __future__ import annotations

import math
from typing import Any

from .._checks import finite_float, shown
from .families import FamilyFit, FitRequest, register_family
from .staircase import StaircasePreisach
from .identification import fit_continuous


class ContinuousPreisach(StaircasePreisach):
    r"""Continuous Preisach operator whose major loop is the paper's pair of power-law branches.

    On a complete cycle between ``u_min`` and ``u_max`` the output follows

    * ascending (Eq. 8): :math:`y_1(u) = y_{min} + \Delta y\,((u-u_{min})/\Delta u)^{r_1}`,
    * descending (Eq. 9): :math:`y_2(u) = y_{max} - \Delta y\,((u_{max}-u)/\Delta u)^{r_2}`.

    For every other history it is the Preisach operator made of a continuum of equal-weight
    relays, one per output level ``y`` in ``[y_min, y_max]``, with switch-on threshold
    :math:`\alpha(y) = y_1^{-1}(y)` and switch-off threshold :math:`\beta(y) = y_2^{-1}(y)`:
    the paper's equal-gain construction (Eq. 12) applied to the two analytic branches with
    infinitely many relays.  Its measure of relays switched on by ``a`` and off by ``b`` is
    ``K(a, b) = max(0, Y1(a) - Y2(b))`` (``Y1``, ``Y2`` the branches held constant outside
    ``[u_min, u_max]``), so reversals inside the range give minor loops with wiping-out and
    congruency, and inputs beyond the bounds saturate.  This needs ``y1 <= y2`` everywhere,
    which holds exactly when ``r1 >= 1`` and ``r2 >= 1``.

    Parameters
    ----------
    u_min, u_max : float
        Input range of the major loop (V in the paper's use), ``u_max > u_min``.
    y_min, y_max : float
        Output at ``u_min`` and ``u_max`` (stroke in m, or strain), ``y_max > y_min``.
    r1, r2 : float
        Exponents of the ascending and descending branch, each ``>= 1``.

    Notes
    -----
    Initial state (after :meth:`reset`): negative saturation, output ``y_min``.
    """

    def __init__(
        self, u_min: float, u_max: float, y_min: float, y_max: float, r1: float, r2: float
    ) -> None:
        u_min, u_max, y_min, y_max = _ranges(u_min, u_max, y_min, y_max)
        r1 = finite_float("r1", r1)
        r2 = finite_float("r2", r2)
        for name, r in (("r1", r1), ("r2", r2)):
            if r < 1.0:
                raise ValueError(
                    f"{name} must be >= 1, got {shown(r)}: with {name} < 1 the ascending branch "
                    "lies above the descending one near the "
                    f"{'lower' if name == 'r1' else 'upper'} end of the range, which is not a "
                    "hysteresis loop"
                )
        self.u_min, self.u_max, self.y_min, self.y_max = u_min, u_max, y_min, y_max
        self.r1, self.r2 = r1, r2
        self._du = u_max - u_min
        self._dy = y_max - y_min
        self._y_reset = y_min
        super().__init__()

    @classmethod
    def from_points(
        cls,
        u_min: float,
        u_max: float,
        y_min: float,
        y_max: float,
        u_m: float,
        y_m1: float,
        y_m2: float,
    ) -> "ContinuousPreisach":
        r"""Model whose branches pass through ``(u_m, y_m1)`` (ascending) and ``(u_m, y_m2)``.

        Uses the corrected Eq. 10:
        :math:`r_1 = \ln((y_{m1}-y_{min})/\Delta y) / \ln((u_m-u_{min})/\Delta u)` and
        :math:`r_2 = \ln((y_{max}-y_{m2})/\Delta y) / \ln((u_{max}-u_m)/\Delta u)`.

        Raises
        ------
        ValueError
            If ``u_m`` is not strictly inside ``(u_min, u_max)``, ``y_m1``/``y_m2`` not strictly
            inside ``(y_min, y_max)``, or the resulting exponents are below 1 (a precision point
            that puts the ascending branch above the descending one).
        """
        u_min, u_max, y_min, y_max = _ranges(u_min, u_max, y_min, y_max)
        u_m = finite_float("u_m", u_m)
        y_m1 = finite_float("y_m1", y_m1)
        y_m2 = finite_float("y_m2", y_m2)
        if not u_min < u_m < u_max:
            raise ValueError(f"u_m must lie strictly between u_min = {u_min!r} and u_max = {u_max!r}, got {shown(u_m)}")
        for name, y in (("y_m1", y_m1), ("y_m2", y_m2)):
            if not y_min < y < y_max:
                raise ValueError(
                    f"{name} must lie strictly between y_min = {y_min!r} and y_max = {y_max!r}, got {shown(y)}"
                )
        du, dy = u_max - u_min, y_max - y_min
        r1 = math.log((y_m1 - y_min) / dy) / math.log((u_m - u_min) / du)
        r2 = math.log((y_max - y_m2) / dy) / math.log((u_max - u_m) / du)
        line = y_min + dy * (u_m - u_min) / du  # the straight line between the end points, at u_m
        for name, y, r, side in (("y_m1", y_m1, r1, "above"), ("y_m2", y_m2, r2, "below")):
            if r < 1.0:
                scale = max(abs(y_min), abs(y_max)) / max(abs(y_m1), abs(y_m2), 1e-300)
                hint = (f"; the end points are {scale:.2g} times the precision points: is y_min = {y_min:g} or y_max = "
                        f"{y_max:g} in another unit?" if scale > 1e3 else "")
                raise ValueError(f"{name} = {y:g} lies {side} the straight line from (u_min, y_min) to (u_max, y_max) at "
                                 f"u_m ({line:g}): its branch's exponent would be {r:.3g}, below 1 (a branch bent the "
                                 f"other way); check the precision points{hint}")
        return cls(u_min, u_max, y_min, y_max, r1, r2)

    @property
    def saturation_range(self) -> tuple[float, float]:
        """``(u_min, u_max)``: beyond it the output saturates at ``y_min``/``y_max``."""
        return (self.u_min, self.u_max)

    @classmethod
    def fit(cls, u: Any, y: Any, *, n_fit: int | None = None, output_unit: str = "", fit_mask: Any = None,
            output_quantity: str | None = None) -> tuple["ContinuousPreisach", Any]:
        """Least-squares fit of the power-law model to a whole record (not three points).

        ``u_min``, ``u_max`` are the input's extremes over the fitted samples; ``y_min``,
        ``y_max``, ``r1`` and ``r2`` (each ``>= 1``) minimise the squared error of the
        operator's output over the record (SciPy's bounded ``least_squares``; every residual
        evaluation runs the operator over the record, so minor loops count too).

        Parameters
        ----------
        u, y : array_like
            Input and output samples in time order (at least 10).
        n_fit : int, optional
            Fit the first ``n_fit`` samples and predict the rest.  Default: all.
        output_unit : str, optional
            Unit of ``y`` (kept as the model's ``output_unit``).
        fit_mask : array_like of bool, optional
            Fit the samples where it is true, predict the others (instead of ``n_fit``).
        output_quantity : str, optional
            What ``y`` is; default from the unit (a length: ``"displacement"``).

        Returns
        -------
        (ContinuousPreisach, FitReport)
            The model's ``fitted_range`` is ``(u_min, u_max)``.

        Raises
        ------
        ValueError
            For fewer than 10 samples, non-finite values, different lengths, or a constant
            input or output.

        Notes
        -----
        The samples before the input first reaches its minimum are left out.
        """
        return fit_continuous(cls, u, y, n_fit=n_fit, output_unit=output_unit, fit_mask=fit_mask,
                              output_quantity=output_quantity)

    def ascending(self, u: float) -> float:
        """Ascending major-loop branch (Eq. 8), held constant outside ``[u_min, u_max]``."""
        if u <= self.u_min:
            return self.y_min
        if u >= self.u_max:
            return self.y_max
        return self.y_min + self._dy * ((u - self.u_min) / self._du) ** self.r1

    def descending(self, u: float) -> float:
        """Descending major-loop branch (Eq. 9), held constant outside ``[u_min, u_max]``."""
        if u <= self.u_min:
            return self.y_min
        if u >= self.u_max:
            return self.y_max
        return self.y_max - self._dy * ((self.u_max - u) / self._du) ** self.r2

    def loop_area(self) -> float:
        """Area enclosed by the major loop, ``Δy·Δu·[1 − 1/(r1+1) − 1/(r2+1)]`` (output × input units)."""
        return self._dy * self._du * (1.0 - 1.0 / (self.r1 + 1.0) - 1.0 / (self.r2 + 1.0))

    def _k_rising(self, a: float, b: float) -> float:
        k = self.ascending(a) - self.descending(b)
        return k if k > 0.0 else 0.0

    _k_falling = _k_rising

    def __repr__(self) -> str:
        return (
            f"ContinuousPreisach(u_min={self.u_min!r}, u_max={self.u_max!r}, y_min={self.y_min!r}, "
            f"y_max={self.y_max!r}, r1={self.r1!r}, r2={self.r2!r})"
        )


def _ranges(u_min: float, u_max: float, y_min: float, y_max: float) -> tuple[float, float, float, float]:
    """Check the loop's input and output ranges; return them as floats."""
    u_min = finite_float("u_min", u_min)
    u_max = finite_float("u_max", u_max)
    y_min = finite_float("y_min", y_min)
    y_max = finite_float("y_max", y_max)
    if u_max <= u_min:
        raise ValueError(f"u_max must be > u_min = {u_min!r}, got {shown(u_max)}")
    if y_max <= y_min:
        raise ValueError(f"y_max must be > y_min = {y_min!r}, got {shown(y_max)}")
    return u_min, u_max, y_min, y_max


def _fit_continuous(request: FitRequest) -> FamilyFit:
    """The ``continuous`` family: :meth:`ContinuousPreisach.fit` (the paper's power law)."""
    model, report = ContinuousPreisach.fit(request.u, request.y, **request.rows, **request.units)
    return FamilyFit("continuous (power law)", model, report, 6)


register_family("continuous", _fit_continuous, inverse="bisection", operator=ContinuousPreisach,
                description="the paper's power-law loop (Eqs. 8-10)")
