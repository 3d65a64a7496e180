"""The cell realisation contract and the open registry of cell kinds (issue 30, part 3).

A cell kind with physics of its own is written here, outside the package: a chain of rigid cells whose
joint springs are ``1.5 EI/L_c`` (end springs ``1.5 * 2 EI/L_c``) instead of the laminate's ``EI/L_c``, and
whose cells have four times a slender bar's rotary inertia.  Its description is a
:class:`~exudyn_atcm.cells.CellKind` registered by name with :func:`exudyn_atcm.register_cell_kind`; its
realisation a :class:`~exudyn_atcm.mbs.realisation.HingedEnds` subclass that writes only through the public
:class:`~exudyn_atcm.mbs.build_context.BuildContext`.  It is then used by name in a lone bender, a lone
``BendingActuator``, a closed mechanism, :func:`exudyn_atcm.add_to`, ``eigenfrequencies``, a case run (the
command line's ``--set cell=...`` and the case API), a sweep, a drawing and a run-cost estimate.

Independent references:

* a chain of torsion springs ``k_i`` at ``x_i`` under a tip force ``P`` (small deflection): each joint turns
  by ``P (L - x_i)/k_i``, so the tip deflects ``P sum (L - x_i)^2/k_i``; a chain guided at both ends
  (the parallel guide's benders, each carrying ``P/2``): moment ``P/2 (L/2 - x)``, deflection
  ``P/2 sum (L/2 - x_i)^2/k_i``;
* its first eigenfrequency from a linear model built here: absolute cell angles ``a_j``, cell centres at
  ``y_j = sum_{i<j} L_c a_i + L_c/2 a_j``, mass matrix ``B^T m B + J``, stiffness from the springs;
* under actuation every spring's rest angle is the free rotation of the half cells it stands for, so the
  joints lie on the arc's inscribed polygon whatever the stiffness (:func:`exudyn_atcm.theory.chain_polygon`).
"""

from __future__ import annotations

import math
import pathlib

import exudyn as exu
import numpy as np
import pytest
import scipy.linalg

import exudyn_atcm as atcm
from exudyn_atcm import theory as bt
from exudyn_atcm.casework import load_case
from exudyn_atcm.cells import CELL_KINDS, CellKind, cell_kind
from exudyn_atcm.cli import main
from exudyn_atcm.mbs import BuildContext, HingedEnds, register_realisation
from exudyn_atcm.mbs.model import Element
from exudyn_atcm.plots.mechanism import plot_mechanism

CASES = pathlib.Path(__file__).resolve().parents[1] / "cases"
CFC = atcm.Layer(0.2e-3, 70e9, 1550.0)
MFC = atcm.Layer(0.3e-3, 30.336e9, 5440.0)
NAME = "test-stiff-chain"
STIFFNESS_FACTOR = 1.5   # joint springs 1.5 EI/L_c (the laminate's chain: EI/L_c)
INERTIA_FACTOR = 4.0     # rotary inertia 4 m L_c^2/12 about the cell's centre (a slender bar: m L_c^2/12)


# ----------------------------------------------------------------------------- the kind, outside the package
class StiffChainCell(CellKind):
    """Rigid cells on the passive mid-plane with their own spring law and inertia (test physics)."""

    name = NAME
    summary = "rigid cells, joint springs 1.5 EI/L_c, 4x a bar's rotary inertia (a test kind)"
    joint_label = "stiff joints"
    realises_mass_damping = True
    cost_per_step = (30e-6, 5e-6, 1e-8)
    static_tolerances = (1e-14, 1e-10)


@register_realisation(StiffChainCell)
class StiffChain(HingedEnds):
    """One rigid body per cell (centre at mid-cell), joined by springs ``1.5 EI/L_c``; massless end interfaces."""

    def add_cells(self, ctx: BuildContext) -> None:
        bender = self.bender
        lam = bender.laminate
        self.ei = STIFFNESS_FACTOR * lam.bending_stiffness
        self.lengths = bender.cell_lengths
        self.segment_of = bender.cell_segments
        self.side, self.c, self.beta = bender.curvature_sign, lam.curvature_per_strain, bender.stiffness_damping_factor
        d, x0, s = bender.direction, np.array(bender.base_position, dtype=float), 0.0
        self.keys = []
        for j, lc in enumerate(self.lengths):
            s += lc
            m = lam.mass_per_length * lc
            key = f"{bender.name}/stiff{j + 1}"
            ctx.add_body(key, x0 + s * d, bender.angle, m, INERTIA_FACTOR * m * lc**2 / 12.0, (-0.5 * lc, 0.0),
                         mass_damping=bender.mass_damping_factor)
            self.keys.append(key)
        ctx.set_cells(bender, self.keys)
        for j in range(len(self.lengths) - 1):
            k = 2.0 * self.ei / (self.lengths[j] + self.lengths[j + 1])
            theta = self.half(ctx, j) + self.half(ctx, j + 1)
            ctx.add_hinge(self.keys[j], self.keys[j + 1], [Element(k, self.beta * k, theta, k * theta)],
                          (0.0, 0.0), (-self.lengths[j + 1], 0.0))

    def half(self, ctx: BuildContext, j: int) -> np.ndarray:
        """The free rotation of half cell ``j`` per unit strain of each source [rad]."""
        out = ctx.zeros()
        source = ctx.source(self.bender, self.segment_of[j])
        if source is not None:
            out[source] = 0.5 * self.side * self.c * self.lengths[j]
        return out

    def end_spring(self, ctx: BuildContext, end: str):
        j = 0 if end == "base" else len(self.lengths) - 1
        k = 2.0 * self.ei / self.lengths[j]
        theta = self.half(ctx, j)
        return Element(k, self.beta * k, theta, k * theta), self.keys[j], \
            ((-self.lengths[j], 0.0) if end == "base" else (0.0, 0.0))


