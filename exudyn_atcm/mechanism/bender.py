"""A bender as a mechanism component: a chain of cells of one laminate, in one or more segments."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..cells import CELL_KINDS, CellKind, cell_kind
from .._checks import finite_float, positive_float, positive_int, shown, warn_implausible
from ..model.drive import PiezoDrive
from ..model.laminate import STIFFNESS_MODELS, Laminate
from ..model.materials import Layer
from ..model.damping import DEFAULT_DAMPING_RATIO, RayleighDamping, check_damping
from ..physical_bounds import MAX_CELLS, check_cell_count
from .damped import MaterialDamped
from .points import MechanismError, PointRef, check_name, unknown_point



def mechanism_cells() -> tuple[str, ...]:
    """Names of the registered cell kinds that a mechanism's bender can be made of (each other kind says why not)."""
    return tuple(name for name, kind in CELL_KINDS.items() if kind.mechanism_refusal() is None)


def passive_strip_cells() -> tuple[str, ...]:
    """Names of those that can also make a passive strip (``active=None``)."""
    return tuple(name for name in mechanism_cells() if not CELL_KINDS[name].needs_active_layer)


#: ``CELL_TYPES`` and ``PASSIVE_STRIP_CELLS``: the same names as module attributes, read when asked
_LIVE = {"CELL_TYPES": mechanism_cells, "PASSIVE_STRIP_CELLS": passive_strip_cells}
ACTIVE_SIDES = ("right", "left")
#: The cell kind of a bender and of a lone actuator when none is given: the fastest at equal accuracy of the
#: kinds that take every load and end connection (benchmarks/bench_discretisation.py, paper actuator: 3 modes
#: reach 3e-4 in f1, bent f1 and tip angle at 0.36 s per simulated second; rigid 16 cells 2e-3 at 0.47 s,
#: six-bar 16 cells 9e-3 at 6.3 s; issue 30).  Before 0.3: "rigid" for a Bender, "six-bar" for an actuator.
DEFAULT_CELL = "rod"
#: ``n_cells`` or ``cell`` left to the package: chosen for a run's stated accuracy (``simulate(...,
#: accuracy=...)`` or :func:`exudyn_atcm.choose_cells`).
AUTO = "auto"
#: The cell kinds ``cell="auto"`` chooses from, cheapest first at equal accuracy (benchmarks/bench_rod_vs_ritz.py:
#: equal errors at equal count, ``ritz`` about 4x cheaper a step; ``ritz`` joins a mechanism as a cantilever
#: without tip loads only, ``rod`` takes every end connection and load).
AUTO_CELLS = ("ritz", "rod")


def is_auto(value: Any) -> bool:
    """Whether ``value`` (an ``n_cells`` or ``cell`` argument) leaves the choice to the package (:data:`AUTO`)."""
    return isinstance(value, str) and value == AUTO


@dataclass(frozen=True)
class Segment:
    """A stretch of a bender with its own drive.

    Parameters
    ----------
    length : float
        Segment length [m], > 0.
    n_cells : int or "auto"
        Number of cells of the segment, >= 1 and at most
        :data:`~exudyn_atcm.physical_bounds.MAX_CELLS` (1e5: more cannot change an answer);
        ``"auto"``: chosen for a run's accuracy (see :class:`Bender`; every open segment of a
        mechanism takes the same count).
    drive : PiezoDrive, optional
        Drive of the segment's active layer; ``None``: unpowered (zero free strain).
    """

    length: float
    n_cells: int | str
    drive: PiezoDrive | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "length", positive_float("length", self.length))
        if isinstance(self.n_cells, str) and not is_auto(self.n_cells):
            raise ValueError(f"n_cells must be an integer >= 1 or {AUTO!r} (chosen for a run's accuracy), got "
                             f"{self.n_cells!r}")
        if not is_auto(self.n_cells):
            object.__setattr__(self, "n_cells", check_cell_count("n_cells", positive_int("n_cells", self.n_cells),
                                                                 "Segment"))
        if self.drive is not None and not isinstance(self.drive, PiezoDrive):
            raise ValueError(f"drive must be a PiezoDrive or None, got {self.drive!r}")

    @property
    def cell_length(self) -> float:
        """Length of one cell of the segment [m]."""
        if is_auto(self.n_cells):
            raise MechanismError(f"this segment's cell count is left to the package (n_cells={AUTO!r}); "
                                 "it has no cell length until one is chosen (exudyn_atcm.choose_cells)")
        return self.length / self.n_cells


