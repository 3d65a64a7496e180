"""What a saved hysteresis model holds: the document, written and read (the file itself: :mod:`.model_files`).

A saved model is a JSON document::

    {"format": "exudyn_atcm.hysteresis_model", "format_version": 1, "package_version": "0.2.0",
     "model": {"kind": "prandtl_ishlinskii",
               "params": {"radii": [...], "weights": [...], "p0": 0.5, "offset": 0.0, "input_offset": 0.0},
               "metadata": {"output_quantity": null, "output_unit": "", "fitted_range": null,
                            "fit_info": null, "input_range": null}}}

``kind`` is a name from the registry (:mod:`.model_registry`), never a Python path: loading builds the model from
the registered class of that name and imports or executes nothing the file names.  ``params``
are the arguments of the class's constructor (a nested model, such as the operator inside a
:class:`~exudyn_atcm.hysteresis.dynamics.WithDynamics`, is again a ``{"kind", "params",
"metadata"}`` object), ``metadata`` what a fit records about the model (see
:data:`METADATA_FIELDS`).  Numbers are written with Python's shortest exact representation, so a
loaded model has bit for bit the parameters of the saved one; the operator's memory is not saved
(a loaded model starts from its reset state).

Reading is strict: the format name and version are checked first (a newer version is refused
with the versions involved), every object must hold exactly its fields, every number must be
finite, and the parameters must satisfy the class's constructor; each refusal is a
:class:`ModelFileError` naming the source, the field (``model.params.operator.params.weights[3]``)
and what is allowed.  Adding a family: :mod:`.model_registry`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import shown
from .._version import __version__
from ..suggestions import close_names
from .model_registry import FLOAT, RANGE, ParameterType, kind_named, kind_of, registered_kinds

__all__ = ["FORMAT_NAME", "FORMAT_VERSION", "METADATA_FIELDS", "ModelFileError", "model_document",
           "model_from_document"]

#: The ``format`` field of every saved model.
FORMAT_NAME = "exudyn_atcm.hysteresis_model"
#: The format version this package writes; it reads this one and older ones, and refuses newer ones.
FORMAT_VERSION = 1
#: Metadata of every saved model (nested ones too) and their meaning; the first four are set on the
#: loaded model, ``input_range`` is written for the reader (the loaded model computes its own).
METADATA_FIELDS = {
    "output_quantity": "what the output is ('strain', 'displacement', ...) or null when not stated",
    "output_unit": "unit of the output ('-', 'm', ...; '' when not stated)",
    "fitted_range": "[u_low, u_high]: the input range the model was fitted on, or null",
    "fit_info": "what the fit did (method, settings, sample counts), a JSON object, or null",
    "input_range": "[u_low, u_high]: where the model is valid, or null (informational)",
}
_TOP_FIELDS = ("format", "format_version", "package_version", "model")
_MODEL_FIELDS = ("kind", "params", "metadata")
_MAX_DEPTH = 16


class ModelFileError(ValueError):
    """A saved model that cannot be read; the message names the file, the field, the value and what is allowed."""


# ----------------------------------------------------------------------------- writing
def model_document(model: Any) -> dict:
    """The saved-model document of ``model`` (what :func:`~.model_files.save_model` writes as JSON).

    Raises
    ------
    TypeError
        If the model's class is not registered (the message names the registered kinds).
    ValueError
        If a parameter or metadata value cannot be written (not finite, wrong type), naming it.
    """
    return {"format": FORMAT_NAME, "format_version": FORMAT_VERSION, "package_version": __version__,
            "model": _encode_model(model, "model")}


def _encode_model(model: Any, where: str) -> dict:
    kind = kind_of(model)
    if kind is None:
        cls = type(model)
        raise TypeError(f"cannot save a {cls.__name__} ({where}): no saved-model kind is registered for "
                        f"{cls.__module__}.{cls.__qualname__}; registered: {', '.join(sorted(registered_kinds()))} "
                        "(a new family registers itself with register_model_kind)")
    try:
        values = kind.to_params(model)
    except AttributeError as exc:
        raise TypeError(f"cannot save a {type(model).__name__} ({where}) as kind {kind.name!r}: {exc}") from None
    params = {key: _encode_value(values[key], ptype, f"{where}.params.{key}") for key, ptype in kind.parameters.items()}
    return {"kind": kind.name, "params": params, "metadata": _encode_metadata(model, where + ".metadata")}


def _encode_value(value: Any, ptype: ParameterType, where: str) -> Any:
    if value is None:
        if ptype.optional:
            return None
        raise ValueError(f"cannot save {where}: it is None, allowed: {ptype.describe()}")
    if ptype.name == "model":
        return _encode_model(value, where)
    if ptype.name == "string":
        if not isinstance(value, str):
            raise ValueError(f"cannot save {where}: allowed {ptype.describe()}, got {shown(value)}")
        return value
    if ptype.name == "int":
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
            raise ValueError(f"cannot save {where}: allowed {ptype.describe()}, got {shown(value)}")
        return int(value)
    array = np.asarray(value, dtype=float)
    if ptype.name == "float":
        if array.ndim != 0:
            raise ValueError(f"cannot save {where}: allowed {ptype.describe()}, got an array of shape {array.shape}")
        if not math.isfinite(float(array)):
            raise ValueError(f"cannot save {where}: {float(array)!r} is not finite")
        return float(array)
    if array.ndim != 1 or (ptype.name == "range" and array.size != 2):
        raise ValueError(f"cannot save {where}: allowed {ptype.describe()}, got shape {array.shape}")
    bad = ~np.isfinite(array)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"cannot save {where}[{i}]: {float(array[i])!r} is not finite")
    return array.tolist()


def _encode_metadata(model: Any, where: str) -> dict:
    quantity = getattr(model, "output_quantity", None)
    unit = getattr(model, "output_unit", "")
    if quantity is not None and not isinstance(quantity, str):
        raise ValueError(f"cannot save {where}.output_quantity: allowed a string or None, got {shown(quantity)}")
    if not isinstance(unit, str):
        raise ValueError(f"cannot save {where}.output_unit: allowed a string, got {shown(unit)}")
    fitted = getattr(model, "fitted_range", None)
    fitted = None if fitted is None else _encode_value(fitted, RANGE, where + ".fitted_range")
    info = getattr(model, "fit_info", None)
    if info is not None and not isinstance(info, Mapping):
        raise ValueError(f"cannot save {where}.fit_info: allowed a dict or None, got {type(info).__name__}")
    valid = getattr(model, "input_range", None)
    try:
        valid = None if valid is None else _encode_value(valid, RANGE, where + ".input_range")
    except (TypeError, ValueError):  # informational only: a range that is not a finite pair is not written
        valid = None
    return {"output_quantity": quantity, "output_unit": unit, "fitted_range": fitted,
            "fit_info": None if info is None else _json_data(info, where + ".fit_info"),
            "input_range": valid}


def _json_data(value: Any, where: str) -> Any:
    """``value`` as plain JSON data (numpy numbers and arrays converted); non-finite numbers refused."""
    if isinstance(value, Mapping):
        out = {}
        for key, item in value.items():
            if not isinstance(key, str):
                raise ValueError(f"cannot save {where}: its keys must be strings, got {shown(key)}")
            out[key] = _json_data(item, f"{where}.{key}")
        return out
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return [_json_data(item, f"{where}[{i}]") for i, item in enumerate(value)]
    if value is None or isinstance(value, (str, bool)):
        return value
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        if not math.isfinite(float(value)):
            raise ValueError(f"cannot save {where}: {float(value)!r} is not finite (strict JSON has no NaN or "
                             "Infinity; use None for a missing value)")
        return float(value)
    raise ValueError(f"cannot save {where}: {type(value).__name__!r} values are not JSON data (allowed: dict, "
                     "list, str, number, bool, None)")


# ----------------------------------------------------------------------------- reading
def model_from_document(document: Any, source: str = "document") -> Any:
    """The model a saved-model document describes (see the module), in its reset state.

    Parameters
    ----------
    document : dict
        Parsed JSON (:func:`~.model_files.load_model` reads it from a file).
    source : str, optional
        Where the document comes from, for the messages (a file name).

    Raises
    ------
    ModelFileError
        Wrong format name, a newer format version, an unknown kind, a missing, extra or ill-typed
        field, a non-finite number, or parameters the model's class refuses; the message names
        ``source``, the field and what is allowed.
    """
    where = _Where(source)
    if not isinstance(document, dict):
        raise where.error("", f"must be a JSON object with the fields {', '.join(_TOP_FIELDS)}, got {_kind_of(document)}")
    if "format" not in document:
        raise where.error("", f"is not a saved exudyn_atcm hysteresis model: it has no 'format' field "
                              f"(expected {FORMAT_NAME!r})")
    if document["format"] != FORMAT_NAME:
        raise where.error("format", f"must be {FORMAT_NAME!r} (a saved exudyn_atcm hysteresis model), got "
                                    f"{_kind_of(document['format'])}")
    version = document.get("format_version")
    if isinstance(version, bool) or not isinstance(version, int) or version < 1:
        raise where.error("format_version", f"must be an integer >= 1, got {_kind_of(version)}")
    if version > FORMAT_VERSION:
        raise where.error("format_version", f"is {version}, written by exudyn_atcm "
                                            f"{document.get('package_version')!r}; this exudyn_atcm ({__version__}) reads "
                                            f"format versions up to {FORMAT_VERSION}: upgrade exudyn_atcm to load it")
    _check_fields(document, _TOP_FIELDS, "", where)
    if not isinstance(document["package_version"], str):
        raise where.error("package_version", f"must be a string, got {_kind_of(document['package_version'])}")
    return _decode_model(document["model"], "model", None, where, 0)


@dataclass(frozen=True)
class _Where:
    source: str

    def error(self, field: str, text: str) -> ModelFileError:
        return ModelFileError(f"{self.source}: " + (f"{field} " if field else "") + text)


def _kind_of(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, dict):
        return f"an object with the fields {sorted(value)[:8]}"
    if isinstance(value, list):
        return f"a list of {len(value)} item(s)"
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _check_fields(obj: dict, allowed: tuple[str, ...], where: str, loc: _Where) -> None:
    prefix = f"{where}." if where else ""
    missing = [key for key in allowed if key not in obj]
    if missing:
        raise loc.error(prefix + missing[0], f"is missing (required: {', '.join(allowed)})")
    extra = [key for key in obj if key not in allowed]
    if extra:
        hint = close_names(extra[0], allowed)
        raise loc.error(prefix + extra[0], "is not a field of a saved model here (allowed: " + ", ".join(allowed)
                        + ")" + (f"; did you mean {hint[0]!r}?" if hint else ""))


def _decode_model(obj: Any, where: str, kinds: tuple[str, ...] | None, loc: _Where, depth: int) -> Any:
    if depth > _MAX_DEPTH:
        raise loc.error(where, f"is nested more than {_MAX_DEPTH} models deep")
    if not isinstance(obj, dict):
        raise loc.error(where, f"must be an object with the fields kind, params, metadata, got {_kind_of(obj)}")
    _check_fields(obj, _MODEL_FIELDS, where, loc)
    name = obj["kind"]
    kind = kind_named(name) if isinstance(name, str) else None
    if kind is None:
        known = sorted(registered_kinds())
        hint = close_names(name, known) if isinstance(name, str) else []
        raise loc.error(f"{where}.kind", f"is an unknown model kind {_kind_of(name)}; this exudyn_atcm ({__version__}) "
                        f"knows {', '.join(known)}" + (f" (did you mean {hint[0]!r}?)" if hint else ""))
    if kinds is not None and name not in kinds:
        raise loc.error(f"{where}.kind", f"must be {' or '.join(repr(k) for k in kinds)} here, got {shown(name)}")
    params = obj["params"]
    if not isinstance(params, dict):
        raise loc.error(f"{where}.params", f"must be an object, got {_kind_of(params)}")
    _check_fields(params, tuple(kind.parameters), f"{where}.params", loc)
    values = {key: _decode_value(params[key], ptype, f"{where}.params.{key}", loc, depth)
              for key, ptype in kind.parameters.items()}
    metadata = _decode_metadata(obj["metadata"], f"{where}.metadata", loc)
    try:
        model = kind.from_params(**values)
    except (ValueError, TypeError) as exc:
        raise loc.error(f"{where}.params", f"do not make a {kind.cls.__name__} (kind {name!r}): {exc}") from None
    for key, value in metadata.items():
        if getattr(model, key, None if key != "output_unit" else "") != value:
            setattr(model, key, value)
    return model


def _decode_value(value: Any, ptype: ParameterType, where: str, loc: _Where, depth: int) -> Any:
    if value is None:
        if ptype.optional:
            return None
        raise loc.error(where, f"must be {ptype.describe()}, got null")
    if ptype.name == "model":
        return _decode_model(value, where, ptype.kinds, loc, depth + 1)
    if ptype.name == "string":
        if not isinstance(value, str):
            raise loc.error(where, f"must be {ptype.describe()}, got {_kind_of(value)}")
        return value
    if ptype.name == "int":
        if isinstance(value, bool) or not isinstance(value, int):
            raise loc.error(where, f"must be {ptype.describe()}, got {_kind_of(value)}")
        return value
    if ptype.name == "float":
        return _number(value, where, ptype, loc)
    if not isinstance(value, list) or (ptype.name == "range" and len(value) != 2):
        raise loc.error(where, f"must be {ptype.describe()}, got {_kind_of(value)}")
    numbers = [_number(item, f"{where}[{i}]", FLOAT, loc) for i, item in enumerate(value)]
    return tuple(numbers) if ptype.name == "range" else np.array(numbers, dtype=float)


def _number(value: Any, where: str, ptype: ParameterType, loc: _Where) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise loc.error(where, f"must be {ptype.describe()}, got {_kind_of(value)}")
    try:
        number = float(value)
    except OverflowError:
        number = math.inf
    if not math.isfinite(number):
        raise loc.error(where, f"must be a finite number, got {shown(value)}")
    return number


def _decode_metadata(obj: Any, where: str, loc: _Where) -> dict:
    if not isinstance(obj, dict):
        raise loc.error(where, f"must be an object with the fields {', '.join(METADATA_FIELDS)}, got {_kind_of(obj)}")
    _check_fields(obj, tuple(METADATA_FIELDS), where, loc)
    quantity, unit, fitted, info = (obj[key] for key in ("output_quantity", "output_unit", "fitted_range", "fit_info"))
    if quantity is not None and (not isinstance(quantity, str) or not quantity.strip()):
        raise loc.error(f"{where}.output_quantity", f"must be a non-empty string or null, got {_kind_of(quantity)}")
    if not isinstance(unit, str):
        raise loc.error(f"{where}.output_unit", f"must be a string ('' when not stated), got {_kind_of(unit)}")
    if fitted is not None:
        fitted = _decode_value(fitted, RANGE, f"{where}.fitted_range", loc, 0)
        if fitted[1] < fitted[0]:
            raise loc.error(f"{where}.fitted_range", f"must have high >= low, got {list(fitted)!r}")
    if info is not None:
        if not isinstance(info, dict):
            raise loc.error(f"{where}.fit_info", f"must be an object or null, got {_kind_of(info)}")
        _check_finite(info, f"{where}.fit_info", loc)
    if obj["input_range"] is not None:
        _decode_value(obj["input_range"], RANGE, f"{where}.input_range", loc, 0)
    return {"output_quantity": quantity, "output_unit": unit, "fitted_range": fitted, "fit_info": info}


def _check_finite(value: Any, where: str, loc: _Where) -> None:
    if isinstance(value, dict):
        for key, item in value.items():
            _check_finite(item, f"{where}.{key}", loc)
    elif isinstance(value, list):
        for i, item in enumerate(value):
            _check_finite(item, f"{where}[{i}]", loc)
    elif isinstance(value, float) and not math.isfinite(value):
        raise loc.error(where, f"must be finite, got {shown(value)}")
