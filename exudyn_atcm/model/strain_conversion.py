r"""From a measured displacement to the free strain a drive needs: arrays, records and fitted models.

A :class:`~exudyn_atcm.model.drive.PiezoDrive` takes the *free strain* ``Λ`` [-] of the active
layer (the strain an MFC patch reaches unloaded), while actuators are usually measured by a
displacement.  Two measurements convert exactly:

* **a free patch** whose elongation ``Δl`` is measured over the gauge length ``l₀`` (the
  distance between the points whose displacement is taken): ``Λ = Δl / l₀``
  (:func:`strain_from_displacement`);
* **a free bender** (a cantilever with no load at its tip) whose deflection ``δ`` is measured at
  the arc length ``s`` from the clamp (``s = L`` at the tip), perpendicular to the clamp's axis.
  The strain mismatch bends the laminate to the uniform curvature (classical lamination theory;
  Timoshenko 1925, the bimetal)

  .. math::

     \kappa = \frac{a_1 a_2}{a_1 + a_2}\,\frac{e\,\Lambda}{EI},\qquad
     EI = E_1 I_1 + E_2 I_2 + \frac{a_1 a_2}{a_1 + a_2} e^2,

  (``a_i = E_i b h_i``, ``e = (h_1 + h_2)/2``: :attr:`~exudyn_atcm.model.laminate.Laminate.curvature_per_strain`,
  which also holds the paper's stiffness variant), and the point lies on the circular arc
  ``δ = (1 − cos κs)/κ``, or ``δ = κ s²/2`` for small deflections (:func:`strain_from_tip_deflection`).

A record is converted before it is identified (:func:`record_to_strain`: exact, the arc
included); a model identified on the displacement is converted by scaling its output
(:func:`model_to_strain`, via :func:`~exudyn_atcm.hysteresis.output_scale.scaled_output`): exact
for a free patch, the small-deflection line for a bender (the arc is not a scale; an
:class:`~exudyn_atcm.errors.AccuracyWarning` says when the line is more than
:data:`LINEAR_DEFLECTION_TOLERANCE` off at the model's largest output).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from typing import Any

import numpy as np

from .._checks import finite_array, positive_float, warn_implausible
from ..errors import AccuracyWarning
from ..hysteresis.output_scale import scaled_output
from ..io.record import Record
from ..io.units import is_length, si_scale
from .laminate import Laminate

__all__ = [
    "ARC_TURN_LIMIT",
    "LINEAR_DEFLECTION_TOLERANCE",
    "strain_from_displacement",
    "strain_from_tip_deflection",
    "record_to_strain",
    "model_to_strain",
]

#: ``κs`` [rad] where the arc's deflection ``(1 − cos κs)/κ`` is largest (the root of
#: ``x sin x = 1 − cos x``); beyond it the deflection falls again, so a deflection is converted
#: on the branch ``|κs| <= ARC_TURN_LIMIT`` (deflections up to 0.7246 s).
ARC_TURN_LIMIT = 2.331122370414423

#: Relative strain error of the small-deflection line above which :func:`model_to_strain` warns.
LINEAR_DEFLECTION_TOLERANCE = 0.005


def strain_from_displacement(displacement: Any, gauge_length: float) -> Any:
    """Free strain ``Λ = Δl / l₀`` [-] of a patch whose elongation ``Δl`` [m] is measured over ``l₀`` [m].

    Parameters
    ----------
    displacement : float or array_like
        Elongation ``Δl`` [m] (finite).
    gauge_length : float
        Distance ``l₀`` [m] over which it is measured, ``> 0``.

    Returns
    -------
    float or numpy.ndarray
        Like ``displacement``.
    """
    length = positive_float("gauge_length", gauge_length)
    scalar = np.ndim(displacement) == 0
    strain = finite_array("displacement", [displacement] if scalar else displacement, min_length=0) / length
    return float(strain[0]) if scalar else strain


def _geometry(laminate: Any, length: float | None) -> tuple[float, float]:
    """``(curvature per unit strain [1/m], s [m])`` of a Laminate and length, or of an object with ``laminate``/``length``."""
    owner = laminate
    if not isinstance(laminate, Laminate):
        laminate = getattr(owner, "laminate", None)
        if not isinstance(laminate, Laminate):
            raise ValueError(
                f"laminate must be a Laminate or a bender with one (BendingActuator, Bender), got {type(owner).__name__}"
            )
        if length is None:
            length = getattr(owner, "length", None)
    if length is None:
        raise ValueError("length must be the arc length [m] from the clamp to the measured point, got None")
    s = positive_float("length", length)
    per_strain = laminate.curvature_per_strain
    if per_strain == 0.0:
        raise ValueError("laminate has no active layer (active=None): a strain does not bend it")
    return per_strain, s


def strain_from_tip_deflection(deflection: Any, laminate: Any, length: float | None = None, *,
                               linear: bool = False) -> Any:
    r"""Free strain ``Λ`` [-] of a free bender whose deflection ``δ`` [m] is measured at arc length ``length``.

    Inverts ``δ = (1 − cos κs)/κ`` (``linear``: ``δ = κ s²/2``) for the curvature ``κ`` and
    returns ``Λ = κ / (curvature per unit strain)`` (see the module).  Exact for an unloaded
    cantilever of uniform laminate, whose free curvature is uniform; the package's geometrically
    exact cells reproduce it (``tests/test_strain_conversion.py``).

    Parameters
    ----------
    deflection : float or array_like
        Deflection ``δ`` [m] perpendicular to the clamp's axis, positive towards the passive
        layer's side (the side the bender curls to for positive strain).
    laminate : Laminate, or an object with ``laminate`` (and ``length``)
        The cross-section, e.g. ``actuator.laminate`` or a
        :class:`~exudyn_atcm.mechanism.actuator.BendingActuator` itself.
    length : float, optional
        Arc length ``s`` [m] from the clamp to the measured point; default the object's
        ``length`` (the tip) when ``laminate`` has one.
    linear : bool, optional
        Use the small-deflection line ``δ = κ s²/2`` (default ``False``: the arc).  The line is
        ``κ²s²/12`` off (relative), 1.1 % at the paper's 15.5 mm on 87 mm.

    Returns
    -------
    float or numpy.ndarray
        Like ``deflection``.

    Raises
    ------
    ValueError
        For a deflection beyond the arc's largest, ``0.7246 s`` (at ``κs =`` :data:`ARC_TURN_LIMIT`),
        a laminate without an active layer, a non-positive length.
    """
    per_strain, s = _geometry(laminate, length)
    scalar = np.ndim(deflection) == 0
    delta = finite_array("deflection", [deflection] if scalar else deflection, min_length=0)
    if linear:
        kappa = 2.0 * delta / s**2
    else:
        limit = _arc_limit(s)
        beyond = np.abs(delta) > limit
        if beyond.any():
            bad = float(delta[np.argmax(beyond)])
            raise ValueError(
                f"deflection = {bad!r} m is beyond the largest deflection of a uniformly curved cantilever at "
                f"length = {s!r} m: {limit:.6g} m (0.7246 length, at a turn of {ARC_TURN_LIMIT:.4f} rad); check the "
                "units (metres) and the length"
            )
        kappa = _arc_curvature(delta / s) / s
    strain = kappa / per_strain
    return float(strain[0]) if scalar else strain


def _arc_limit(s: float) -> float:
    """The largest deflection [m] of a uniformly curved cantilever at arc length ``s`` [m]."""
    return s * (1.0 - math.cos(ARC_TURN_LIMIT)) / ARC_TURN_LIMIT


def _arc_curvature(ratio: np.ndarray) -> np.ndarray:
    """``x`` with ``(1 − cos x)/x = ratio`` on ``|x| <= ARC_TURN_LIMIT`` (safeguarded Newton from the line's ``2 ratio``).

    ``1 − cos x`` is evaluated as ``2 sin²(x/2)``, without the cancellation at small ``x``.
    """
    sign = np.sign(ratio)
    r = np.abs(ratio)
    lo, hi = np.zeros_like(r), np.full_like(r, ARC_TURN_LIMIT)
    x = np.minimum(2.0 * r, ARC_TURN_LIMIT)
    for _ in range(100):
        safe = np.where(x > 0.0, x, 1.0)
        half = 2.0 * np.sin(0.5 * safe) ** 2 / safe
        f = np.where(x > 0.0, half, 0.0) - r
        df = np.where(x > 0.0, np.sin(safe) / safe - half / safe, 0.5)
        lo = np.where(f < 0.0, x, lo)
        hi = np.where(f > 0.0, x, hi)
        step = x - f / df
        x_new = np.where((step >= lo) & (step <= hi), step, 0.5 * (lo + hi))
        done = np.all(np.abs(x_new - x) <= 4e-16 * x_new)
        x = x_new
        if done:
            break
    return sign * x


def _output_metres(unit: str, what: str) -> float:
    """The factor from ``unit`` to metres; refuses a unit that is not a length (with what to do)."""
    if not is_length(unit):
        stated = f"{unit!r}" if unit else "not stated (unknown)"
        raise ValueError(
            f"{what}: the output unit is {stated}, not a length (m, mm, um, ...), so it is not a displacement this "
            "converts; give the unit (read_record(..., units={'output': 'um'}), or output_unit= here) or, if the "
            "output already is the free strain, use it as it is"
        )
    return si_scale(unit)[0]


def _conversion(gauge_length: Any, laminate: Any, length: Any) -> str:
    if (gauge_length is None) == (laminate is None):
        raise ValueError(
            "give either gauge_length (a free patch's elongation over that length) or laminate and length (a free "
            f"bender's deflection at that arc length), got gauge_length = {gauge_length!r} and laminate = "
            f"{type(laminate).__name__ if laminate is not None else None}"
        )
    return "patch" if gauge_length is not None else "bender"


def record_to_strain(record: Record, *, gauge_length: float | None = None, laminate: Any = None,
                     length: float | None = None, linear: bool = False) -> Record:
    """The record with its displacement output converted to the free strain [-] (then identify it).

    Parameters
    ----------
    record : Record
        A record whose output unit is a length (``m``, ``mm``, ``um``, ...).
    gauge_length : float, optional
        A free patch: the length ``l₀`` [m] over which the elongation was measured
        (:func:`strain_from_displacement`).
    laminate, length : optional
        A free bender: its cross-section and the arc length [m] of the measured point
        (:func:`strain_from_tip_deflection`; ``linear`` as there).

    Returns
    -------
    Record
        Output in strain (unit ``"-"``, name ``"free strain"``), the conversion in ``processing``.

    Raises
    ------
    ValueError
        If the output unit is not a length (an unknown unit included: give it to
        :func:`~exudyn_atcm.io.measurements.read_record` with ``units=``), or neither or both
        conversions are given.
    """
    if not isinstance(record, Record):
        raise ValueError(f"record must be a Record (see read_record), got {type(record).__name__}")
    to_metres = _output_metres(record.units.get("output", ""), "record")
    displacement = record.output * to_metres
    if _conversion(gauge_length, laminate, length) == "patch":
        strain = strain_from_displacement(displacement, gauge_length)
        how = f"free strain = displacement / gauge length {float(gauge_length):g} m"
    else:
        strain = strain_from_tip_deflection(displacement, laminate, length, linear=linear)
        per_strain, s = _geometry(laminate, length)
        how = (f"free strain from a free bender's deflection at {s:g} m ({'line kappa s^2/2' if linear else 'arc'}, "
               f"curvature per strain {per_strain:.6g} 1/m)")
    units = {**record.units, "output": "-"}
    names = {**record.names, "output": "free strain"}
    return replace(record, output=strain, units=units, names=names,
                   processing=record.processing + (f"output converted from {record.units['output']}: {how}",))


def _largest_output(model: Any) -> float | None:
    """The largest output magnitude of ``model`` over its input range (a major loop), ``None`` if unknown."""
    inner, gain = model, 1.0
    lags = getattr(model, "lags", None)
    if lags is not None and getattr(model, "operator", None) is not None:
        inner, gain = model.operator, lags.static_gain
    elif getattr(model, "creep", None) is not None and getattr(model, "hysteresis", None) is not None:
        inner, gain = model.hysteresis, model.creep.long_term_gain
    bounds = getattr(inner, "fitted_range", None) or getattr(inner, "input_range", None)
    if bounds is None or not callable(getattr(inner, "apply", None)):
        return None
    lo, hi = float(bounds[0]), float(bounds[1])
    ramp = np.linspace(lo, hi, 101)
    outputs = np.asarray(inner.apply(np.concatenate([ramp, ramp[::-1]])), dtype=float)
    return float(np.max(np.abs(outputs))) * abs(gain)


def model_to_strain(model: Any, *, gauge_length: float | None = None, laminate: Any = None,
                    length: float | None = None, output_unit: str | None = None) -> Any:
    """A model identified on a displacement, as the model of the free strain a drive takes.

    A new operator of the model's class with its output scaled
    (:func:`~exudyn_atcm.hysteresis.output_scale.scaled_output`), ``output_quantity = "strain"``,
    ``output_unit = "-"``; its input range and fit information are kept.  Factor: ``1/l₀`` (a
    free patch; exact) or ``2/(c s²)`` (a free bender, ``c`` the curvature per unit strain; the
    small-deflection line: exact for small deflections, ``κ²s²/12`` off for larger ones, which an
    :class:`~exudyn_atcm.errors.AccuracyWarning` reports above
    :data:`LINEAR_DEFLECTION_TOLERANCE` at the model's largest output over its input range;
    convert the record with :func:`record_to_strain` instead, which is exact).

    Parameters
    ----------
    model : operator
        Fitted on a displacement: its ``output_unit`` (or ``output_unit`` here) is a length.
    gauge_length, laminate, length :
        As :func:`record_to_strain`.
    output_unit : str, optional
        The model's output unit where the model does not state it (``"m"``, ``"um"``, ...).

    Raises
    ------
    ValueError
        If the output unit is not a length, the model already gives a strain, neither or both
        conversions are given, or the model's class cannot be scaled.
    """
    quantity = getattr(model, "output_quantity", None)
    if quantity == "strain":
        raise ValueError(f"model already gives the free strain (output_quantity = 'strain'); use it as it is")
    stated = getattr(model, "output_unit", "") or ""
    unit = stated if output_unit is None else output_unit
    if output_unit is not None and stated and stated != output_unit and is_length(stated):
        raise ValueError(f"output_unit = {output_unit!r} conflicts with the model's own output_unit {stated!r}")
    to_metres = _output_metres(unit, "model")
    if _conversion(gauge_length, laminate, length) == "patch":
        metres_per_strain = positive_float("gauge_length", gauge_length)
        warn_implausible("gauge_length", metres_per_strain, "length", "model_to_strain")  # 60 for 60 mm: strains /1000
        note = f"displacement [{unit}] over gauge length {metres_per_strain:g} m"
    else:
        per_strain, s = _geometry(laminate, length)
        metres_per_strain = 0.5 * per_strain * s**2
        note = f"free bender's deflection [{unit}] at {s:g} m, small-deflection line (curvature per strain {per_strain:.6g} 1/m)"
        largest = _largest_output(model)
        if largest is not None and largest > 0.0:
            delta = min(largest * to_metres, _arc_limit(s))
            exact = strain_from_tip_deflection(delta, laminate, s)
            error = abs(delta / metres_per_strain / exact - 1.0)
            if error > LINEAR_DEFLECTION_TOLERANCE:
                warnings.warn(
                    f"model_to_strain: the model reaches a deflection of {delta:.4g} m at {s:g} m, where the "
                    f"small-deflection line is {100 * error:.2g} % off the arc (more than "
                    f"{100 * LINEAR_DEFLECTION_TOLERANCE:g} %); convert the record with record_to_strain (exact) and "
                    "identify the strain model from it",
                    AccuracyWarning,
                    stacklevel=2,
                )
    return scaled_output(model, to_metres / metres_per_strain, quantity="strain", unit="-", note=note)

