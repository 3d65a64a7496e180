"""Draw the README figure from the code: the paper's hysteresis loop with a minor loop.

Run: ``python docs/make_readme_figure.py`` (writes docs/_static/readme_figure.png).
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from exudyn_atcm.parameter_sets import paper_stroke_preisach  # noqa: E402


def main() -> Path:
    model = paper_stroke_preisach()
    knots = [-500, 1500, -500, 1000, 200, 1000]
    u = np.concatenate([np.linspace(a, b, 300) for a, b in zip(knots, knots[1:])])
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=110)
    ax.plot(u, model.apply(u) * 1e6, lw=1.5)
    ax.set_xlabel("voltage U [V]")
    ax.set_ylabel("stroke of a 29 mm cell [µm]")
    ax.set_title("MFC stroke with Preisach hysteresis: major loop and a minor loop")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    out = Path(__file__).parent / "_static" / "readme_figure.png"
    fig.savefig(out)
    plt.close(fig)
    return out


if __name__ == "__main__":
    print(main())
