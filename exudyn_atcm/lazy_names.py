"""Package faces whose names are imported on first use (PEP 562), so that ``import exudyn_atcm`` is cheap.

A face (a package's ``__init__``) lists its names in a table ``name -> (module, attribute)``: ``module`` is
the module that defines the name, written relative to the face as in its import statement (``".materials"``,
``"..errors"``) and ``attribute`` the name there (``None``: the module itself).  The entry
``"Layer": (".model.materials", "Layer")`` reads as ``from .model.materials import Layer``.
:func:`lazy_face` turns the table into the face's module-level ``__getattr__`` and ``__dir__``: the first
``face.name`` (or ``from face import name``, ``from face import *``, Sphinx autodoc, ``hasattr``) imports the
module and stores the value on the face, so later uses are plain attribute look-ups and return the very same
object.  ``__all__`` stays an explicit list in the face.

The table holds no import statements, so it creates no import edge and no cycle; the import happens when
a name is first used, never at ``import exudyn_atcm``.  Exudyn (about 0.2 s), numpy, scipy, h5py and
matplotlib are then loaded only by the first name that needs them.
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
import types
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_face"]


def lazy_face(package: str, table: Mapping[str, tuple[str, str | None]], *,
              submodules: bool = False) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The ``__getattr__`` and ``__dir__`` of a package face whose names load on first use.

    Parameters
    ----------
    package : str
        The face's module name (its ``__name__``), e.g. ``"exudyn_atcm"``.
    table : mapping of str to (str, str or None)
        ``name -> (module, attribute)``; the module is relative to ``package`` as in a ``from`` import
        (``".model.materials"``) and ``attribute`` is the name in it, or ``None`` for the module itself.
    submodules : bool, optional
        Also answer any other submodule of ``package`` by name (``exudyn_atcm.solve`` after a bare
        ``import exudyn_atcm``), as an eagerly importing face did.  Default ``False``.

    Returns
    -------
    (callable, callable)
        ``__getattr__(name)`` (raises :class:`AttributeError` for an unknown name, as a module does) and
        ``__dir__()`` (the face's globals and the table's names, sorted).
    """
    for name, entry in table.items():
        if not (isinstance(entry, tuple) and len(entry) == 2 and isinstance(entry[0], str)
                and entry[0].startswith(".") and (entry[1] is None or isinstance(entry[1], str))):
            raise ValueError(f"lazy table of {package}: entry {name!r} must be (relative module such as "
                             f"'.model.materials', attribute or None), got {entry!r}")

    def __getattr__(name: str) -> Any:
        face = sys.modules[package]
        entry = table.get(name)
        if entry is not None:
            module = importlib.import_module(entry[0], package)
            value = module if entry[1] is None else getattr(module, entry[1])
        elif submodules and name.isidentifier() and not name.startswith("_") \
                and importlib.util.find_spec(f"{package}.{name}") is not None:
            value = importlib.import_module(f"{package}.{name}")
        else:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        setattr(face, name, value)
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(table))

    sys.modules[package].__class__ = _face_class(table)
    return __getattr__, __dir__


def _face_class(table: Mapping[str, tuple[str, str | None]]) -> type[types.ModuleType]:
    """A module type that keeps a face's name when a submodule of the same name is imported.

    The import system binds every submodule on its package (``solve.step_error = <module>``).  An eager face
    rebound the name right after (``from .step_error import step_error``: the function); a lazy face does it
    here, so that ``exudyn_atcm.solve.step_error`` is the function however the submodule got imported.
    """

    class LazyFace(types.ModuleType):
        def __setattr__(self, name: str, value: Any) -> None:
            entry = table.get(name)
            if (entry is not None and entry[1] is not None and isinstance(value, types.ModuleType)
                    and value.__name__ == f"{self.__name__}.{name}"):
                if importlib.util.resolve_name(entry[0], self.__name__) != value.__name__:
                    return  # the face's name comes from another module: resolved on first use
                value = getattr(value, entry[1])
            super().__setattr__(name, value)

    return LazyFace
