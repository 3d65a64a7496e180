"""The cell kind: what a discretisation of a bender is, independent of how Exudyn realises it.

A :class:`CellKind` holds everything about one kind of cell that the description, the run
checks and the plots need: its name, whether it can carry a tip load, join a mechanism or
model a passive strip, how a bender made of it ends (where joints attach), its measured
run cost and its known limits.  How it adds itself to an Exudyn system lives in the Exudyn
layer (:mod:`exudyn_atcm.mbs`), registered per class, so that a subclass of a cell kind
(outside the package, too) is realised like its parent unless it registers its own.
"""

from __future__ import annotations

from typing import Any, ClassVar
from .._checks import shown

__all__ = ["CellKind", "CELL_KINDS", "END_BODY", "END_CHAIN", "END_NODE", "CONNECTIONS", "cantilever_refusal"]

#: The registry of cell kinds by name, filled by :mod:`exudyn_atcm.cells` (the package's kinds) and
#: :func:`exudyn_atcm.cells.register_cell_kind`; exported there as ``CELL_KINDS``.
CELL_KINDS: dict[str, "CellKind"] = {}

#: The bender's end is an interface body of its own (rigid cells).
END_BODY = "body"
#: The bender's chain ends on the body of the group it joins (six-bar cells: real interface bodies).
END_CHAIN = "chain"
#: The bender's end is a node of the discretisation (beam elements): welded to what it joins.
END_NODE = "node"

#: How a bender end can be connected in a mechanism (see :meth:`CellKind.end_refusal`), in words.
CONNECTIONS = {"ground": "welded to the ground", "free": "free", "joined": "joined to other parts"}


def cantilever_refusal(name: str, end: str, connection: str, why: str) -> str | None:
    """The refusal of a kind that joins a mechanism as a cantilever only (base welded to the ground, tip
    free): ``None`` for those two connections, else the reason, with ``why`` the kind's own."""
    if (end, connection) in (("base", "ground"), ("tip", "free")):
        return None
    return (f"the {name} cell joins a mechanism as a cantilever only (base welded to the ground, tip free; {why}), "
            f"got its {end} {CONNECTIONS[connection]}; use cell='beam' (geometrically exact elements) for other end "
            "connections")


