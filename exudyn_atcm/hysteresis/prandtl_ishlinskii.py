"""Prandtl-Ishlinskii operator: a weighted sum of play operators, with its analytic inverse."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np

from .._checks import finite_array, finite_float, same_length
from ..physical_bounds import check_element_count
from .base import HysteresisOperator, check_input
from .bisection import BisectionInverse
from .families import FamilyFit, FitRequest, register_family
from .pi_fit import fit_prandtl_ishlinskii


class PrandtlIshlinskii(HysteresisOperator):
    r"""Prandtl-Ishlinskii operator ``y = offset + p0·v + Σ_j p_j·z_j`` of ``v = u − input_offset``.

    Each play operator of radius ``r_j`` follows
    :math:`z_j(t) = \max(v - r_j, \min(v + r_j, z_j(t^-)))`.

    Parameters
    ----------
    radii : array_like
        Play radii ``r_j >= 0``, strictly increasing (input units).
    weights : array_like
        Play weights ``p_j`` (output units per input unit), same length as ``radii``.
    p0 : float
        Weight of the input itself (the play of radius 0).
    offset : float, optional
        Output added to the sum (default 0; set by :meth:`fit` for measured outputs).
    input_offset : float, optional
        Input at which the plays are at rest, subtracted from every input (default 0; the
        :meth:`inverse` of an operator with an ``offset`` has it).

    Notes
    -----
    Initial state (after :meth:`reset`): every play at ``z_j = 0``, the usual initial
    condition of the PI literature (the plays are at rest for a history that starts at
    ``u = input_offset``); not a negative saturation, which a PI operator does not have.
    """

    def __init__(self, radii: Any, weights: Any, p0: float, offset: float = 0.0, input_offset: float = 0.0) -> None:
        r = finite_array("radii", radii, min_length=0)
        p = finite_array("weights", weights, min_length=0)
        same_length(("radii", "weights"), (r, p))
        check_element_count("len(radii)", r.size, "plays")
        if r.size and r[0] < 0.0:
            raise ValueError(f"radii must be >= 0, got {float(r[0])!r}")
        steps = np.diff(r)
        if (steps <= 0).any():
            i = int(np.argmax(steps <= 0)) + 1
            raise ValueError(f"radii must be strictly increasing, got radii[{i}] = {float(r[i])!r} after {float(r[i - 1])!r}")
        self.radii = r.copy()
        self.weights = p.copy()
        self.p0 = finite_float("p0", p0)
        self.offset = finite_float("offset", offset)
        self.input_offset = finite_float("input_offset", input_offset)
        self.reset()

    def reset(self) -> None:
        """All plays at zero."""
        self._z = np.zeros(self.radii.size)
        self._y = self.offset

    def checkpoint(self) -> tuple:
        """Snapshot of the play states and the last output."""
        return (self._z.copy(), self._y)

    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint`."""
        z, y = snapshot
        z = np.asarray(z, dtype=float)
        if z.shape != self._z.shape:
            raise ValueError(f"snapshot holds {z.size} play states, this operator has {self._z.size}")
        self._z, self._y = z.copy(), float(y)

    @property
    def output(self) -> float:
        """Output for the last committed input."""
        return self._y

    def _plays(self, u: float) -> np.ndarray:
        return np.maximum(u - self.radii, np.minimum(u + self.radii, self._z))

    def evaluate(self, u: float) -> float:
        """Output for input ``u`` from the committed play states; nothing is changed."""
        v = check_input(u) - self.input_offset
        return self.offset + self.p0 * v + float(self.weights @ self._plays(v))

    def commit(self, u: float) -> float:
        """Accept input ``u``: update the play states and return the output."""
        v = check_input(u) - self.input_offset
        self._z = self._plays(v)
        self._y = self.offset + self.p0 * v + float(self.weights @ self._z)
        return self._y

    def input_for_output(self, y: float, u_lo: float, u_hi: float) -> float:
        """The input in ``[u_lo, u_hi]`` whose output from the committed plays is ``y`` (exact).

        From a fixed memory the output is piecewise linear in the input (each play follows the
        input beyond ``z_j ± r_j``), so the root is found between two breakpoints and
        interpolated: exact to rounding.  :class:`~exudyn_atcm.hysteresis.bisection.BisectionInverse`
        uses it instead of bisection; it expects ``output(u_lo) < y <= output(u_hi)``.
        """
        lo, hi = u_lo - self.input_offset, u_hi - self.input_offset
        knots = np.concatenate(([lo, hi], self._z - self.radii, self._z + self.radii))
        v = np.unique(knots[(knots >= lo) & (knots <= hi)])
        plays = np.maximum(v[:, None] - self.radii, np.minimum(v[:, None] + self.radii, self._z))
        out = self.offset + self.p0 * v + plays @ self.weights
        k = min(max(int(np.searchsorted(out, y)), 1), v.size - 1)
        y0, y1 = float(out[k - 1]), float(out[k])
        s = 0.0 if y1 == y0 else (y - y0) / (y1 - y0)
        return float(v[k - 1] + s * (v[k] - v[k - 1])) + self.input_offset

    def inverse(self, input_range: tuple[float, float] | None = None) -> HysteresisOperator:
        r"""The inverse: the analytic one (a :class:`ShiftedPIInverse`), or one bounded to an input range.

        A model that was not fitted, without ``input_range``: the analytic inverse, again a
        Prandtl-Ishlinskii operator (every output is reachable: a PI operator with ``p0 > 0`` is
        unbounded).  With ``input_range`` (e.g. a drive's voltage limits [V]), and for a fitted
        model without it (then its :attr:`fitted_range`, as the Preisach fits' inverses use
        theirs: :func:`~exudyn_atcm.hysteresis.bisection.default_input_range`), a
        :class:`~exudyn_atcm.hysteresis.bisection.BisectionInverse` on that range, which clips
        unreachable outputs with an :class:`~exudyn_atcm.errors.OutOfReachWarning` (the input is
        solved exactly inside the range, :meth:`input_for_output`).

        With ``P_j = p0 + Σ_{i<=j} p_i`` (plays of radius 0 are merged into ``p0``):
        :math:`\hat p_0 = 1/p_0`,
        :math:`\hat p_j = -p_j / (P_j P_{j-1})`,
        :math:`\hat r_j = p_0 r_j + \sum_{i \le j} p_i (r_j - r_i)`.
        The offsets swap: the inverse of ``y = c + P[u − d]`` is ``u = d + P⁻¹[y − c]``, so the
        inverse has ``input_offset = c`` and ``offset = d`` (a fitted model, whose ``offset`` is
        the output at rest, inverts with its offset included).  Starting both from the reset
        state, ``inverse().apply(apply(u)) == u``.

        Raises
        ------
        ValueError
            If some ``P_j <= 0`` (the operator is not strictly increasing, so not invertible).
        """
        if input_range is not None or self.fitted_range is not None:
            self.inverse_parameters()  # refuses an operator that is not strictly increasing
            return BisectionInverse(self, input_range)
        return ShiftedPIInverse(self)

    def inverse_parameters(self) -> dict[str, Any]:
        """Constructor parameters of the analytic inverse (see :meth:`inverse`): radii, weights, p0, offsets.

        Raises
        ------
        ValueError
            If some ``P_j <= 0`` (the operator is not strictly increasing, so not invertible).
        """
        radii, weights = self.radii, self.weights
        p0 = self.p0 + float(weights[radii == 0.0].sum())
        keep = radii > 0.0
        radii, weights = radii[keep], weights[keep]
        cumulative = p0 + np.cumsum(weights)
        previous = np.concatenate(([p0], cumulative[:-1]))
        if p0 <= 0.0 or (cumulative <= 0.0).any():
            raise ValueError(
                f"p0 and every p0 + sum(weights[:j+1]) must be > 0 for an inverse, got p0 = {p0!r} "
                f"and partial sums {cumulative.tolist()!r}"
            )
        inv_weights = -weights / (cumulative * previous)
        inv_radii = p0 * radii + np.array(
            [float(np.sum(weights[: j + 1] * (radii[j] - radii[: j + 1]))) for j in range(radii.size)]
        )
        return {"radii": inv_radii, "weights": inv_weights, "p0": 1.0 / p0, "offset": self.input_offset,
                "input_offset": self.offset}

    def __repr__(self) -> str:
        extra = (f", offset={self.offset!r}" if self.offset else "") + (
            f", input_offset={self.input_offset!r}" if self.input_offset else "")
        return (f"PrandtlIshlinskii(radii={self.radii.tolist()!r}, weights={self.weights.tolist()!r}, "
                f"p0={self.p0!r}{extra})")

    @classmethod
    def fit(cls, u: Any, y: Any, n: int, *, n_fit: int | None = None, fit_mask: Any = None,
            output_unit: str = "", output_quantity: str | None = None,
            initial: str = "auto") -> tuple["PrandtlIshlinskii", Any]:
        """Fit ``n`` plays (radius 0 included) with non-negative weights to a record.

        The radii are ``r_j = j·Δu/(2n)``, ``j = 1 … n−1`` (``Δu`` the input range of the fitted
        samples); the play outputs along the record follow from the input and the plays' state
        at its start (``initial``), so ``p0``, the weights and the offset are a linear
        least-squares problem, solved with SciPy's NNLS under ``p_j >= 0`` and
        ``p0 >= 10⁻³ Δy/Δu``: a strictly increasing operator, so :meth:`inverse` exists.

        Parameters
        ----------
        u, y : array_like
            Input and output samples in time order (at least 10).
        n : int
            Number of plays including the radius-0 one, ``>= 2``.
        n_fit : int, optional
            Fit the first ``n_fit`` samples and predict the rest.  Default: all.
        fit_mask : array_like of bool, optional
            Fit the samples where it is true (one entry per sample), predict the others; instead
            of ``n_fit``.
        output_unit : str, optional
            Unit of ``y`` (``"m"``, ``"-"``, ...); kept as the model's :attr:`output_unit`.
        output_quantity : str, optional
            What ``y`` is (``"strain"``, ``"displacement"``, ...); default from the unit (a
            length: ``"displacement"``, else not stated).
        initial : {"auto", "rest", "descended", "covered"}, optional
            The plays' state at the record's start (:mod:`exudyn_atcm.hysteresis.pi_fit`):
            ``"auto"`` (default) fits a record that starts at its lowest input from its first
            sample, at rest or as after a descent, whichever fits better; any other record
            from where the input has covered its range.

        Returns
        -------
        (PrandtlIshlinskii, FitReport)
            The model (its ``input_offset`` puts the plays, from the reset state, where the fit
            took them; its :attr:`fitted_range` is the fitted inputs' range) and its errors.

        Raises
        ------
        ValueError
            For fewer than 10 samples, non-finite values, different lengths, a constant input
            or output, ``n < 2``, an unknown ``initial`` or a strain in a length unit.

        Notes
        -----
        Which samples were left out and which initial state was used is in the report's notes
        and ``settings`` (``initial``, ``initial_rms``).
        """
        return fit_prandtl_ishlinskii(cls, u, y, n, n_fit=n_fit, fit_mask=fit_mask, output_unit=output_unit,
                                      output_quantity=output_quantity, initial=initial)


