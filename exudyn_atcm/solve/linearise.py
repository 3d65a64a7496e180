"""Linear state-space models of a mechanism about a static equilibrium: :func:`linearise`.

What is linearised about what (``docs/control.rst``): the equations of motion about the static
equilibrium at the given voltages with the mechanism's loads, with the tangent stiffness including
the constraint forces' geometric stiffness, the damping the simulation has, on the coordinates of
the constraints' null space (:mod:`exudyn_atcm.mbs.linear_model`); a drive's voltage input enters
through its strain, scaled by the hysteresis operator's local slope on the chosen branch
(:mod:`exudyn_atcm.model.drive_gain`).
"""

from __future__ import annotations

import copy
import warnings
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._checks import shown
from ..errors import StabilityWarning
from ..mbs import builder as mb
from ..mbs import linear_model as lm
from ..mechanism.build_cost import warn_if_large
from ..model.drive_gain import check_branch, drive_gain
from ..suggestions import close_names
from .linear_state import as_mechanism, equilibrium_state
from .long_runs import is_announced
from .mechanism_static import VoltageSpec, describe, drive_voltages
from .static_stability import free_motion_note, load_path_note, warn_unstable
from .state_space import LinearModel

__all__ = ["linearise", "linearise_model", "warn_if_not_a_plant", "FORCE_SUFFIXES"]

#: an input ``"<point>_Fx"`` / ``"<point>_Fy"`` is a dead force [N] at the point in x / y
FORCE_SUFFIXES = ("_Fx", "_Fy")


def _names(what: str, value: Any) -> list[str]:
    if isinstance(value, str):
        value = [value]
    try:
        names = list(value)
    except TypeError:
        raise ValueError(f"{what} must be a list of names, got {shown(value)}") from None
    if not names or not all(isinstance(n, str) for n in names):
        raise ValueError(f"{what} must be a non-empty list of names (str), got {shown(value)}")
    if len(set(names)) != len(names):
        raise ValueError(f"{what} must not repeat a name, got {shown(names)}")
    return names


def _suggest(name: str, candidates: Sequence[str]) -> str:
    close = close_names(name, candidates, n=3, cutoff=0.5)
    return f"; did you mean {' or '.join(map(repr, close))}?" if close else ""


def _check_inputs(mech: Any, model: Any, inputs: list[str]) -> list[tuple[str, str, Any]]:
    """Each input as ``("drive", name, None)`` or ``("force", point, axis index)``."""
    drives = list(mech.drives)
    points = list(model.anchors)
    allowed = drives + [p + s for p in points for s in FORCE_SUFFIXES]
    out = []
    for name in inputs:
        if name in mech.drives:
            out.append(("drive", name, None))
        elif name.endswith(FORCE_SUFFIXES) and name[:-3] in model.anchors:
            out.append(("force", name[:-3], FORCE_SUFFIXES.index(name[-3:])))
        else:
            raise ValueError(
                f"inputs: {name!r} is not a drive or a point force of mechanism {mech.name!r}{_suggest(name, allowed)} "
                f"(drives: {', '.join(map(repr, drives)) or 'none'}; a point force is '<point>_Fx' or '<point>_Fy' "
                "at a named point, e.g. " + (repr(points[-1] + '_Fy') if points else "'link.P_Fy'") + ")")
    return out


