"""A hysteresis family defined outside the package is one file (issue 30, part 4): a Bouc-Wen family.

Written here without touching the package: the operator (``evaluate``/``commit``/``checkpoint``/
``restore``), its fit, its registration as a family (:func:`register_family`) and as a saved-model
kind.  Used standalone, inverted (:func:`inverse_operator` reads the range it declares), in a
:class:`PiezoDrive` (a bender's static tip and a simulation exact under step rejection), saved and
loaded, and chosen by :func:`identify` on a record of a Bouc-Wen truth.

Reference: the Bouc-Wen equation integrated independently in this file with SciPy's ``solve_ivp``
(DOP853), not the operator's closed form.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares

from exudyn_atcm.hysteresis import HysteresisOperator, identify, inverse_operator, load_model
from exudyn_atcm.hysteresis.bisection import BisectionInverse
from exudyn_atcm.hysteresis.families import FamilyFit, register_family, registered_families, unregister_family
from exudyn_atcm.hysteresis.fit_report import make_report
from exudyn_atcm.hysteresis.identification import fit_samples, record_fit
from exudyn_atcm.hysteresis.model_registry import FLOAT, register_model_kind, unregister_model_kind
from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.model.signals import Triangle
from exudyn_atcm.solve import simulate, solve_static

from _actuator_geometries import REF_A
from _actuator_runs import coarse_step_expected
from test_identification import corners_path


# ----------------------------------------------------------------------------- the family (one file)

class BoucWen(HysteresisOperator):
    """``y = offset + k u − z``, ``dz = A du − β |du| z − γ du |z|`` (Bouc-Wen, exponent 1), rate independent.

    The piezo form (e.g. Low and Guo 2009): the output lags the input, the ascending branch below
    the descending one.  Between two inputs the input moves monotonically, and ``z`` follows in
    closed form (a linear ODE in ``u`` on each side of ``z = 0``).  Reset: ``u = 0``, ``z = 0``.
    Needs ``A > 0`` and ``β > |γ|`` (then ``|z| <= A/(β + γ)``, where ``dz/du <= 2Aβ/(β + γ)``) and
    ``k > 2Aβ/(β + γ)``: then the output increases with the input.
    """

    def __init__(self, k: float, A: float, beta: float, gamma: float, offset: float = 0.0) -> None:
        if not (A > 0.0 and beta > abs(gamma) and k > 2.0 * A * beta / (beta + gamma)):
            raise ValueError(f"need A > 0, beta > |gamma| and k > 2 A beta / (beta + gamma), got k={k!r}, A={A!r}, beta={beta!r}, "
                             f"gamma={gamma!r}")
        self.k, self.A, self.beta, self.gamma, self.offset = (float(v) for v in (k, A, beta, gamma, offset))
        self.reset()

    def _z(self, u: float) -> float:
        d = u - self._u
        z, xi = self._zc, abs(d)
        if d == 0.0:
            return z
        s = 1.0 if d > 0.0 else -1.0
        if z != 0.0 and (z > 0.0) != (s > 0.0):  # z is driven towards 0 (rate beta - gamma) and may cross it
            lam = self.beta - self.gamma
            z_inf = s * self.A / lam
            cross = math.log((z_inf - z) / z_inf) / lam
            if xi <= cross:
                return z_inf + (z - z_inf) * math.exp(-lam * xi)
            xi, z = xi - cross, 0.0
        lam = self.beta + self.gamma
        z_inf = s * self.A / lam
        return z_inf + (z - z_inf) * math.exp(-lam * xi)

    def evaluate(self, u: float) -> float:
        return self.offset + self.k * u - self._z(float(u))

    def commit(self, u: float) -> float:
        self._zc, self._u = self._z(float(u)), float(u)
        return self.output

    def reset(self) -> None:
        self._u, self._zc = 0.0, 0.0

    def checkpoint(self):
        return (self._u, self._zc)

    def restore(self, snapshot) -> None:
        self._u, self._zc = snapshot

    @property
    def output(self) -> float:
        return self.offset + self.k * self._u - self._zc

    def inverse(self, input_range=None) -> HysteresisOperator:
        return BisectionInverse(self, input_range)  # monotone; default range: the declared fitted_range


def z_along(u, beta, gamma):
    """``z`` of ``A = 1`` along ``u`` from the reset state (``z`` is proportional to ``A``), for the fit's design matrix."""
    unit = object.__new__(BoucWen)  # any beta, gamma the search tries, without the monotonicity check
    unit.k, unit.A, unit.beta, unit.gamma, unit.offset = 0.0, 1.0, beta, gamma, 0.0
    unit.reset()
    return -unit.apply(u)