@pytest.fixture(autouse=True, scope="module")
def registered():
    """Register the kind for this file's tests, and take it out of the registry afterwards (other test files
    list the package's kinds)."""
    atcm.register_cell_kind(StiffChainCell)
    yield
    CELL_KINDS.pop(NAME, None)


# ----------------------------------------------------------------------------- references
def joints(n: int, length: float, guided: bool) -> tuple[np.ndarray, np.ndarray]:
    """Positions [m] and stiffnesses [N m/rad] of the chain's springs (base end, inner, tip end if guided)."""
    lc = length / n
    x = np.arange(n + (1 if guided else 0)) * lc
    k = np.full(x.size, 1.0)
    k[0] = 2.0
    if guided:
        k[-1] = 2.0
    return x, k * STIFFNESS_FACTOR * EI(length) / lc


def EI(length: float) -> float:
    return atcm.Bender("probe", width=10e-3, passive=CFC, active=MFC, length=length, n_cells=1).laminate.bending_stiffness


def first_frequency_by_hand(bender: atcm.Bender) -> float:
    """f1 [Hz] of the cantilevered chain from its linear model (absolute cell angles)."""
    n, lc = bender.n_cells, bender.length / bender.n_cells
    m = bender.laminate.mass_per_length * lc
    B = np.tril(np.full((n, n), lc), -1) + np.eye(n) * 0.5 * lc   # centre velocities per angle rate
    M = m * B.T @ B + np.eye(n) * INERTIA_FACTOR * m * lc**2 / 12.0
    _, k = joints(n, bender.length, guided=False)
    K = np.zeros((n, n))
    K[0, 0] += k[0]
    for j in range(1, n):  # the spring between cells j-1 and j
        e = np.zeros(n)
        e[j], e[j - 1] = 1.0, -1.0
        K += k[j] * np.outer(e, e)
    return float(np.sqrt(scipy.linalg.eigh(K, M, eigvals_only=True)[0]) / (2.0 * math.pi))


def cantilever(n: int = 5, voltage: float = 0.0, name: str = "b") -> atcm.Bender:
    return atcm.Bender(name, width=10e-3, passive=CFC, active=MFC, length=0.05, n_cells=n, cell=NAME,
                       drive=atcm.PiezoDrive(voltage))


# ----------------------------------------------------------------------------- the registry
def test_the_kind_is_known_by_name_everywhere_the_registry_is_read():
    from exudyn_atcm.mechanism import actuator, bender
    from exudyn_atcm.model import damping
    from exudyn_atcm.solve import run_checks

    assert cell_kind(NAME) is CELL_KINDS[NAME] and isinstance(CELL_KINDS[NAME], StiffChainCell)
    # the name lists are read from the registry when asked, not copied at import
    assert NAME in bender.CELL_TYPES and NAME in bender.PASSIVE_STRIP_CELLS and NAME in actuator.CELL_TYPES
    assert NAME in actuator.TIP_LOAD_CELLS and NAME in damping.MASS_DAMPING_CELLS
    assert run_checks.COST_PER_STEP[NAME] == StiffChainCell.cost_per_step
    # cost estimate by name: n_steps (a + b n + c n^2)
    a, b, c = StiffChainCell.cost_per_step
    assert run_checks.estimate_run_time(NAME, 10, 1000) == pytest.approx(1000 * (a + 10 * b + 100 * c), rel=1e-12)
    # mass-proportional damping is accepted by name because the kind realises it
    atcm.Bender("d", width=10e-3, passive=CFC, active=MFC, length=0.05, n_cells=3, cell=NAME,
                damping=atcm.RayleighDamping(alpha=5.0, beta=1e-5))


