"""Preisach operators evaluated from the memory staircase of dominant input extrema.

Notation (Mayergoyz, *Mathematical Models of Hysteresis*, 2003): a relay with switch-on
threshold ``alpha`` and switch-off threshold ``beta <= alpha`` has output 1 once the input
reaches ``u >= alpha``, 0 once ``u <= beta`` (and ``u < alpha``), and keeps its state in
between.  A Preisach operator is a weighted, possibly continuous, sum of relays.  Starting
from negative saturation (all relays off), its state is fixed by the alternating sequence of
dominant input extrema (the staircase in the Preisach plane); a new extremum wipes out all
earlier extrema it exceeds.  With

``K(a, b) = measure of the relays with alpha <= a and beta >= b``

the output is updated from the last reversal point only:

* rising from a minimum ``m`` whose output was ``Y_m``: ``y = Y_m + K(u, m) - K(m, m)``,
* falling from a maximum ``M`` whose output was ``Y_M``: ``y = Y_M - K(M, u) + K(u, u)``.

(``K(u, u)`` is the weight of relays with ``alpha == beta == u``; zero for a density.)
The staircase stores each surviving reversal point with its output, so a step costs a few
comparisons plus one evaluation of ``K``, independent of the history's length on average.
"""

from __future__ import annotations

import abc
import math
from typing import Any

from .._checks import shown
from .base import HysteresisOperator, check_input
from .bisection import BisectionInverse

_INF = math.inf
_NAN = math.nan


def _staircase_step(store: bool):
    """One body for :meth:`StaircasePreisach.evaluate` (``store=False``) and ``commit`` (``True``).

    Both methods are made from this one function, so they cannot drift apart, and neither
    carries a private argument nor pays for an extra call level (the step is a hot path: it
    runs once per attempted solver step).

    ``evaluate`` keeps its input and output (``_trial_u``, ``_trial_y``); a ``commit`` of the
    same input from the same memory (the accepted step of a solver run: trial, then commit)
    takes that output instead of evaluating ``K`` again.  Every change of the memory (commit,
    :meth:`~StaircasePreisach.reset`, :meth:`~StaircasePreisach.restore`) forgets it.
    """

    def step(self, u: float) -> float:
        if type(u) is not float:
            u = check_input(u)
        elif not -_INF < u < _INF:  # nan compares false, too
            raise ValueError(f"u must be a finite real number, got {shown(u)}")
        u_now = self._u
        if u == u_now:
            return self._y
        known = self._trial_y if store and u == self._trial_u else None
        values = self._values
        new_extremum = False  # u_now becomes a reversal point, no extremum wiped out
        if u > u_now:
            rising = True
            if self._rising:
                i = len(values) - 1
            elif u < values[-1]:
                new_extremum = True
            else:
                i = len(values) - 2  # the new minimum and the last maximum are wiped out
            if new_extremum:
                y = known if known is not None else (
                    self._y + self._k_rising(u, u_now) - (self._tie(u_now) if self._has_ties else 0.0))
            else:
                while u >= values[i - 1]:
                    i -= 2
                m = values[i]
                y = known if known is not None else (
                    self._outputs[i] + self._k_rising(u, m) - (self._tie(m) if self._has_ties else 0.0))
        else:
            rising = False
            if not self._rising:
                i = len(values) - 1
            elif u > values[-1]:
                new_extremum = True
            else:
                i = len(values) - 2
            if new_extremum:
                y = known if known is not None else (
                    self._y - self._k_falling(u_now, u) + (self._tie(u) if self._has_ties else 0.0))
            else:
                while u <= values[i - 1]:
                    i -= 2
                big_m = values[i]
                y = known if known is not None else (
                    self._outputs[i] - self._k_falling(big_m, u) + (self._tie(u) if self._has_ties else 0.0))
        if not store:
            self._trial_u, self._trial_y = u, y
            return y
        if new_extremum:
            values.append(u_now)
            self._outputs.append(self._y)
        elif i + 1 < len(values):
            del values[i + 1 :]
            del self._outputs[i + 1 :]
        self._rising, self._u, self._y = rising, u, y
        self._trial_u = _NAN
        return y

    name = "commit" if store else "evaluate"
    step.__name__ = name
    step.__qualname__ = f"StaircasePreisach.{name}"
    return step