def fit_bouc_wen(u, y, *, n_fit=None, fit_mask=None, output_unit="", output_quantity=None):
    """Least squares: ``offset``, ``k``, ``A`` linear (``z`` is proportional to ``A``), ``β``, ``γ/β`` searched.

    A record the family cannot describe gives ``ValueError`` (from the constructor: not increasing)."""
    started = time.perf_counter()
    u_a, y_a, mask, stop = fit_samples(u, y, n_fit, fit_mask)
    scale = 1.0 / float(np.ptp(u_a[mask]))

    def solve(p):
        beta = math.exp(p[0]) * scale
        X = np.column_stack([np.ones(u_a.size), u_a, -z_along(u_a, beta, beta * math.tanh(p[1]))])
        coef = np.linalg.lstsq(X[mask], y_a[mask], rcond=None)[0]
        return beta, coef, X[mask] @ coef - y_a[mask]

    p = least_squares(lambda q: solve(q)[2], [math.log(3.0), 0.0], bounds=([-10.0, -3.0], [10.0, 3.0])).x
    beta, (offset, k, A), _ = solve(p)
    model = BoucWen(k, A, beta, beta * math.tanh(p[1]), offset)
    report = make_report(model, u_a, y_a, stop if fit_mask is None else u_a.size, 0, "BoucWen.fit",
                         output_unit=output_unit, fit_time=time.perf_counter() - started,
                         fit_mask=None if fit_mask is None else mask)
    record_fit(model, report, mask, 0, u_a[mask], output_unit, output_quantity)
    return model, report


def bouc_wen_family(request):
    model, report = fit_bouc_wen(request.u, request.y, **request.rows, **request.units)
    return FamilyFit("bouc_wen (n = 1)", model, report, parameters=5)


@pytest.fixture(scope="module", autouse=True)
def registered():
    """Register the family and its saved kind for this file's tests only (the other files' stay the package's)."""
    register_family("bouc_wen", bouc_wen_family, inverse="bisection", operator=BoucWen,
                    description="Bouc-Wen differential model, exponent 1")
    register_model_kind("bouc_wen", BoucWen, {"k": FLOAT, "A": FLOAT, "beta": FLOAT, "gamma": FLOAT, "offset": FLOAT})
    yield
    unregister_family("bouc_wen")
    unregister_model_kind("bouc_wen")


# ----------------------------------------------------------------------------- the independent reference

def reference(u, k, A, beta, gamma, offset=0.0):
    """Bouc-Wen output along ``u`` (linear between samples) from ``u = 0``, ``z = 0``, by ``solve_ivp``.

    Each monotone run of the input is one integration in ``ξ = |u − u_start|`` of
    ``dz/dξ = s A − β z − γ s |z|`` (``s`` the run's direction), output at every sample of the run.
    """
    u = np.concatenate([[0.0], np.asarray(u, dtype=float)])
    z = np.zeros(u.size)
    step = np.diff(u)
    start = 0
    while start < u.size - 1:
        moving = np.flatnonzero(step[start:])
        if not moving.size:  # the input stays: so does z
            z[start:] = z[start]
            break
        s = float(np.sign(step[start + moving[0]]))
        stop = start + 1
        while stop + 1 < u.size and s * step[stop] >= 0.0:
            stop += 1
        xi = np.abs(u[start:stop + 1] - u[start])
        at, where = np.unique(xi, return_inverse=True)  # t_eval must increase strictly (held inputs repeat)
        sol = solve_ivp(lambda _, zz: s * A - beta * zz - gamma * s * np.abs(zz), (0.0, at[-1]), [z[start]],
                        method="DOP853", t_eval=at, rtol=1e-12, atol=1e-14 * A / beta)
        z[start:stop + 1] = sol.y[0][where]
        start = stop
    return offset + k * u[1:] - z[1:]


TRUTH = dict(k=0.5, A=0.3, beta=2.0, gamma=1.0)  # u in [-1, 1]: |z| <= 0.1, output range 1.2
U = corners_path([0.0, 1.0, -1.0, 1.0, -0.3, 0.6, -1.0, 1.0, 0.2, -0.5, 1.0, -1.0, 0.7, -0.6, 0.4, -0.2, 1.0,
                  -1.0, 0.5], 0.01)
