"""A study's stored runs follow the user's own modules the case reads (the run key covers their text).

A case importing a helper of its own (here ``mymat.VALUE``, at the top and inside ``run``) was keyed by
its own text only: after the helper was edited a study replayed the stored runs with the old numbers, and
a process that had imported the helper kept the old one.  The truth of each check is the case's own
arithmetic (``value = VALUE * x`` and ``inner = VALUE``, with the value written into the helper by the test).
"""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from exudyn_atcm.casework import load_case
from exudyn_atcm.study import run_study
from exudyn_atcm.study.case_modules import local_modules
from exudyn_atcm.study.options import RunOptions
from exudyn_atcm.study.table import column

CASE_TEXT = '''
"""A case that reads a number from a helper module beside it and from a case file it loads."""
from pathlib import Path

import mymat
from exudyn_atcm.casework import Case, CaseOutput, Parameter, case_module
from exudyn_atcm.io.result import Result

SHAPES = case_module(Path(__file__).with_name("shapes.py"))


def run(p, ctx):
    import mymat as inner  # imported again inside the run: the same module object
    value = mymat.VALUE * p.x * SHAPES.FACTOR
    return CaseOutput(Result({"x": [p.x]}, {"x": "-"}), {"value": (value, "-"), "inner": (inner.VALUE, "-")})


CASE = Case("helper_study", __doc__, [Parameter("x", 1.0, "-", "input x")], run)
'''

SHAPES_TEXT = '''
"""A case file loaded by the other one (its FACTOR)."""
from exudyn_atcm.casework import Case, CaseOutput
from exudyn_atcm.io.result import Result

FACTOR = {factor}
CASE = Case("shapes", __doc__, [], lambda p, ctx: CaseOutput(Result({{"x": [FACTOR]}}, {{"x": "-"}}), {{}}))
'''


def write(folder: Path, value: float, factor: float = 1.0) -> None:
    (folder / "mymat.py").write_text(f"VALUE = {value!r}\n")
    (folder / "shapes.py").write_text(textwrap.dedent(SHAPES_TEXT).format(factor=factor))


@pytest.fixture
def project(tmp_path, monkeypatch):
    folder = tmp_path / "project"
    folder.mkdir()
    (folder / "helper_study.py").write_text(textwrap.dedent(CASE_TEXT))
    write(folder, 2.0)
    monkeypatch.syspath_prepend(str(folder))
    monkeypatch.chdir(tmp_path)
    yield folder
    sys.modules.pop("mymat", None)


def test_the_helpers_a_case_reads_are_found_without_importing_them(project):
    sys.modules.pop("mymat", None)
    found = local_modules(project / "helper_study.py")
    assert found == [project / "mymat.py", project / "shapes.py"]
    assert "mymat" not in sys.modules
    # the package, numpy and the standard library are not the user's
    assert not any("site-packages" in str(p) or p.name == "__init__.py" for p in found)


@pytest.mark.parametrize("workers", [1, 2])
def test_an_edited_helper_makes_new_runs_that_read_it(project, tmp_path, workers):
    study = dict(run=RunOptions(workers=workers, out=tmp_path / "out"))
    case = load_case(project / "helper_study.py")
    first = run_study(case, {"x": [1.0, 3.0]}, **study)
    assert first.executed == 2
    np.testing.assert_array_equal(column(first.table, "value"), [2.0, 6.0])

    write(project, 5.0)  # the helper edited (same length), the case file untouched
    second = run_study(load_case(project / "helper_study.py"), {"x": [1.0, 3.0]}, **study)
    assert second.executed == 2 and second.reused == 0 and second.stale == 2
    np.testing.assert_array_equal(column(second.table, "value"), [5.0, 15.0])  # not the stored 2 x
    np.testing.assert_array_equal(column(second.table, "inner"), [5.0, 5.0])  # the module read again
    assert column(second.table, "stale").tolist() == [f"{str(project / 'mymat.py')!r}, which the case reads, changed"] * 2

    write(project, 5.0, factor=10.0)  # the loaded case file edited
    third = run_study(load_case(project / "helper_study.py"), {"x": [1.0, 3.0]}, **study)
    assert third.executed == 2
    np.testing.assert_array_equal(column(third.table, "value"), [50.0, 150.0])

    again = run_study(load_case(project / "helper_study.py"), {"x": [1.0, 3.0]}, **study)
    assert again.executed == 0 and again.reused == 2  # nothing changed: the store's runs are right
