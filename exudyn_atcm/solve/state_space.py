"""The state-space model :class:`LinearModel` that :func:`exudyn_atcm.linearise` returns.

``x' = A x + B u``, ``y = C x + D u`` with the state ``x = [z, z']``: ``z`` the coordinates on the
constraints' null space about the equilibrium, ``u`` the inputs (drive voltages [V], point forces
[N]) and ``y`` the outputs (point coordinates [m], angles [rad]) as deviations from the equilibrium.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._checks import finite_array, shown

__all__ = ["LinearModel"]


@dataclass(frozen=True)
class LinearModel:
    """A linear time-invariant model of a mechanism about a static equilibrium.

    Attributes
    ----------
    A, B, C, D : numpy.ndarray
        The state-space matrices: ``A`` (2m x 2m) [1/s, 1/s^2], ``B`` (2m x p), ``C`` (q x 2m),
        ``D`` (q x p); ``m`` the degrees of freedom, ``p`` the inputs, ``q`` the outputs.
    inputs, input_units : tuple of str
        The inputs' names and units: a drive's name (its voltage [V]) or ``"<point>_Fx"`` /
        ``"<point>_Fy"`` (a dead force [N] at a named point).
    outputs, output_units : tuple of str
        The outputs' names (result columns: ``"coupler.P_x"``, ``"lever.angle"``) and units [m, rad].
    operating_point : dict
        The outputs' values at the equilibrium [m, rad].
    voltages : dict
        The drives' voltages at the equilibrium [V].
    strains : dict
        The drives' free strains at the equilibrium [-] (on the branch's history).
    gains : dict
        The drives' small-signal gains ``d eps/d U`` [1/V] on :attr:`branch`.
    branch : str
        The hysteresis branch the gains are taken on (:data:`~exudyn_atcm.model.drive_gain.BRANCHES`).
    state : str
        The equilibrium in words.
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    inputs: tuple[str, ...]
    input_units: tuple[str, ...]
    outputs: tuple[str, ...]
    output_units: tuple[str, ...]
    operating_point: dict = field(default_factory=dict)
    voltages: dict = field(default_factory=dict)
    strains: dict = field(default_factory=dict)
    gains: dict = field(default_factory=dict)
    branch: str = "ascending"
    state: str = ""

    def to_scipy(self) -> Any:
        """The model as a ``scipy.signal.StateSpace`` (continuous time)."""
        from scipy.signal import StateSpace  # noqa: PLC0415 - lazy: scipy.signal is slow to import
        return StateSpace(self.A, self.B, self.C, self.D)

    def frequency_response(self, frequencies_hz: Sequence[float] | np.ndarray) -> np.ndarray:
        """Complex response ``G(i 2 pi f) = C (i 2 pi f I - A)^-1 B + D`` [output unit per input unit].

        Parameters
        ----------
        frequencies_hz : array_like
            Frequencies [Hz], finite and >= 0.

        Returns
        -------
        numpy.ndarray
            Shape (n_frequencies, n_outputs, n_inputs); ``abs`` is the gain, ``numpy.angle`` the phase [rad]
            of the output's sine against the input's.
        """
        f = finite_array("frequencies_hz", frequencies_hz)
        if np.any(f < 0.0):
            raise ValueError(f"frequencies_hz must be >= 0 Hz, got {float(f.min())!r}")
        n = self.A.shape[0]
        out = np.empty((f.size, self.C.shape[0], self.B.shape[1]), dtype=complex)
        for k, fk in enumerate(f):
            out[k] = self.C @ np.linalg.solve(2j * math.pi * fk * np.eye(n) - self.A, self.B) + self.D
        return out

    def response(self, output: str, input: str, frequencies_hz: Sequence[float] | np.ndarray) -> np.ndarray:
        """The complex response of one output to one input (names as in :attr:`outputs`, :attr:`inputs`)."""
        for name, names, what in ((output, self.outputs, "output"), (input, self.inputs, "input")):
            if name not in names:
                raise ValueError(f"{what} must be one of {', '.join(map(repr, names))}, got {shown(name)}")
        return self.frequency_response(frequencies_hz)[:, self.outputs.index(output), self.inputs.index(input)]

    @property
    def poles(self) -> np.ndarray:
        """Eigenvalues of ``A`` [1/s], sorted by their magnitude."""
        values = np.linalg.eigvals(self.A)
        return values[np.argsort(np.abs(values))]

    @property
    def natural_frequencies(self) -> np.ndarray:
        """Undamped natural frequencies ``|pole| / 2 pi`` [Hz] of the poles with a positive imaginary part
        (one per oscillating mode), ascending.  Real poles are not among them: a positive one is a divergence
        (an unstable equilibrium, which :func:`~exudyn_atcm.linearise` warns about); see :attr:`poles`."""
        p = self.poles
        return np.sort(np.abs(p[p.imag > 0.0])) / (2.0 * math.pi)

    @property
    def damping_ratios(self) -> np.ndarray:
        """Damping ratios ``-Re(pole)/|pole|`` [-] of the oscillating modes, in the order of
        :attr:`natural_frequencies`."""
        p = self.poles
        p = p[p.imag > 0.0]
        p = p[np.argsort(np.abs(p))]
        return -p.real / np.abs(p)

    def dc_gain(self) -> np.ndarray:
        """Static gain ``D - C A^-1 B`` (n_outputs x n_inputs) [output unit per input unit]."""
        return self.D - self.C @ np.linalg.solve(self.A, self.B)