N_FIT = int(np.flatnonzero(np.isclose(U, -1.0))[2])  # fitted: up to the third visit of -1


def test_standalone_operator_is_the_integrated_equation():
    op = BoucWen(**TRUTH)
    # closed form against DOP853 at rtol 1e-12: agree to 1e-10 of the output range
    y = op.apply(U)
    np.testing.assert_allclose(y, reference(U, **TRUTH), rtol=0, atol=1e-10 * np.ptp(y))
    # evaluate has no side effect; commit of the same input gives the same output
    op.reset()
    op.commit(0.7)
    trial = op.evaluate(-0.4)
    assert op.evaluate(-0.4) == trial and op.output == op.evaluate(0.7)
    assert op.commit(-0.4) == trial
    # a loop with the piezo's sense: at u = 0.5 the ascending branch (first rise) lies below the descending one
    rising, falling = y[np.flatnonzero(np.isclose(U, 0.5))[:2]]
    assert falling - rising > 0.1


def test_inverse_operator_uses_the_declared_fitted_range():
    op = BoucWen(**TRUTH)
    # not fitted, no saturation: nothing declared, so the range must be given (no attribute guesses)
    with pytest.raises(ValueError, match="input_range must be given for a BoucWen"):
        inverse_operator(op)
    model, _ = fit_bouc_wen(U, reference(U, **TRUTH))
    assert model.fitted_range == (-1.0, 1.0)
    inverse = inverse_operator(model)
    assert (inverse.u_lo, inverse.u_hi) == (-1.0, 1.0)
    # strictly increasing (k > 0): the input comes back to the bisection's 1e-9 of the range.  Inputs inside
    # the range: at its ends the inverse's memory, 1e-9 off the forward's (Bouc-Wen's memory is continuous,
    # not wiped out), may leave a wanted output 1e-12 beyond reach (clipped, with a warning)
    u = 0.95 * U
    np.testing.assert_allclose(inverse.apply(model.apply(u)), u, rtol=0, atol=1e-8)
    np.testing.assert_allclose(model.inverse().apply(model.apply(u)), u, rtol=0, atol=1e-8)


def test_fit_recovers_the_truth():
    model, report = fit_bouc_wen(U, reference(U, **TRUTH), n_fit=N_FIT)
    # noise-free record of the model's own family: the parameters to the least-squares tolerance
    for name, value in TRUTH.items():
        assert getattr(model, name) == pytest.approx(value, rel=1e-4), name
    assert report.model_errors["held_out"]["rms"] < 1e-5 * np.ptp(U)


def test_saved_and_loaded(tmp_path):
    op = BoucWen(**TRUTH, offset=0.01)
    again = load_model(op.save(tmp_path / "bw.json"))
    assert type(again) is BoucWen
    np.testing.assert_array_equal(again.apply(U), op.apply(U))


def test_chosen_by_identify_on_a_bouc_wen_record():
    clean = reference(U, **TRUTH)
    sigma = 0.003 * np.ptp(clean)
    y = clean + sigma * np.random.default_rng(30).standard_normal(U.size)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # e.g. equal_gain not fitted to this record
        choice = identify(U, y, n_fit=N_FIT)
    assert {c.family for c in choice.candidates} == set(registered_families())
    assert choice.chosen.family == "bouc_wen", choice.to_text()
    c = choice.candidate("bouc_wen")
    assert (c.parameters, c.invertible, c.inverse) == (5, True, "bisection")
    # the truth's family predicts the held-out part to the noise (0.3 % of the range): within 1.3x (measured
    # 0.283 %; the next, prandtl_ishlinskii with 21 parameters, 0.641 %)
    assert c.held_out_rms_percent < 1.3 * 0.3
    assert "bouc_wen (n = 1) *" in choice.to_text()


# ----------------------------------------------------------------------------- in a drive

# volts to free strain: 3e-7/V linear and a loop about 1.2e-4 wide (|z| <= 6.25e-5; the MFC's range is 1.4e-3)
STRAIN = dict(k=3e-7, A=1.5e-7, beta=1.0 / 500.0, gamma=0.2 / 500.0)
# one Newton iteration per attempt: Exudyn rejects and cuts steps (measured 375 rejections in 0.1 s)
REJECTING = {"timeIntegration.newton.maxIterations": 1, "timeIntegration.newton.useModifiedNewton": False}


def strain_operator():
    op = BoucWen(**STRAIN)
    op.output_unit = "-"
    return op.with_output_quantity("strain")


