"""A case is one file (issue 30, part 4): it declares its smoke settings, its regression benchmarks and
its row of the case tables, and the suite, the smoke test and the README/docs tables are read from there.

The outside case of these tests is a cantilever written into a temporary folder: its tip deflection under
an end force, integrated numerically from the bending moment, against the closed form F L^3 / (3 EI)
(Euler-Bernoulli; Timoshenko & Gere, Mechanics of Materials, cantilever with an end load) computed here.
"""

from __future__ import annotations

import json
import warnings

import pytest

from exudyn_atcm.casework import (Case, CaseError, CaseOutput, Parameter, case_table, find_case, list_cases, load_case,
                                  load_cases, load_suite, run_suite)
from exudyn_atcm.errors import AtcmWarning
from exudyn_atcm.io.result import Result

from _cli_helpers import CASES, REPO, cli

SUITE = REPO / "benchmarks" / "regression"
EI = 1.28699e-2  # N m², the paper's actuator (composite calibration); any bending stiffness would do


def closed_form_tip(force: float, length: float) -> float:
    """Tip deflection of a cantilever with an end force: F L^3 / (3 EI)."""
    return force * length**3 / (3.0 * EI)


CANTILEVER = '''"""A cantilever under an end force: the tip deflection from the bending moment, integrated twice.

Written by tests/test_case_declarations.py to show that a case of one's own is one file.
"""

import numpy as np

from exudyn_atcm.casework import Case, CaseOutput, Parameter
from exudyn_atcm.io.result import Result

EI = {ei!r}  # N m²

PARAMETERS = [
    Parameter("force", 0.1, "N", "end force", exclusive_minimum=0.0, maximum=10.0),
    Parameter("length", 0.087, "m", "free length", exclusive_minimum=0.0, maximum=1.0),
]


def run(p, ctx):
    x = np.linspace(0.0, p.length, 2001)
    curvature = p.force * (p.length - x) / EI                      # M(x) / EI
    h = np.diff(x)
    slope = np.concatenate(([0.0], np.cumsum(0.5 * h * (curvature[1:] + curvature[:-1]))))
    deflection = np.concatenate(([0.0], np.cumsum(0.5 * h * (slope[1:] + slope[:-1]))))
    result = Result({{"x": x, "deflection": deflection}}, {{"x": "m", "deflection": "m"}})
    return CaseOutput(result, scalars={{"tip_deflection": (float(deflection[-1]), "m")}}, steps=len(x))


CASE = Case("{name}", __doc__, PARAMETERS, run,
            smoke={{"force": 0.5}},
            benchmarks=[{{
                "id": "{name}_tip",
                "quick": True,
                "parameters": {{"force": 0.2, "length": 0.1}},
                "scalars": [{{"scalar": "tip_deflection", "analytic": {tip!r}, "rel": 1e-6,
                             "source": "F L^3 / (3 EI), computed in the test"}}],
            }}],
            summary="a cantilever under an end force (F L^3 / 3 EI)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
'''


def write_case(folder, name="cantilever_check", tip=None):
    """The outside case file in ``folder``; ``tip`` its benchmark's analytic value (default: the closed form)."""
    folder.mkdir(parents=True, exist_ok=True)
    tip = closed_form_tip(0.2, 0.1) if tip is None else tip
    path = folder / f"{name}.py"
    path.write_text(CANTILEVER.format(ei=EI, name=name, tip=tip), encoding="utf-8")
    return path


def shipped_cases():
    cases, failed = load_cases(CASES, package=False)
    assert failed == []
    return cases


# ----------------------------------------------------------------------------- the tables
def test_the_readme_table_is_the_one_the_case_files_declare():
    table = case_table(shipped_cases(), "md")
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    assert table in readme, "README.md's case table differs from `exudyn-atcm list --table md`:\n" + table
    # one row per case file, except the three paper hysteresis cases, which share one row
    files = [p for p in CASES.glob("*.py") if p.name != "__init__.py"]
    assert len(files) >= 13
    assert table.count("\n| `") == len(files) - 2


def test_the_docs_table_is_the_one_the_case_files_declare():
    table = case_table(shipped_cases(), "rst")
    page = (REPO / "docs" / "cases.rst").read_text(encoding="utf-8")
    assert table in page, "docs/cases.rst's case table differs from `exudyn-atcm list --table rst`:\n" + table


def test_a_changed_declaration_no_longer_matches_the_readme(tmp_path):
    # the check above fails when a case's declaration and the README disagree: a summary edited in the file
    text = (CASES / "bender_with_lever.py").read_text(encoding="utf-8")
    edited = text.replace('summary="a rigid extension welded', 'summary="a rigid lever welded')
    assert edited != text
    (tmp_path / "bender_with_lever.py").write_text(edited, encoding="utf-8")
    cases = [load_case(tmp_path / "bender_with_lever.py") if c.name == "bender_with_lever" else c for c in shipped_cases()]
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    assert case_table(cases, "md") not in readme
    assert "| `bender_with_lever` | a rigid lever welded to a bender tip (lever kinematics) |" in case_table(cases, "md")


