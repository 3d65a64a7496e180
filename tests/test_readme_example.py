"""The README's Python example runs as printed, without warnings, and its answer is checked.

Reference: the coupler is a rigid link, so the distances between its points (A, B, P in the
README's description, in metres) stay those of the reference pose; and the crank tip and the
coupler's point A stay joined by the pin.
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np

README = Path(__file__).resolve().parent.parent / "README.md"


def test_readme_python_example_runs_and_keeps_the_coupler_rigid():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.S)
    assert blocks, "the README has no python example"
    namespace: dict = {"__name__": "__readme__"}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the example must not warn on its own parameters
        exec(compile(blocks[0], "README.md", "exec"), namespace)  # noqa: S102 - the README's example
    r = namespace["result"]
    # accuracy=1e-3 with the crank's cells left open (n_cells="auto"): the cells chosen within 0.3 of the
    # target, the step it chose divides 0.1 s, every step is recorded, and the run's own error estimate (a
    # probe run at twice the step, Richardson) is within the step's share
    step = r.info["step [s]"]
    accuracy = r.info["accuracy"]
    assert r.n_rows == round(0.1 / step) + 1
    assert accuracy["target"] == 1e-3 and accuracy["cells_estimated_error"] <= 0.3e-3
    assert accuracy["estimated_error"] <= accuracy["step_target"] <= 1e-3
    assert r.info["cell_choice"].startswith(f"bender 'crank': {r.parameters['crank.segment_1.n_cells']} rod modes "
                                            "for 0.0003 of the travel")
    assert "of 0.001" in r.info["step_choice"]
    point = {k: np.column_stack([r[f"coupler.{k}_x"], r[f"coupler.{k}_y"]]) for k in "ABP"}
    for a, b, ref in (("A", "B", 0.04), ("A", "P", math.hypot(0.02, 0.02)), ("B", "P", math.hypot(0.02, 0.02))):
        np.testing.assert_allclose(np.linalg.norm(point[a] - point[b], axis=1), ref, rtol=0, atol=1e-9)
    tip = np.column_stack([r["crank.tip_x"], r["crank.tip_y"]])
    np.testing.assert_allclose(tip, point["A"], rtol=0, atol=1e-9)
    assert np.ptp(point["P"][:, 0]) > 1e-4  # the drive moves the mechanism (not a trivial pass)
