"""A synthetic case for the study tests: closed-form scalars, optional failure, delay and run log.

Scalars: ``y = a x^2 + n`` [m] and ``z = sin(x) n`` [-], so every value of a study table has
an independent expected value.  ``fail_below`` makes runs with ``x < fail_below`` raise (a
failing run); ``delay`` sleeps that long (a run of known duration); ``crash_at`` ends the worker process
(a crash); ``log_dir`` gets one file per executed run (to count the runs a study really
executes).
"""

from __future__ import annotations

import math
import os
import time
import uuid
from pathlib import Path

from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, RunContext
from exudyn_atcm.io.result import Result

PARAMETERS = [
    Parameter("x", 1.0, "m", "input x"),
    Parameter("n", 2, "-", "an integer input"),
    Parameter("a", 1.0, "1/m", "coefficient of x^2"),
    Parameter("mode", "plain", "-", "a string parameter", choices=("plain", "other")),
    Parameter("fail_below", -1e30, "m", "runs with x below this raise ValueError"),
    Parameter("delay", 0.0, "s", "sleep this long in each run", minimum=0.0),
    Parameter("crash_at", -1e30, "m", "a run with x equal to this ends its process at once (a crashing solver)"),
    Parameter("log_dir", "", "-", "directory receiving one file per executed run ('' = none)"),
]


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    if p.delay > 0.0:
        time.sleep(p.delay)
    if p.x == p.crash_at:
        os._exit(3)  # no exception, no cleanup: like a segmentation fault inside a solver
    if p.x < p.fail_below:
        raise ValueError(f"x = {p.x} is below fail_below = {p.fail_below}")
    if p.log_dir:
        Path(p.log_dir, f"{p.x!r}_{p.n}_{os.getpid()}_{uuid.uuid4().hex}.run").write_text("ran\n")
    y = p.a * p.x**2 + p.n
    result = Result({"x": [p.x], "y": [y]}, {"x": "m", "y": "m"})
    return CaseOutput(result, {"y": (y, "m"), "z": (math.sin(p.x) * p.n, "-")})


CASE = Case("synthetic_study", __doc__, PARAMETERS, run)

if __name__ == "__main__":
    raise SystemExit(CASE.main())
