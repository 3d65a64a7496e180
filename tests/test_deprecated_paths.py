"""Old module paths of modules that were split (issue 14, part 4) still give every public name they had.

``exudyn_atcm.cases``, ``exudyn_atcm.regression`` and ``exudyn_atcm.beam_theory`` were one module
each before 0.9; they are now served by the faces ``exudyn_atcm.casework`` and ``exudyn_atcm.theory``.
The expected names are the public module-level definitions of the old files (read from commit
d102aa6, the last one with the flat layout), written out here so that a name dropped from a face
fails this test.  Each old path is imported in a fresh interpreter, so the warning is not hidden by
an earlier import.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

OLD_NAMES = {
    "cases": ["Case", "CaseError", "CaseOutput", "ENV_CASES", "Parameter", "Parameters", "PlotFunction",
              "RunContext", "RunFunction", "add_run_options", "case_dirs", "closest", "find_case", "list_cases",
              "load_case", "run_and_report", "versions"],
    "regression": ["ENV_SUITE", "MetricRow", "SuiteReport", "default_suite_dir", "load_suite", "run_suite"],
    "beam_theory": ["BETA1_L", "ELASTICA_TIP_FORCE", "actuator_work", "arc_point", "axial_rigidity",
                    "beam_element_compliance_factor", "blocked_force", "chain_polygon",
                    "composite_bending_stiffness", "curved_cantilever_end_load", "curved_cantilever_spring_force",
                    "end_moment_tip_rotation", "extension_blocked_force", "extension_compliance",
                    "extension_free_deflection", "first_bending_frequency", "free_curvature", "layer_offset",
                    "linear_tip_deflection", "mass_per_length", "optimal_thickness_ratio", "paper_bending_stiffness",
                    "paper_free_curvature", "piezo_strain", "rigid_chain_compliance_factor",
                    "rigid_chain_extension_compliance", "rigid_extension_point", "s_blade_deflection_linear",
                    "s_blade_end", "second_moment", "series_axial_rigidity", "six_bar_chain_compliance_factor",
                    "spring_contact_force", "tip_compliance"],
}
NEW_FACE = {"cases": "exudyn_atcm.casework", "regression": "exudyn_atcm.casework", "beam_theory": "exudyn_atcm.theory"}

PROBE = textwrap.dedent("""
    import importlib, json, sys, warnings
    old, face, names = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
    new = importlib.import_module(face)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        module = importlib.import_module("exudyn_atcm." + old)
    print(json.dumps({
        "missing": [n for n in names if not hasattr(module, n)],
        "different": [n for n in names if hasattr(module, n) and getattr(module, n) is not getattr(new, n, None)],
        "warnings": [str(w.message) for w in caught if issubclass(w.category, DeprecationWarning)],
        "module": module.__name__,
    }))
""")


@pytest.mark.parametrize("old", sorted(OLD_NAMES))
def test_old_path_gives_the_same_objects_and_warns(old):
    names = OLD_NAMES[old]
    proc = subprocess.run([sys.executable, "-c", PROBE, old, NEW_FACE[old], json.dumps(names)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    found = json.loads(proc.stdout.strip().splitlines()[-1])
    assert found["missing"] == [], f"exudyn_atcm.{old} lost {found['missing']}"
    assert found["different"] == [], f"exudyn_atcm.{old} gives other objects for {found['different']}"
    assert found["module"] == NEW_FACE[old]
    assert len(found["warnings"]) == 1
    assert found["warnings"][0].startswith(f"exudyn_atcm.{old} moved to {NEW_FACE[old]};")


@pytest.mark.parametrize("old", sorted(OLD_NAMES))
def test_every_old_name_is_in_the_face_all(old):
    """The faces export the old names in ``__all__`` (so ``from exudyn_atcm.casework import *`` has them)."""
    import importlib

    face = importlib.import_module(NEW_FACE[old])
    assert sorted(set(OLD_NAMES[old]) - set(face.__all__)) == []


#: the cell kinds' Exudyn realisations moved into ``mbs/chains/`` (one file per kind, found by the folder)
MOVED_REALISATIONS = {"six_bar": ("chains.six_bar", "add_six_bar_chain"), "beam_chain": ("chains.beam", "add_beam_chain"),
                      "rigid_chain": ("chains.rigid", "add_rigid_chain"), "ancf_chain": ("chains.ancf", "add_ancf_chain"),
                      "ritz_bender": ("chains.ritz", "add_ritz_bender")}


@pytest.mark.parametrize("old", sorted(MOVED_REALISATIONS))
def test_moved_realisation_paths_warn_and_give_the_module(old):
    new, name = MOVED_REALISATIONS[old]
    proc = subprocess.run([sys.executable, "-c", PROBE, f"mbs.{old}", f"exudyn_atcm.mbs.{new}", json.dumps([name])],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    found = json.loads(proc.stdout.strip().splitlines()[-1])
    assert found["missing"] == [] and found["different"] == [] and found["module"] == f"exudyn_atcm.mbs.{new}"
    assert found["warnings"] == [f"exudyn_atcm.mbs.{old} moved to exudyn_atcm.mbs.{new}; the old path goes away in "
                                 f"the next release (import from exudyn_atcm or exudyn_atcm.mbs.{new})"]
