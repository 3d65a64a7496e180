"""The registry of saved-model kinds: kind name -> class, constructor parameters and their types.

A kind is what a saved model file (:mod:`.model_format`) names instead of a Python path: loading
looks the name up here and builds the registered class, and imports or executes nothing the file
names.  The package's own kinds are registered in :mod:`.model_kinds`.

Adding a family (e.g. a new rate-dependent operator) is one call::

    from exudyn_atcm.hysteresis.model_registry import FLOAT, FLOATS, nested, register_model_kind

    register_model_kind("my_operator", MyOperator, {"edges": FLOATS, "weights": FLOATS, "T": FLOAT,
                                                    "creep": nested("creep", optional=True)})

with the type of each constructor parameter (:data:`FLOAT`, :data:`FLOATS`, :data:`INT`,
:data:`RANGE`, :data:`STRING`, :func:`nested` for a parameter that is itself a model).  By default
the parameters are read from the model's attributes of the same names and the model is built as
``cls(**params)``; ``to_params``/``from_params`` replace either where the names differ.  Give the
class the ``save`` method by deriving it from
:class:`~exudyn_atcm.hysteresis.HysteresisOperator` (or
:class:`~exudyn_atcm.hysteresis.model_files.SavableModel`), and put the registration where the
class is imported with the package (e.g. in :mod:`.model_kinds`).  A change of a kind's
parameters that old files cannot satisfy needs a new kind name or a new format version.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from .._checks import shown

__all__ = ["FLOAT", "FLOATS", "INT", "RANGE", "STRING", "ParameterType", "ModelKind", "nested",
           "register_model_kind", "unregister_model_kind", "registered_kinds", "kind_named", "kind_of"]


@dataclass(frozen=True)
class ParameterType:
    """Type of one constructor parameter in a saved model.

    ``name`` is one of ``"float"`` (a finite number), ``"floats"`` (a list of finite numbers),
    ``"int"`` (an integer), ``"range"`` (two finite numbers), ``"string"`` or ``"model"`` (a
    nested model; ``kinds`` restricts its kind); ``optional`` allows ``null`` (``None``).
    """

    name: str
    optional: bool = False
    kinds: tuple[str, ...] | None = None

    def describe(self) -> str:
        """The allowed values in words."""
        text = {"float": "a finite number", "floats": "a list of finite numbers", "int": "an integer",
                "range": "a list of two finite numbers [low, high]", "string": "a string",
                "model": "a saved model object {kind, params, metadata}"}[self.name]
        if self.kinds:
            text += " of kind " + " or ".join(repr(k) for k in self.kinds)
        return text + (" or null" if self.optional else "")


FLOAT = ParameterType("float")
FLOATS = ParameterType("floats")
INT = ParameterType("int")
RANGE = ParameterType("range")
STRING = ParameterType("string")


def nested(*kinds: str, optional: bool = False) -> ParameterType:
    """A parameter that is itself a saved model (of one of ``kinds``; any registered kind if none)."""
    return ParameterType("model", optional, tuple(kinds) or None)


@dataclass(frozen=True)
class ModelKind:
    """One registered kind: its name in files, its class, its parameters, and how to get and use them."""

    name: str
    cls: type
    parameters: Mapping[str, ParameterType]
    to_params: Callable[[Any], Mapping[str, Any]]
    from_params: Callable[..., Any]


_KINDS: dict[str, ModelKind] = {}
_BY_CLASS: dict[type, ModelKind] = {}


def register_model_kind(name: str, cls: type, parameters: Mapping[str, ParameterType], *,
                        to_params: Callable[[Any], Mapping[str, Any]] | None = None,
                        from_params: Callable[..., Any] | None = None) -> ModelKind:
    """Make instances of ``cls`` savable and loadable as kind ``name``.

    Parameters
    ----------
    name : str
        The kind's name in files: lower case letters, digits and ``_``, starting with a letter.
    cls : type
        The model class.  Exactly this class is saved under ``name`` (a subclass needs its own kind).
    parameters : mapping of str to ParameterType
        Constructor parameter -> its type (:data:`FLOAT`, :data:`FLOATS`, :data:`INT`,
        :data:`RANGE`, :data:`STRING`, :func:`nested`), in the order they are written.
    to_params : callable, optional
        ``model -> {parameter: value}``; default: the model's attributes of the same names.
    from_params : callable, optional
        ``(**params) -> model``; default: ``cls(**params)``.

    Returns
    -------
    ModelKind

    Raises
    ------
    ValueError
        For a malformed name or parameter type, or a name or class registered already for
        another class or name (registering the same class under the same name again replaces it).
    """
    if not isinstance(name, str) or not re.fullmatch(r"[a-z][a-z0-9_]*", name):
        raise ValueError(f"name must be lower case letters, digits and '_' starting with a letter, got {shown(name)}")
    if not isinstance(cls, type):
        raise ValueError(f"cls must be a class, got {shown(cls)}")
    for key, kind in parameters.items():
        if not isinstance(kind, ParameterType):
            raise ValueError(f"parameters[{key!r}] must be a ParameterType (FLOAT, FLOATS, INT, RANGE, STRING or "
                             f"nested(...)), got {shown(kind)}")
    old = _KINDS.get(name)
    if old is not None and _qualified(old.cls) != _qualified(cls):
        raise ValueError(f"name {name!r} is registered already for {_qualified(old.cls)}; choose another name")
    for other in _KINDS.values():
        if other.cls is cls and other.name != name:
            raise ValueError(f"cls {_qualified(cls)} is registered already as {other.name!r}")
    fields = tuple(parameters)
    kind = ModelKind(name, cls, dict(parameters),
                     to_params or (lambda model: {key: getattr(model, key) for key in fields}),
                     from_params or cls)
    if old is not None:
        _BY_CLASS.pop(old.cls, None)
    _KINDS[name] = kind
    _BY_CLASS[cls] = kind
    return kind


def unregister_model_kind(name: str) -> ModelKind:
    """Remove a registered kind (e.g. one a test registered) and return it.

    Raises
    ------
    ValueError
        If no kind is registered as ``name``.
    """
    kind = _KINDS.pop(name, None) if isinstance(name, str) else None
    if kind is None:
        raise ValueError(f"name must be a registered kind, one of {tuple(_KINDS)}, got {shown(name)}")
    _BY_CLASS.pop(kind.cls, None)
    return kind


def registered_kinds() -> dict[str, type]:
    """The registered kinds: name -> class."""
    return {name: kind.cls for name, kind in _KINDS.items()}


def _qualified(cls: type) -> str:
    return f"{cls.__module__}.{cls.__qualname__}"



def kind_named(name: str) -> ModelKind | None:
    """The kind registered as ``name`` (``None`` if there is none)."""
    return _KINDS.get(name)


def kind_of(model: Any) -> ModelKind | None:
    """The kind registered for exactly the class of ``model`` (``None`` if there is none)."""
    return _BY_CLASS.get(type(model))
