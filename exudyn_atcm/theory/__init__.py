"""Closed-form and semi-analytic references: composite beam theory, the elastica, the rigid four-bar
and the assumed-modes (Rayleigh-Ritz) mathematics of the ``ritz`` cell.

The face (``from exudyn_atcm.theory import free_curvature``) exports the references of

* :mod:`~exudyn_atcm.theory.beam`: the laminate and the cantilever (stiffness, free curvature,
  tip deflection, blocked force, chain compliance factors, the elastica, work and optimum);
* :mod:`~exudyn_atcm.theory.beam_mechanisms`: the mechanism cases (S-blade, rigid extension,
  spring contact, curved cantilever in large deflection);
* :mod:`~exudyn_atcm.theory.beam_dynamics`: the first bending frequency and the modal end-moment
  response;
* :mod:`~exudyn_atcm.theory.four_bar`: the rigid four-bar (Freudenstein, Grashof).

The assumed-modes mathematics of the ``ritz`` cell stays in :mod:`exudyn_atcm.theory.ritz_beam`, the
geometrically exact rod of the ``rod`` cell in :mod:`exudyn_atcm.theory.rotation_rod` (its compiled
step kernels in :mod:`exudyn_atcm.theory.rod_kernels`, the one module that imports numba, imported
only when a ``rod`` bender is built).

May import: numpy, scipy and the package's argument checks only (and numba in ``rod_kernels``).
"""

from .beam import (
    ELASTICA_TIP_FORCE,
    actuator_work,
    arc_point,
    axial_rigidity,
    beam_element_compliance_factor,
    blocked_force,
    chain_polygon,
    composite_bending_stiffness,
    free_curvature,
    layer_offset,
    linear_tip_deflection,
    mass_per_length,
    optimal_thickness_ratio,
    paper_bending_stiffness,
    paper_free_curvature,
    piezo_strain,
    rigid_chain_compliance_factor,
    second_moment,
    series_axial_rigidity,
    six_bar_chain_compliance_factor,
    tip_compliance,
)
from .beam_dynamics import BETA1_L, end_moment_tip_rotation, first_bending_frequency
from .beam_mechanisms import (
    curved_cantilever_end_load,
    curved_cantilever_spring_force,
    extension_blocked_force,
    extension_compliance,
    extension_free_deflection,
    rigid_chain_extension_compliance,
    rigid_extension_point,
    s_blade_deflection_linear,
    s_blade_end,
    spring_contact_force,
)
from .four_bar import (
    RigidFourBar,
    branch_of,
    circle_intersection,
    freudenstein_constants,
    freudenstein_rocker_angle,
    grashof_type,
)

__all__ = [
    # laminate and cantilever
    "ELASTICA_TIP_FORCE", "second_moment", "axial_rigidity", "layer_offset", "series_axial_rigidity",
    "composite_bending_stiffness", "paper_bending_stiffness", "free_curvature", "paper_free_curvature",
    "piezo_strain", "linear_tip_deflection", "arc_point", "chain_polygon", "blocked_force", "tip_compliance",
    "rigid_chain_compliance_factor", "six_bar_chain_compliance_factor", "beam_element_compliance_factor",
    "mass_per_length", "actuator_work", "optimal_thickness_ratio",
    # dynamics
    "BETA1_L", "first_bending_frequency", "end_moment_tip_rotation",
    # mechanism cases
    "s_blade_deflection_linear", "s_blade_end", "extension_free_deflection", "extension_compliance",
    "rigid_chain_extension_compliance", "extension_blocked_force", "spring_contact_force", "rigid_extension_point",
    "curved_cantilever_end_load", "curved_cantilever_spring_force",
    # rigid four-bar
    "RigidFourBar", "circle_intersection", "branch_of", "freudenstein_constants", "freudenstein_rocker_angle",
    "grashof_type",
]
