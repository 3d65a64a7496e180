"""The piezo bending actuator: a chain of simulation cells (paper Figs. 2, 3, 11).

This module holds the geometry, the stiffness calibration, masses and damping of the
actuator, as plain numbers.  The Exudyn model is built from them by
:mod:`exudyn_atcm.mbs.builder` as the one-bender mechanism the actuator is
(:mod:`exudyn_atcm.solve.as_mechanism`); the closed-form references the tests compare against
are in :mod:`exudyn_atcm.theory.beam`.

Coordinates: ``x`` runs along the undeformed actuator from the clamp, ``y`` across it.
The passive layer's mid-plane lies on ``y = 0``; the active layer's mid-plane lies at
``y = -e`` with ``e = (h_passive + h_active)/2``, so a positive free strain of the active
layer bends the actuator towards ``+y``.  **The tip** is the passive-layer point of the last
interface element, ``(L, 0)`` in the undeformed state; the tip angle is the rotation of that
interface element (positive counter-clockwise).
"""

from __future__ import annotations

from typing import Any

from ..cells import CELL_KINDS, CellKind, cell_kind
from .bender import DEFAULT_CELL, Bender, mechanism_cells
from .._checks import finite_float, positive_float, positive_int, shown, warn_implausible
from ..model.drive import PiezoDrive
from ..model.laminate import STIFFNESS_MODELS, Laminate
from ..model.materials import Layer
from .assembly import Mechanism
from .damped import MaterialDamped
from ..model.damping import DEFAULT_DAMPING_RATIO, RayleighDamping, check_damping, damping_already_checked
from ..physical_bounds import check_cell_count

#: The bender's (and its drive's) name in the actuator's one-bender mechanism (:meth:`BendingActuator.as_mechanism`).
NAME = "actuator"
#: ``CELL_TYPES`` (one meaning: :data:`exudyn_atcm.mechanism.bender.CELL_TYPES`, the registered kinds a bender can be
#: made of, lone or in a mechanism) and ``TIP_LOAD_CELLS`` (those that carry a tip load; ``"ritz"`` refuses one):
#: module attributes read from the registry when asked
_LIVE = {"CELL_TYPES": mechanism_cells,
         "TIP_LOAD_CELLS": lambda: tuple(name for name, kind in CELL_KINDS.items() if kind.carries_tip_load)}


