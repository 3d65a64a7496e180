"""Saved hysteresis models: ``model.save(path)`` and :func:`load_model` (JSON, no pickle).

What the file holds and how a new family registers itself: :mod:`exudyn_atcm.hysteresis.model_format`;
the kinds the package registers: :mod:`exudyn_atcm.hysteresis.model_kinds`.

* :func:`save_model` (and the ``save`` method of every operator and wrapper) writes the model's
  constructor parameters and metadata as strict JSON (no NaN or Infinity), atomically
  (:func:`~exudyn_atcm.io.atomic.write_text`: a reader never sees half a file).  An existing file
  is replaced, as any save does.  The same model always gives the same bytes (no time stamp), so
  a file's hash changes exactly when the model does.
* :func:`load_model` reads it back: the same class with bit for bit the same parameters and
  metadata, in its reset state (the committed memory is not saved).  It refuses, naming the file
  and the field, whatever is not a saved model of a kind this package knows.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from ..io.atomic import write_text
from .model_format import ModelFileError, model_document, model_from_document

__all__ = ["save_model", "load_model", "model_text", "SavableModel"]


def model_text(model: Any) -> str:
    """The JSON text :func:`save_model` writes for ``model`` (two-space indent, number lists on one line)."""
    return _format(model_document(model), 0) + "\n"


def save_model(model: Any, path: str | os.PathLike) -> Path:
    """Write ``model`` to ``path`` as a saved-model JSON file (replacing an existing file).

    Parameters
    ----------
    model : hysteresis operator or wrapper
        Any model of a registered kind (:func:`~exudyn_atcm.hysteresis.model_format.registered_kinds`).
    path : str or os.PathLike
        Target file (``.json`` by convention), in an existing directory.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    TypeError
        If the model's class has no registered kind.
    ValueError
        If a parameter or metadata value is not finite or not JSON data (naming it), or the
        directory does not exist.
    exudyn_atcm.io.atomic.WriteError
        If the file cannot be written.
    """
    text = model_text(model)
    return write_text(path, text)


def load_model(path: str | os.PathLike) -> Any:
    """The model saved in ``path`` (by :func:`save_model` or ``model.save``), in its reset state.

    Parameters
    ----------
    path : str or os.PathLike
        A saved-model JSON file.

    Returns
    -------
    hysteresis operator or wrapper
        Of the class the file's ``kind`` names, with the saved parameters and metadata
        (``output_quantity``, ``output_unit``, ``fitted_range``, ``fit_info``).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    ModelFileError
        (a ``ValueError``) If the file is not UTF-8 JSON, holds NaN or Infinity or a key twice, is
        not a saved model, has a newer format version, an unknown kind, a missing, extra or
        ill-typed field or parameters its class refuses; the message names the file and the field.
    """
    source = os.fspath(path)
    file = Path(path)
    if not file.exists():
        raise FileNotFoundError(f"no saved model at {source!r}: the file does not exist")
    if file.is_dir():
        raise ModelFileError(f"{source}: is a directory, not a saved model file")
    try:
        text = file.read_bytes().decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ModelFileError(f"{source}: is not a saved model: not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    return model_from_document(_parse(text, source), source)


class SavableModel:
    """Gives a model class the :meth:`save` method (its kind must be registered, see :mod:`.model_format`)."""

    def save(self, path: str | os.PathLike) -> Path:
        """Write this model to ``path`` as JSON; read it back with :func:`~exudyn_atcm.load_model`.

        The file holds the constructor parameters (bit for bit), the output quantity and unit,
        the fitted input range and the fit settings, the package and format version; not the
        memory (the loaded model starts from its reset state).  An existing file is replaced
        (atomically).  See :func:`~exudyn_atcm.hysteresis.model_files.save_model`.

        Returns
        -------
        pathlib.Path
            ``path``.
        """
        return save_model(self, path)


def _format(value: Any, level: int) -> str:
    """JSON of ``value``: objects and lists of objects indented, lists of numbers on one line."""
    pad = "  " * (level + 1)
    if isinstance(value, dict) and value:
        items = [f"{pad}{json.dumps(key)}: {_format(item, level + 1)}" for key, item in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + "  " * level + "}"
    if isinstance(value, list) and any(isinstance(item, (dict, list)) for item in value):
        return "[\n" + ",\n".join(pad + _format(item, level + 1) for item in value) + "\n" + "  " * level + "]"
    return json.dumps(value, allow_nan=False, ensure_ascii=False)


def _parse(text: str, source: str) -> Any:
    """Strict JSON: no NaN/Infinity, no key twice; errors as :class:`ModelFileError` naming ``source``."""

    def constant(name: str) -> Any:
        raise ModelFileError(f"{source}: holds {name}, which strict JSON and a saved model do not allow")

    def pairs(items: list[tuple[str, Any]]) -> dict:
        out: dict = {}
        for key, value in items:
            if key in out:
                raise ModelFileError(f"{source}: the field {key!r} appears twice in one object")
            out[key] = value
        return out

    try:
        return json.loads(text, parse_constant=constant, object_pairs_hook=pairs)
    except json.JSONDecodeError as exc:
        raise ModelFileError(f"{source}: is not a saved model: not JSON (line {exc.lineno} column {exc.colno}: "
                             f"{exc.msg})") from None
    except RecursionError:
        raise ModelFileError(f"{source}: is not a saved model: nested too deeply") from None
