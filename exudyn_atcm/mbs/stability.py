"""Stability of a static equilibrium: the lowest eigenvalue of the constrained tangent stiffness.

An equilibrium is stable when the tangent stiffness ``K_T`` of the constrained system
(:mod:`exudyn_atcm.mbs.eigen`: with the constraint forces' geometric stiffness), projected onto
the motions the joints allow (the null space ``N`` of the constraint Jacobian), is positive
definite.  Its lowest eigenvalue relative to the mass, ``omega_1^2`` of
``N^T K_T N v = omega^2 N^T M N v``, says how far from the stability limit it is: negative, the
equilibrium is unstable (a buckled column held straight, a snap-through mechanism on its
unstable branch); near zero, it is at a bifurcation or limit point (critical: the answer
depends on imperfections the model does not hold).

Follower (non-conservative) loads make the tangent unsymmetric: its symmetric part says nothing
about stability (a cantilever under a follower force, Beck's column, never diverges, yet the
symmetric part of its tangent turns indefinite).  For them the unsymmetric eigenproblem is solved
and only *divergence*, a real eigenvalue below zero, is reported; flutter (a complex pair) is a
dynamic instability that a static check cannot decide (Bolotin, *Nonconservative Problems of the
Theory of Elastic Stability*, 1963): follow it with ``simulate()``.

:class:`StabilityProbe` measures it relative to the same mechanism unloaded in its reference pose
(``omega_1^2 / omega_ref^2``, for a column under an axial load about ``1 - P/P_cr``).  The cost per
check, so that every point of a static sweep can be checked:

* the tangent by grouped differences (:class:`~exudyn_atcm.mbs.tangent.TangentPlan`, made once);
* first one Cholesky factorisation of ``K_T - sigma M + rho C_q^T C_q`` (symmetrised), ``sigma`` the
  critical margin times the reference eigenvalue: when it succeeds ``N^T (K_T - sigma M) N`` is
  positive definite (Finsler's lemma, :mod:`exudyn_atcm.mbs.definite`), every eigenvalue lies above
  ``sigma`` and the equilibrium is stable with a margin, without the null space ``N``, the
  projection or an eigenvalue solution (along a sweep of a stable mechanism nearly every point);
* only when it fails, the null space (a pivoted QR) and one Cholesky factorisation of
  ``N^T (K_T - sigma M) N`` (Sylvester's law of inertia: success proves the same); only when that
  fails too is the lowest eigenvalue computed;
* the dense algebra on one BLAS thread (``threadpoolctl``): for matrices of a few hundred rows a
  second thread gains nothing, and on a machine whose cores are busy (a study's workers) threads
  waiting for each other made a 192-row Cholesky factorisation 13 times slower (8.7 ms against
  0.65 ms, measured).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import exudyn as exu
import numpy as np

from .definite import PenaltyProof
from .model import MechanismModel
from .solver_jacobian import SolverJacobian
from .tangent import TangentPlan

from .blas_threads import one_blas_thread

__all__ = ["Stability", "STABLE", "StabilityProbe", "CRITICAL_MARGIN", "null_space", "one_blas_thread", "snapshot"]

#: ``omega_1^2 / omega_ref^2`` below which an equilibrium is critical (at a stability limit; for a
#: column ``P > 0.999 P_cr``): an imperfection's effect is amplified about ``1 / margin`` times.
CRITICAL_MARGIN = 1e-3

#: largest ``|K_r - K_r^T|`` relative to ``|K_r|`` (elementwise maxima) of a tangent taken as symmetric
#: (conservative loads; the grouped differences leave about 1e-8); above it the loads are
#: non-conservative (follower forces) and only divergence is checked (:meth:`StabilityProbe.check`).
ASYMMETRY_TOLERANCE = 1e-5

#: most coordinates for which the proof from Exudyn's Jacobian runs compiled (:mod:`exudyn_atcm.mbs.definite_kernel`):
#: measured 6 against 16 us (12 coordinates), 19 against 28 us (40); equal near 64, where LAPACK's blocked
#: factorisation overtakes the kernel's loops
KERNEL_SIZE = 48

#: largest difference, relative to ``max|K|``, between Exudyn's Jacobian (:mod:`exudyn_atcm.mbs.solver_jacobian`,
#: one-sided item-wise differences) and the central differences' tangent of the systems it is used for:
#: ten times the largest measured (1e-8, rod cells)
JACOBIAN_DIFFERENCE = 1e-7


@dataclass(frozen=True)
class Stability:
    """The stability of one equilibrium.

    Attributes
    ----------
    state : str
        ``"stable"``, ``"critical"`` (``|margin| <= CRITICAL_MARGIN``) or ``"unstable"``.
    margin : float
        ``omega_1^2 / omega_ref^2`` [-] when computed (critical or unstable states); for a stable
        state only a lower bound, :data:`CRITICAL_MARGIN`, is known and ``margin`` is ``nan``.
    lowest : float
        ``omega_1^2`` [1/s^2] (``nan`` for a stable state).
    mode : numpy.ndarray or None
        The lowest mode in the ODE2 coordinates (critical and unstable states).
    """

    state: str
    margin: float = math.nan
    lowest: float = math.nan
    mode: np.ndarray | None = None

    @property
    def frequency(self) -> float:
        """The lowest eigenfrequency [Hz], negative for an unstable direction (``nan`` when not computed)."""
        return math.copysign(math.sqrt(abs(self.lowest)), self.lowest) / (2.0 * math.pi)


#: a stable equilibrium's :class:`Stability` (frozen: one instance serves every point proved stable in a sweep)
STABLE = Stability("stable")


def null_space(cq: np.ndarray, n: int, tolerance: float = 1e-9) -> np.ndarray:
    """Orthonormal basis (n x r) of the null space of the constraint Jacobian ``cq`` (m x n), by pivoted QR;
    rows of ``cq`` whose pivot falls below ``tolerance`` times the largest count as dependent."""
    from scipy.linalg import qr  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
    if cq.shape[0] == 0:
        return np.eye(n)
    q, r, _ = qr(cq.T, mode="full", pivoting=True)
    diagonal = np.abs(np.diag(r))
    rank = int(np.sum(diagonal > tolerance * max(float(diagonal[0]) if diagonal.size else 0.0, 1e-300)))
    return q[:, rank:]


class StabilityProbe:
    """Checks the equilibria of one built model (the tangent plan and the reference eigenvalue made once).

    Parameters
    ----------
    model : MechanismModel
        The built model, in its undeformed reference pose when the probe is made (the reference
        eigenvalue is computed there, with the joints unloaded).
    fallback_scale : float
        ``omega^2`` [1/s^2] used as the reference when the unloaded mechanism has a direction
        without stiffness (e.g. a link on a free pin that only the loads hold): the lowest
        clamped-free frequency estimate of its parts, squared.
    """

    def __init__(self, model: MechanismModel, fallback_scale: float) -> None:
        from scipy.linalg import LinAlgError, cho_factor  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
        self.model = model
        self._plan: TangentPlan | None = None  # made on first use (:attr:`plan`)
        #: the cheap stability proof tried first by :meth:`check` (its counts say how often it sufficed)
        self.proof = PenaltyProof()
        #: Exudyn's Jacobian as the tangent where it is exact, and the proof tried with it first
        self.jacobian = SolverJacobian(model.mbs)
        self.jacobian_proof = PenaltyProof()
        #: whether :meth:`check` tries the proof from Exudyn's Jacobian (where it is exact, until it misses twice)
        self.use_jacobian = self.jacobian.exact
        self._jacobian_misses = 0
        self.use_mass = True
        self._identity: np.ndarray | None = None  # the metric without mass, kept for the compiled proof
        self._k_reference: np.ndarray | None = None
        if self.use_jacobian:  # the reference from Exudyn's Jacobian (unloaded joints: no lever terms either)
            model.before_linearisation()
            kr, mr = self._reduced(self.jacobian.system(mass=True))
        else:
            kr, mr = self._reduced()
        self._k_reference = self._k
        with one_blas_thread():
            try:
                cho_factor(mr)
            except LinAlgError:  # a direction without mass: the stiffness alone decides (identity metric)
                self.use_mass = False
                mr = np.eye(kr.shape[0])
            lowest, mode = self._lowest(kr, mr)
        self.reference = lowest if 0.0 < lowest < math.inf else float(fallback_scale)
        #: the unloaded mechanism's lowest eigenvalue ``omega^2`` [1/s^2] and its mode (ODE2 coordinates), as computed;
        #: far below ``fallback_scale`` it is a motion without stiffness (a link on a free pin)
        self.reference_lowest, self.reference_mode, self.fallback_scale = lowest, mode, float(fallback_scale)
        #: the last :meth:`check`'s result
        self.last: Stability | None = None

    @property
    def plan(self) -> TangentPlan:
        """The grouped central differences of the tangent (:class:`~exudyn_atcm.mbs.tangent.TangentPlan`), made on
        first use (a sweep proved from Exudyn's Jacobian never needs them: 0.3 to 0.5 ms saved)."""
        if self._plan is None:
            self._plan = TangentPlan(self.model.mbs)
        return self._plan

    def _tangent(self) -> dict:
        """The tangent system (:meth:`~exudyn_atcm.mbs.tangent.TangentPlan.system`) at the model's current state."""
        self.model.before_linearisation()
        ts = self.plan.system(mass=self.use_mass)
        self._k = ts["K"]
        self._basis = None  # projected on demand (:meth:`_reduced`)
        self._ts = ts
        return ts

    def _reduced(self, ts: dict | None = None) -> tuple[np.ndarray, np.ndarray]:
        """``N^T K_T N`` and ``N^T M N`` (the identity without mass), symmetrised, of the tangent system ``ts``
        (default: a new one at the model's current state)."""
        ts = self._tangent() if ts is None else ts
        k = self._k = ts["K"]
        with one_blas_thread():
            basis = null_space(ts["Cq"], k.shape[0])
            self._basis = basis
            kr = basis.T @ k @ basis
            self._kr = kr
            scale = float(np.max(np.abs(kr))) if kr.size else 0.0
            self._conservative = scale == 0.0 or float(np.max(np.abs(kr - kr.T))) <= ASYMMETRY_TOLERANCE * scale
            if not self.use_mass:
                return 0.5 * (kr + kr.T), np.eye(kr.shape[0])
            mr = basis.T @ ts["M"] @ basis
        return 0.5 * (kr + kr.T), 0.5 * (mr + mr.T)

    def _lowest(self, kr: np.ndarray, mr: np.ndarray) -> tuple[float, np.ndarray]:
        """The lowest eigenvalue [1/s^2] and its mode in the ODE2 coordinates (``inf`` without free directions)."""
        from scipy.linalg import eigh  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
        if kr.shape[0] == 0:
            return math.inf, np.zeros(self._basis.shape[0])
        w2, vecs = eigh(kr, mr, subset_by_index=[0, 0])
        return float(w2[0]), self._basis @ vecs[:, 0]

    def _lowest_divergence(self, mr: np.ndarray) -> tuple[float, np.ndarray]:
        """The lowest real eigenvalue [1/s^2] of the unsymmetrised ``N^T K_T N v = omega^2 N^T M N v`` (a
        follower load's tangent is not symmetric) and its mode; ``inf`` when every eigenvalue is complex."""
        from scipy.linalg import eig  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
        kr = self._kr
        with one_blas_thread():
            values, vecs = eig(kr, mr)
        finite = np.isfinite(values)
        real = finite & (np.abs(values.imag) <= 1e-6 * np.maximum(np.abs(values), 1e-300))
        if not np.any(real):
            return math.inf, np.zeros(self._basis.shape[0])
        k = int(np.flatnonzero(real)[np.argmin(values.real[real])])
        return float(values.real[k]), self._basis @ vecs[:, k].real

    def check(self) -> Stability:
        """The :class:`Stability` of the model's current state (a static equilibrium); also kept as :attr:`last`."""
        self.last = self._check()
        return self.last

    def _shifted(self, ts: dict, cushion: float = 0.0) -> np.ndarray:
        """``K - sigma M - cushion I`` (``M`` the identity without mass) of the tangent system ``ts``."""
        k = ts["K"]
        metric = ts["M"] if self.use_mass else np.eye(k.shape[0])
        shifted = k - (CRITICAL_MARGIN * self.reference) * metric
        if cushion:
            shifted.flat[::k.shape[0] + 1] -= cushion  # the diagonal
        return shifted

    def _check(self) -> Stability:
        with one_blas_thread():
            # the cheap proof first: K_T - sigma M positive definite on the joints' free motions, without
            # their basis (:mod:`exudyn_atcm.mbs.definite`); every eigenvalue's real part is then above sigma.
            # Where Exudyn's Jacobian is the tangent (:mod:`exudyn_atcm.mbs.solver_jacobian`), from it, with a
            # cushion n * JACOBIAN_DIFFERENCE * max|K| that bounds the 2-norm of its difference to the tangent
            # of the central differences; else (or when that proof fails) from the central differences
            if self.use_jacobian:
                self.model.before_linearisation()
                if self._jacobian_proved(self.jacobian.system(mass=self.use_mass)):
                    return Stability("stable")
            ts = self._tangent()
            shifted = self._shifted(ts)
            if self.proof(shifted, ts["Cq"]):
                self._jacobian_missed()
                return Stability("stable")
        result = self._full_check(ts)
        if result.state == "stable" and self._basis.shape[1] > 0:
            with one_blas_thread():
                self.proof.missed(shifted, ts["Cq"])  # stable after all: a penalty that proves it, for the next state
            self._jacobian_missed()
        return result

    def _jacobian_proved(self, js: dict) -> bool:
        """The cheap proof from Exudyn's Jacobian ``js`` (:class:`SolverJacobian`), with its cushion (compiled
        for up to :data:`KERNEL_SIZE` coordinates, :mod:`exudyn_atcm.mbs.definite_kernel`)."""
        k = js["K"]
        n = k.shape[0]
        if 0 < n <= KERNEL_SIZE:
            proved = self.jacobian_proof.prove_shifted(k, js["M"] if self.use_mass else self._eye(n), js["Cq"],
                                                       CRITICAL_MARGIN * self.reference, n * JACOBIAN_DIFFERENCE)
        else:
            cushion = n * JACOBIAN_DIFFERENCE * (float(abs(k).max()) if k.size else 0.0)
            proved = self.jacobian_proof(self._shifted(js, cushion), js["Cq"])
        if proved:
            self._proved(js)
        return proved

    def proved_in_solve(self, solver, q: np.ndarray | None = None, multipliers: np.ndarray | None = None) -> bool:
        """Whether the cheap proof from Exudyn's Jacobian shows the current state stable, inside a running static solve.

        ``solver``: the ``exudyn.MainSolverStatic`` whose step hook calls this, its settings with the
        connector derivative (:meth:`SolverJacobian.running_system`); ``q`` and ``multipliers``: copies of
        the current ODE2 coordinates and multipliers where the caller has them (read here otherwise).  ``True`` sets :attr:`last` to a
        stable :class:`Stability`, as :meth:`check` would; ``False`` proves nothing (and changes
        nothing): the caller then calls :meth:`check` on this state outside the solve.  Always
        ``False`` where Exudyn's Jacobian is not the tangent (:attr:`use_jacobian`).  Up to
        :data:`KERNEL_SIZE` coordinates the whole proof is one compiled call on the solver's Jacobian
        (:func:`~exudyn_atcm.mbs.definite_kernel.jacobian_penalised_cholesky`; the tangent is split
        out of it only if :meth:`critical_load_factor` asks for it).
        """
        if not self.use_jacobian:
            return False
        self.model.before_linearisation()
        jacobian, m = self.jacobian.running_jacobian(solver, mass=self.use_mass)
        n = self.jacobian.n_ode2
        if 0 < n <= KERNEL_SIZE:
            sd = self.model.mbs.systemData
            if q is None:
                q = np.array(sd.GetODE2Coordinates(copy=False), dtype=float)
            if multipliers is None:
                multipliers = np.array(sd.GetAECoordinates(copy=False), dtype=float)
            proved = self.jacobian_proof.prove_from_jacobian(jacobian, n, m if self.use_mass else self._eye(n),
                                                             self.jacobian.levers.arrays, q, multipliers,
                                                             CRITICAL_MARGIN * self.reference, n * JACOBIAN_DIFFERENCE)
            if proved:
                self._proved((jacobian, m, q, multipliers))
        else:
            with one_blas_thread():
                proved = self._jacobian_proved(self.jacobian.split(jacobian, m))
        if proved:
            self.last = STABLE
        return proved

    def _eye(self, n: int) -> np.ndarray:
        """The identity of order ``n`` (the metric without mass), kept."""
        if self._identity is None or self._identity.shape[0] != n:
            self._identity = np.eye(n)
        return self._identity

    def _proved(self, tangent: dict | tuple) -> None:
        """Keep the state just proved stable from Exudyn's Jacobian: its tangent system, or the Jacobian, mass
        matrix, coordinates and multipliers to split it from on demand (:meth:`_kept_tangent`)."""
        self._jacobian_misses = 0
        self._basis = None
        self._ts = tangent

    def _kept_tangent(self) -> dict:
        """The tangent system of the last state checked (split from Exudyn's Jacobian if it was kept unsplit)."""
        if isinstance(self._ts, tuple):
            jacobian, m, q, multipliers = self._ts
            self._ts = self.jacobian.split(jacobian, m, q, multipliers)
        return self._ts

    def _jacobian_missed(self) -> None:
        """The proof from Exudyn's Jacobian failed on a stable state: a larger penalty for the next one; after
        two such misses in a row it is not tried again (its cushion, relative to the largest stiffness, hides
        the bending stiffness of elements stiff along their axis: beam and ANCF cells, measured)."""
        if not self.use_jacobian:
            return
        self.jacobian_proof.missed()
        self._jacobian_misses += 1
        if self._jacobian_misses >= 2:
            self.use_jacobian = False

    def _full_check(self, ts: dict) -> Stability:
        """The check by the projection on the null space: Cholesky, then the lowest eigenvalue if that fails."""
        from scipy.linalg import LinAlgError, cho_factor  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
        kr, mr = self._reduced(ts)
        if kr.shape[0] == 0:
            return Stability("stable")
        if not self._conservative:  # follower loads: only divergence (a real eigenvalue through zero) is static
            lowest, mode = self._lowest_divergence(mr)
            if lowest == math.inf:
                return Stability("stable")
            margin = lowest / self.reference
            state = "unstable" if margin < -CRITICAL_MARGIN else ("critical" if margin <= CRITICAL_MARGIN else "stable")
            return Stability(state, margin if state != "stable" else math.nan, lowest if state != "stable" else math.nan,
                             mode if state != "stable" else None)
        with one_blas_thread():
            try:
                cho_factor(kr - CRITICAL_MARGIN * self.reference * mr)
                return Stability("stable")
            except LinAlgError:
                pass
            lowest, mode = self._lowest(kr, mr)
        margin = lowest / self.reference
        state = "unstable" if margin < -CRITICAL_MARGIN else ("critical" if margin <= CRITICAL_MARGIN else "stable")
        return Stability(state, margin, lowest, mode)


    def critical_load_factor(self) -> float:
        """The load factor at which the last checked state's loading path lost stability, estimated linearly.

        Along a path from the unloaded reference (load factor 0, tangent ``K_0``) to the last
        checked state (load factor 1, tangent ``K_1``), the tangent taken as
        ``K_0 + f (K_1 - K_0)`` in the last state's free directions: the smallest ``f`` in
        ``(0, 1]`` that makes it singular (the classical linear buckling estimate; exact for a
        column that stays straight, approximate where the path bends before it buckles).
        ``nan`` when there is none.
        """
        from scipy.linalg import eig  # noqa: PLC0415 - lazy: scipy.linalg is slow to import
        if self._basis is None:  # the last check was proved stable without the projection
            self._reduced(self._kept_tangent())
        basis = self._basis
        k0 = basis.T @ self._k_reference @ basis
        k0 = 0.5 * (k0 + k0.T)
        k1 = 0.5 * (self._kr + self._kr.T)
        with one_blas_thread():
            # (K_0 + f (K_1 - K_0)) v = 0  <=>  K_0 v = f (K_0 - K_1) v
            values = eig(k0, k0 - k1, right=False)
        factors = [v.real for v in values if np.isfinite(v) and abs(v.imag) <= 1e-9 * abs(v) and 0.0 < v.real <= 1.0]
        return min(factors) if factors else math.nan


def snapshot(model: MechanismModel) -> Callable[[], None]:
    """Save the model's current and initial states; returns the function that restores them."""
    sd = model.mbs.systemData
    cur, ini = exu.ConfigurationType.Current, exu.ConfigurationType.Initial
    saved = sd.GetSystemState(configuration=cur), sd.GetSystemState(configuration=ini)

    def restore() -> None:
        sd.SetSystemState(systemStateList=saved[0], configuration=cur)
        sd.SetSystemState(systemStateList=saved[1], configuration=ini)

    return restore
