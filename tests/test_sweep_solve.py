"""A static sweep's points as the load steps of one Exudyn static solve (:mod:`exudyn_atcm.mbs.sweep_solve`).

References: the Jacobian a solver of its own forms at the same state (:meth:`SolverJacobian.system`,
whose agreement with central differences ``test_stability_proof.py`` checks), and the equilibria of
the same solve run to its end.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.mbs import builder as mb
import exudyn_atcm as atcm
from exudyn_atcm.mbs import continuation_settings, solver_runs, sweep_solve
from exudyn_atcm.mbs.stepping import Stepping
from exudyn_atcm.mbs.sweep_solve import LARGEST_SECANT_RATIO, secant_steps, solve_points, system_state
from exudyn_atcm.solve import mechanism_static as ms
from exudyn_atcm.solve.static_stability import stability_probe

from test_one_stepping import lone, paper_drive
from test_stability_proof import readme_four_bar

VOLTS = np.concatenate([np.linspace(0.0, 1200.0, 7), np.linspace(1200.0, -200.0, 8)[1:]])


def prepared(mech):
    """A built model in the equilibrium of the sweep's first point, its probe and every point's strains."""
    model = mb.build(mech)
    probe = stability_probe(mech, model)
    strains = Stepping.static(model).hold_path(VOLTS[:, None] * np.ones((1, len(model.sources))))
    ms.equilibrium(mech, model, np.zeros(len(model.sources)), strains[0], True, None, "point 0", probe)
    solver_runs.set_current_as_initial(model, zero_velocity=True)
    return model, probe, strains


@pytest.mark.parametrize("make", [lambda: lone(paper_drive(), cell="rod"), readme_four_bar,
                                  lambda: lone(paper_drive(), cell="rigid")], ids=["lone rod", "four-bar rod", "lone rigid"])
def test_the_running_solvers_jacobian_is_the_probes_to_the_bit(make):
    # the mass matrix too, at every point: a rigid cell's turns with it (it was once formed only once, and the
    # rigid case here showed it 20 % off in its coupling terms at the second point)
    model, probe, strains = prepared(make())
    assert probe.jacobian.exact
    seen = []

    def on_point(k, solver, state):
        model.before_linearisation()
        running = probe.jacobian.running_system(solver, mass=True)
        own = probe.jacobian.system(mass=True)
        for key in ("M", "K", "Cq"):
            np.testing.assert_array_equal(running[key], own[key], err_msg=f"{key} at point {k}")
        seen.append(k)
        return True

    solved = solve_points(model, strains, 1, on_point, connector_derivative=True)
    assert seen == list(range(1, len(VOLTS))) and solved.last == len(VOLTS) - 1
    assert not solved.stopped and solved.failure is None


def test_the_secant_step_is_the_next_strain_step_over_the_last_along_it():
    one = secant_steps(np.array([0.0, 1e-4, 2e-4, 1e-4, 1e-4, 2e-4, 4.5e-4, 1e-4])[:, None])
    # points 0 and 1: no last step; an even step: 1; a reversal: back along it (-1); a repeated point: 0, and no
    # last step after it (nan); 2.5 times the last: beyond LARGEST_SECANT_RATIO (2), a jump: started from the
    # last point (nan); then -3.5 / 2.5
    np.testing.assert_allclose(one, [np.nan, np.nan, 1.0, -1.0, 0.0, np.nan, np.nan, -1.4], rtol=1e-12)
    assert LARGEST_SECANT_RATIO == 2.0
    np.testing.assert_allclose(secant_steps(np.array([[0.0], [1e-4], [3e-4]])), [np.nan, np.nan, 2.0], rtol=1e-12)
    # two sources: the projection of the next step on the last one
    two = secant_steps(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 5.0]]))
    np.testing.assert_allclose(two, [np.nan, np.nan, 1.0], rtol=1e-12)
    assert secant_steps(np.zeros((2, 1))).shape == (2,) and np.isnan(secant_steps(np.zeros((2, 1)))).all()


@pytest.mark.parametrize("make", [lambda: lone(paper_drive(), cell="rod"), readme_four_bar,
                                  lambda: lone(paper_drive(), cell="rigid"), lambda: lone(paper_drive(), cell="six-bar")],
                         ids=["lone rod", "four-bar rod", "lone rigid", "lone six-bar"])
def test_the_secant_prediction_saves_newton_iterations_and_leaves_the_equilibria(make, monkeypatch):
    # the reference: the same solve with every point's iteration started from the last point's equilibrium (no
    # prediction: what the continuation did before it had one); the same equations and tolerances, so the same
    # equilibria within the Newton tolerance (1e-9, as the per-point sweep's, tests/test_static_sweep_continuation.py)
    def solved() -> tuple[dict, int]:
        model, _, strains = prepared(make())
        states, newton = {}, [0]

        def on_point(k, solver, state):
            states[k], newton[0] = state[0], solver.it.newtonStepsCount
            return True

        assert solve_points(model, strains, 1, on_point).last == len(VOLTS) - 1
        return states, newton[0]

    predicted, with_prediction = solved()
    monkeypatch.setattr(sweep_solve, "secant_steps", lambda strains: np.full(len(strains), np.nan))
    plain, without = solved()
    assert sorted(predicted) == sorted(plain) == list(range(1, len(VOLTS)))
    for k in plain:
        np.testing.assert_allclose(predicted[k], plain[k], rtol=0.0, atol=1e-9, err_msg=f"point {k}")
    # on this coarse cycle (200 V a point, a reversal) 0.52-0.81 of the iterations (measured); the README
    # four-bar's 100-point cycle: 393 -> 105 (benchmarks/REPORTS.md)
    assert with_prediction <= 0.85 * without


def test_a_point_reached_with_reduced_steps_ends_the_solve_there(monkeypatch):
    # a wild prediction (300 times the last step along it): Newton's iteration from there fails, Exudyn reduces
    # the point's step, the reduced steps start from the last point's equilibrium; the solve stops at the point
    # so reached (Exudyn would grow the step again without regard to the points), with that point's equilibrium
    def from_start(ratio) -> tuple[dict, object]:
        monkeypatch.setattr(sweep_solve, "secant_steps", lambda strains: np.full(len(strains), ratio))
        model, _, strains = prepared(readme_four_bar())
        states, attempts = {}, []

        def on_point(k, solver, state):
            states[k] = state[0]
            attempts.append(solver.it.currentStepIndex)
            return True

        return states, solve_points(model, strains, 1, on_point), attempts

    wild, stop, attempts = from_start(300.0)
    plain, end, _ = from_start(np.nan)
    assert end.last == len(VOLTS) - 1 and not end.stopped and end.failure is None
    assert stop.stopped and stop.failure is None and 1 < stop.last < len(VOLTS) - 1
    assert sorted(wild) == list(range(1, stop.last + 1))
    assert attempts[-1] > stop.last  # the last point took more than its one step
    for k in wild:
        np.testing.assert_allclose(wild[k], plain[k], rtol=0.0, atol=1e-9, err_msg=f"point {k}")


@pytest.mark.parametrize("grow", [False, True], ids=["never grown (the settings)", "grown back"])
def test_a_sweep_whose_steps_are_reduced_keeps_every_point(monkeypatch, grow):
    # the sweep goes on after such a stop in a new solve; with the step let grow again (Exudyn's default
    # recovery), a grown step ends beyond the next point: reported as a failure there, and that point solved as
    # its own equilibrium, never left out
    reference = atcm.static_sweep(readme_four_bar(), VOLTS, method="points")
    monkeypatch.setattr(sweep_solve, "secant_steps", lambda strains: np.full(len(strains), 300.0))
    if grow:
        monkeypatch.setattr(continuation_settings, "NEVER_GROW", 1)
    r = atcm.static_sweep(readme_four_bar(), VOLTS)
    assert list(r["point"]) == list(range(len(VOLTS)))
    notes = r.info["fallback_points"]
    assert ("went beyond point" in notes) == grow
    assert (r.info["continued_points"] < len(VOLTS) - 1) == grow
    for c in (c for c in r.names if r.unit(c) == "m"):
        np.testing.assert_allclose(r[c], reference[c], rtol=0.0, atol=1e-9, err_msg=c)


def test_a_stopped_solve_holds_the_point_it_stopped_at():
    model, _, strains = prepared(lone(paper_drive(), cell="rod"))
    states = {}

    def to_the_end(k, solver, state):
        states[k] = np.array(system_state(model)[0])
        return True

    start = system_state(model)
    solve_points(model, strains, 1, to_the_end)
    model2, _, _ = prepared(lone(paper_drive(), cell="rod"))
    np.testing.assert_array_equal(system_state(model2)[0], start[0])

    def stop_at_5(k, solver, state):
        return k < 5

    solved = solve_points(model2, strains, 1, stop_at_5)
    assert solved.last == 5 and solved.stopped and solved.failure is None
    np.testing.assert_array_equal(system_state(model2)[0], states[5])
    # and it continues from there to the same end
    rest = solve_points(model2, strains, 6, lambda k, solver, state: True)
    assert rest.last == len(VOLTS) - 1
    np.testing.assert_allclose(system_state(model2)[0], states[len(VOLTS) - 1], rtol=0.0, atol=1e-12)


def test_an_error_in_the_point_hook_is_raised_as_itself():
    model, _, strains = prepared(lone(paper_drive(), cell="rigid"))

    def broken(k, solver, state):
        raise KeyError("mine")

    with pytest.raises(KeyError, match="mine"):
        solve_points(model, strains, 1, broken)


def test_a_bad_first_point_is_refused():
    model, _, strains = prepared(lone(paper_drive(), cell="rigid"))
    with pytest.raises(ValueError, match=r"first: expected a point in 1 \.\.\. 13, got 0"):
        solve_points(model, strains, 0, lambda k, solver, state: True)


def test_the_rods_truncation_estimate_of_many_states_is_the_estimate_of_each():
    """A sweep reads every point's state and estimates them together (``estimate.many``): the same numbers as
    the estimate of each state alone (the same algebra, stacked), over random states with dead and follower
    forces."""
    from exudyn_atcm.theory import rotation_rod as rr
    shapes = rr.rod_shapes(3, 0.087)
    estimate = rr.truncation_estimator(shapes, 0.01)
    rng = np.random.default_rng(1)
    p = 25
    angles, q = rng.uniform(-1.0, 1.0, p), rng.uniform(-0.5, 0.5, (p, shapes.n))
    forces, followers = rng.uniform(-1.0, 1.0, (p, 2)), rng.uniform(-0.3, 0.3, (p, 2))
    one = np.array([estimate(angles[i], q[i], forces[i], followers[i]) for i in range(p)])
    np.testing.assert_allclose(estimate.many(angles, q, forces, followers), one, rtol=1e-12, atol=0.0)
    assert np.all(one > 0.0)


def test_the_joint_lever_term_of_a_pinned_bar_is_the_analytic_one():
    """Exudyn's Jacobian of a revolute joint leaves out ``lambda . d^2(R p)/dtheta^2``; :class:`JointLevers` adds it.
    Reference: the closed form ``s lambda . (R(theta) p)`` and the central differences of the residual."""
    import exudyn as exu
    import exudyn.itemInterface as ii
    from exudyn_atcm.mbs.solver_jacobian import SolverJacobian
    from exudyn_atcm.mbs.tangent import TangentPlan

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddObject(ii.ObjectGround())
    node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[0.05, 0.0, 0.0]))
    bar = mbs.AddObject(ii.ObjectRigidBody2D(nodeNumber=node, mass=0.1, inertia=1e-3))
    pin = [mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0])),
           mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=bar, localPosition=[-0.05, 0.0, 0.0]))]
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=pin))
    mbs.Assemble()
    theta, lam = 0.3, np.array([1.5, -0.7])
    for configuration in (exu.ConfigurationType.Current, exu.ConfigurationType.Initial):
        mbs.systemData.SetODE2Coordinates([0.0, 0.0, theta], configuration=configuration)
        mbs.systemData.SetAECoordinates(lam, configuration=configuration)
    closed_form = lam @ np.array([-0.05 * np.cos(theta), -0.05 * np.sin(theta)])  # s = +1: the second marker
    fast = SolverJacobian(mbs).system(mass=False)["K"]
    differences = TangentPlan(mbs).system(mass=False)["K"]
    assert closed_form == pytest.approx(-0.0613070, rel=1e-5)
    assert fast[2, 2] == pytest.approx(closed_form, rel=1e-12)
    assert differences[2, 2] == pytest.approx(closed_form, rel=1e-6)


def test_without_the_lever_terms_a_buckled_rigid_column_would_be_proved_stable(monkeypatch):
    """Why the lever terms matter: a rigid-cell column under 1.5 times Euler's load is unstable (the compressive
    force's geometric softening ``F L_c`` at every joint is what buckles it); from Exudyn's Jacobian alone the
    proof would pass it."""
    from exudyn_atcm.mbs.solver_jacobian import JointLevers
    from test_static_stability import column

    def probe_of_column():
        mech, _ = column("rigid", 8, 1.5, nudge=0.0)
        model = mb.build(mech)
        probe = stability_probe(mech, model)
        ms.equilibrium(mech, model, np.zeros(1), np.zeros(1), True, None, "the column", probe)  # the straight one
        return probe

    probe = probe_of_column()
    assert probe.jacobian.exact and probe.check().state == "unstable"
    monkeypatch.setattr(JointLevers, "add_to", lambda self, k, q, multipliers: None)
    probe = probe_of_column()
    probe.model.before_linearisation()
    assert probe._jacobian_proved(probe.jacobian.system(mass=probe.use_mass))  # the false proof, without them


def test_the_compiled_proof_is_the_numpy_proof_and_never_false():
    """:func:`shifted_penalised_cholesky` against the numpy proof on the same shifted matrix (same decision away
    from round-off) and against the truth, the lowest eigenvalue of the projection on the null space."""
    from scipy.linalg import null_space as scipy_null_space
    from exudyn_atcm.mbs.definite import PenaltyProof, positive_definite_on_null_space

    rng = np.random.default_rng(7)
    agree = proved = 0
    for trial in range(300):
        n, m = int(rng.integers(4, 20)), int(rng.integers(0, 4))
        cq = rng.normal(size=(m, n))
        k = rng.normal(size=(n, n))
        k = k @ k.T - rng.uniform(0.0, 3.0) * np.eye(n) + 0.3 * rng.normal(size=(n, n))
        mass = np.diag(rng.uniform(0.5, 2.0, n))
        sigma, per_size = float(rng.uniform(0.0, 0.5)), n * 1e-7
        a = k - sigma * mass - per_size * np.max(np.abs(k)) * np.eye(n)
        proof = PenaltyProof()
        proof.scale = float(10.0 ** rng.integers(0, 5))
        fast = proof.prove_shifted(k, mass, cq, sigma, per_size)
        slow = positive_definite_on_null_space(a, cq, proof._rho(a, cq.T @ cq if m else None))
        basis = scipy_null_space(cq) if m else np.eye(n)
        lowest = float(np.linalg.eigvalsh(basis.T @ (0.5 * (a + a.T)) @ basis)[0])
        if fast:
            assert lowest > 0.0, f"trial {trial}: a false proof"
            proved += 1
        if abs(lowest) > 1e-6 * np.max(np.abs(a)):  # away from round-off, both decide alike
            assert fast == slow, trial
            agree += 1
    assert agree > 250 and proved > 15  # the sample holds definite cases too (27 of 300 proved)


def test_the_proof_on_the_solvers_jacobian_is_the_proof_on_its_split_tangent():
    """:func:`jacobian_penalised_cholesky` (the solver's whole Jacobian, levers added and ``C_q^T C_q`` formed in the
    compiled call) against :meth:`PenaltyProof.prove_shifted` on the tangent split out of it with the lever terms
    written here in numpy (``K[r, r] += s lambda . R(theta) p``, see :class:`JointLevers`): the same decision
    away from round-off, and never a proof where the projected matrix is not positive definite."""
    from scipy.linalg import null_space as scipy_null_space
    from exudyn_atcm.mbs.definite import PenaltyProof

    rng = np.random.default_rng(11)
    agree = proved = 0
    for trial in range(300):
        n2, m = int(rng.integers(4, 20)), int(rng.integers(0, 5))
        jacobian = rng.normal(size=(n2 + m, n2 + m))
        k0 = rng.normal(size=(n2, n2))
        jacobian[:n2, :n2] = k0 @ k0.T - rng.uniform(0.0, 3.0) * np.eye(n2) + 0.3 * rng.normal(size=(n2, n2))
        q, multipliers = rng.normal(size=n2), rng.normal(size=m)
        levers = int(rng.integers(0, 4)) if m else 0
        rows = rng.integers(0, n2, size=levers)
        signs = rng.choice([-1.0, 1.0], size=levers)
        angles, local = rng.uniform(-3.0, 3.0, size=levers), rng.normal(size=(levers, 2))
        ae = rng.integers(0, max(m, 1), size=(levers, 2))
        mass = np.diag(rng.uniform(0.5, 2.0, n2))
        sigma, per_size = float(rng.uniform(0.0, 0.5)), n2 * 1e-7
        k = jacobian[:n2, :n2].copy()
        for r, s, a0, p, (i0, i1) in zip(rows, signs, angles, local, ae):
            c, sn = np.cos(a0 + q[r]), np.sin(a0 + q[r])
            k[r, r] += s * (multipliers[i0] * (c * p[0] - sn * p[1]) + multipliers[i1] * (sn * p[0] + c * p[1]))
        cq = jacobian[n2:, :n2]
        scale = float(10.0 ** rng.integers(0, 5))
        split_proof, fused_proof = PenaltyProof(), PenaltyProof()
        split_proof.scale = fused_proof.scale = scale
        split = split_proof.prove_shifted(k, mass, cq, sigma, per_size)
        fused = fused_proof.prove_from_jacobian(jacobian, n2, mass, (rows, signs, angles, local, ae), q, multipliers,
                                                sigma, per_size)
        a = k - sigma * mass - per_size * np.max(np.abs(k)) * np.eye(n2)
        basis = scipy_null_space(cq) if m else np.eye(n2)
        lowest = float(np.linalg.eigvalsh(basis.T @ (0.5 * (a + a.T)) @ basis)[0]) if basis.shape[1] else 1.0
        if fused:
            assert lowest > 0.0, f"trial {trial}: a false proof"
            proved += 1
        if abs(lowest) > 1e-6 * np.max(np.abs(a)):
            assert fused == split, trial
            agree += 1
    assert agree > 250 and proved > 15


@pytest.mark.parametrize("make", [readme_four_bar, lambda: lone(paper_drive(), cell="rigid")],
                         ids=["four-bar rod", "lone rigid"])
def test_the_in_solve_proof_decides_as_the_proof_on_the_split_tangent_along_a_sweep(make):
    # the same states as the compiled call sees them inside the solve; the rigid chain has lever terms on every cell
    model, probe, strains = prepared(make())
    assert probe.jacobian.exact
    decisions = []

    def on_point(k, solver, state):
        model.before_linearisation()
        split = probe._jacobian_proved(probe.jacobian.running_system(solver, mass=probe.use_mass))
        fused = probe.proved_in_solve(solver)  # last: the probe keeps its Jacobian unsplit
        decisions.append((k, fused, split))
        return True

    solve_points(model, strains, 1, on_point, connector_derivative=True)
    assert len(decisions) == len(VOLTS) - 1
    assert all(fused == split for _, fused, split in decisions), decisions
    assert all(fused for _, fused, _ in decisions)  # these sweeps are stable throughout, with a margin
    # the tangent of the last state proved inside the solve, split on demand, is the one a solver of its own forms
    model.before_linearisation()
    own = probe.jacobian.system(mass=probe.use_mass)
    assert isinstance(probe._ts, tuple)
    kept = probe._kept_tangent()
    for key in ("K", "Cq"):
        np.testing.assert_array_equal(kept[key], own[key], err_msg=key)
