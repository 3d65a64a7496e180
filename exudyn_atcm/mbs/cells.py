"""Retired registries of cell realisations, kept for one release.

The realisation of a cell kind is a :class:`~exudyn_atcm.mbs.realisation.CellRealisation` subclass
registered with :func:`~exudyn_atcm.mbs.realisation.register_realisation` (the written contract).
:data:`add_mechanism_bender` (a generic function of earlier releases, ``(cell, builder, bender)``)
still accepts a registration for one release, with an
:class:`~exudyn_atcm.errors.AtcmDeprecationWarning`: the registered function adds the cells, and
when it hands the bender on to another kind (``add_mechanism_bender(RigidCell(), ctx, bender)``)
that kind's realisation also joins the bender's ends.  :data:`add_actuator_cells` is retired.
"""

from __future__ import annotations

import warnings
from typing import Any, Callable

from ..cells import CellKind
from ..errors import AtcmDeprecationWarning
from .realisation import CellRealisation, register_realisation, realisation_for

__all__ = ["add_mechanism_bender", "add_actuator_cells"]

_HOW = ("register a CellRealisation subclass with exudyn_atcm.mbs.realisation.register_realisation "
        "(see the realisation contract in docs/architecture.rst)")


class _FunctionRealisation(CellRealisation):
    """A realisation made of an old-style registered function; the ends are joined by the realisation of
    the kind the function hands the bender on to."""

    function: Callable = staticmethod(lambda cell, ctx, bender: None)

    def __init__(self, bender: Any) -> None:
        super().__init__(bender)
        self.inner: CellRealisation | None = None

    def add_cells(self, ctx) -> None:
        type(self).function(self.cell, _Handing(ctx, self), self.bender)

    def _delegate(self) -> CellRealisation:
        if self.inner is None:
            raise ValueError(f"cell kind {self.cell.name!r}: its realisation (registered with the retired "
                             f"add_mechanism_bender) did not hand its bender on to a kind that joins its ends; {_HOW}")
        return self.inner

    def connect_end(self, ctx, end: str) -> None:
        self._delegate().connect_end(ctx, end)

    def end_spring(self, ctx, end: str):
        return self._delegate().end_spring(ctx, end)

    def end_body_key(self, end: str) -> str | None:
        return self.inner.end_body_key(end) if self.inner is not None else None

    def strain_writer(self):
        return self.inner.strain_writer() if self.inner is not None else None

    def linearisation_hook(self):
        return self.inner.linearisation_hook() if self.inner is not None else None


class _Handing:
    """The build context handed to an old-style function, remembering the realisation it hands on to."""

    def __init__(self, ctx: Any, owner: _FunctionRealisation) -> None:
        self._ctx = ctx
        self._owner = owner

    def __getattr__(self, name: str) -> Any:
        return getattr(self._ctx, name)


class _RetiredMechanismRealisations:
    """``add_mechanism_bender`` of earlier releases: ``.register(Kind)(function)`` warns and registers the
    function; calling it realises the bender as ``cell``'s kind (for functions that hand a bender on)."""

    def register(self, cls: Any, func: Callable | None = None) -> Any:
        warnings.warn(f"exudyn_atcm.mbs.cells.add_mechanism_bender is deprecated and goes away in the next release: "
                      f"{_HOW}", AtcmDeprecationWarning, stacklevel=2)

        def decorate(function: Callable) -> Callable:
            realisation = type(f"{cls.__name__}FunctionRealisation", (_FunctionRealisation,),
                               {"function": staticmethod(function)})
            register_realisation(cls)(realisation)
            return function
        return decorate if func is None else decorate(func)

    def __call__(self, cell: CellKind, builder: Any, bender: Any) -> None:
        inner = realisation_for(cell)(bender)
        if isinstance(builder, _Handing):
            builder._owner.inner = inner
            builder = builder._ctx
        inner.add_cells(builder)

    def dispatch(self, cls: type) -> type[CellRealisation]:
        """The realisation class registered for the kind class ``cls`` (:func:`realisation_for`)."""
        return realisation_for(cls)


#: Deprecated (one release): see :class:`_RetiredMechanismRealisations`.
add_mechanism_bender = _RetiredMechanismRealisations()


class _RetiredActuatorRealisations:
    """``add_actuator_cells`` of earlier releases, kept for one release: the lone actuator has no builder of
    its own any more (it is built as a one-bender mechanism).  Registering with it warns and registers
    nothing; calling it raises."""

    def register(self, cls: Any, func: Callable | None = None) -> Any:
        warnings.warn("exudyn_atcm.mbs.cells.add_actuator_cells is retired and this registration has no effect: the "
                      f"lone actuator is built as a one-bender mechanism, so {_HOW}", AtcmDeprecationWarning,
                      stacklevel=2)
        if func is None and isinstance(cls, type):
            return lambda f: f
        return cls if func is None else func

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        raise ValueError("exudyn_atcm.mbs.cells.add_actuator_cells is retired: the lone actuator is built as a "
                         "one-bender mechanism (exudyn_atcm.mbs.builder.build of "
                         "exudyn_atcm.solve.as_mechanism.actuator_mechanism(actuator))")


#: Retired (one release): see :class:`_RetiredActuatorRealisations`.
add_actuator_cells = _RetiredActuatorRealisations()