def linearise(system: Any, *, voltage: VoltageSpec = None, loads: Mapping[str, Any] | None = None,
              inputs: Sequence[str] | None = None, outputs: Sequence[str], branch: str = "ascending",
              voltage_step: float = 1.0) -> LinearModel:
    """A linear state-space model of a mechanism or actuator about its static equilibrium.

    Parameters
    ----------
    system : Mechanism or BendingActuator
        The system (an actuator is linearised as its one-bender mechanism, outputs ``"actuator.tip_y"`` ...).
    voltage : float or mapping, optional
        Drive voltages [V] of the equilibrium (a number for every drive or ``{drive: volts}``; default:
        each drive's program at ``t = 0``).  The mechanism's loads act, as in :func:`exudyn_atcm.solve_static`.
    loads : mapping, optional
        Further dead forces ``{point: (Fx, Fy)}`` [N] at named points acting at the equilibrium, besides the
        mechanism's own loads (the mechanism itself is not changed: a copy carries them).
    inputs : list of str, optional
        Drive names (input: the drive's voltage [V] about its operating value) and point forces
        ``"<point>_Fx"``, ``"<point>_Fy"`` (a dead force [N] at a named point, e.g. ``"lever.end_Fy"``).
        Default: every drive.
    outputs : list of str
        Result columns of point coordinates and angles [m, rad] (``"lever.end_y"``, ``"rocker.angle"``,
        ``"crank.tip_angle"``), as deviations from their equilibrium values.
    branch : str, optional
        The hysteresis branch of every drive's small-signal gain: ``"ascending"`` (default),
        ``"descending"`` or ``"reversal"`` (:mod:`exudyn_atcm.model.drive_gain`); the equilibrium is solved at
        the strain of that branch's state.  Irrelevant for drives without hysteresis.
    voltage_step : float, optional
        Signal amplitude [V] over which the hysteresis slope is taken (default 1 V).

    Returns
    -------
    LinearModel
        ``A, B, C, D`` with the state ``[z, z']`` on the constraints' null space (``to_scipy()``,
        ``frequency_response(f)``, ``poles``, ``dc_gain()``).

    Raises
    ------
    ValueError
        For an input that is not a drive or a point force, an output that is not a point coordinate or an
        angle of the mechanism (with the closest names), an unknown branch, a drive whose strain is a
        prescribed motion (six-bar cells), a drive operator with creep or rate dynamics.
    NoEquilibriumError
        (a ``ValueError`` and a :class:`~exudyn_atcm.SolverError`) if the static equilibrium is not found.

    Notes
    -----
    The tangent stiffness includes the joints' constraint forces' geometric stiffness, which Exudyn's
    ``ComputeLinearizedSystem`` leaves out; the damping is the one the simulation has (derivatives of the
    forces with respect to the velocities).  Valid for small signals about the state: a hysteretic drive's
    gain depends on the branch and on the amplitude (``docs/control.rst``).  Validated in
    ``tests/test_linearise.py`` against a closed-form single degree of freedom, differences of the nonlinear
    model, sine simulations and Exudyn's ``ComputeLinearizedSystem``.
    """
    mech = as_mechanism(system, "linearise")
    check_branch(branch)
    if loads is not None:
        if not isinstance(loads, Mapping):
            raise ValueError(f"loads must be a mapping {{point: (Fx, Fy)}} [N], got {shown(loads)}")
        mech = copy.deepcopy(mech)
        points = [f"{c.name}.{p}" for c in mech.components.values() for p in c.points]
        for point, force in loads.items():
            if point not in points:
                raise ValueError(f"loads: {point!r} is not a named point of mechanism {mech.name!r}"
                                 f"{_suggest(str(point), points)}")
            mech.force(point, force)
    warn_if_large(mech, "linearise", equilibria=1, eigen=True, quiet=is_announced(), stacklevel=4)
    return linearise_model(mech, mb.build(mech), voltage=voltage, inputs=inputs, outputs=outputs, branch=branch,
                           voltage_step=voltage_step)


def warn_if_not_a_plant(state: Any) -> None:
    """A :class:`~exudyn_atcm.StabilityWarning` when the equilibrium a linear model is taken about is unstable or
    critical (its poles then include a divergence, which :attr:`~exudyn_atcm.solve.state_space.LinearModel.natural_frequencies`,
    listing the oscillating modes, does not show, and its ``dc_gain`` is no steady state), or has a motion without
    stiffness (a link on a free pin: no static gain exists, the "lowest mode" is round-off)."""
    probe = state.probe
    if probe is None:
        return
    free = free_motion_note(state.model, probe)
    if free:  # its sign is round-off: said as what it is, not as an unstable equilibrium
        warnings.warn(f"linearise: {free}. Its linear model has a pole at about 0 and no static gain (dc_gain is "
                      "round-off)", StabilityWarning, stacklevel=4)
        return
    warn_unstable(describe(state.mechanism), [(state.description, probe.last)], load_path_note(probe), stacklevel=4)


