"""The Exudyn realisation of each cell kind: one module per kind, named like the kind's module in
:mod:`exudyn_atcm.cells` (``cells/ritz.py`` describes the kind, ``mbs/chains/ritz.py`` builds it).

Each module registers its kind's realisation with
:func:`exudyn_atcm.mbs.cells.add_mechanism_bender` when it is imported, and this package imports
every module in its folder when it is imported itself (by :mod:`exudyn_atcm.mbs.builder`).  A new
cell kind's realisation is therefore one new file here: nothing else lists it.

Package kinds: :mod:`.rigid` (rigid bodies and spring-damper joints), :mod:`.six_bar` (the
paper's six-bar cells), :mod:`.beam` (geometrically exact beam elements), :mod:`.ancf` (ANCF
cable elements), :mod:`.ritz` (assumed modes of the rotation field).  What the chains whose ends
are nodes share is in :mod:`exudyn_atcm.mbs.node_chain`.

May import: Exudyn, :mod:`exudyn_atcm.cells`, :mod:`exudyn_atcm.mechanism`, :mod:`exudyn_atcm.theory`
and the other modules of :mod:`exudyn_atcm.mbs` except the builder; they write through the build context only (:mod:`exudyn_atcm.mbs.build_context`).
"""

from __future__ import annotations

import importlib
import pkgutil

#: The realisation modules found in this folder, in name order.
MODULES: tuple[str, ...] = tuple(sorted(info.name for info in pkgutil.iter_modules(__path__)))

for _name in MODULES:
    importlib.import_module(f"{__name__}.{_name}")

__all__ = ["MODULES"]