def _pair(name: str, value: Any) -> tuple[float, float]:
    try:
        x, y = value
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (x, y) of finite numbers [m], got {shown(value)}") from None
    return finite_float(f"{name}[0]", x), finite_float(f"{name}[1]", y)


class Bender(MaterialDamped):
    """A piezo bender (or a passive textile strip) as a component of a planar mechanism.

    Parameters
    ----------
    name : str
        Component name (no ``.``, ``,``, brackets, ``#`` or spaces).
    width : float
        Width of both layers [m], > 0.
    passive : Layer
        Passive layer (textile composite).
    active : Layer, optional
        Active (MFC) layer.  ``None``: a passive strip (a textile flexure); then every drive
        must be ``None``.
    length, n_cells, drive : optional
        A one-segment bender: length [m], number of cells and drive.  Give either these or
        ``segments``.  ``n_cells="auto"``: the count is chosen for the accuracy of a run,
        by ``simulate(..., accuracy=...)`` or :func:`~exudyn_atcm.choose_cells` (the lowest
        eigenfrequency and the static poses at the next count, module
        :mod:`exudyn_atcm.solve.cell_choice`); every other analysis refuses such a bender until
        it is chosen.
    segments : sequence of Segment, optional
        Segments in series from the base, each with its own drive (all share the laminate).
    base : (float, float), optional
        Base point in the reference pose [m] (default the origin).
    angle : float, optional
        Direction from base to tip in the reference pose [rad] (default 0: along +x).
    cell : {"rod", "rigid", "six-bar", "beam", "ancf", "ritz", "auto"} or CellKind, optional
        Cell model by name or as a :class:`~exudyn_atcm.cells.CellKind` (``"auto"``: chosen with
        the count, the cheapest of :data:`AUTO_CELLS` that the bender's connections allow; see
        ``n_cells``) (see
        :class:`~exudyn_atcm.BendingActuator`), default :data:`DEFAULT_CELL` (``"rod"``, the same as a
        lone actuator's: ``n_cells`` modes of a geometrically exact rod); ``"ancf"`` and ``"ritz"``
        join a mechanism as a cantilever only (base welded to the ground, tip free; other end
        connections are refused with the cell's own reason); the six-bar cell needs an active
        layer.  ``"beam"``: one geometrically exact beam element
        per cell (the actuator's beam cell): bending stiffness ``EI``, a practically
        inextensible axis, each segment's free curvature as end torques ``EI kappa`` on its end
        nodes; the ends are real nodes (no interface mass).  It converges at second order like
        the rigid chain but its first frequency needs about half the cells for equal accuracy
        (see the cells section of the mechanisms page of the docs).
    stiffness : {"composite", "paper"}, optional
        Layer coupling, as for :class:`~exudyn_atcm.BendingActuator`.
    active_side : {"right", "left"}, optional
        Side of the active layer seen from base to tip.  ``"right"`` (default, the layout of
        :class:`~exudyn_atcm.BendingActuator`): a positive free strain bends the bender
        counter-clockwise; ``"left"`` mirrors it.
    damping : float or RayleighDamping, optional
        A float: the modal damping ratio ``zeta`` of *this* bender's first clamped-free
        bending mode [-] (default 0.02), realised as stiffness-proportional damping
        ``beta k`` on its joints (beam cells: on its elements) with ``beta = 2 zeta / omega_1``
        of the bender's own length; the same as ``RayleighDamping(beta=2 zeta / omega_1)``.
        Because ``omega_1`` depends on the length, benders cut from one strip get different
        ``beta``.  A :class:`~exudyn_atcm.RayleighDamping`: material damping of the laminate
        (``alpha`` [1/s] on the masses, ``beta`` [s] on the stiffnesses), independent of how a
        strip is split into benders: two benders of one laminate welded end to end are then
        damped exactly as one bender of the summed length.  ``alpha > 0`` needs
        ``cell="rigid"`` or ``"six-bar"`` (see :mod:`exudyn_atcm.model.damping`).  A ratio of 1
        or more (``damping=5`` meant as 5 %?) gives an
        :class:`~exudyn_atcm.errors.InputRangeWarning`.

    Notes
    -----
    Points: ``"base"`` and ``"tip"`` (``bender.base``, ``bender.tip``), on the passive
    layer's mid-plane at the ends (beam cells: the end nodes).  Drive names: the bender's name for a one-segment bender,
    ``f"{name}.{k}"`` (``k = 1, 2, ...``) per segment otherwise.
    """

    def __init__(
        self,
        name: str,
        *,
        width: float,
        passive: Layer,
        active: Layer | None = None,
        length: float | None = None,
        n_cells: int | str | None = None,
        drive: PiezoDrive | None = None,
        segments: Sequence[Segment] | None = None,
        base: tuple[float, float] = (0.0, 0.0),
        angle: float = 0.0,
        cell: str | CellKind = DEFAULT_CELL,
        stiffness: str = "composite",
        active_side: str = "right",
        damping: float | RayleighDamping = DEFAULT_DAMPING_RATIO,
    ) -> None:
        self.name = check_name("Bender name", name)
        self.width = positive_float("width", width)
        if not isinstance(passive, Layer):
            raise ValueError(f"passive must be an exudyn_atcm Layer, got {shown(passive)}")
        if active is not None and not isinstance(active, Layer):
            raise ValueError(f"active must be an exudyn_atcm Layer or None, got {shown(active)}")
        if segments is not None:
            if length is not None or n_cells is not None or drive is not None:
                raise ValueError(
                    f"bender {name!r}: give either length, n_cells and drive, or segments, not both "
                    f"(got segments={segments!r} and length={length!r}, n_cells={n_cells!r}, drive={drive!r})")
            segments = tuple(segments)
            if not segments or not all(isinstance(s, Segment) for s in segments):
                raise ValueError(f"segments must be a non-empty sequence of Segment, got {shown(segments)}")
        else:
            if length is None or n_cells is None:
                raise ValueError(
                    f"bender {name!r}: give length [m] and n_cells (and a drive), or segments; "
                    f"got length={length!r}, n_cells={n_cells!r}")
            if not is_auto(n_cells):
                check_cell_count("n_cells", n_cells, f"bender {name!r}")
            segments = (Segment(length, n_cells, drive),)
        if active is None:
            powered = [k + 1 for k, s in enumerate(segments) if s.drive is not None]
            if powered:
                raise ValueError(
                    f"bender {name!r} has no active layer (active=None) but segment(s) {powered} have a drive; "
                    "a passive strip cannot be driven: give the active Layer or drop the drives")
        self.segments: tuple[Segment, ...] = segments
        self.passive = passive
        self.active = active
        self.base_position = _pair("base", base)
        self.angle = finite_float("angle", angle)
        owner = f"bender {name!r}"
        warn_implausible("width", self.width, "length", owner)
        for k, s in enumerate(segments):
            warn_implausible("length" if len(segments) == 1 else f"segments[{k}].length", s.length, "length", owner)
        for axis, value in zip("xy", self.base_position):
            warn_implausible(f"base {axis}", value, "position", owner)
        warn_implausible("angle", self.angle, "angle", owner)
        open_kind = is_auto(cell)
        cell = cell_kind(AUTO_CELLS[-1] if open_kind else cell)  # "auto": its checks are those of the kinds chosen from
        refusal = cell.mechanism_refusal()
        if refusal is not None:
            raise ValueError(f"cell={cell.name!r} cannot be a mechanism's bender: {refusal} "
                             f"(the registered cells that can: {mechanism_cells()})")
        for pname, value, allowed in (("stiffness", stiffness, STIFFNESS_MODELS),
                                      ("active_side", active_side, ACTIVE_SIDES)):
            if not isinstance(value, str) or value not in allowed:
                raise ValueError(f"{pname} must be one of {allowed}, got {shown(value)}")
        self._cell: CellKind | None = None if open_kind else cell
        self.stiffness = stiffness
        self.active_side = active_side
        self.damping: float | RayleighDamping = check_damping(damping, cell=cell, owner=owner)
        if not self.open_choices and self.n_cells > MAX_CELLS:  # segments within the bound can sum beyond it
            check_cell_count("n_cells (all segments)", self.n_cells, owner)

    # ------------------------------------------------------------------ choices left to the package
    @property
    def open_choices(self) -> tuple[str, ...]:
        """The discretisation choices left to the package (``"cell"``, ``"n_cells"``; empty when both are fixed)."""
        return tuple(name for name, is_open in (("cell", self._cell is None),
                                                ("n_cells", any(is_auto(s.n_cells) for s in self.segments)))
                     if is_open)

    def _refuse_open(self, what: str) -> None:
        if self.open_choices:
            given = ", ".join(f"{c}={AUTO!r}" for c in self.open_choices)
            raise MechanismError(
                f"bender {self.name!r} has no {what} yet: it leaves its discretisation to the package ({given}). "
                "Only simulate(..., accuracy=...) chooses it, for the run's accuracy; for any other analysis fix "
                "it (n_cells=..., cell=...) or take the choice of exudyn_atcm.choose_cells(mechanism, t_end, "
                "accuracy)")

    @property
    def cell(self) -> CellKind:
        """The cell kind (:class:`~exudyn_atcm.cells.CellKind`); refused while it is left to the package."""
        if self._cell is None:
            self._refuse_open("cell kind")
        return self._cell

    @cell.setter
    def cell(self, value: str | CellKind) -> None:
        self._cell = cell_kind(value)

    # ------------------------------------------------------------------ geometry
    @property
    def laminate(self) -> Laminate:
        """The cross-section (layers, width, stiffness model)."""
        material = self.damping if isinstance(self.damping, RayleighDamping) else None
        return self._cached("laminate", (self.width, self.passive, self.active, self.stiffness, material),
                            lambda: Laminate(self.width, self.passive, self.active, self.stiffness, material))

    @property
    def length(self) -> float:
        """Total length [m]."""
        return float(sum(s.length for s in self.segments))

    @property
    def n_cells(self) -> int:
        """Total number of cells (refused while the count is left to the package)."""
        if "n_cells" in self.open_choices:
            self._refuse_open("cell count")
        return int(sum(s.n_cells for s in self.segments))

    @property
    def cell_lengths(self) -> np.ndarray:
        """Length of every cell from the base [m]."""
        self.n_cells  # noqa: B018 - refused while the count is left to the package
        return np.concatenate([np.full(s.n_cells, s.cell_length) for s in self.segments])

    @property
    def cell_segments(self) -> np.ndarray:
        """Index (0-based) of the segment of every cell from the base."""
        self.n_cells  # noqa: B018 - refused while the count is left to the package
        return np.concatenate([np.full(s.n_cells, k) for k, s in enumerate(self.segments)])

    @property
    def direction(self) -> np.ndarray:
        """Unit vector from base to tip in the reference pose."""
        return np.array([math.cos(self.angle), math.sin(self.angle)])

    @property
    def curvature_sign(self) -> float:
        """+1 if a positive free strain bends counter-clockwise (active layer on the right), else -1."""
        return 1.0 if self.active_side == "right" else -1.0


    # ------------------------------------------------------------------ points and drives
    @property
    def points(self) -> dict[str, tuple[float, float]]:
        """Named points in the reference pose [m]: ``base`` and ``tip``."""
        x0, y0 = self.base_position
        d = self.direction * self.length
        return {"base": (x0, y0), "tip": (x0 + float(d[0]), y0 + float(d[1]))}

    def point(self, name: str) -> PointRef:
        """The point ``"base"`` or ``"tip"`` as a :class:`PointRef`."""
        if name not in ("base", "tip"):
            raise unknown_point(self.name, name, ("base", "tip"))
        return PointRef(self.name, name)

    @property
    def base(self) -> PointRef:
        """The base point (passive-layer point of the first interface)."""
        return PointRef(self.name, "base")

    @property
    def tip(self) -> PointRef:
        """The tip point (passive-layer point of the last interface)."""
        return PointRef(self.name, "tip")

    def drive_name(self, segment: int) -> str:
        """Drive name of segment ``segment`` (0-based)."""
        return self.name if len(self.segments) == 1 else f"{self.name}.{segment + 1}"

    @property
    def drives(self) -> dict[str, PiezoDrive]:
        """Drives by name (segments without a drive are left out)."""
        return {self.drive_name(k): s.drive for k, s in enumerate(self.segments) if s.drive is not None}

    def parameters(self) -> dict[str, Any]:
        """Parameters with units, for result headers."""
        p = self.name
        out: dict[str, Any] = {
            f"{p}.type": "Bender",
            f"{p}.cell": AUTO if self._cell is None else self._cell.name,
            f"{p}.stiffness": self.stiffness,
            f"{p}.active_side": self.active_side,
            f"{p}.base [m]": self.base_position,
            f"{p}.angle [rad]": self.angle,
            f"{p}.width [m]": self.width,
            f"{p}.passive.thickness [m]": self.passive.thickness,
            f"{p}.passive.youngs_modulus [Pa]": self.passive.youngs_modulus,
            f"{p}.passive.density [kg/m^3]": self.passive.density,
        }
        if self.active is not None:
            out[f"{p}.active.thickness [m]"] = self.active.thickness
            out[f"{p}.active.youngs_modulus [Pa]"] = self.active.youngs_modulus
            out[f"{p}.active.density [kg/m^3]"] = self.active.density
        for k, s in enumerate(self.segments):
            q = f"{p}.segment_{k + 1}"
            out[f"{q}.length [m]"] = s.length
            out[f"{q}.n_cells"] = s.n_cells
            out[f"{q}.drive"] = repr(s.drive)
        if isinstance(self.damping, RayleighDamping):
            out[f"{p}.damping.alpha [1/s]"] = self.damping.alpha
            out[f"{p}.damping.beta [s]"] = self.damping.beta
        else:
            out[f"{p}.damping ratio [-]"] = self.damping
        out[f"{p}.bending_stiffness [N m^2]"] = self.laminate.bending_stiffness
        return out

    def __repr__(self) -> str:
        cell = repr(AUTO) if self._cell is None else self._cell.spelled()
        return (f"Bender({self.name!r}, width={self.width!r}, passive={self.passive!r}, active={self.active!r}, "
                f"segments={self.segments!r}, base={self.base_position!r}, angle={self.angle!r}, "
                f"cell={cell}, stiffness={self.stiffness!r}, active_side={self.active_side!r}, "
                f"damping={self.damping!r})")


def __getattr__(name: str):
    # the registry's names, read when asked (kinds registered with exudyn_atcm.register_cell_kind included)
    if name in _LIVE:
        return _LIVE[name]()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