def test_an_unknown_name_is_refused_listing_the_registered_kinds_and_a_kind_reads_as_a_kind():
    with pytest.raises(ValueError, match=rf"cell must be one of \(.*'{NAME}'\) or a CellKind, got 'stiff-chain'"
                                         r".*register_cell_kind"):
        cantilever().__class__("x", width=10e-3, passive=CFC, active=MFC, length=0.05, n_cells=2, cell="stiff-chain")
    assert repr(CELL_KINDS[NAME]) == f"<cell kind '{NAME}' (StiffChainCell)>"
    assert f"cell='{NAME}'" in repr(cantilever())  # a registered kind is spelled by its name
    # a kind object given to a string parameter: the message says what it got
    case = load_case(CASES / "parallel_guide.py")
    with pytest.raises(ValueError, match=rf"cell must be a string, got <cell kind '{NAME}' \(StiffChainCell\)>"):
        case.run({"cell": CELL_KINDS[NAME]})


def test_register_cell_kind_refuses_bad_kinds_and_taken_names():
    class Rival(CellKind):
        name = "rigid"

    with pytest.raises(ValueError, match="kind: the name 'rigid' is taken by RigidCell"):
        atcm.register_cell_kind(Rival)
    with pytest.raises(ValueError, match="kind must be a CellKind instance or subclass, got 'rigid'"):
        atcm.register_cell_kind("rigid")

    class Other(CellKind):
        name = NAME

    with pytest.raises(ValueError, match=rf"the name '{NAME}' is taken by StiffChainCell.*replace=True"):
        atcm.register_cell_kind(Other)
    assert atcm.register_cell_kind(StiffChainCell) is not None  # the same class again: no conflict


# ----------------------------------------------------------------------------- its physics, by name
def test_a_lone_bender_deflects_as_its_chain_of_springs():
    b = cantilever()
    P = 1e-4  # tip deflection ~1e-5 L: the geometric nonlinearity is ~(1e-5)^2 relative
    r = atcm.solve_static(atcm.Mechanism("m").add(b).ground(b.base).force(b.tip, (0.0, -P)))
    x, k = joints(b.n_cells, b.length, guided=False)
    expected = -P * float(np.sum((b.length - x) ** 2 / k))
    assert r["b.tip_y"][0] == pytest.approx(expected, rel=1e-6)
    # the laminate's own chain (cell="rigid") is 1.5x more compliant at these joints: the kind's law is used
    rigid = atcm.Bender("b", width=10e-3, passive=CFC, active=MFC, length=0.05, n_cells=5, cell="rigid",
                         drive=atcm.PiezoDrive(0.0))
    r_rigid = atcm.solve_static(atcm.Mechanism("m").add(rigid).ground(rigid.base).force(rigid.tip, (0.0, -P)))
    assert r_rigid["b.tip_y"][0] == pytest.approx(STIFFNESS_FACTOR * expected, rel=1e-6)


def test_a_bending_actuator_by_name_follows_the_arcs_inscribed_polygon():
    act = atcm.BendingActuator(4, 0.087 / 4, 28e-3, CFC, MFC, atcm.PiezoDrive(1500.0), cell=NAME)
    r = atcm.solve_static(act)
    kappa = act.free_curvature(act.drive.static_strain(1500.0))
    px, py = bt.chain_polygon(kappa, act.length, act.n_cells)
    assert r["actuator.tip_x"][0] == pytest.approx(px[-1], abs=1e-9 * act.length)
    assert r["actuator.tip_y"][0] == pytest.approx(py[-1], abs=1e-9 * act.length)
    assert r["actuator.tip_angle"][0] == pytest.approx(kappa * act.length, rel=1e-9)


def test_its_first_eigenfrequency_is_the_hand_built_linear_models():
    b = cantilever(n=6)
    f = atcm.eigenfrequencies(atcm.Mechanism("m").add(b).ground(b.base), n=2)
    assert f[0] == pytest.approx(first_frequency_by_hand(b), rel=1e-7)


def guide(n: int) -> tuple[atcm.Mechanism, float]:
    L, h = 0.05, 0.02
    lower, upper = cantilever(n, name="lower"), atcm.Bender("upper", width=10e-3, passive=CFC, active=MFC, length=L,
                                                            n_cells=n, cell=NAME, drive=atcm.PiezoDrive(0.0),
                                                            base=(0.0, h))
    coupler = atcm.Link("coupler", {"A": (L, 0.0), "B": (L, h), "C": (L, h / 2)}, mass=2e-3, inertia=1e-7)
    mech = (atcm.Mechanism("guide").add(lower, upper, coupler).ground(lower.base).ground(upper.base)
            .weld(lower.tip, coupler.point("A")).weld(upper.tip, coupler.point("B")))
    return mech, L


