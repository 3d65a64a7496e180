"""Old module paths: those of 0.2 are gone in 0.3, the faces keep every public name the old modules had.

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


@pytest.mark.parametrize("old", sorted(OLD_NAMES) + ["simulation", "mbs.six_bar", "result", "drive"])
def test_the_paths_that_moved_in_0_2_are_gone_in_0_3(old):
    """Kept one release (0.2) with a warning; removed in 0.3 as announced (docs/changelog.rst)."""
    proc = subprocess.run([sys.executable, "-c", f"import exudyn_atcm.{old}"], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode != 0 and "ModuleNotFoundError" in proc.stderr, proc.stderr


def test_a_path_moved_in_0_3_warns_and_gives_the_module():
    proc = subprocess.run([sys.executable, "-c", PROBE, "solve.step_record", "exudyn_atcm.mbs.step_record",
                           json.dumps(["StepRecord"])], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    found = json.loads(proc.stdout.strip().splitlines()[-1])
    assert found["missing"] == [] and found["different"] == [] and found["module"] == "exudyn_atcm.mbs.step_record"
    assert found["warnings"] == ["exudyn_atcm.solve.step_record moved to exudyn_atcm.mbs.step_record; the old path "
                                 "goes away in the next release (import from exudyn_atcm or "
                                 "exudyn_atcm.mbs.step_record)"]


def test_signals_stays_a_silent_path_of_the_face():
    proc = subprocess.run([sys.executable, "-W", "error", "-c", "import exudyn_atcm.signals as s; print(s.Triangle)"],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0 and "Triangle" in proc.stdout, proc.stderr


@pytest.mark.parametrize("old", sorted(OLD_NAMES))
def test_every_old_name_is_in_the_face_all(old):
    """The faces export the old names in ``__all__`` (so ``from exudyn_atcm.casework import *`` has them)."""
    import importlib

    face = importlib.import_module(NEW_FACE[old])
    assert sorted(set(OLD_NAMES[old]) - set(face.__all__)) == []
