"""Material damping of a laminate: Rayleigh coefficients that do not depend on how a bender is cut.

A bender's damping matrix is ``C = alpha M + beta K`` (Rayleigh damping) with

* ``beta`` [s] on the stiffness: every spring (or beam element) of stiffness ``k`` gets the
  damping ``beta k``.  For a laminate this is a material property: a Kelvin-Voigt material
  with the loss factor ``eta(f) = 2 pi f beta`` at the frequency ``f``.  Springs in series
  with one ``beta`` give ``beta k_series``, so two benders of one laminate welded end to end
  are damped exactly as one bender of the summed length.
* ``alpha`` [1/s] on the mass: a force ``-alpha m v`` on every mass, with ``v`` its velocity
  relative to the ground (the inertial frame), and a torque ``-alpha J omega`` on every
  rotary inertia.  It acts like a viscous surrounding medium: it also damps the rigid-body
  motion of a bender's parts (for example a bender carried by a moving link), not only its
  deformation.  Only the benders' own masses are damped (links are not of the laminate).

The modal damping ratio of a mode of circular frequency ``omega`` is
``zeta(omega) = alpha/(2 omega) + beta omega/2``.

The ``damping=`` argument of :class:`~exudyn_atcm.mechanism.Bender` and
:class:`~exudyn_atcm.mechanism.actuator.BendingActuator` also takes a plain ratio ``zeta`` (default
0.02): that is stiffness-proportional damping with ``beta = 2 zeta / omega_1``, ``omega_1`` the
first clamped-free frequency of *that* bender, i.e. the same damping ratio ``zeta`` at the
bender's own first mode.  It is the same material damping as
``RayleighDamping(beta=2 zeta / omega_1)`` for an unsplit bender, but it changes with the
length of each part; give a :class:`~exudyn_atcm.RayleighDamping` to make the damping a property of the
material (independent of how a bender is split into parts).

A free decay with the logarithmic decrement ``delta = ln(x_k / x_{k+1})`` (successive peaks of
one side) has the damping ratio ``zeta = delta / sqrt(4 pi^2 + delta^2)``
(:func:`damping_ratio_from_log_decrement`); :meth:`~exudyn_atcm.RayleighDamping.from_log_decrement` turns a
decrement measured at a frequency into the material coefficient.

A damping ratio at or above :data:`~exudyn_atcm.physical_bounds.DAMPING_RATIO_SUSPECT` (1: critical
damping) is most likely a percentage (``damping=5`` meant as 5 %) and gives an
:class:`~exudyn_atcm.errors.InputRangeWarning` naming the parameter and the value, wherever a ratio is
given (:func:`check_damping`, :meth:`RayleighDamping.from_damping_ratio`; :func:`warn_damping_ratio`).

``MASS_DAMPING_CELLS`` lists the cells that realise ``alpha M`` exactly (``"rigid"`` and
``"six-bar"``: all their masses are rigid bodies, see ``exudyn_atcm.mbs.mass_damping``); the
continuum cells refuse ``alpha > 0`` (:func:`check_damping`).
"""

from __future__ import annotations

import contextlib
import contextvars
import math
import numbers
import warnings
from collections.abc import Iterator
from dataclasses import dataclass

from .._checks import shown
from ..cells import CELL_KINDS, CellKind, cell_kind
from ..errors import InputRangeWarning
from ..physical_bounds import DAMPING_RATIO_SUSPECT

__all__ = ["DEFAULT_DAMPING_RATIO", "MASS_DAMPING_CELLS", "RayleighDamping", "check_damping", "damping_ratio_from_log_decrement",
           "log_decrement_from_damping_ratio", "warn_damping_ratio", "damping_already_checked"]

_CHECKED: contextvars.ContextVar[bool] = contextvars.ContextVar("exudyn_atcm_damping_checked", default=False)

#: The cells that realise the mass-proportional part ``alpha M`` exactly: every mass of theirs is
#: a rigid body, which gets a force ``-alpha m v`` at its centre of mass and a torque
#: ``-alpha J omega``.  The continuum cells (consistent mass matrices) refuse ``alpha > 0``.
#: Default damping: this modal damping ratio of a bender's own first bending mode [-], realised as
#: stiffness-proportional damping (2 % is an assumed, typical order of magnitude for fibre-composite
#: laminates, not a value from the paper).
DEFAULT_DAMPING_RATIO = 0.02



def mass_damping_cells() -> tuple[str, ...]:
    """The registered cell kinds that realise ``alpha M`` exactly (also as the module attribute ``MASS_DAMPING_CELLS``)."""
    return tuple(name for name, kind in CELL_KINDS.items() if kind.realises_mass_damping)


_LIVE = {"MASS_DAMPING_CELLS": mass_damping_cells}


