"""The Fig. 12 case overlays the paper's published strokes and says what cannot be compared."""

from __future__ import annotations

import importlib.util
import sys

import pytest

from _cli_helpers import CASES

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def case_module():
    spec = importlib.util.spec_from_file_location("paper_bending_actuator_case", CASES / "paper_bending_actuator.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    yield module
    sys.modules.pop(spec.name, None)


def test_docstring_says_what_cannot_be_compared(case_module):
    doc = case_module.__doc__
    assert "40 µm at 1500 V" in doc and "-4 µm at -500 V" in doc and "12 µm" in doc and "28 µm" in doc
    assert "cannot" in doc and "Fig. 12" in doc and "without" in doc


@pytest.mark.parametrize("exponents, rising, falling", [
    # exact exponents (corrected Eq. 10) pass through the paper's precision points by construction
    ("exact", 12e-6, 28e-6),
    # the paper's rounded r1 = 1.5, r2 = 2: -4 + 44 * 0.5**1.5 = 11.556 µm, 40 - 44 * 0.5**2 = 29 µm
    ("rounded", -4e-6 + 44e-6 * 0.5**1.5, 29e-6),
])
def test_overlay_values_and_plot(case_module, tmp_path, exponents, rising, falling):
    case = case_module.CASE
    out = case.run({"cell": "rigid", "period": 0.4, "cycles": 1, "exponents": exponents, "animation": False},
                   out_dir=tmp_path)
    rows = case_module.paper_comparison(out.result, 0.4, 1)
    labels = [r[0] for r in rows]
    assert [r[1] for r in rows] == [1500.0, -500.0, 500.0, 500.0]
    assert [r[2] for r in rows] == [40e-6, -4e-6, 12e-6, 28e-6]  # the paper's numbers, Sect. 3
    simulated = dict(zip(labels, (r[3] for r in rows)))
    # the loop's ends are the operator's range (-4 ... 40 µm for a 29 mm cell), reached exactly
    assert simulated[labels[0]] == pytest.approx(40e-6, abs=1e-12)
    assert simulated[labels[1]] == pytest.approx(-4e-6, abs=1e-12)
    # at 500 V: linear interpolation between recorded steps (voltage steps of 1 V at this period);
    # the branch's curvature makes that error below 1e-4 µm
    assert simulated[labels[2]] == pytest.approx(rising, abs=1e-10)
    assert simulated[labels[3]] == pytest.approx(falling, abs=1e-10)
    png = tmp_path / "paper_bending_actuator_stroke_vs_paper.png"
    assert png.name in [p.name for p in out.files]
    assert png.read_bytes()[:8] == PNG