class CellKind:
    """One kind of cell (discretisation) of a bender.

    Subclass it (or an existing kind) to define a new kind; class attributes describe it.
    Instances compare equal to their :attr:`name` (``cell == "rigid"``) so that code written
    for the string names keeps working, and are hashable by name.

    Attributes
    ----------
    name : str
        The name accepted as ``cell=...`` and written into results' parameters.
    summary : str
        One line for listings and error messages.
    carries_tip_load : bool
        A lone actuator made of it accepts ``tip_force``.
    needs_active_layer : bool
        It models both layers as separate bodies (a passive strip cannot be made of it).
    chain_of_cells : bool
        The ``cell_angle_j`` columns are rotations of cells of a chain: a warning is issued when
        one turns by more than 0.5 rad against its neighbour (coarse discretisation).
    end_kind : str
        How a bender's end joins other parts in a mechanism, in words for listings: :data:`END_BODY`,
        :data:`END_CHAIN` or :data:`END_NODE`.  Informative only: the builder asks the kind's
        realisation (:class:`exudyn_atcm.mbs.realisation.CellRealisation`), which joins the ends.
    joint_label : str
        What the points between cells are called in drawings.
    realises_mass_damping : bool
        Every mass of the kind is a rigid body, so mass-proportional (Rayleigh ``alpha``) damping is
        realised exactly as ``-alpha m v`` and ``-alpha J omega`` on each body.
    cost_per_step : tuple of float or None
        ``(a, b, c)`` [s]: measured wall time per accepted step ``a + b n + c n^2`` for ``n`` cells
        (``None``: not measured; no run-time estimate).
    build_cost : tuple of float or None
        ``(a, b, m, k)``: measured wall time ``n (a + b n)`` [s] and memory ``n (m + k n)`` [bytes]
        of building the Exudyn model of ``n`` cells, before the first step
        (``benchmarks/bench_build_cost.py``; ``None``: not measured, the build is left out of the
        estimate).
    limits : str
        Known limits, stated in the documentation.
    stroke_paths : tuple of str
        How the stroke can reach the Exudyn model (an internal choice that tests compare):
        ``"prestep"`` (the default: written in the pre-step hook as torques, offsets or loads),
        ``"offsets"`` (as every spring's or element's rest angle or reference curvature),
        ``"user_function"`` (returned by Exudyn user functions at the step's time).
    static_tolerances : (float, float) or None
        Absolute [SI: N, N m] and relative Newton tolerances of a static solve of a chain of
        these cells, when the package defaults (absolute 1e-8) are not right for it
        (``None``: the defaults, or what the Exudyn builder sets).
    time_order : float
        Order of accuracy of a time integration of this kind with the package's solver
        (generalized-alpha): a run at step ``h`` misses the exact motion of the model by about
        ``C h^p`` for smooth programs and loads.  :func:`~exudyn_atcm.step_error` assumes the lowest
        order among a system's cells in its estimate and its suggested step, and names them.
    space_order : float
        Order of the discretisation error in the count ``n``: about ``C n^-p`` (chains of cells:
        2); ``inf`` where the count is a number of assumed modes, whose error falls by an order of
        magnitude or more per mode (``benchmarks/bench_rod_vs_ritz.py``).  How
        :func:`~exudyn_atcm.choose_cells` steps through counts and reads their differences.
    """

    name: ClassVar[str] = ""
    summary: ClassVar[str] = ""
    carries_tip_load: ClassVar[bool] = True
    needs_active_layer: ClassVar[bool] = False
    chain_of_cells: ClassVar[bool] = True
    end_kind: ClassVar[str] = END_BODY
    joint_label: ClassVar[str] = "cell joints"
    realises_mass_damping: ClassVar[bool] = False
    cost_per_step: ClassVar[tuple[float, float, float] | None] = None
    build_cost: ClassVar[tuple[float, float, float, float] | None] = None
    limits: ClassVar[str] = ""
    static_tolerances: ClassVar[tuple[float, float] | None] = None
    stroke_paths: ClassVar[tuple[str, ...]] = ("prestep", "offsets", "user_function")
    # Exudyn's own items (rigid bodies, springs, beam and ANCF elements) and the assumed-mode cells, whose
    # items are written at the state of each step's end, are integrated by generalized-alpha as they are
    time_order: ClassVar[float] = 2.0
    space_order: ClassVar[float] = 2.0

    def mechanism_refusal(self) -> str | None:
        """Why a bender of this kind cannot be part of a :class:`~exudyn_atcm.Mechanism` (``None``: it can)."""
        return None

    def end_refusal(self, end: str, connection: str) -> str | None:
        """Why a bender end of this kind cannot have ``connection`` in a mechanism (``None``: it can).

        ``end`` is ``"base"`` or ``"tip"``; ``connection`` is ``"ground"`` (welded to the ground),
        ``"free"`` (nothing attached) or ``"joined"`` (anything else: a pin, a slider, a weld to
        another part).  Every end connection is allowed by default.
        """
        return None

    def check_stroke_path(self, stroke_path: str) -> None:
        """Refuse a ``stroke_path`` this kind cannot realise (``ValueError`` naming the allowed ones)."""
        if stroke_path not in self.stroke_paths:
            allowed = " or ".join(repr(p) for p in self.stroke_paths)
            raise ValueError(f"stroke_path must be {allowed} for the {self.name} cell, got {shown(stroke_path)}")

    def add_to_refusal(self) -> str | None:
        """Why a bender of this kind cannot be added to a user's own Exudyn system with
        :func:`~exudyn_atcm.add_to` (``None``: it can)."""
        return None

    def tip_load_refusal(self) -> str | None:
        """Why a lone actuator of this kind refuses a tip load (``None``: it carries one)."""
        if self.carries_tip_load:
            return None
        return f"the {self.name} cell does not carry tip loads"

    def check_run(self, result: Any, actuator: Any, stacklevel: int = 2) -> None:
        """Checks of a finished run of a bender made of this kind (warnings); none by default.

        Called for every bender of a simulated mechanism, a lone actuator included: ``result`` holds
        the bender's own columns under bare names (:func:`exudyn_atcm.solve.bender_checks.bender_view`),
        ``actuator`` is the :class:`~exudyn_atcm.Bender` (its ``laminate``, ``length``, ``n_cells``).
        """

    def estimate_step_cost(self, n_cells: int) -> float | None:
        """Measured wall time per accepted step [s] for ``n_cells`` cells, or ``None`` if not measured."""
        if self.cost_per_step is None:
            return None
        a, b, c = self.cost_per_step
        return a + n_cells * (b + c * n_cells)

    def estimate_build(self, n_cells: int) -> tuple[float, float] | None:
        """Measured wall time [s] and memory [bytes] of building ``n_cells`` cells, or ``None`` if not measured."""
        if self.build_cost is None:
            return None
        a, b, m, k = self.build_cost
        return n_cells * (a + b * n_cells), n_cells * (m + k * n_cells)

    # --------------------------------------------------------------- identity by name
    def __eq__(self, other: object) -> bool:
        if isinstance(other, CellKind):
            return type(self) is type(other) and self.name == other.name
        if isinstance(other, str):
            return self.name == other
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.name)

    def __str__(self) -> str:
        return self.name

    def __repr__(self) -> str:
        # not the bare name: a message about a kind object must not read as if it were a string
        return f"<cell kind {self.name!r} ({type(self).__name__})>"

    def spelled(self) -> str:
        """How to pass this kind as ``cell=``: its quoted name if that name is registered for it
        (:func:`exudyn_atcm.register_cell_kind`), else the kind's class called."""
        registered = CELL_KINDS.get(self.name)
        return repr(self.name) if type(registered) is type(self) else f"{type(self).__name__}()"