def test_static_tip_in_a_drive():
    # the voltage is reached by a monotone ramp from the reset state (0 V); the same strain from a
    # linear drive gives the same equilibrium
    strain = float(reference([1500.0], **STRAIN)[-1])
    bw = solve_static(REF_A.actuator(PiezoDrive(1500.0, hysteresis=strain_operator()), cell="rigid"))
    linear = solve_static(REF_A.actuator(PiezoDrive(1500.0, d33=strain * 0.5e-3 / 1500.0, electrode_spacing=0.5e-3),
                                         cell="rigid"))
    assert bw["actuator.strain"][0] == pytest.approx(strain, rel=1e-10)
    for name in ("actuator.tip_x", "actuator.tip_y", "actuator.tip_angle"):
        assert bw[name][0] == pytest.approx(linear[name][0], rel=1e-9)
    assert abs(bw["actuator.tip_angle"][0]) > 0.1


def test_simulation_exact_under_step_rejection():
    drive = lambda: PiezoDrive(Triangle(500.0, 1000.0, 0.05), hysteresis=strain_operator())  # noqa: E731
    with coarse_step_expected():
        coarse = simulate(REF_A.actuator(drive(), cell="rigid"), 0.1, step=2e-3, settings=REJECTING)
    fine = simulate(REF_A.actuator(drive(), cell="rigid"), 0.1, step=2.5e-4)
    assert coarse.info["rejected_steps"] > 0 and np.diff(coarse["time"]).min() < 0.75 * 2e-3
    for r in (coarse, fine):
        # in-step strain = the equation integrated along the accepted voltages: trials of rejected
        # steps left no trace (closed form vs DOP853: 1e-10 of the range)
        expected = reference(r["actuator.voltage"], **STRAIN)
        np.testing.assert_allclose(r["actuator.strain"], expected, rtol=0, atol=1e-10 * np.ptp(expected))
        # the run covers the loop: -500 ... 1500 V, k 2000 V = 6e-4 less the loop's 1.25e-4 width at the ends
        assert np.ptp(r["actuator.strain"]) > 4.5e-4
    # both runs, at the times both recorded, carry the same strain: the voltages there are the program's, and
    # the memory differs only where a coarse step cut a triangle corner (a corner at t = 0.025 s, 0.075 s;
    # cut by at most one step of 2 ms, 80 V: measured 6.0e-4 of the range at 273 common times)
    common, i, j = np.intersect1d(np.round(coarse["time"], 12), np.round(fine["time"], 12), return_indices=True)
    assert common.size > 20
    np.testing.assert_allclose(coarse["actuator.strain"][i], fine["actuator.strain"][j], rtol=0, atol=1e-3 * np.ptp(fine["actuator.strain"]))


# ----------------------------------------------------------------------------- the registry's refusals

@pytest.mark.parametrize("kwargs, match", [
    ({"name": "Bouc Wen"}, "name must be lower case letters"),
    ({"fit": "fit_bouc_wen"}, "fit must be callable"),
    ({"inverse": "newton"}, r"inverse must be one of \('analytic', 'bisection', 'none \(staircase\)'\), got 'newton'"),
    ({"operator": BoucWen(**TRUTH)}, "operator must be a class or None"),
    ({"name": "bouc_wen"}, "name 'bouc_wen' is registered already"),
])
def test_register_family_refuses_bad_input(kwargs, match):
    args = {"name": "another", "fit": bouc_wen_family, "inverse": "bisection", **kwargs}
    with pytest.raises(ValueError, match=match):
        register_family(args.pop("name"), args.pop("fit"), **args)
    assert "another" not in registered_families()


def test_identify_refuses_an_unknown_family_and_families_is_a_deprecated_name():
    with pytest.raises(ValueError, match=r"families must be a non-empty selection of the registered families .*"
                                         r"'bouc_wen'\), got \('bouc_wenn',\)"):
        identify(U, reference(U, **TRUTH), families=("bouc_wenn",))
    from exudyn_atcm.errors import AtcmDeprecationWarning
    from exudyn_atcm.hysteresis import model_choice

    with pytest.warns(AtcmDeprecationWarning, match="FAMILIES is deprecated"):
        assert model_choice.FAMILIES == tuple(registered_families())
    with pytest.raises(ValueError, match="name must be a registered family, one of .*, got 'no_such'"):
        unregister_family("no_such")
    with pytest.raises(ValueError, match="name must be a registered kind, one of .*, got 'no_such'"):
        unregister_model_kind("no_such")