def linearise_model(mech: Any, model: Any, *, voltage: VoltageSpec, inputs: Sequence[str] | None,
                    outputs: Sequence[str], branch: str, voltage_step: float) -> LinearModel:
    """:func:`linearise` of ``mech`` on its built ``model`` (in its built state; a
    :class:`~exudyn_atcm.BuiltSystem`'s)."""
    branch = check_branch(branch)
    outputs = _names("outputs", outputs)
    inputs = list(mech.drives) if inputs is None else _names("inputs", inputs)
    if not inputs:
        raise ValueError(f"inputs: mechanism {mech.name!r} has no drives; name point forces ('<point>_Fy') as inputs")
    kinds = _check_inputs(mech, model, inputs)
    volts = drive_voltages(mech, voltage)
    gains = {name: drive_gain(mech.drives[name], volts[name], branch, voltage_step=voltage_step, name=name,
                              stacklevel=5) for name in mech.drives}  # a flat branch warned at the caller
    columns = lm.output_columns(model, np.zeros(len(model.sources)))
    for name in outputs:
        if name not in columns:
            raise ValueError(f"outputs: {name!r} is not a point coordinate or an angle of mechanism {mech.name!r}"
                             f"{_suggest(name, list(columns))} (outputs are result columns in m or rad, e.g. "
                             f"{', '.join(map(repr, list(columns)[:4]))})")
    state = equilibrium_state(mech, "linearise", voltage=voltage, model=model,
                              strains={name: g.strain for name, g in gains.items()})
    warn_if_not_a_plant(state)
    model.before_linearisation()
    mats = lm.linear_matrices(model)
    N = mats.N
    Mr, Kr, Dr = N.T @ mats.M @ N, N.T @ mats.K @ N, N.T @ mats.D @ N
    values, dq, de = lm.output_jacobian(model, outputs, state.strains)
    b_strain = lm.strain_forces(model, state.strains) if any(k == "drive" for k, _, _ in kinds) else None
    force_columns = {}
    if any(k == "force" for k, _, _ in kinds):
        names, _, jac = lm.point_jacobians(model)
        force_columns = {(p, a): jac[names.index(p), a] for k, p, a in kinds if k == "force"}
    Bq = np.zeros((mats.M.shape[0], len(kinds)))
    Du = np.zeros((len(outputs), len(kinds)))
    units = []
    for j, (kind, name, axis) in enumerate(kinds):
        if kind == "drive":
            source = model.drive_source[name]
            Bq[:, j] = b_strain[:, source] * gains[name].gain
            Du[:, j] = de[:, source] * gains[name].gain
            units.append("V")
        else:
            Bq[:, j] = force_columns[(name, axis)]
            units.append("N")
    m = N.shape[1]
    try:
        Minv = np.linalg.inv(Mr)
    except np.linalg.LinAlgError:
        raise ValueError(f"linearise: the mass matrix of {mech.name!r} on its degrees of freedom is singular "
                         "(a massless degree of freedom); a state-space model needs every degree of freedom to "
                         "carry mass") from None
    A = np.block([[np.zeros((m, m)), np.eye(m)], [-Minv @ Kr, -Minv @ Dr]])
    B = np.vstack([np.zeros((m, len(kinds))), Minv @ (N.T @ Bq)])
    C = np.hstack([dq @ N, np.zeros((len(outputs), m))])
    return LinearModel(A=A, B=B, C=C, D=Du, inputs=tuple(inputs), input_units=tuple(units), outputs=tuple(outputs),
                       output_units=tuple(columns[o] for o in outputs),
                       operating_point=dict(zip(outputs, map(float, values))), voltages=dict(state.voltages),
                       strains={name: g.strain for name, g in gains.items()},
                       gains={name: g.gain for name, g in gains.items()}, branch=branch, state=state.description)
