"""The interface shared by every rate-independent hysteresis operator."""

from __future__ import annotations

import abc
import math
import numbers
from typing import Any

import numpy as np

from .model_files import SavableModel  # the save() method of every operator
from .._checks import finite_array


def check_input(u: Any) -> float:
    """Return the operator input ``u`` as a float; raise ``ValueError`` if it is not finite."""
    if isinstance(u, (bool, np.bool_)) or not isinstance(u, (numbers.Real, np.floating, np.integer)):
        raise ValueError(f"u must be a finite real number, got {u!r}")
    value = float(u)
    if not math.isfinite(value):
        raise ValueError(f"u must be a finite real number, got {u!r}")
    return value


class HysteresisOperator(SavableModel, abc.ABC):
    """A rate-independent hysteresis operator with an explicit, committed memory.

    The memory changes only in :meth:`commit`, so :meth:`evaluate` can be called any number
    of times for trial inputs (inside the Newton iterations of a solver step) and
    :meth:`commit` once the step is accepted.  Inputs and outputs are unit-free floats
    (volts in and strain out when the operator models a piezo layer).
    """

    #: What the output is: ``"strain"`` [-], ``"stroke"`` [m], ... or ``None`` when not stated.
    #: The parameter sets state it; :class:`~exudyn_atcm.model.drive.PiezoDrive` accepts ``"strain"``
    #: or ``None`` only.  Set it with :meth:`with_output_quantity`.
    output_quantity: str | None = None

    @property
    def input_range(self) -> tuple[float, float] | None:
        """``(u_low, u_high)``: beyond it the output saturates; ``None`` if the operator has no such range."""
        return None

    def with_output_quantity(self, quantity: str | None) -> "HysteresisOperator":
        """Set :attr:`output_quantity` (e.g. ``"strain"`` or ``"stroke"``) and return the operator."""
        if quantity is not None and (not isinstance(quantity, str) or not quantity.strip()):
            raise ValueError(f"quantity must be None or a non-empty string such as 'strain', got {quantity!r}")
        self.output_quantity = quantity
        return self

    @abc.abstractmethod
    def evaluate(self, u: float) -> float:
        """Output for input ``u`` from the committed memory, without changing it."""

    @abc.abstractmethod
    def commit(self, u: float) -> float:
        """Accept input ``u``: update the memory and return the output."""

    @abc.abstractmethod
    def reset(self) -> None:
        """Return to the documented initial state of the model."""

    @abc.abstractmethod
    def checkpoint(self) -> Any:
        """Return an opaque snapshot of the memory, for :meth:`restore`."""

    @abc.abstractmethod
    def restore(self, snapshot: Any) -> None:
        """Put back a memory returned by :meth:`checkpoint` of this operator."""

    @property
    @abc.abstractmethod
    def output(self) -> float:
        """Output for the last committed input (the initial output after :meth:`reset`)."""

    def apply(self, u_series: Any) -> np.ndarray:
        """Outputs for a whole input series, starting from the reset state.

        The operator's own memory is left as it was: the series is run from a reset copy.

        Parameters
        ----------
        u_series : array_like
            1-D sequence of finite inputs, in order.

        Returns
        -------
        numpy.ndarray
            One output per input.
        """
        inputs = finite_array("u_series", u_series, min_length=0)
        saved = self.checkpoint()
        try:
            self.reset()
            commit = self.commit
            return np.array([commit(u) for u in inputs.tolist()], dtype=float)
        finally:
            self.restore(saved)