def test_the_command_line_prints_the_tables(tmp_path):
    proc = cli(["list", "--table", "md"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == case_table(shipped_cases(), "md")
    proc = cli(["list", "--table", "tex"], tmp_path)
    assert proc.returncode == 2 and "invalid choice: 'tex'" in proc.stderr


# ----------------------------------------------------------------------------- the shipped suite
def test_the_suite_is_the_benchmarks_the_cases_declare():
    suite = load_suite(SUITE)
    ids = [b["id"] for b in suite["benchmarks"]]
    declared = [b["id"] for c in shipped_cases() for b in c.benchmarks]
    assert sorted(ids) == sorted(declared) and len(set(ids)) == len(ids) == 12
    assert "benchmarks" not in json.loads((SUITE / "suite.json").read_text(encoding="utf-8"))
    # every stored reference belongs to a declared benchmark, and every benchmark comparing stored values has one
    stored = {p.stem for p in (SUITE / "references").glob("*.json")}
    assert stored == set(ids)
    fig12 = next(b for b in suite["benchmarks"] if b["id"] == "bending_actuator_fig12")
    assert fig12["case"] == "paper_bending_actuator" and fig12["parameters"]["cell"] == "six-bar"


# ----------------------------------------------------------------------------- an outside case
def test_an_outside_case_is_discovered_smoke_run_benchmarked_and_tabled(tmp_path, monkeypatch):
    folder = tmp_path / "my_cases"
    path = write_case(folder)
    monkeypatch.setenv("EXUDYN_ATCM_CASES", str(folder))
    # discovered by name, as a user's case is ($EXUDYN_ATCM_CASES)
    assert find_case("cantilever_check") == path.resolve()
    assert path.resolve() in [p.resolve() for p in list_cases()]
    case = load_case("cantilever_check")
    assert [p.name for p in case.parameters] == ["force", "length"] and case.smoke == {"force": 0.5}

    # smoke-run as the package's smoke test runs a shipped case: its smoke settings, package warnings as errors
    with warnings.catch_warnings():
        warnings.simplefilter("error", AtcmWarning)
        out = case.run(case.smoke, plot=False)
    # trapezoidal rule on 2000 intervals: relative error ~ h^2 / L^2 ~ 1e-7, checked to 1e-6
    assert out.scalars["tip_deflection"] == pytest.approx(closed_form_tip(0.5, 0.087), rel=1e-6)

    # in the regression suite of the package (the checkout's suite, the case found through the variable)
    suite = load_suite(SUITE)
    ids = [b["id"] for b in suite["benchmarks"]]
    assert "cantilever_check_tip" in ids and len(ids) == 13
    report = run_suite(SUITE, tmp_path / "bench", plots=False, only=["cantilever_check_tip"])
    assert report.passed and len(report.rows) == 1
    row = report.rows[0]
    assert row.kind == "analytic" and row.reference == closed_form_tip(0.2, 0.1)
    assert row.value == pytest.approx(closed_form_tip(0.2, 0.1), rel=1e-6)

    # in the generated table, after the ordered rows (it declares no order), without touching package files
    table = case_table(load_cases()[0], "md")
    assert table.endswith("| `cantilever_check` | a cantilever under an end force (F L^3 / 3 EI) |")
    assert table.startswith(case_table(shipped_cases(), "md"))


def test_list_shows_an_outside_case_with_its_declarations(tmp_path):
    folder = tmp_path / "my_cases"
    write_case(folder)
    proc = cli(["list", "--cases-dir", str(folder)], tmp_path)
    assert proc.returncode == 0, proc.stderr
    block = proc.stdout.split("cantilever_check  (")[1].split("\n\n")[0]
    assert "    --set force = 0.1 [N] (float, > 0 and <= 10)" in block
    assert "    smoke test: --set force=0.5" in block and "    regression benchmarks: cantilever_check_tip" in block
    assert "    regression benchmarks: stiffness_ref_a, convergence_48_rigid_cells" in proc.stdout


def test_an_outside_benchmark_with_a_wrong_reference_fails_the_bench(tmp_path):
    # the same case with its analytic value 1 % off: the command line's bench fails on it (exit status 1)
    folder = tmp_path / "my_cases"
    write_case(folder, tip=1.01 * closed_form_tip(0.2, 0.1))
    proc = cli(["bench", "--only", "cantilever_check_tip", "--out", str(tmp_path / "b"), "--no-plots"], tmp_path,
               EXUDYN_ATCM_CASES=str(folder))
    assert proc.returncode == 1, proc.stdout[-2000:] + proc.stderr
    assert "| cantilever_check_tip | tip_deflection |" in proc.stdout and "**FAIL**" in proc.stdout
    # and with the right value it passes, found through --cases-dir this time
    write_case(folder)
    proc = cli(["bench", "--only", "cantilever_check_tip", "--cases-dir", str(folder), "--out", str(tmp_path / "c"),
                "--no-plots"], tmp_path)
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr
    assert "Verdict: PASS (1/1 metrics passed)" in proc.stdout


def test_a_broken_case_in_a_suite_folder_fails_the_suite(tmp_path, monkeypatch):
    folder = tmp_path / "my_cases"
    write_case(folder)
    (folder / "broken.py").write_text("from exudyn_atcm.casework import Case\nCASE = Case('broken', '', [], 3)\n")
    (folder / "helper.py").write_text("VALUE = 1  # not a case: left out, not executed\n")
    monkeypatch.setenv("EXUDYN_ATCM_CASES", str(folder))
    suite = load_suite(SUITE)
    assert [name for name, _ in suite["failed_cases"]] == [str((folder / "broken.py").resolve())]
    assert "run must be callable, got 3" in suite["failed_cases"][0][1]


# ----------------------------------------------------------------------------- refusals
def _run(p, ctx):
    return CaseOutput(Result({"x": [0.0]}, {"x": "m"}))


PARAMS = [Parameter("force", 0.1, "N", "end force", exclusive_minimum=0.0, maximum=10.0)]
GOOD = {"id": "b", "scalars": [{"scalar": "s", "rel": 1e-6}]}


@pytest.mark.parametrize("kwargs, message", [
    ({"smoke": {"forse": 1.0}}, "case c: smoke: unknown parameter 'forse' for case c (did you mean 'force'?)"),
    ({"smoke": {"force": 20.0}}, "case c: smoke: force must be > 0 and <= 10 [N], got 20.0"),
    ({"smoke": [("force", 1.0)]}, "case c: smoke must be a mapping"),
    ({"benchmarks": [{"id": "b", "scalars": [{"scalar": "s"}]}]}, "give a tolerance 'abs' and/or 'rel'"),
    ({"benchmarks": [{"id": "b", "scalars": [{"scalar": "s", "analytic": 1.0, "abs": 0.1}]}]}, "needs its 'source'"),
    ({"benchmarks": [{"id": "b", "scalars": [{"scalar": "s", "rel": -1e-6}]}]}, "'rel' must be a number >= 0, got -1e-06"),
    ({"benchmarks": [{**GOOD, "parameters": {"force": -1.0}}]}, "case c: benchmarks[0] (b): parameters: force must be > 0"),
    ({"benchmarks": [GOOD, GOOD]}, "benchmarks[1]: duplicate id 'b'"),
    ({"benchmarks": [{**GOOD, "case": "other"}]}, "'case' is the declaring case 'c', got 'other'"),
    ({"benchmarks": [{**GOOD, "tolerance": 1}]}, "unknown keys ['tolerance']"),
    ({"benchmarks": GOOD}, "benchmarks must be a list of suite entries, got dict"),
    ({"table_order": "first"}, "table_order must be a number (the row's position), got 'first'"),
])
def test_a_bad_declaration_is_refused_naming_the_case(kwargs, message):
    with pytest.raises(ValueError) as info:
        Case("c", "A case.", PARAMS, _run, **kwargs)
    assert message in str(info.value)


def test_declarations_are_copied_and_the_case_name_filled_in():
    bench = {"id": "b", "parameters": {"force": 2.0}, "scalars": [{"scalar": "s", "rel": 1e-6}]}
    case = Case("c", "A case.\n\nMore.", PARAMS, _run, benchmarks=[bench])
    bench["scalars"][0]["rel"] = 1.0
    assert case.benchmarks == ({"id": "b", "case": "c", "parameters": {"force": 2.0}, "scalars": [{"scalar": "s", "rel": 1e-6}]},)
    assert case.smoke == {} and case.summary == "A case." and case.table_order == float("inf")


def test_an_id_declared_twice_across_suite_and_case_is_refused(tmp_path, monkeypatch):
    folder = tmp_path / "my_cases"
    write_case(folder)
    suite = tmp_path / "suite"
    suite.mkdir()
    entry = {"id": "cantilever_check_tip", "case": "cantilever_check", "scalars": [{"scalar": "tip_deflection", "rel": 1e-6}]}
    (suite / "suite.json").write_text(json.dumps({"cases_dir": str(folder), "benchmarks": [entry]}))
    with pytest.raises(ValueError, match="'cantilever_check_tip' is declared by case cantilever_check .* give each "
                                         "benchmark its own id"):
        load_suite(suite)
    with pytest.raises(CaseError):
        load_case("no_such_case_anywhere")