class StaircasePreisach(HysteresisOperator):
    """Base class: staircase memory plus a model-specific function ``K``.

    Subclasses implement :meth:`_k_rising` (``K(a, b)`` with ``b`` a stored minimum),
    :meth:`_k_falling` (``K(a, b)`` with ``a`` a stored maximum) and :meth:`_tie`
    (``K(u, u)``), and set ``_y_reset`` (output with all relays off).
    """

    _y_reset: float
    #: whether some relays have alpha == beta (then K(u, u) can be non-zero)
    _has_ties: bool = False
    #: the last :meth:`evaluate`'s input and output from the current memory (nan: none)
    _trial_u: float = _NAN
    _trial_y: float = _NAN

    def __init__(self) -> None:
        self.reset()

    # -- the function K, supplied by the model --------------------------------------
    @abc.abstractmethod
    def _k_rising(self, a: float, b: float) -> float:
        """``K(a, b)`` where ``b`` is a reversal minimum (may be cached per ``b``)."""

    @abc.abstractmethod
    def _k_falling(self, a: float, b: float) -> float:
        """``K(a, b)`` where ``a`` is a reversal maximum (may be cached per ``a``)."""

    def _tie(self, u: float) -> float:
        """``K(u, u)``: weight of relays with ``alpha == beta == u`` (used if ``_has_ties``)."""
        return 0.0

    # -- memory ----------------------------------------------------------------------
    def reset(self) -> None:
        """Negative saturation: all relays off, output at its lower bound."""
        # Reversal values alternate max, min, max, ...: index 0 is a +inf sentinel maximum
        # and index 1 the -inf minimum of the reset state, so loops need no index checks.
        self._values: list[float] = [_INF, -_INF]
        self._outputs: list[float] = [self._y_reset, self._y_reset]
        self._u = -_INF
        self._y = self._y_reset
        self._rising = True
        self._trial_u = _NAN

    def checkpoint(self) -> tuple:
        """Snapshot of the staircase (reversal points, last input and output, direction)."""
        return (tuple(self._values), tuple(self._outputs), self._u, self._y, self._rising)

    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint`."""
        try:
            values, outputs, u, y, rising = snapshot
        except (TypeError, ValueError):
            raise ValueError(
                f"snapshot must come from checkpoint() of a Preisach operator, got {shown(snapshot)}"
            ) from None
        self._values = list(values)
        self._outputs = list(outputs)
        self._u, self._y, self._rising = u, y, rising
        self._trial_u = _NAN

    @property
    def output(self) -> float:
        """Output for the last committed input."""
        return self._y

    @property
    def last_input(self) -> float:
        """Last committed input (``-inf`` after :meth:`reset`)."""
        return self._u

    @property
    def reversal_points(self) -> list[tuple[float, float]]:
        """The surviving dominant extrema ``(input, output)``, oldest first (no sentinels)."""
        return list(zip(self._values[2:], self._outputs[2:]))

    def inverse(self, input_range: tuple[float, float] | None = None) -> BisectionInverse:
        """The inverse operator: input the wanted output, output the input that produces it.

        Bisection on the input from the forward model's committed memory
        (:class:`~exudyn_atcm.hysteresis.bisection.BisectionInverse`, which keeps its own copy
        of this model, reset); the model's offset is included, so a fitted model inverts as
        it is.  Outputs beyond what ``input_range`` can reach are clipped with a warning.

        Parameters
        ----------
        input_range : (float, float), optional
            Allowed inputs (e.g. the drive's voltage limits [V]); default: the range over
            which the output changes.

        Returns
        -------
        BisectionInverse
            Starting, like this model after :meth:`reset`, from the reset state.
        """
        return BisectionInverse(self, input_range)

    # -- stepping ----------------------------------------------------------------------
    # evaluate and commit are one body (_staircase_step below) with the memory update
    # switched off or on.
    evaluate = _staircase_step(store=False)
    evaluate.__doc__ = """Output for input ``u`` from the committed memory; the memory is not changed.

        Parameters
        ----------
        u : float
            Input (finite).

        Returns
        -------
        float
            The output :meth:`commit` would return for ``u``.

        Raises
        ------
        ValueError
            If ``u`` is not a finite real number.
        """

    commit = _staircase_step(store=True)
    commit.__doc__ = """Accept input ``u``, update the staircase and return the output.

        A new extremum is stored as a reversal point; an input beyond earlier extrema of its
        kind wipes them out.

        Parameters
        ----------
        u : float
            Input (finite).

        Returns
        -------
        float
            The output for ``u``.

        Raises
        ------
        ValueError
            If ``u`` is not a finite real number.
        """
