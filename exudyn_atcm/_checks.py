"""Argument checks shared by the package: each raises ``ValueError`` naming the
parameter, the value received and what is allowed."""

from __future__ import annotations

import dataclasses
import inspect
import math
import warnings
from typing import Any

import numpy as np

from .errors import AtcmDeprecationWarning, InputRangeWarning


def shown(value: Any) -> str:
    """``value`` for a message: its repr, a NumPy scalar as its Python value (``-1.0``, not ``np.float64(-1.0)``,
    which NumPy 2 writes), in a tuple or list too."""
    if isinstance(value, np.generic):
        return repr(value.item())
    if isinstance(value, (tuple, list)) and any(isinstance(v, np.generic) for v in value):
        items = [v.item() if isinstance(v, np.generic) else v for v in value]
        return repr(tuple(items) if isinstance(value, tuple) else items)
    return repr(value)


def _short(value: Any) -> str:
    """:func:`shown`, cut at 80 characters."""
    text = shown(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _not_a_number(value: Any) -> bool:
    """True for what ``float()`` would accept but is not a number: text (``"5"``, ``b"5"``) and booleans."""
    return isinstance(value, (str, bytes, bytearray, bool, np.bool_))


def finite_float(name: str, value: Any) -> float:
    """Return ``value`` as a float; raise ``ValueError`` unless it is a finite real number.

    Text (``"5"``) and booleans are refused although ``float()`` would take them: a number read from a
    file or typed on a command line is converted where it is read, with its own message.
    """
    if _not_a_number(value):
        raise ValueError(f"{name} must be a finite real number, got {_short(value)} "
                         f"({type(value).__name__}; pass a float)")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a finite real number, got {_short(value)}") from None
    if not math.isfinite(number):
        raise ValueError(f"{name} must be a finite real number, got {_short(value)}")
    return number


def positive_float(name: str, value: Any) -> float:
    """Return ``value`` as a float; raise ``ValueError`` unless it is finite and > 0."""
    number = finite_float(name, value)
    if number <= 0.0:
        raise ValueError(f"{name} must be > 0, got {_short(value)}")
    return number


def positive_int(name: str, value: Any) -> int:
    """Return ``value`` as an int; raise ``ValueError`` unless it is an integer >= 1."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be an integer >= 1, got {_short(value)}")
    if value < 1:
        raise ValueError(f"{name} must be an integer >= 1, got {_short(value)}")
    return int(value)


def finite_array(name: str, value: Any, *, min_length: int = 1) -> np.ndarray:
    """Return ``value`` as a 1-D float array of finite numbers with at least ``min_length`` entries."""
    try:
        raw = np.asarray(value)
        if raw.dtype.kind not in "iuf" and raw.size:  # text, booleans, objects: not numbers
            raise TypeError
        array = raw.astype(float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a 1-D sequence of finite numbers, got {_short(value)}") from None
    if array.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got an array of shape {array.shape}")
    if array.size < min_length:
        raise ValueError(f"{name} must hold at least {min_length} value(s), got {array.size}")
    bad = ~np.isfinite(array)
    if bad.any():
        index = int(np.argmax(bad))
        raise ValueError(f"{name} must hold finite numbers only, got {float(array[index])!r} at index {index}")
    return array


def sample_times(name: str, t: Any, n: int) -> np.ndarray:
    """``t`` as a strictly increasing array of ``n`` finite sample times [s], or ``ValueError`` naming ``name``."""
    t_a = finite_array(name, t)
    if t_a.size != n:
        raise ValueError(f"{name} must have one time per sample ({n}), got {t_a.size}")
    if t_a.size > 1 and np.any(np.diff(t_a) <= 0.0):
        k = int(np.argmax(np.diff(t_a) <= 0.0)) + 1
        raise ValueError(f"{name} must be strictly increasing, got {name}[{k}] = {float(t_a[k])!r} after {float(t_a[k - 1])!r}")
    return t_a


def same_length(names: tuple[str, ...], arrays: tuple[np.ndarray, ...]) -> None:
    """Raise ``ValueError`` unless all arrays have the same length."""
    lengths = [len(a) for a in arrays]
    if len(set(lengths)) > 1:
        described = ", ".join(f"{n} has {k}" for n, k in zip(names, lengths))
        raise ValueError(f"{', '.join(names)} must have the same length: {described}")


#: Plausible magnitudes of geometric inputs (SI): ``(low, high, unit, likely mistake)``.  An A-TCM
#: bender, flexure or link is millimetres to a metre long; outside this a unit slip is likely.
PLAUSIBLE_GEOMETRY = {
    "length": (1e-4, 2.0, "m", "a length in mm passed as metres"),
    "position": (0.0, 10.0, "m", "a coordinate in mm passed as metres"),
    "angle": (0.0, 2.0 * math.pi, "rad", "an angle in degrees passed as radians"),
}


def warn_implausible(name: str, value: float, kind: str, owner: str, *, stacklevel: int = 3) -> None:
    """Warn (``RuntimeWarning``) when ``|value|`` lies outside :data:`PLAUSIBLE_GEOMETRY` ``[kind]``."""
    low, high, unit, mistake = PLAUSIBLE_GEOMETRY[kind]
    if not low <= abs(float(value)) <= high:
        warnings.warn(
            f"{owner}: {name} = {float(value)!r} {unit} is outside the plausible range "
            f"{'|value| <= ' if low == 0.0 else f'{low:g} ... '}{high:g} {unit}; is it {mistake}? "
            "All values are SI units",
            InputRangeWarning,
            stacklevel=stacklevel,
        )


def options_from_keywords(function: str, legacy: dict[str, Any], **groups: tuple[type, Any]) -> tuple[Any, ...]:
    """The option objects of ``function`` with the keywords of its earlier, flat signature merged in.

    Parameters
    ----------
    function : str
        Name of the public function (for the messages).
    legacy : dict
        The keyword arguments that are fields of the option classes (the earlier signature's).
    **groups : (type, object or None)
        Per option parameter (``options=``, ``run=``): its dataclass and the value received.

    Returns
    -------
    tuple
        One instance per group, in the order given: the value received, or the class's defaults
        with the earlier keywords filled in (warns
        :class:`~exudyn_atcm.errors.AtcmDeprecationWarning` naming where they go now).

    Raises
    ------
    TypeError
        For an unknown keyword, an option parameter of the wrong type, or a field given both as
        a keyword and in its option object.
    """
    owner = {f.name: group for group, (cls, _) in groups.items() for f in dataclasses.fields(cls)}
    unknown = [name for name in legacy if name not in owner]
    if unknown:
        raise TypeError(f"{function}() got an unexpected keyword argument {unknown[0]!r}")
    out = []
    for group, (cls, given) in groups.items():
        if given is not None and not isinstance(given, cls):
            raise TypeError(f"{function}(): {group} must be a {cls.__name__}, got {_short(given)}")
        mine = {name: value for name, value in legacy.items() if owner[name] == group}
        if mine and given is not None:
            raise TypeError(f"{function}(): {', '.join(mine)} given both as keywords and in {group}=")
        out.append(cls(**mine) if mine else given if given is not None else cls())
    if legacy:
        where = "; ".join(f"{', '.join(n for n in legacy if owner[n] == g)} into {g}={groups[g][0].__name__}(...)"
                          for g in groups if any(owner[n] == g for n in legacy))
        warnings.warn(f"{function}(): pass {where} (the flat keywords go away in the next release)",
                      AtcmDeprecationWarning, stacklevel=3)
    return tuple(out)


def option_values(options: Any) -> tuple[Any, ...]:
    """The fields of a dataclass instance in their order, not copied (unlike ``dataclasses.astuple``)."""
    return tuple(getattr(options, f.name) for f in dataclasses.fields(options))


def hide_keywords(function: Any) -> Any:
    """Give ``function`` the signature without its ``**legacy`` catch-all (returns the same object)."""
    sig = inspect.signature(function)
    function.__signature__ = sig.replace(
        parameters=[p for p in sig.parameters.values() if p.kind is not inspect.Parameter.VAR_KEYWORD])
    return function