class BendingActuator(MaterialDamped):
    """Two-layer piezo bending actuator as a chain of ``n_cells`` simulation cells.

    Parameters
    ----------
    n_cells : int
        Number of cells ``N >= 1``, linked base-to-end; the first interface is clamped.  At most
        :data:`~exudyn_atcm.physical_bounds.MAX_CELLS` (1e5: more cannot change an answer).
    cell_length : float
        Length of one cell ``L_j`` [m], > 0.  The actuator length is ``N L_j``.
    width : float
        Width ``b`` of both layers [m], > 0.
    passive : Layer
        Passive layer (CFC), layer 1 (index 1 in the formulas).
    active : Layer
        Active layer (MFC), layer 2 (index 2 in the formulas).
    drive : PiezoDrive
        Voltage program and voltage-to-strain law of the active layer.
    cell : {"rod", "six-bar", "rigid", "beam", "ancf", "ritz"} or CellKind, optional
        A cell kind by name, or a :class:`~exudyn_atcm.cells.CellKind` (also one defined outside the
        package, e.g. a subclass of an existing kind); ``actuator.cell`` is the kind object.
        Default :data:`~exudyn_atcm.mechanism.bender.DEFAULT_CELL`, ``"rod"`` (as for a
        :class:`~exudyn_atcm.Bender`; before 0.4 ``"six-bar"``: pass ``cell="six-bar"`` for the paper's
        cell): ``n_cells`` modes of a geometrically exact rod (:class:`~exudyn_atcm.cells.RodCell`),
        exact arc under actuation, f1 +2.8e-4 at 3 modes, tip loads carried.
        ``"six-bar"``: the paper's cell (Fig. 2): interface elements, the passive
        bar, the active layer as three bodies A1-A2-A3, four revolute joints with torsion
        spring-dampers, the prismatic motor A1-A2 (prescribed stroke) and the prismatic
        joint A2-A3 carrying the axial spring ``k1``.
        ``"rigid"``: one rigid body per cell (passive layer's mid-plane, carrying the mass
        of both layers) with a torsion spring at each joint whose rest angle follows the
        stroke; the same bending stiffness and free curvature, without the six-bar cell's
        shear mode; much faster.
        ``"beam"``: one geometrically exact beam element per cell (Exudyn's
        ``ObjectBeamGeometricallyExact2D``, Simo-Reissner, linear elements) on the passive
        layer's mid-plane with the laminate's ``EI``, mass and rotary inertia and a
        practically inextensible, shear-rigid axis; the free curvature enters as one tip
        torque ``EI kappa``.  Exact under actuation alone at any element count; tip
        compliance factor ``1 - 1/(4 N^2)``, f1 from above.  ``cell_angle_j`` is the mean of
        the element's two node rotations.
        ``"ancf"``: one ANCF cable element per cell (Exudyn's ``ObjectANCFCable2D``, cubic
        Bernoulli-Euler element in node positions and slopes), same laminate data and tip
        torque; higher-order accurate (f1 +0.05 % at 2 elements): the cheapest at equal
        accuracy for small deflections.  In strongly bent states coarse meshes lock (f1
        about 1500 V +4 % at 2 elements): use >= 8 elements for large deflections.  Node
        rotations are the slope angles.
        ``"ritz"``: assumed modes of the whole bender's rotation field (Rayleigh-Ritz,
        :mod:`exudyn_atcm.theory.ritz_beam`; one ``ObjectGenericODE2``): ``n_cells`` is the number of
        modes ``n >= 1`` (integrated shifted Legendre polynomials), the bender is one piece of
        length ``n_cells * cell_length``, and ``cell_angle_j`` is the mean rotation of the
        ``j``-th of ``n`` equal segments.  Inextensible Euler-Bernoulli beam with the
        laminate's ``EI``, mass and rotary inertia: the static shape under actuation is the
        exact arc for any ``n`` (``n = 1`` included); the dynamics are linearised about the
        quasi-static arc of the current free curvature (mass matrix updated with it), so a
        ``RuntimeWarning`` says when the tip rotation deviates from that arc by more than
        0.05 rad.  f1 +0.47 % / +0.03 % / +1.5e-6 at n = 2 / 3 / 4.  The cheapest cell at
        equal accuracy.  Tip loads are refused (``tip_force`` must be zero: the model leaves
        out a load's geometric stiffness); use ``"beam"`` or ``"ancf"`` for them.
    stiffness : {"composite", "paper"}, optional
        ``"composite"`` (default): torsion springs ``2 E_i I_i / L_j`` per layer joint and
        ``k1 = [a1 a2/(a1 + a2)] / L_j`` (``a_i = E_i b h_i``): reproduces the laminate's
        bending stiffness and free curvature exactly (lamination theory; Timoshenko 1925; see the theory page of the documentation).
        ``"paper"``: as printed, ``k1 = E2 b h2 / L_j`` (Eq. 4) with a rigid passive bar and
        the torsion springs ``2 E_i I_i / L_j`` (Eq. 5 with the text's doubling).
    damping : float or RayleighDamping, optional
        A float: modal damping ratio ``zeta >= 0`` of the first bending mode [-], default 0.02.
        Realised as stiffness-proportional damping ``d = beta k`` on every spring
        (torsion springs and ``k1``; beam cells: their elements) with ``beta = 2 zeta / omega_1``,
        ``omega_1`` the first bending frequency of the continuous beam of this length: higher
        modes are damped more (ratio ``zeta omega / omega_1``).  2 % is an assumed, typical
        order of magnitude for fibre-composite laminates, not a value from the paper.  The
        same as the material damping ``RayleighDamping(beta=2 zeta / omega_1)`` for this
        length.  A :class:`~exudyn_atcm.RayleighDamping`: material damping of the laminate
        (``alpha`` [1/s] on the masses, ``beta`` [s] on the stiffnesses), which does not depend
        on the length; ``alpha > 0`` needs ``cell="rigid"`` or ``"six-bar"`` (see
        :mod:`exudyn_atcm.model.damping`, and :meth:`~exudyn_atcm.RayleighDamping.from_log_decrement`
        for a measured decay).  A ratio of 1 or more (``damping=5`` meant as 5 %?) gives an
        :class:`~exudyn_atcm.errors.InputRangeWarning`.

    Raises
    ------
    ValueError
        For non-positive or non-finite sizes, ``n_cells < 1``, an unknown ``cell`` or
        ``stiffness``, a negative ``damping``, or ``passive``/``active``/``drive`` of the
        wrong type.  The message names the parameter and the value received.

    Notes
    -----
    Masses: the passive bar carries the passive layer, A1, A2, A3 one third of the active
    layer each.  Six-bar interface elements need a mass of their own: each gets the mass
    of the laminate over a length ``s = min(h1 + h2, L_j/10)``, half taken from the layer
    bodies of each adjacent cell (lumped like the nodes of a finite-element mesh: the last
    interface gets half, the clamped interface's half stays at the clamp), so the mass
    distribution converges to the laminate's as the cells get shorter.
    """

    def __init__(
        self,
        n_cells: int,
        cell_length: float,
        width: float,
        passive: Layer,
        active: Layer,
        drive: PiezoDrive,
        cell: str | CellKind = DEFAULT_CELL,
        stiffness: str = "composite",
        damping: float | RayleighDamping = DEFAULT_DAMPING_RATIO,
    ) -> None:
        self.n_cells = check_cell_count("n_cells", positive_int("n_cells", n_cells), "BendingActuator")
        self.cell_length = positive_float("cell_length", cell_length)
        self.width = positive_float("width", width)
        warn_implausible("cell_length", self.cell_length, "length", "BendingActuator")
        warn_implausible("width", self.width, "length", "BendingActuator")
        for name, layer in (("passive", passive), ("active", active)):
            if not isinstance(layer, Layer):
                raise ValueError(f"{name} must be an exudyn_atcm Layer, got {shown(layer)}")
        if not isinstance(drive, PiezoDrive):
            raise ValueError(f"drive must be an exudyn_atcm PiezoDrive, got {shown(drive)}")
        cell = cell_kind(cell)
        if not isinstance(stiffness, str) or stiffness not in STIFFNESS_MODELS:
            raise ValueError(f"stiffness must be one of {STIFFNESS_MODELS}, got {shown(stiffness)}")
        damping = check_damping(damping, cell=cell, owner="BendingActuator")
        self.passive = passive
        self.active = active
        self.drive = drive
        self.cell = cell
        self.stiffness = stiffness
        self.damping = damping

    # ------------------------------------------------------------------ geometry
    @property
    def length(self) -> float:
        """Actuator length ``L = N L_j`` [m]."""
        return self.n_cells * self.cell_length

    @property
    def laminate(self) -> Laminate:
        """The cross-section (layers, width, stiffness model) whose formulas this actuator uses."""
        material = self.damping if isinstance(self.damping, RayleighDamping) else None
        return Laminate(self.width, self.passive, self.active, self.stiffness, material)

    @property
    def layer_offset(self) -> float:
        """Distance ``e`` between the layers' mid-planes [m]; the interface element's height."""
        return self.laminate.layer_offset

    # ------------------------------------------------------------------ stiffness
    @property
    def torsion_stiffness_passive(self) -> float:
        """Torsion spring at each passive-layer (lower) revolute joint, ``2 E1 I1 / L_j`` [N m/rad]."""
        return self.laminate.layer_joint_stiffness(self.cell_length)[0]

    @property
    def torsion_stiffness_active(self) -> float:
        """Torsion spring at each active-layer (upper) revolute joint, ``2 E2 I2 / L_j`` [N m/rad]."""
        return self.laminate.layer_joint_stiffness(self.cell_length)[1]

    @property
    def axial_rigidity_effective(self) -> float:
        """Axial rigidity that couples the layers [N]: ``a1 a2/(a1+a2)`` (composite) or ``a2`` (paper)."""
        return self.laminate.axial_rigidity_effective

    @property
    def axial_spring_stiffness(self) -> float:
        """Stiffness ``k1`` of the axial spring A2-A3 in each cell [N/m]."""
        return self.laminate.axial_spring_stiffness(self.cell_length)

    @property
    def bending_stiffness(self) -> float:
        """Bending stiffness ``EI`` of the modelled laminate [N m²].

        ``E1 I1 + E2 I2 + a_eff e²``; equal to lamination theory for ``stiffness="composite"``.
        """
        return self.laminate.bending_stiffness

    @property
    def spring_share(self) -> float:
        """Share ``rho_s = (E1 I1 + E2 I2)/EI`` of the bending stiffness held by the torsion springs [-]."""
        laminate = self.laminate
        return laminate.own_bending_stiffness / laminate.bending_stiffness

    @property
    def curvature_per_strain(self) -> float:
        """Free curvature per unit free strain ``a_eff e / EI`` [1/m]."""
        return self.laminate.curvature_per_strain

    def free_curvature(self, strain: float) -> float:
        """Free curvature [1/m] of the modelled laminate at free strain ``strain`` [-]."""
        return self.curvature_per_strain * strain

    @property
    def joint_stiffness_inside(self) -> float:
        """Rigid cell: torsion spring between two cells, ``EI / L_j`` [N m/rad]."""
        return self.bending_stiffness / self.cell_length

    @property
    def joint_stiffness_end(self) -> float:
        """Rigid cell: torsion spring at the clamp (and the tip interface), ``2 EI / L_j`` [N m/rad].

        Each end joint stands for half a cell.
        """
        return 2.0 * self.bending_stiffness / self.cell_length

    # ------------------------------------------------------------------ masses
    @property
    def mass_per_length(self) -> float:
        """Mass per unit length ``b (rho1 h1 + rho2 h2)`` [kg/m]."""
        return self.laminate.mass_per_length

    @property
    def interface_length(self) -> float:
        """Length ``s = min(h1 + h2, L_j/10)`` of laminate lumped into each six-bar interface [m]."""
        return self.laminate.interface_length(self.cell_length)

    @property
    def first_frequency_estimate(self) -> float:
        """First bending frequency of the continuous beam with this ``EI`` and mass [Hz]."""
        return self.laminate.first_frequency(self.length)


    # ------------------------------------------------------------------ the one-bender mechanism
    @property
    def bender(self) -> Bender:
        """The actuator as a :class:`~exudyn_atcm.Bender` named ``"actuator"``: base at the origin along +x,
        active layer on its right, the same layers, cells, cell kind, stiffness model, damping and drive."""
        with damping_already_checked():  # a damping ratio was warned about where the actuator was made
            return Bender(NAME, width=self.width, passive=self.passive, active=self.active, length=self.length,
                          n_cells=self.n_cells, drive=self.drive, cell=self.cell, stiffness=self.stiffness,
                          damping=self.damping)

    def as_mechanism(self, tip_force: tuple[float, float] = (0.0, 0.0)) -> Mechanism:
        """The actuator as what it is: a one-bender :class:`~exudyn_atcm.Mechanism` named ``"actuator"``.

        The :attr:`bender` with its base welded to the ground and, if not zero, the dead ``tip_force``
        ``(Fx, Fy)`` [N] at its tip (a mechanism force, ``mechanism.force(bender.tip, tip_force)``).  A
        drive with a controller observes ``"actuator.tip_y"``.  Every solve and drawing of an actuator
        goes through this one description (the result columns are those of any bender,
        ``actuator.tip_y`` ..., see :func:`exudyn_atcm.solve.as_mechanism.actuator_result`).

        Raises
        ------
        ValueError
            For a ``tip_force`` that is not a pair of finite numbers, or one a cell kind refuses
            (:meth:`~exudyn_atcm.cells.CellKind.tip_load_refusal`; ``"ritz"``), or a cell kind that cannot
            join a mechanism (:meth:`~exudyn_atcm.cells.CellKind.mechanism_refusal`).
        """
        try:
            fx, fy = tip_force
        except (TypeError, ValueError):
            raise ValueError(f"tip_force must be a pair (Fx, Fy) of finite numbers [N], got {shown(tip_force)}") from None
        force = (finite_float("tip_force[0]", fx), finite_float("tip_force[1]", fy))
        refusal = self.cell.mechanism_refusal()
        if refusal is not None:
            raise ValueError(f"cell={self.cell.name!r} cannot be solved as a one-bender mechanism: {refusal}")
        refusal = self.cell.tip_load_refusal()
        if refusal is not None and force != (0.0, 0.0):
            raise ValueError(f"tip_force must be (0, 0) for cell={self.cell.name!r}, got {tuple(tip_force)!r}: "
                             f"{refusal}")
        bender = self.bender
        mech = Mechanism(NAME).add(bender).ground(bender.base)
        if force != (0.0, 0.0):
            mech.force(bender.tip, force)
        if getattr(self.drive, "controller", None) is not None:
            mech.feedback(NAME, f"{NAME}.tip_y")
        return mech

    # ------------------------------------------------------------------ description
    def parameters(self) -> dict[str, Any]:
        """Parameters with units, for headers of result files."""
        drive = self.drive
        hyst = drive.hysteresis
        return {
            "cell": self.cell.name,
            "stiffness": self.stiffness,
            "n_cells": self.n_cells,
            "cell_length [m]": self.cell_length,
            "width [m]": self.width,
            "passive.thickness [m]": self.passive.thickness,
            "passive.youngs_modulus [Pa]": self.passive.youngs_modulus,
            "passive.density [kg/m^3]": self.passive.density,
            "active.thickness [m]": self.active.thickness,
            "active.youngs_modulus [Pa]": self.active.youngs_modulus,
            "active.density [kg/m^3]": self.active.density,
            **({"damping.alpha [1/s]": self.damping.alpha, "damping.beta [s]": self.damping.beta}
               if isinstance(self.damping, RayleighDamping) else {"damping ratio [-]": self.damping}),
            "voltage": repr(drive.voltage),
            "d33 [m/V]": drive.d33,
            "electrode_spacing [m]": drive.electrode_spacing,
            "hysteresis": "None" if hyst is None else repr(hyst),
            "bending_stiffness [N m^2]": self.bending_stiffness,
        }

    def __repr__(self) -> str:
        return (
            f"BendingActuator(n_cells={self.n_cells}, cell_length={self.cell_length!r}, "
            f"width={self.width!r}, passive={self.passive!r}, active={self.active!r}, "
            f"drive={self.drive!r}, cell={self.cell.spelled()}, stiffness={self.stiffness!r}, "
            f"damping={self.damping!r})"
        )


def __getattr__(name: str):
    # the registry's names, read when asked (kinds registered with exudyn_atcm.register_cell_kind included)
    if name in _LIVE:
        return _LIVE[name]()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
