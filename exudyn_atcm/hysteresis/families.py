"""The registry of hysteresis families: what :func:`~exudyn_atcm.hysteresis.identify` fits and ranks.

A *family* is a way to identify an operator from a record: its name, its fit, the number of
parameters it identifies, whether and how its operators invert, and the operator class (whose
:meth:`~exudyn_atcm.hysteresis.HysteresisOperator.inverse` and declared input range,
:attr:`~exudyn_atcm.hysteresis.HysteresisOperator.saturation_range` or
:attr:`~exudyn_atcm.hysteresis.HysteresisOperator.fitted_range`, the inverse uses).  Each
family registers itself, with :func:`register_family`, in the module that defines its operator
(:mod:`~exudyn_atcm.hysteresis.discrete` registers ``equal_gain`` and ``discrete``,
:mod:`~exudyn_atcm.hysteresis.everett` ``everett``, ...); :func:`~exudyn_atcm.hysteresis.identify`,
the docs' family table and the tests iterate :func:`registered_families`.  Saving and loading
models is a different registry (:mod:`~exudyn_atcm.hysteresis.model_registry`: kinds of saved
files); a new family whose operators should be saved registers a model kind as well.

Adding a family is one module (or one test file)::

    from exudyn_atcm.hysteresis.families import FamilyFit, register_family

    def fit_bouc_wen(request):                       # a FitRequest: the record and the settings
        model, report = BoucWen.fit(request.u, request.y, **request.rows, **request.units)
        return FamilyFit("bouc_wen (n = 1)", model, report, parameters=5)

    register_family("bouc_wen", fit_bouc_wen, inverse="bisection", operator=BoucWen,
                    description="Bouc-Wen differential model, n = 1")

The fit receives the record and the fitted samples as a :class:`FitRequest` and returns a
:class:`FamilyFit` (a label, the operator, its :class:`~exudyn_atcm.hysteresis.FitReport` and the
parameter count); a ``ValueError`` from it means "this family cannot be fitted to this record"
and is listed with its message instead of failing :func:`~exudyn_atcm.hysteresis.identify`.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from .._checks import shown

__all__ = ["INVERSE_KINDS", "FitRequest", "FamilyFit", "Family", "register_family", "unregister_family",
           "registered_families", "family_named"]

#: How a family's operators invert: in closed form, by bisection on the input (monotone operators),
#: or not continuously (a staircase reaches only its step values).
INVERSE_KINDS = ("analytic", "bisection", "none (staircase)")


@dataclass(frozen=True)
class FitRequest:
    """What a family's fit receives from :func:`~exudyn_atcm.hysteresis.identify`.

    Attributes
    ----------
    u, y : numpy.ndarray
        The whole record's input and output samples, in time order.
    fit_mask : numpy.ndarray
        Boolean, one per sample: the fitted samples (the others are held out).
    n_fit : int or None
        First held-out sample when the fitted samples are the first ones, else ``None``.
    output_unit : str
        Unit of ``y``.
    output_quantity : str or None
        What ``y`` is (``"strain"``, ``"displacement"``, ...).
    options : mapping
        :func:`~exudyn_atcm.hysteresis.identify`'s family settings (``n_levels``, ``n_plays``,
        ``n_relays``, ``smoothing``, ``prior``, ``reversal_tolerance``, ``levels``,
        ``relays_per_cell``); a family uses those it needs and its own defaults otherwise.
    """

    u: np.ndarray
    y: np.ndarray
    fit_mask: np.ndarray
    n_fit: int | None
    output_unit: str = ""
    output_quantity: str | None = None
    options: Mapping[str, Any] = field(default_factory=dict)

    @property
    def contiguous(self) -> bool:
        """Whether the fitted samples are the first ``n_fit`` ones."""
        return self.n_fit is not None

    @property
    def rows(self) -> dict[str, Any]:
        """The fitted samples as the fits' keywords: ``{"n_fit": n}`` or ``{"fit_mask": mask}``."""
        return {"n_fit": self.n_fit} if self.contiguous else {"fit_mask": self.fit_mask}

    @property
    def units(self) -> dict[str, Any]:
        """``{"output_unit": ..., "output_quantity": ...}``, the fits' keywords."""
        return {"output_unit": self.output_unit, "output_quantity": self.output_quantity}