def _real(name: str, value: object, *, allow_zero: bool = True) -> float:
    """A finite real number >= 0 (> 0 with ``allow_zero=False``), or a ValueError naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(float(value)):
        raise ValueError(f"{name} must be a finite number, got {shown(value)}")
    x = float(value)
    if x < 0.0 or (x == 0.0 and not allow_zero):
        raise ValueError(f"{name} must be {'>= 0' if allow_zero else '> 0'}, got {shown(value)}")
    return x


def warn_damping_ratio(value: float, owner: str, name: str = "damping", *, stacklevel: int = 3) -> None:
    """Warn (:class:`~exudyn_atcm.errors.InputRangeWarning`) when a damping ratio looks like a percentage.

    A ratio ``>=`` :data:`~exudyn_atcm.physical_bounds.DAMPING_RATIO_SUSPECT` (1, critical damping) is
    most likely a percentage written as a number: ``damping=5`` for 5 % is a ratio of 500 %.
    Quiet inside :func:`damping_already_checked`.

    Parameters
    ----------
    value : float
        The ratio [-], already checked to be a finite number >= 0.
    owner : str
        Who takes it (``"bender 'b'"``), for the message.
    name : str, optional
        The parameter's name in the message (``"damping"``, ``"zeta"``).
    stacklevel : int, optional
        Passed to ``warnings.warn``: the frame the warning points at (default: the caller's caller).
    """
    if value < DAMPING_RATIO_SUSPECT or _CHECKED.get():
        return
    state = "critical damping" if value == 1.0 else f"{value:g} times critical damping"
    warnings.warn(
        f"{owner}: {name} = {value!r} is a damping ratio of {100.0 * value:g} % ({state}: the mode no longer vibrates)"
        f"; fibre-composite laminates have about 0.005 ... 0.05 (0.5 ... 5 %, the default is "
        f"{DEFAULT_DAMPING_RATIO}). The ratio is a fraction, not a percentage: if you meant {value:g} %, give "
        f"{name}={value / 100.0:g}",
        InputRangeWarning,
        stacklevel=stacklevel + 1,
    )


@contextlib.contextmanager
def damping_already_checked() -> Iterator[None]:
    """Within this block :func:`warn_damping_ratio` is quiet: the package rebuilds a part (a
    :class:`~exudyn_atcm.BendingActuator` as its one-bender mechanism, a flexure as its cells) from a
    ratio that was warned about where the user gave it."""
    token = _CHECKED.set(True)
    try:
        yield
    finally:
        _CHECKED.reset(token)


def damping_ratio_from_log_decrement(delta: float) -> float:
    """Damping ratio ``zeta = delta / sqrt(4 pi^2 + delta^2)`` [-] of a logarithmic decrement.

    Parameters
    ----------
    delta : float
        Logarithmic decrement ``ln(x_k / x_{k+1})`` of successive same-side peaks of a free
        decay [-], >= 0.

    Returns
    -------
    float
        The viscous damping ratio ``zeta`` (< 1) of a single-degree-of-freedom oscillator
        with that decrement.
    """
    d = _real("delta", delta)
    return d / math.sqrt(4.0 * math.pi**2 + d * d)


def log_decrement_from_damping_ratio(zeta: float) -> float:
    """Logarithmic decrement ``delta = 2 pi zeta / sqrt(1 - zeta^2)`` [-] of a damping ratio ``0 <= zeta < 1``."""
    z = _real("zeta", zeta)
    if z >= 1.0:
        raise ValueError(f"zeta must be < 1 (an underdamped oscillation has a decrement), got {shown(zeta)}")
    return 2.0 * math.pi * z / math.sqrt(1.0 - z * z)


@dataclass(frozen=True)
class RayleighDamping:
    """Material damping ``C = alpha M + beta K`` of a laminate (Rayleigh damping).

    Parameters
    ----------
    alpha : float, optional
        Mass-proportional coefficient [1/s], >= 0 (default 0): a force ``-alpha m v`` on every
        mass of the bender (velocity relative to the ground) and a torque ``-alpha J omega``
        on every rotary inertia.  Realised exactly by the ``"rigid"`` and ``"six-bar"`` cells
        (all their masses are rigid bodies); the continuum cells (``"beam"``, ``"ancf"``,
        ``"ritz"``, ``"rod"``) refuse a non-zero ``alpha``.
    beta : float, optional
        Stiffness-proportional coefficient [s], >= 0 (default 0): every spring or beam
        element of stiffness ``k`` gets the damping ``beta k`` (loss factor
        ``eta = 2 pi f beta`` at the frequency ``f`` [Hz]).

    Notes
    -----
    A mode of circular frequency ``omega`` [rad/s] gets the damping ratio
    ``alpha/(2 omega) + beta omega/2`` (:meth:`damping_ratio`).
    """

    alpha: float = 0.0
    beta: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "alpha", _real("alpha", self.alpha))
        object.__setattr__(self, "beta", _real("beta", self.beta))

    @classmethod
    def from_damping_ratio(cls, zeta: float, frequency_hz: float) -> RayleighDamping:
        """Stiffness-proportional damping with the ratio ``zeta`` [-] at ``frequency_hz`` [Hz].

        ``beta = 2 zeta / omega`` with ``omega = 2 pi frequency_hz`` (and ``alpha = 0``).  A ``zeta``
        of 1 or more (a percentage?) gives an :class:`~exudyn_atcm.errors.InputRangeWarning`
        (:func:`warn_damping_ratio`).
        """
        z = _real("zeta", zeta)
        f = _real("frequency_hz", frequency_hz, allow_zero=False)
        warn_damping_ratio(z, "RayleighDamping.from_damping_ratio", "zeta", stacklevel=2)
        return cls(0.0, 2.0 * z / (2.0 * math.pi * f))

    @classmethod
    def from_log_decrement(cls, delta: float, frequency_hz: float) -> RayleighDamping:
        """Stiffness-proportional material damping from a measured free decay.

        Parameters
        ----------
        delta : float
            Logarithmic decrement ``ln(x_k / x_{k+1})`` of successive same-side peaks [-], >= 0.
        frequency_hz : float
            Frequency of the decaying oscillation [Hz], > 0 (a bender's first mode: its
            measured ringing frequency).

        Returns
        -------
        RayleighDamping
            ``beta = 2 zeta / (2 pi frequency_hz)`` [s] with
            ``zeta = delta / sqrt(4 pi^2 + delta^2)``, ``alpha = 0``: the mode at that frequency
            decays with the decrement ``delta``; a mode at ``f`` has ``zeta f / frequency_hz``.

        Notes
        -----
        ``frequency_hz`` is the damped frequency one reads off a record; the undamped one
        is ``frequency_hz / sqrt(1 - zeta^2)`` (0.02 % higher at ``zeta = 0.02``).  The
        coefficient uses the given frequency as it is, which is what a measurement supplies.
        """
        return cls.from_damping_ratio(damping_ratio_from_log_decrement(delta), frequency_hz)

    def damping_ratio(self, frequency_hz: float) -> float:
        """Modal damping ratio ``alpha/(2 omega) + beta omega/2`` [-] of a mode at ``frequency_hz`` [Hz]."""
        omega = 2.0 * math.pi * _real("frequency_hz", frequency_hz, allow_zero=False)
        return 0.5 * self.alpha / omega + 0.5 * self.beta * omega

    def loss_factor(self, frequency_hz: float) -> float:
        """Loss factor ``eta = 2 zeta`` [-] at ``frequency_hz`` [Hz] (``2 pi f beta`` without ``alpha``)."""
        return 2.0 * self.damping_ratio(frequency_hz)


def check_damping(damping: object, *, cell: str | CellKind, owner: str, stacklevel: int = 3) -> float | RayleighDamping:
    """The ``damping=`` argument of a bender: a damping ratio ``>= 0`` or a :class:`~exudyn_atcm.RayleighDamping`.

    Parameters
    ----------
    damping : float or RayleighDamping
        The value given.
    cell : str or CellKind
        The bender's cell kind: a :class:`~exudyn_atcm.RayleighDamping` with ``alpha > 0`` needs a kind
        whose ``realises_mass_damping`` is true (the package's: ``MASS_DAMPING_CELLS``).
    owner : str
        Who is checking (for the message), e.g. ``"bender 'b'"``.
    stacklevel : int, optional
        Frames from this function's caller to the line the warning points at (default 3: the
        caller of the constructor that calls this).

    Returns
    -------
    float or RayleighDamping
        The ratio as a float, or the RayleighDamping itself.

    Raises
    ------
    ValueError
        For a bool, a non-number, a negative or non-finite ratio, or ``alpha > 0`` with a cell
        that cannot realise mass-proportional damping (the message names the cell).

    Warns
    -----
    InputRangeWarning
        For a ratio of 1 or more (``damping=5`` meant as 5 %?), naming ``damping`` and the value
        (:func:`warn_damping_ratio`).
    """
    if isinstance(damping, RayleighDamping):
        cell = cell_kind(cell)
        if damping.alpha > 0.0 and not cell.realises_mass_damping:
            raise ValueError(
                f"{owner}: damping={damping!r} has a mass-proportional part alpha={damping.alpha!r} 1/s, which the "
                f"{cell.name!r} cell cannot realise exactly (its mass matrix is not a set of rigid bodies); cells that "
                f"can: {mass_damping_cells()}. Use alpha=0 (stiffness-proportional damping) with cell={cell.name!r}")
        return damping
    if isinstance(damping, bool) or not isinstance(damping, numbers.Real) or not math.isfinite(float(damping)):
        raise ValueError(f"damping must be a finite damping ratio >= 0 or a RayleighDamping, got {shown(damping)}")
    if float(damping) < 0.0:
        raise ValueError(f"damping must be a damping ratio >= 0 or a RayleighDamping, got {shown(damping)}")
    warn_damping_ratio(float(damping), owner, stacklevel=stacklevel)
    return float(damping)


def __getattr__(name: str):
    # the registry's names, read when asked (kinds registered with exudyn_atcm.register_cell_kind included)
    if name in _LIVE:
        return _LIVE[name]()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
