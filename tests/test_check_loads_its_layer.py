"""``Mechanism.check()`` and ``degrees_of_freedom()`` after a plain ``import exudyn_atcm`` (a fresh process).

``import exudyn_atcm`` loads its parts on first use, so the Exudyn layer that registers the check of
dependent joints was not loaded: ``check()`` skipped it and passed an over-constrained bender (its base
and tip both welded to the ground: one of its constraint equations is dependent), and
``degrees_of_freedom()`` asked the user to ``import exudyn_atcm``.  Reference: the same mechanism's
check with the layer imported first, and the count of a clamped-clamped chain (no free motion).
"""

from __future__ import annotations

import subprocess
import sys

SCRIPT = """
import sys
{first}
import exudyn_atcm as atcm
from exudyn_atcm import MechanismError
cfc = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
def clamped():
    b = atcm.Bender("b", width=10e-3, passive=cfc, length=0.03, n_cells=4, cell="rigid")
    return atcm.Mechanism("clamped").add(b).ground(b.base).ground(b.tip)
print("layer loaded first:", "exudyn_atcm.mbs" in sys.modules)
try:
    clamped().check()
    print("check: passed")
except MechanismError as exc:
    print("check:", "over-constrained" in str(exc) and "dependent" in str(exc))
report = clamped().degrees_of_freedom()
print("dof:", report.dof, "redundant:", report.redundant)
"""


def run(first: str) -> list[str]:
    done = subprocess.run([sys.executable, "-c", SCRIPT.format(first=first)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


def test_check_refuses_an_over_constrained_bender_without_its_layer_imported_first():
    plain, layer_first = run(""), run("import exudyn_atcm.mbs")
    assert plain[0] == "layer loaded first: False"  # the situation of the finding: nothing loaded the layer
    assert layer_first[0] == "layer loaded first: True"
    assert plain[1] == layer_first[1] == "check: True"  # refused as over-constrained, naming the dependent joints
    assert plain[2] == layer_first[2]
    assert plain[2].endswith("redundant: 1")  # the tip's weld repeats what the base's weld and the cells fix
