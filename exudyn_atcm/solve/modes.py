"""Mode shapes of a mechanism or actuator about a static equilibrium: :func:`modes`.

The eigenproblem is the one :func:`exudyn_atcm.eigenfrequencies` solves (the tangent stiffness with
the constraint forces' geometric stiffness, projected onto the constraints' null space,
:mod:`exudyn_atcm.mbs.eigen`); :func:`modes` also returns what the eigenvectors mean for the
mechanism: the displacement of every named point and cell point, the modal mass and how strongly
each drive's strain excites each mode.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import positive_int, shown
from ..errors import AccuracyWarning
from ..mbs import linear_model as lm
from ..mechanism.points import MechanismError, closest
from .linear_state import as_mechanism, equilibrium_state
from .mechanism_static import VoltageSpec
from ..mbs.blas_threads import one_blas_thread

__all__ = ["Modes", "modes", "modes_of_state", "modes_state"]


@dataclass(frozen=True)
class Modes:
    """Undamped modes of a mechanism about a static equilibrium.

    Attributes
    ----------
    frequencies : numpy.ndarray
        Eigenfrequencies [Hz], ascending, shape (n,).  An unstable direction is a negative number
        (as :func:`exudyn_atcm.eigenfrequencies`).
    points : tuple of str
        The points the shapes are given at: the mechanism's named points (``"coupler.P"``,
        ``"crank.tip"``) and its benders' cell points (``"crank.cell_1"`` ...: the cell bodies of
        rigid and six-bar cells, the nodes of beam, ANCF and rod benders).
    positions : numpy.ndarray
        Their positions ``(x, y)`` [m] at the equilibrium, shape (P, 2).
    shapes : numpy.ndarray
        Displacement ``(dx, dy)`` [m] of every point in every mode, shape (n, P, 2), normalised so that
        the largest point displacement ``hypot(dx, dy)`` of each mode is 1 m, with the sign that
        makes that point's larger component positive.  Small motions: the mode moves the points by
        ``a * shapes[j]`` for a small amplitude ``a`` [-].
    modal_masses : numpy.ndarray
        ``phi^T M phi`` [kg] of each mode with the normalisation of :attr:`shapes`: the mass that,
        moving as fast as the mode's fastest point, has the mode's kinetic energy.
    drives : tuple of str
        The drives, in the columns of :attr:`modal_forces` and :attr:`participation`.
    modal_forces : numpy.ndarray or None
        ``phi^T (d f / d eps)`` [N per unit strain], shape (n, n_drives): the generalised force
        a unit free strain of each drive puts on each mode.  ``None`` when a drive's strain is a
        prescribed motion (six-bar cells), see :attr:`note`.
    participation : numpy.ndarray or None
        ``modal_forces / (modal_masses * omega^2)`` [-], shape (n, n_drives): the static amplitude of
        each mode per unit strain of each drive.  ``participation[j, k] * shapes[j]`` [m] is mode
        ``j``'s share of the static displacement a unit strain of drive ``k`` gives; summed over all
        modes it is the whole static displacement per unit strain (the modal expansion).  Infinite for a mode
        without stiffness (a mechanism that can move freely has no static amplitude in it).
    coordinates : numpy.ndarray
        The mode vectors in the system's coordinates, scaled as :attr:`shapes`, shape (n_coordinates, n).
    state : str
        The state in words (``"voltage 300 V"``, ``"the undeformed reference pose"``).
    note : str
        Why :attr:`modal_forces` is ``None`` (empty otherwise).
    """

    frequencies: np.ndarray
    points: tuple[str, ...]
    positions: np.ndarray
    shapes: np.ndarray
    modal_masses: np.ndarray
    drives: tuple[str, ...]
    modal_forces: np.ndarray | None
    participation: np.ndarray | None
    coordinates: np.ndarray
    state: str
    note: str = ""

    def shape(self, point: str) -> np.ndarray:
        """Displacement ``(dx, dy)`` [m] of ``point`` in every mode, shape (n, 2).

        Raises
        ------
        MechanismError
            For a name that is not one of :attr:`points` (with the closest names).
        """
        if point not in self.points:
            raise MechanismError(f"point must be one of the modes' points, got {shown(point)}{closest(point, self.points)}")
        return self.shapes[:, self.points.index(point), :]

    def __len__(self) -> int:
        return int(self.frequencies.size)


def modes(system: Any, n: int = 3, *, voltage: VoltageSpec = None, loaded: bool = False) -> Modes:
    """The ``n`` lowest undamped modes of a mechanism or actuator about a static equilibrium.

    Parameters
    ----------
    system : Mechanism or BendingActuator
        The system (an actuator is solved as its one-bender mechanism).
    n : int, optional
        Number of modes, >= 1 and at most the degrees of freedom (default 3).
    voltage : float or mapping, optional
        Drive voltages [V] of the equilibrium (a number for every drive or ``{drive: volts}``);
        default: the undeformed reference pose without loads, as :func:`exudyn_atcm.eigenfrequencies`.
    loaded : bool, optional
        With ``voltage=None``: about the equilibrium under the mechanism's loads at zero strain.

    Returns
    -------
    Modes
        Frequencies [Hz], shapes at the named and cell points (normalised, see :class:`Modes`), modal
        masses [kg], the drives' modal forces and participation.

    Raises
    ------
    ValueError
        For ``n`` < 1 or above the degrees of freedom, a system that is neither a mechanism nor an
        actuator.
    NoEquilibriumError
        If the static equilibrium is not found.

    Notes
    -----
    The frequencies equal :func:`exudyn_atcm.eigenfrequencies` (one eigenproblem, with the
    constraint forces' geometric stiffness).  Validated in ``tests/test_modes.py`` against the
    Euler-Bernoulli cantilever and a rigid four-bar with a torsional spring.
    """
    n = positive_int("n", n)
    mech = as_mechanism(system, "modes")
    return modes_of_state(modes_state(mech, voltage, loaded), n)


def modes_state(mech: Any, voltage: VoltageSpec, loaded: bool, model: Any = None) -> Any:
    """The state :func:`modes` analyses: the equilibrium at ``voltage``; with ``voltage=None`` and ``loaded``
    the one under the loads at zero strain (as :func:`exudyn_atcm.eigenfrequencies`); else the reference pose."""
    if not isinstance(loaded, bool):
        raise ValueError(f"loaded must be True or False, got {shown(loaded)}")
    if voltage is None and loaded:
        zero = {name: 0.0 for name in mech.drives}
        return equilibrium_state(mech, "modes", voltage=zero, strains=zero, model=model)
    return equilibrium_state(mech, "modes", voltage=voltage, deformed=voltage is not None, model=model)


def modes_of_state(state: Any, n: int) -> Modes:
    """:class:`Modes` of a :class:`~exudyn_atcm.solve.linear_state.LinearState` (its model at the equilibrium)."""
    from scipy.linalg import eigh  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
    model = state.model
    model.before_linearisation()
    mats = lm.linear_matrices(model, damping=False)
    N = mats.N
    if n > N.shape[1]:
        raise ValueError(f"n must be <= the number of degrees of freedom ({N.shape[1]}), got {n}")
    with one_blas_thread():  # after the import: scipy's own BLAS limited too
        Kr = N.T @ mats.K @ N
        Mr = N.T @ mats.M @ N
        w2, vecs = eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T), subset_by_index=[0, n - 1])
    if np.any(w2 < 0.0):
        warnings.warn(f"modes: {int(np.sum(w2 < 0))} of the lowest {n} eigenvalues of the tangent stiffness are "
                      f"negative at {state.description}: the equilibrium is unstable; those modes have negative "
                      "frequencies", AccuracyWarning, stacklevel=3)
    phi = N @ vecs
    names, positions, jac = lm.point_jacobians(model)
    shapes = np.einsum("pan,nm->mpa", jac, phi)
    for j in range(n):
        size = np.hypot(shapes[j, :, 0], shapes[j, :, 1])
        p = int(np.argmax(size))
        big = shapes[j, p, int(np.argmax(np.abs(shapes[j, p])))]
        scale = math.copysign(1.0 / size[p], big) if size[p] > 0.0 else 1.0
        shapes[j] *= scale
        phi[:, j] *= scale
    masses = np.einsum("nm,nk,km->m", phi, mats.M, phi)
    drives = tuple(model.drive_source)
    forces = participation = None
    note = ""
    if drives:
        try:
            b = lm.strain_forces(model, state.strains)
        except ValueError as exc:
            note = f"no modal forces: {exc}"
        else:
            per_drive = b[:, [model.drive_source[d] for d in drives]]
            forces = phi.T @ per_drive
            with np.errstate(divide="ignore", invalid="ignore"):
                participation = forces / (masses * w2)[:, None]
    freqs = np.sign(w2) * np.sqrt(np.abs(w2)) / (2.0 * math.pi)
    return Modes(frequencies=freqs, points=tuple(names), positions=positions, shapes=shapes, modal_masses=masses,
                 drives=drives, modal_forces=forces, participation=participation, coordinates=phi,
                 state=state.description, note=note)