class ShiftedPIInverse(PrandtlIshlinskii):
    """The analytic inverse of ``y = offset + P[u − input_offset]``: again a Prandtl-Ishlinskii operator.

    What :meth:`PrandtlIshlinskii.inverse` returns: the inverse's radii, weights, ``p0`` and
    swapped offsets (:meth:`PrandtlIshlinskii.inverse_parameters`), plus the forward model
    (``model``, a copy: what :meth:`save` writes and :meth:`inverse` returns) and the clip
    counters of the other inverses (always 0: every output is reachable).
    """

    def __init__(self, model: PrandtlIshlinskii) -> None:
        if not isinstance(model, PrandtlIshlinskii):
            raise ValueError(f"model must be a PrandtlIshlinskii, got {type(model).__name__}")
        super().__init__(**model.inverse_parameters())
        self.model = copy.deepcopy(model)  # the forward model, kept for save() and inverse()
        self.model.reset()
        self.clip_count = 0
        self.largest_clip = 0.0

    def inverse(self, input_range: tuple[float, float] | None = None) -> HysteresisOperator:
        """The forward model (a copy at its reset state); with ``input_range`` its bisection inverse's range."""
        if input_range is not None:
            return BisectionInverse(self, input_range)
        forward = copy.deepcopy(self.model)
        forward.reset()
        return forward

    def __repr__(self) -> str:
        return f"ShiftedPIInverse({self.model!r})"


def _fit_pi(request: FitRequest) -> FamilyFit:
    """The ``prandtl_ishlinskii`` family: :meth:`PrandtlIshlinskii.fit`."""
    n_plays = request.options.get("n_plays", 20)
    model, report = PrandtlIshlinskii.fit(request.u, request.y, n_plays, **request.rows, **request.units)
    return FamilyFit(f"prandtl_ishlinskii ({n_plays} plays)", model, report, n_plays + 1)


register_family("prandtl_ishlinskii", _fit_pi, inverse="analytic", operator=PrandtlIshlinskii,
                description="weighted play operators, non-negative weights")
