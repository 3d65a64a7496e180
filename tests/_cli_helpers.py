"""Helpers for tests that run the command line and case scripts in subprocesses."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
CASES = REPO / "cases"


def env(**extra: str) -> dict[str, str]:
    """Environment with the checkout importable and a headless matplotlib."""
    result = dict(os.environ)
    result["PYTHONPATH"] = str(REPO) + (os.pathsep + result["PYTHONPATH"] if result.get("PYTHONPATH") else "")
    result["MPLBACKEND"] = "Agg"
    result.pop("EXUDYN_ATCM_CASES", None)
    result.pop("EXUDYN_ATCM_BENCH", None)
    result.update(extra)
    return result


def run(args: list[str], cwd: Path, **extra: str) -> subprocess.CompletedProcess:
    """Run ``python ARGS`` and capture text output."""
    return subprocess.run(
        [sys.executable, *args], cwd=cwd, env=env(**extra), capture_output=True, text=True, timeout=300
    )


def cli(args: list[str], cwd: Path, **extra: str) -> subprocess.CompletedProcess:
    """Run ``python -m exudyn_atcm ARGS``."""
    return run(["-m", "exudyn_atcm", *args], cwd, **extra)
