"""The cell drawings: headless, a PNG file, the paper's symbols, spring values from the formulas."""

from __future__ import annotations

import sys

import pytest

from exudyn_atcm.theory import beam as beam_theory
from exudyn_atcm.plots.cells import cell_figure, height_exaggeration, paper_actuator, save_cell_drawing

PNG = b"\x89PNG\r\n\x1a\n"


def _texts(fig) -> str:
    return "\n".join(t.get_text() for ax in fig.axes for t in ax.texts)


def test_drawing_is_headless_and_writes_a_png(tmp_path):
    path = save_cell_drawing(tmp_path / "cells.png")
    assert path.read_bytes()[:8] == PNG
    assert path.stat().st_size > 20_000  # a real drawing, not an empty canvas
    assert [p.name for p in tmp_path.iterdir()] == ["cells.png"]  # atomic: no temporary file left
    # drawn on its own Agg canvas, not through pyplot's global figure manager (no display used)
    assert cell_figure().canvas.get_default_filetype() == "png"
    assert "matplotlib.pyplot" not in sys.modules or not sys.modules["matplotlib.pyplot"].get_fignums()


def test_both_cells_carry_the_papers_symbols():
    fig = cell_figure()
    top, bottom = fig.axes
    six_bar = "\n".join(t.get_text() for t in top.texts)
    for symbol in (r"$L_j$", r"$h_1$", r"$h_2$", r"$e$", r"$k_{\theta 1}$", r"$k_{\theta 2}$", r"$k_1$",
                   r"$x_a = \Lambda L_j$", "A1", "A2", "A3", r"$I_j$", r"$I_{j+1}$", "passive layer (CFC)",
                   "active layer (MFC)"):
        assert symbol in six_bar, symbol
    rigid = "\n".join(t.get_text() for t in bottom.texts)
    for symbol in (r"$L_j$", r"$k_\theta = 2EI/L_j$", r"$k_\theta = EI/L_j$", r"$h_1$", r"$h_2$", "clamp", "tip"):
        assert symbol in rigid, symbol
    for ax in fig.axes:
        assert "[mm]" in ax.get_xlabel() and "[mm]" in ax.get_ylabel()
        assert "heights ×35" in ax.get_ylabel()  # 0.3 L_j / e = 0.3 * 29 / 0.25 = 34.8


@pytest.mark.parametrize("stiffness, k1_text", [
    # composite: a1 a2 / (a1 + a2) / L_j with a1 = 70e9*28e-3*0.2e-3, a2 = 30.336e9*28e-3*0.3e-3 -> 5.33 MN/m
    ("composite", "5.33 MN/m"),
    # paper's Eq. 4: E2 b h2 / L_j = 254822.4 N / 0.029 m -> 8.79 MN/m
    ("paper", "8.79 MN/m"),
])
def test_spring_values_shown_are_the_calibrations(stiffness, k1_text):
    act = paper_actuator()
    act.stiffness = stiffness
    a_eff = (beam_theory.series_axial_rigidity(70e9, 0.2e-3, 30.336e9, 0.3e-3, 28e-3) if stiffness == "composite"
             else beam_theory.axial_rigidity(30.336e9, 28e-3, 0.3e-3))
    assert f"{a_eff / 29e-3 / 1e6:.3g} MN/m" == k1_text
    text = _texts(cell_figure(act))
    assert f"$k_1$ ({stiffness}) = {k1_text}" in text
    # torsion springs 2 E_i I_i / L_j: 2*70e9*28e-3*(0.2e-3)^3/12/0.029 = 90.1 mN m/rad (passive)
    assert "90.1 mN m/rad" in text and "132 mN m/rad" in text


def test_exaggeration_and_bad_input():
    act = paper_actuator()
    assert height_exaggeration(act) == pytest.approx(0.3 * 29e-3 / 0.25e-3)
    with pytest.raises(ValueError, match="drawn_offset"):
        height_exaggeration(act, 0.0)
    with pytest.raises(ValueError, match="n_cells"):
        cell_figure(act, rigid_cells=0)