def test_a_closed_mechanism_of_the_kind_is_guided_as_its_springs_say():
    mech, L = guide(4)
    P = 2e-4  # on the coupler's line through both tips: no axial forces, each bender carries P/2
    r = atcm.solve_static(mech.force("coupler.C", (0.0, -P)))
    x, k = joints(4, L, guided=True)
    expected = -0.5 * P * float(np.sum((0.5 * L - x) ** 2 / k))
    assert r["coupler.C_y"][0] - 0.01 == pytest.approx(expected, rel=1e-6)
    assert abs(r["coupler.angle"][0]) < 1e-9 * abs(expected) / L


def test_add_to_a_users_system_by_name():
    b = cantilever()
    P = 1e-4
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    handle = atcm.add_to(mbs, atcm.Mechanism("m").add(b).ground(b.base))
    tip = handle.position_marker("b.tip")
    mbs.AddLoad(exu.itemInterface.LoadForceVector(markerNumber=tip, loadVector=[0.0, -P, 0.0]))
    sensor = mbs.AddSensor(exu.itemInterface.SensorMarker(markerNumber=tip, outputVariableType=exu.OutputVariableType.Position,
                                                          storeInternal=True))
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.solution.file.write = False
    settings.staticSolver.newton.relativeTolerance = 1e-12
    settings.staticSolver.newton.absoluteTolerance = 1e-14
    settings.linearSolver.solverType = exu.LinearSolverType.EXUdense
    mbs.SolveStatic(settings)
    y = mbs.GetSensorValues(sensor)[1]
    x, k = joints(b.n_cells, b.length, guided=False)
    assert y == pytest.approx(-P * float(np.sum((b.length - x) ** 2 / k)), rel=1e-6)


def test_a_case_runs_with_the_kind_by_name_from_the_command_line_the_api_and_a_sweep(tmp_path):
    """The parallel guide's S-blades are compatible with the coupler: the coupler follows the arcs' inscribed
    polygons (the case's ``translation_error_chain_polygon`` reference) for any joint stiffness."""
    assert main(["run", str(CASES / "parallel_guide.py"), "--out", str(tmp_path / "cli"), "--no-plot",
                 "--set", f"cell={NAME}", "--set", "n_cells=2", "--set", "n_steps=4", "--set", "animation=false"]) == 0
    s = load_case(CASES / "parallel_guide.py").run({"cell": NAME, "n_cells": 2, "n_steps": 4}, plot=False).scalars
    assert s["translation_error_chain_polygon"] < 1e-9
    assert s["rotation_max"] < 1e-12
    from exudyn_atcm.study import RunOptions, sweep

    table = sweep(CASES / "parallel_guide.py", {"cell": ["rigid", NAME]}, fixed={"n_cells": 2, "n_steps": 4},
                  run=RunOptions(workers=1, out=tmp_path / "sweep"))
    cells = list(table["cell"]) if not hasattr(table, "column") else list(table.column("cell"))
    assert cells == ["rigid", NAME]


def test_a_drawing_of_the_kind_uses_its_joint_label(tmp_path, monkeypatch):
    import matplotlib.axes

    mech, _ = guide(3)
    r = atcm.solve_static(mech.force("coupler.C", (0.0, -1e-3)))
    labels = []
    original = matplotlib.axes.Axes.legend

    def spy(self, *args, **kwargs):
        labels.extend(t.get_label() for t in self.get_lines() + list(self.collections))
        return original(self, *args, **kwargs)

    monkeypatch.setattr(matplotlib.axes.Axes, "legend", spy)
    path = tmp_path / "guide.png"
    plot_mechanism(mech, r, path=path)
    assert pathlib.Path(path).stat().st_size > 1000
    assert any("stiff joints" in label for label in labels), labels


# ----------------------------------------------------------------------------- the builder keeps to the contract
def test_the_builder_has_no_switch_on_a_kind_or_an_end_type():
    source = (pathlib.Path(atcm.__file__).parent / "mbs" / "builder.py").read_text()
    for word in ("end_kind", "END_CHAIN", "END_NODE", "END_BODY", "six_bar", "SixBar", "cell.name ==", "beam_end_key",
                 "cell_rotations"):
        assert word not in source, word
    # the realisations write through the build context only: no chain module assigns the model's attributes
    chains = pathlib.Path(atcm.__file__).parent / "mbs" / "chains"
    for path in chains.glob("*.py"):
        text = path.read_text()
        for pattern in ("model.bodies[", "model.cells[", "model.springs.append", "model.strain_writers",
                        "model.linearisation_hooks", "model.varying_mass_benders", "builder."):
            assert pattern not in text, (path.name, pattern)
