"""A case that reads a number from a file named by a parameter: the run store must key its contents.

Scalar ``value = factor * x`` [-] with ``factor`` the number in the file ``data`` (a relative
path is read from the current directory, as ``open`` does); ``log_dir`` names a directory that
receives one file per executed run (to count the runs a study really executes, and a parameter
naming a directory whose contents change with every run).
"""

from __future__ import annotations

import os
import uuid
from pathlib import Path

from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, RunContext
from exudyn_atcm.io.result import Result

PARAMETERS = [
    Parameter("data", "factor.txt", "-", "file holding the factor"),
    Parameter("x", 1.0, "-", "input x"),
    Parameter("log_dir", "", "-", "directory receiving one file per executed run ('' = none)"),
    Parameter("mode", "plain", "-", "a choice", choices=("plain", "other")),
]


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    factor = float(Path(p.data).read_text())
    if p.log_dir:
        Path(p.log_dir, f"{os.getpid()}_{uuid.uuid4().hex}.run").write_text("ran\n")
    value = factor * p.x
    return CaseOutput(Result({"x": [p.x], "value": [value]}, {"x": "-", "value": "-"}), {"value": (value, "-")})


CASE = Case("file_study", __doc__, PARAMETERS, run)
