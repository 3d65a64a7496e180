"""The regression benchmark suite: run case scripts, compare with stored and analytic references.

A suite is a directory (``benchmarks/regression/`` in the source checkout)::

    suite.json                 the suite: its description, its case folder ("cases_dir") and
                               optionally explicit benchmark entries
    references/<id>.csv        reference time series of benchmark <id> (Result CSV)
    references/<id>.json       reference scalars, wall time, steps and provenance history
    references/HISTORY.md      one line per reference change: date, versions, platform, reason

The benchmarks are declared by the cases themselves (``Case(..., benchmarks=[...])``,
:mod:`exudyn_atcm.casework.declarations`): the suite runs those of every case in its case folders
(the suite's ``"cases_dir"``, ``--cases-dir``, ``$EXUDYN_ATCM_CASES``; :func:`load_suite`), after the
entries ``suite.json`` lists itself, if any.  Each benchmark runs one case with fixed parameters and checks

* ``channels``: whole time series; the new series is interpolated linearly onto the
  reference's base (``"base"``, default ``time``) and its RMS and maximum error are compared
  with that channel's own absolute tolerances ``{"rms": ..., "max": ...}`` (in the channel's
  SI unit);
* ``scalars``: key scalars of the case, each either against an ``"analytic"`` value (from
  the paper or a closed form of the theory page, with its ``"source"``; never from the code's output) or against
  the stored reference, with tolerance ``"abs"`` and/or ``"rel"`` (passes if the error is
  within either).

Speed (wall time against the reference's) is reported separately and never fails the
verdict.  References are only written by :func:`run_suite` with ``update=True`` and a reason
(``exudyn-atcm bench --update-references --reason TEXT``); analytic references are never
written.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import os
import platform
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Sequence

from ..io.atomic import write_json, write_text
from .case import Case
from .declarations import check_benchmark
from .discovery import ENV_CASES, find_case, load_case, load_cases
from .outputs import versions
from .parameters import json_value
from ..io.result import read_csv
from ..io.result import Result
from .metrics import MetricRow, compare_benchmark

__all__ = ["MetricRow", "SuiteReport", "default_suite_dir", "load_suite", "run_suite", "ENV_SUITE"]

#: Environment variable naming the suite directory.
ENV_SUITE = "EXUDYN_ATCM_BENCH"


def default_suite_dir() -> Path:
    """``$EXUDYN_ATCM_BENCH``, else ``./benchmarks/regression`` of the current directory, else
    ``benchmarks/regression`` of the source checkout beside the package.

    Raises
    ------
    ValueError
        If none of these exists.
    """
    env = os.environ.get(ENV_SUITE)
    if env:
        return Path(env)
    candidates = [Path.cwd() / "benchmarks" / "regression", Path(__file__).resolve().parents[2] / "benchmarks" / "regression"]
    for candidate in candidates:
        if (candidate / "suite.json").is_file():
            return candidate
    raise ValueError(
        "suite: no regression suite found; looked for suite.json in "
        + ", ".join(str(c) for c in candidates)
        + f"; run from the source checkout, pass --suite DIR or set {ENV_SUITE}"
    )


@dataclass
class SuiteReport:
    """The outcome of a suite run."""

    rows: list[MetricRow] = field(default_factory=list)
    speed: list[dict[str, Any]] = field(default_factory=list)
    skipped: list[dict[str, str]] = field(default_factory=list)
    updated: list[str] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)
    wall_time: float = 0.0

    @property
    def passed(self) -> bool:
        """True if every accuracy metric passed (speed is not part of the verdict)."""
        return all(r.passed for r in self.rows)

    def table(self) -> str:
        """The accuracy and speed tables as Markdown."""
        head = "| case | metric | unit | reference | value | abs error | rel error | tolerance | pass | wall time [s] | steps |"
        lines = [head, "|" + "---|" * 11]
        for r in self.rows:
            lines.append(
                f"| {r.case} | {r.metric} | {r.unit} | {_fmt(r.reference)} | {_fmt(r.value)} | {_fmt(r.abs_error)} | "
                f"{_fmt(r.rel_error)} | {r.tolerance} | {'pass' if r.passed else '**FAIL**'} | {r.wall_time:.3f} | "
                f"{'' if r.steps is None else r.steps} |"
                + (f" {r.note}" if r.note and not r.passed else "")
            )
        lines += ["", "Speed (informative; never fails the verdict):", ""]
        lines += ["| case | wall time [s] | reference wall time [s] | ratio | steps |", "|---|---|---|---|---|"]
        for s in self.speed:
            lines.append(
                f"| {s['case']} | {s['wall_time']:.3f} | {_fmt(s['reference_wall_time'])} | {_fmt(s['ratio'])} | {s['steps']} |"
            )
        if self.skipped:
            lines += ["", "Skipped: " + "; ".join(f"{s['case']} ({s['reason']})" for s in self.skipped)]
        n_fail = sum(not r.passed for r in self.rows)
        lines += ["", f"Verdict: {'PASS' if self.passed else 'FAIL'} ({len(self.rows) - n_fail}/{len(self.rows)} metrics passed)"]
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        """JSON form of the report."""
        return {
            "passed": self.passed,
            "date": _now(),
            "versions": versions(),
            "platform": platform.platform(),
            "wall_time [s]": self.wall_time,
            "rows": [asdict(r) for r in self.rows],
            "speed": self.speed,
            "skipped": self.skipped,
            "updated_references": self.updated,
        }


def _fmt(x: Any) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if isinstance(x, (int, float)):
        return f"{x:.7g}"
    return str(x)


def _now() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


# ----------------------------------------------------------------------------- suite file
def load_suite(suite_dir: str | os.PathLike, cases_dir: str | os.PathLike | None = None) -> dict[str, Any]:
    """Read ``suite.json`` and collect the benchmarks: its own entries and those the cases declare.

    The declared benchmarks are those of every case in the suite's case folders: ``cases_dir``
    (``exudyn-atcm bench --cases-dir``), the suite's ``"cases_dir"`` (relative to the suite), and
    ``$EXUDYN_ATCM_CASES``, the first file of a name winning (:func:`~exudyn_atcm.casework.discovery.list_cases`).

    Returns
    -------
    dict
        ``suite.json``'s content with ``"benchmarks"`` the explicit entries followed by the declared
        ones (each with its ``"case"``), and ``"failed_cases"``: ``[path, message]`` of each case
        file in those folders that could not be loaded.

    Raises
    ------
    ValueError
        For a missing file, invalid JSON, an entry with unknown keys, a missing case or scalar
        name, a tolerance that is not a number >= 0, or an id given twice.
    """
    suite, _, _ = _collect(Path(suite_dir), cases_dir)
    return suite


def _collect(suite_path: Path, cases_dir: str | os.PathLike | None) -> tuple[dict[str, Any], dict[str, Case], list[Path]]:
    """The suite (as :func:`load_suite`), the declaring case of each declared benchmark id, the case folders."""
    path = suite_path / "suite.json"
    try:
        suite = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ValueError(f"{path}: no suite file (suite_dir must hold suite.json)") from None
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path}, line {exc.lineno}: invalid JSON: {exc.msg}") from None
    benchmarks = list(suite.get("benchmarks", []))
    for i, bench in enumerate(benchmarks):
        check_benchmark(bench, f"{path}: benchmarks[{i}]")
        if bench["id"] in [b["id"] for b in benchmarks[:i]]:
            raise ValueError(f"{path}: benchmarks[{i}]: duplicate id {bench['id']!r}")
    folders = [Path(cases_dir)] if cases_dir is not None else []
    if suite.get("cases_dir"):
        folders.append((suite_path / suite["cases_dir"]).resolve())
    cases, failed = load_cases(folders, package=False) if folders or os.environ.get(ENV_CASES) else ([], [])
    declaring: dict[str, Case] = {}
    where = {b["id"]: f"{path}: benchmarks[{i}]" for i, b in enumerate(benchmarks)}
    for case in cases:
        for bench in case.benchmarks:
            if bench["id"] in where:
                raise ValueError(f"benchmark id {bench['id']!r} is declared by case {case.name} ({case.source}) and "
                                 f"in {where[bench['id']]}: give each benchmark its own id")
            where[bench["id"]] = f"case {case.name} ({case.source})"
            declaring[bench["id"]] = case
            benchmarks.append(dict(bench))
    suite["benchmarks"] = benchmarks
    suite["failed_cases"] = [[str(p), message] for p, message in failed]
    return suite, declaring, [f for f in folders if f.is_dir()]


# ----------------------------------------------------------------------------- running
def run_suite(
    suite_dir: str | os.PathLike | None = None,
    out_dir: str | os.PathLike = "out/bench",
    *,
    quick: bool = False,
    update: bool = False,
    reason: str | None = None,
    plots: bool = True,
    only: Sequence[str] | None = None,
    echo: Any = None,
    cases_dir: str | os.PathLike | None = None,
) -> SuiteReport:
    """Run the suite, compare, write ``report.md``, ``report.json`` and the channel plots.

    Parameters
    ----------
    suite_dir : str or os.PathLike, optional
        Suite directory (default :func:`default_suite_dir`).
    out_dir : str or os.PathLike
        Report directory (created); each benchmark's case output goes to ``out_dir/<id>/``.
    quick : bool
        Only the benchmarks marked ``"quick": true``.
    update : bool
        Rewrite the stored references of the benchmarks run (needs ``reason``).
    reason : str, optional
        Why the references change; recorded in each reference's history and HISTORY.md.
    plots : bool
        Write a plot of each channel against its reference.
    only : sequence of str, optional
        Run only the benchmarks with these ids (for example to update one reference).
    echo : callable, optional
        ``echo(text)`` for progress lines (e.g. ``print``).
    cases_dir : str or os.PathLike, optional
        A further folder of cases whose declared benchmarks join the suite, searched first
        (``exudyn-atcm bench --cases-dir``; see :func:`load_suite`).

    Returns
    -------
    SuiteReport
        ``report.passed`` is the accuracy verdict.

    Raises
    ------
    ValueError
        For ``update`` without a non-empty ``reason``, or a malformed suite.
    """
    if update and (not reason or not reason.strip()):
        raise ValueError("reason must be a non-empty text when updating references, got " + repr(reason))
    suite_path = Path(suite_dir) if suite_dir is not None else default_suite_dir()
    suite, declaring, folders = _collect(suite_path, cases_dir)
    if only is not None:
        known = [b["id"] for b in suite.get("benchmarks", [])]
        unknown = [b for b in only if b not in known]
        if unknown:
            raise ValueError(f"only: unknown benchmark id(s) {', '.join(unknown)}; the suite has {', '.join(known)}")
    ref_dir = suite_path / "references"
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    search = folders[0] if folders else None  # where the explicit entries' cases are found first
    say = echo or (lambda text: None)
    report = SuiteReport()
    start_all = time.perf_counter()
    for file, message in suite["failed_cases"] if only is None else []:  # a broken case must not drop out unseen
        report.rows.append(MetricRow(Path(file).stem, "load", "run", "-", math.nan, math.nan, math.nan, math.nan, "loads",
                                     False, math.nan, None, message))
        say(f"  FAILED to load {file}: {message}")
    for bench in suite.get("benchmarks", []):
        bid = bench["id"]
        if only is not None and bid not in only:
            continue
        if not bench.get("enabled", True):
            report.skipped.append({"case": bid, "reason": bench.get("note", "disabled")})
            continue
        if quick and not bench.get("quick", False):
            report.skipped.append({"case": bid, "reason": "not in --quick"})
            continue
        say(f"running {bid} ({bench['case']}) ...")
        try:
            case = declaring[bid] if bid in declaring else load_case(find_case(bench["case"], search))
            output = case.run(bench.get("parameters", {}), out_dir=out / bid, plot=False)
        except Exception as exc:  # noqa: BLE001 - a failing case is a failed metric
            message = " ".join(str(exc).split())
            report.rows.append(MetricRow(bid, "run", "run", "-", math.nan, math.nan, math.nan, math.nan, "runs", False, math.nan, None, f"{type(exc).__name__}: {message}"))
            say(f"  FAILED to run: {type(exc).__name__}: {message}")
            continue
        if update:
            _write_reference(ref_dir, bid, bench, output, reason or "")
            report.updated.append(bid)
        reference = _read_reference(ref_dir, bid)
        rows = compare_benchmark(bench, output, reference, out / "plots" if plots else None, report.files)
        report.rows.extend(rows)
        ref_wall = reference["meta"].get("wall_time [s]") if reference else None
        report.speed.append(
            {
                "case": bid,
                "wall_time": output.wall_time,
                "reference_wall_time": ref_wall,
                "ratio": output.wall_time / ref_wall if ref_wall else None,
                "steps": output.steps,
            }
        )
        n_bad = sum(not r.passed for r in rows)
        say(f"  {len(rows) - n_bad}/{len(rows)} metrics passed in {output.wall_time:.2f} s")
    report.wall_time = time.perf_counter() - start_all
    report.files.append(write_text(out / "report.md", "# Regression benchmark report\n\n" + report.table() + "\n"))
    report.files.append(write_json(out / "report.json", report.to_dict()))
    return report


def _read_reference(ref_dir: Path, bid: str) -> dict[str, Any] | None:
    meta_path = ref_dir / f"{bid}.json"
    csv_path = ref_dir / f"{bid}.csv"
    if not meta_path.is_file():
        return None
    meta = json.loads(meta_path.read_text(encoding="utf-8"))
    series = read_csv(csv_path) if csv_path.is_file() else None
    return {"meta": meta, "series": series}


def _write_reference(ref_dir: Path, bid: str, bench: dict[str, Any], output: Any, reason: str) -> None:
    ref_dir.mkdir(parents=True, exist_ok=True)
    meta_path = ref_dir / f"{bid}.json"
    previous = json.loads(meta_path.read_text(encoding="utf-8")) if meta_path.is_file() else {}
    vers = versions()
    entry = {"date": _now(), "reason": reason.strip(), **vers, "platform": platform.platform()}
    meta = {
        "id": bid,
        "case": bench["case"],
        "parameters": {n: json_value(output.parameters[n]) for n in output.parameters},
        "scalars": {n: {"value": v, "unit": output.scalar_units[n]} for n, v in output.scalars.items()},
        "wall_time [s]": output.wall_time,
        "steps": output.steps,
        "provenance": entry,
        "history": previous.get("history", []) + [entry],
    }
    # only the series the benchmark compares (its base and channels): a scalars-only benchmark
    # stores no CSV, so the references stay small
    csv_path = ref_dir / f"{bid}.csv"
    channels = list(bench.get("channels", {}))
    if channels:
        base = bench.get("base", "time")
        names = [n for n in [base, *channels] if n in output.result]
        series = Result({n: output.result[n] for n in names}, {n: output.result.unit(n) for n in names},
                        parameters={"benchmark": bid, "case": bench["case"], "reason": reason.strip()},
                        info={"exudyn_version": vers["exudyn"], "date": entry["date"]})
        series.to_csv(csv_path)
    elif csv_path.is_file():
        csv_path.unlink()
    write_json(meta_path, meta)
    history = ref_dir / "HISTORY.md"
    old = history.read_text(encoding="utf-8") if history.is_file() else (
        "# Reference history\n\nOne line per change of a stored reference (written by "
        "`exudyn-atcm bench --update-references --reason TEXT`).\n\n"
        "| date | benchmark | exudyn_atcm | exudyn | python | platform | reason |\n|---|---|---|---|---|---|---|\n"
    )
    line = f"| {entry['date']} | {bid} | {vers['exudyn_atcm']} | {vers['exudyn']} | {vers['python']} | {entry['platform']} | {entry['reason']} |\n"
    write_text(history, old + line)