@dataclass(frozen=True)
class FamilyFit:
    """What a family's fit returns: ``label`` (family and size, e.g. ``"everett (30 levels, pi)"``),
    ``model`` (the identified operator), ``report`` (its
    :class:`~exudyn_atcm.hysteresis.FitReport` on the fitted and the held-out samples) and
    ``parameters`` (the number of identified values: weights, thresholds, gains, offset, ...)."""

    label: str
    model: Any
    report: Any
    parameters: int


@dataclass(frozen=True)
class Family:
    """One registered family (see the module)."""

    name: str
    fit: Callable[[FitRequest], FamilyFit]
    inverse: str
    operator: type | None = None
    description: str = ""

    @property
    def invertible(self) -> bool:
        """Whether its operators have a continuous inverse."""
        return self.inverse != "none (staircase)"


_FAMILIES: dict[str, Family] = {}


def register_family(name: str, fit: Callable[[FitRequest], FamilyFit], *, inverse: str,
                    operator: type | None = None, description: str = "", replace: bool = False) -> Family:
    """Make a family known to :func:`~exudyn_atcm.hysteresis.identify` (and the docs' table).

    Parameters
    ----------
    name : str
        Lower case letters, digits and ``_``, starting with a letter (e.g. ``"bouc_wen"``).
    fit : callable
        ``fit(request: FitRequest) -> FamilyFit``; raises ``ValueError`` when the record does
        not allow the family (the reason is listed in the :class:`~exudyn_atcm.hysteresis.ModelChoice`).
    inverse : {"analytic", "bisection", "none (staircase)"}
        How its operators invert (:meth:`~exudyn_atcm.hysteresis.HysteresisOperator.inverse`).
    operator : type, optional
        The operator class the fit returns (for the docs and for readers).
    description : str, optional
        One line for the family table.
    replace : bool, optional
        Replace a family registered already under ``name`` (default: refuse).

    Returns
    -------
    Family

    Raises
    ------
    ValueError
        For a malformed name, a fit that is not callable, an unknown ``inverse``, or a name
        registered already (without ``replace``).
    """
    if not isinstance(name, str) or not re.fullmatch(r"[a-z][a-z0-9_]*", name):
        raise ValueError(f"name must be lower case letters, digits and '_' starting with a letter, got {shown(name)}")
    if not callable(fit):
        raise ValueError(f"fit must be callable as fit(request) -> FamilyFit, got {shown(fit)}")
    if inverse not in INVERSE_KINDS:
        raise ValueError(f"inverse must be one of {INVERSE_KINDS}, got {shown(inverse)}")
    if operator is not None and not isinstance(operator, type):
        raise ValueError(f"operator must be a class or None, got {shown(operator)}")
    if name in _FAMILIES and not replace:
        raise ValueError(f"name {name!r} is registered already (for {_FAMILIES[name].fit!r}); choose another name "
                         "or pass replace=True")
    family = Family(name, fit, inverse, operator, str(description))
    _FAMILIES[name] = family
    return family


def unregister_family(name: str) -> Family:
    """Remove a registered family (e.g. one a test registered) and return it.

    Raises
    ------
    ValueError
        If no family is registered as ``name``.
    """
    if name not in _FAMILIES:
        raise ValueError(f"name must be a registered family, one of {tuple(_FAMILIES)}, got {shown(name)}")
    return _FAMILIES.pop(name)


def registered_families() -> dict[str, Family]:
    """The registered families, name -> :class:`Family`, in the order they were registered."""
    return dict(_FAMILIES)


def family_named(name: str) -> Family:
    """The family registered as ``name``.

    Raises
    ------
    ValueError
        If there is none (the message lists the registered ones).
    """
    try:
        return _FAMILIES[name]
    except (KeyError, TypeError):
        raise ValueError(f"family must be one of the registered families {tuple(_FAMILIES)}, got {shown(name)}") from None
