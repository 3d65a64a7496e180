"""A passive compliant hinge: a pseudo-rigid-body model or a passive cell chain."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._checks import hide_keywords, options_from_keywords, positive_float, positive_int, shown, warn_implausible
from ..model.laminate import Laminate
from ..model.materials import Layer
from ..model.damping import RayleighDamping, check_damping, damping_already_checked
from .bender import DEFAULT_DAMPING_RATIO, Bender
from .link import point_pair
from .damped import MaterialDamped
from .points import MechanismError, PointRef, check_name, unknown_point
from ..physical_bounds import check_cell_count

FLEXURE_MODELS = ("prbm", "cells")


class Flexure(MaterialDamped):
    """A passive flexure hinge (a straight strip of one material) between two points.

    Parameters
    ----------
    name : str
        Component name.
    base, tip : (float, float)
        End points in the reference pose [m] (the strip is straight there).
    width : float
        Width of the strip [m], > 0.
    layer : Layer
        The strip's material and thickness (``thickness`` [m], ``youngs_modulus`` [Pa],
        ``density`` [kg/m³]), as a bender's ``passive`` layer.  The earlier flat keywords
        ``thickness``, ``youngs_modulus``, ``density`` still work for one release (with an
        :class:`~exudyn_atcm.AtcmDeprecationWarning`).
    model : {"prbm", "cells"}, optional
        ``"prbm"`` (default): Howell's pseudo-rigid-body model for a fixed-guided/cantilever
        flexure: two rigid segments joined by a pin at the characteristic pivot, at the
        distance ``gamma L`` from the tip (``(1 - gamma) L`` from the base), with a torsion
        spring ``K = gamma k_theta E I / L`` (Howell 2001).  ``gamma = 0.5, k_theta = 2``
        gives the small-length flexural pivot (``K = E I / L``).
        ``"cells"``: a passive chain of ``n_cells`` rigid cells (a :class:`Bender` without
        active layer).
    n_cells : int, optional
        Cells of the ``"cells"`` model (default 4), at most
        :data:`~exudyn_atcm.physical_bounds.MAX_CELLS`.
    gamma : float, optional
        Characteristic radius factor, 0 < gamma <= 1 (default 0.8517, Howell's value for an
        end force).
    k_theta : float, optional
        Stiffness coefficient, > 0 (default 2.65).
    damping : float or RayleighDamping, optional
        A float: modal damping ratio of the strip's first clamped-free mode [-] (default
        0.02), i.e. ``beta = 2 zeta / omega_1`` of this strip.  A
        :class:`~exudyn_atcm.RayleighDamping`: the material's damping (``alpha`` [1/s] on
        the masses, ``beta`` [s] on the stiffnesses), independent of the strip's length.  A
        ratio of 1 or more (a percentage?) gives an :class:`~exudyn_atcm.errors.InputRangeWarning`.
    """

    @hide_keywords
    def __init__(self, name: str, *, base: tuple[float, float], tip: tuple[float, float], width: float,
                 layer: Layer | None = None, model: str = "prbm", n_cells: int = 4,
                 gamma: float = 0.8517, k_theta: float = 2.65,
                 damping: float | RayleighDamping = DEFAULT_DAMPING_RATIO, **flat: float) -> None:
        self.name = check_name("Flexure name", name)
        self.base_position = point_pair("base", base)
        self.tip_position = point_pair("tip", tip)
        self.width = positive_float("width", width)
        if layer is None and not flat:
            raise ValueError(f"flexure {name!r}: give layer=Layer(thickness, youngs_modulus, density) [m, Pa, kg/m³]")
        if flat:  # the earlier Flexure(..., thickness=, youngs_modulus=, density=)
            missing = [k for k in ("thickness", "youngs_modulus", "density") if k not in flat]
            if missing and layer is None and all(k in ("thickness", "youngs_modulus", "density") for k in flat):
                raise ValueError(f"flexure {name!r}: the earlier flat keywords need all three of thickness, "
                                 f"youngs_modulus, density (missing {missing}); better give layer=Layer(...)")
            (layer,) = options_from_keywords("Flexure", flat, layer=(Layer, layer))
        elif not isinstance(layer, Layer):
            raise ValueError(f"layer must be an exudyn_atcm Layer, got {shown(layer)}")
        self.thickness = layer.thickness
        self.youngs_modulus = layer.youngs_modulus
        self.density = layer.density
        if not isinstance(model, str) or model not in FLEXURE_MODELS:
            raise ValueError(f"model must be one of {FLEXURE_MODELS}, got {shown(model)}")
        self.model = model
        self.n_cells = check_cell_count("n_cells", positive_int("n_cells", n_cells), f"flexure {name!r}")
        self.gamma = positive_float("gamma", gamma)
        if self.gamma > 1.0:
            raise ValueError(f"gamma must be in (0, 1], got {shown(gamma)}")
        self.k_theta = positive_float("k_theta", k_theta)
        # both models' masses are rigid bodies (cells, or the PRBM's two segments)
        self.damping: float | RayleighDamping = check_damping(damping, cell="rigid", owner=f"flexure {name!r}")
        if self.length <= 0.0:
            raise MechanismError(f"flexure {name!r}: base and tip coincide ({self.base_position}); it needs a length")
        owner = f"flexure {name!r}"
        warn_implausible("length |tip - base|", self.length, "length", owner)
        warn_implausible("width", self.width, "length", owner)
        for pname, xy in (("base", self.base_position), ("tip", self.tip_position)):
            for axis, value in zip("xy", xy):
                warn_implausible(f"{pname} {axis}", value, "position", owner)
        # thickness, modulus and density: the Layer checked their plausible ranges (InputRangeWarning) when made

    @property
    def length(self) -> float:
        """Length ``L`` [m]."""
        return math.dist(self.base_position, self.tip_position)

    @property
    def angle(self) -> float:
        """Direction from base to tip [rad]."""
        dx = self.tip_position[0] - self.base_position[0]
        dy = self.tip_position[1] - self.base_position[1]
        return math.atan2(dy, dx)

    @property
    def layer(self) -> Layer:
        """The strip's material as a layer."""
        return Layer(self.thickness, self.youngs_modulus, self.density)

    @property
    def laminate(self) -> Laminate:
        """The cross-section as a passive laminate."""
        material = self.damping if isinstance(self.damping, RayleighDamping) else None
        return self._cached("laminate", (self.width, self.thickness, self.youngs_modulus, self.density, material),
                            lambda: Laminate(self.width, self.layer, None, "composite", material))

    @property
    def bending_stiffness(self) -> float:
        """``E I`` [N m²]."""
        return self.laminate.bending_stiffness

    @property
    def torsion_stiffness(self) -> float:
        """PRBM torsion spring ``K = gamma k_theta E I / L`` [N m/rad]."""
        return self.gamma * self.k_theta * self.bending_stiffness / self.length

    @property
    def pivot(self) -> tuple[float, float]:
        """PRBM characteristic pivot in the reference pose [m], ``(1 - gamma) L`` from the base."""
        s = 1.0 - self.gamma
        return (self.base_position[0] + s * (self.tip_position[0] - self.base_position[0]),
                self.base_position[1] + s * (self.tip_position[1] - self.base_position[1]))

    @property
    def segment_lengths(self) -> tuple[float, float]:
        """PRBM rigid segments: base side ``(1 - gamma) L`` and tip side ``gamma L`` [m]."""
        return (1.0 - self.gamma) * self.length, self.gamma * self.length


    @property
    def points(self) -> dict[str, tuple[float, float]]:
        """Named points in the reference pose [m]: ``base``, ``tip``."""
        return {"base": self.base_position, "tip": self.tip_position}

    def point(self, name: str) -> PointRef:
        """``"base"`` or ``"tip"`` as a :class:`PointRef`."""
        if name not in ("base", "tip"):
            raise unknown_point(self.name, name, ("base", "tip"))
        return PointRef(self.name, name)

    @property
    def base(self) -> PointRef:
        """The base point."""
        return PointRef(self.name, "base")

    @property
    def tip(self) -> PointRef:
        """The tip point."""
        return PointRef(self.name, "tip")

    def as_bender(self) -> Bender:
        """The ``"cells"`` model: a passive :class:`Bender` of ``n_cells`` rigid cells with this name."""
        with damping_already_checked():  # a damping ratio was warned about where the flexure was made
            return Bender(self.name, width=self.width, passive=self.layer, active=None, length=self.length,
                          n_cells=self.n_cells, base=self.base_position, angle=self.angle, damping=self.damping,
                          cell="rigid")

    def segment_masses(self) -> list[tuple[float, float, np.ndarray]]:
        """PRBM: (mass [kg], inertia about the centre [kg m²], centre [m]) of the base and tip segments."""
        mpl = self.laminate.mass_per_length
        b = np.array(self.base_position)
        t = np.array(self.tip_position)
        p = np.array(self.pivot)
        out = []
        for a, c in ((b, p), (p, t)):
            seg = float(np.linalg.norm(c - a))
            m = mpl * seg
            out.append((m, m * (seg**2 + self.thickness**2) / 12.0, 0.5 * (a + c)))
        return out

    def parameters(self) -> dict[str, Any]:
        """Parameters with units, for result headers."""
        p = self.name
        out: dict[str, Any] = {f"{p}.type": "Flexure", f"{p}.model": self.model, f"{p}.base [m]": self.base_position,
                               f"{p}.tip [m]": self.tip_position, f"{p}.width [m]": self.width,
                               f"{p}.thickness [m]": self.thickness, f"{p}.youngs_modulus [Pa]": self.youngs_modulus,
                               f"{p}.density [kg/m^3]": self.density}
        if isinstance(self.damping, RayleighDamping):
            out[f"{p}.damping.alpha [1/s]"] = self.damping.alpha
            out[f"{p}.damping.beta [s]"] = self.damping.beta
        else:
            out[f"{p}.damping ratio [-]"] = self.damping
        if self.model == "prbm":
            out[f"{p}.gamma [-]"] = self.gamma
            out[f"{p}.k_theta [-]"] = self.k_theta
            out[f"{p}.torsion_stiffness [N m/rad]"] = self.torsion_stiffness
        else:
            out[f"{p}.n_cells"] = self.n_cells
        return out

    def __repr__(self) -> str:
        return (f"Flexure({self.name!r}, base={self.base_position!r}, tip={self.tip_position!r}, width={self.width!r}, "
                f"layer={self.layer!r}, "
                f"model={self.model!r}, n_cells={self.n_cells!r}, gamma={self.gamma!r}, k_theta={self.k_theta!r}, "
                f"damping={self.damping!r})")
