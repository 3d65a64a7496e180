"""Draw the README figures from the code: the paper's hysteresis loop and the actuator's tip loop,
and the drawing of the two simulation cells.

Run: ``python docs/make_readme_figure.py`` (writes docs/_static/readme_figure.png and
docs/_static/cell_drawing.png; about 5 s).
"""

from pathlib import Path

import numpy as np

import exudyn_atcm as atcm
from exudyn_atcm.plots import save_cell_drawing
from exudyn_atcm.model import paper_strain_preisach, paper_stroke_preisach
from exudyn_atcm.plots import new_figure, save_figure
from exudyn_atcm.model import Triangle


def main() -> Path:
    model = paper_stroke_preisach()
    knots = [-500, 1500, -500, 1000, 200, 1000]
    u = np.concatenate([np.linspace(a, b, 300) for a, b in zip(knots, knots[1:])])
    actuator = atcm.BendingActuator(
        n_cells=3, cell_length=29e-3, width=28e-3,
        passive=atcm.Layer(0.2e-3, 70e9, 1550.0), active=atcm.Layer(0.3e-3, 30.336e9, 5440.0),
        drive=atcm.PiezoDrive(Triangle(500.0, 1000.0, 2.0), hysteresis=paper_strain_preisach()), cell="six-bar"
    )
    result = atcm.simulate(actuator, t_end=4.0)
    last = result["time"] >= 2.0
    fig, (left, right) = new_figure(1, 2, width=10, height=3.8)
    left.plot(u, model.apply(u) * 1e6)
    left.set_xlabel("voltage U [V]")
    left.set_ylabel("stroke of a 29 mm cell [µm]")
    left.set_title("Preisach loop (paper, Fig. 6) and a minor loop")
    right.plot(result["actuator.voltage"][last], result["actuator.tip_y"][last] * 1e3)
    right.set_xlabel("voltage U [V]")
    right.set_ylabel("tip deflection y [mm]")
    right.set_title("Bending actuator, hysteresis in the solver step")
    out = Path(__file__).parent / "_static" / "readme_figure.png"
    save_figure(fig, out)
    save_cell_drawing(out.with_name("cell_drawing.png"))
    return out


if __name__ == "__main__":
    path = main()
    print(path)
    print(path.with_name("cell_drawing.png"))
