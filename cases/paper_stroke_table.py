"""Fig. 9: the displacement-versus-time table that drives the paper's linear motor.

The paper feeds its simulation cell's linear motor with a table of stroke values at time
points, interpolated linearly (Figs. 9, 10).  This case produces that table for the triangle
input of Eq. 11 (U_med = 500 V, U_amp = 1000 V) through the continuous Preisach model of a
29 mm cell (the paper's rounded exponents 1.5 and 2 by default), as CSV with the columns
``time [s], voltage [V], stroke [m]``.

Key scalars: the peak and lowest stroke (40 µm and -4 µm in the paper), the stroke of the
linear law of Eqs. 2-3 at U_max (40.02 µm), and the largest error of the linearly
interpolated table against the model on a fine time grid (how many table points are
enough: "the simulation is more accurate as more precision points on the action table are
used").
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_atcm import Result
from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, RunContext
from exudyn_atcm.model import PAPER_D33, PAPER_ELECTRODE_SPACING, PAPER_LOOP, Triangle, paper_stroke_preisach
from exudyn_atcm.plots import axis_label, display_scale, new_figure, plot_time_series, save_figure

PARAMETERS = [
    Parameter("period", 1.0, "s", "period T of the triangle input (Eq. 11)", exclusive_minimum=0.0),
    Parameter("cycles", 1, "-", "number of input periods in the table", minimum=1),
    Parameter("points_per_period", 20, "-", "table intervals per period (even, so the reversals are table points)"),
    Parameter("exponents", "rounded", "-", "continuous model exponents", choices=("rounded", "exact")),
    Parameter("fine_factor", 50, "-", "fine samples per table interval for the interpolation error", minimum=1),
]


def _stroke(model, t: np.ndarray, signal: Triangle, period: float) -> np.ndarray:
    """Operator output at the times ``t``, with every input reversal (multiples of T/2) included."""
    reversals = np.arange(0.0, t[-1] + 0.5 * period, 0.5 * period)
    grid = np.union1d(t, reversals[reversals <= t[-1]])
    y = model.apply(signal(grid))
    return np.interp(t, grid, y)  # exact at t: every t is a grid point


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    if p.points_per_period < 2 or p.points_per_period % 2:
        raise ValueError(f"points_per_period must be an even integer >= 2, got {p.points_per_period}")
    model = paper_stroke_preisach(rounded=(p.exponents == "rounded"))
    loop = PAPER_LOOP
    signal = Triangle(0.5 * (loop["u_min [V]"] + loop["u_max [V]"]), 0.5 * (loop["u_max [V]"] - loop["u_min [V]"]), p.period)
    n = p.cycles * p.points_per_period
    t = np.linspace(0.0, p.cycles * p.period, n + 1)
    u = signal(t)
    x = _stroke(model, t, signal, p.period)

    t_fine = np.linspace(0.0, t[-1], n * p.fine_factor + 1)
    x_fine = _stroke(model, t_fine, signal, p.period)
    table_error = np.abs(np.interp(t_fine, t, x) - x_fine)

    result = Result(
        {"time": t, "voltage": u, "stroke": x},
        {"time": "s", "voltage": "V", "stroke": "m"},
        parameters={"signal": signal.parameters, "model": repr(model), "cell_length [m]": loop["cell_length [m]"]},
    )
    linear = PAPER_D33 * loop["u_max [V]"] / PAPER_ELECTRODE_SPACING * loop["cell_length [m]"]
    scalars = {
        "stroke_max": (float(x.max()), "m"),
        "stroke_min": (float(x.min()), "m"),
        "stroke_linear_law": (linear, "m"),
        "table_max_interpolation_error": (float(table_error.max()), "m"),
        "table_rows": (float(t.size), "-"),
    }
    return CaseOutput(result, scalars, notes={"fine_time_step [s]": float(t_fine[1] - t_fine[0])})


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    series = out_dir / f"{output.case}_time.png"
    plot_time_series(r, [["voltage"], ["stroke"]], path=series, title="Motor table (Fig. 9)")
    fig, (ax,) = new_figure(1, height=3.6)
    factor, unit = display_scale(r["stroke"], "m")
    ax.plot(r["time"], factor * r["stroke"], "o-", markersize=4, label="table points, linear interpolation")
    ax.set_xlabel(axis_label("time", "s"))
    ax.set_ylabel(axis_label("stroke", unit))
    ax.set_title("Displacement versus time points (Fig. 9)")
    ax.legend(loc="lower center")
    table = save_figure(fig, out_dir / f"{output.case}_table.png")
    return [series, table]


#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "stroke_table",
        "quick": True,
        "parameters": {"period": 1.0, "cycles": 1, "points_per_period": 20, "exponents": "rounded"},
        "channels": {
            "voltage": {"rms": 1e-9, "max": 1e-9},
            "stroke": {"rms": 1e-12, "max": 1e-11}
        },
        "scalars": [
            {"scalar": "stroke_max", "analytic": 40e-6, "abs": 1e-12, "source": "paper Sect. 3: total stroke 40 µm"},
            {"scalar": "stroke_min", "analytic": -4e-6, "abs": 1e-12, "source": "paper Sect. 3: -4 µm at -500 V"},
            {"scalar": "stroke_linear_law", "analytic": 40.02e-6, "abs": 5e-9, "source": "docs/theory.rst, piezo actuation: x_a = 40.02 µm (Eqs. 2, 3)"},
            {"scalar": "table_max_interpolation_error", "rel": 1e-6}
        ]
    },
]

CASE = Case("paper_stroke_table", __doc__, PARAMETERS, run, plot, benchmarks=BENCHMARKS, table_order=2,
            summary="the paper's Figs. 6, 8, 9, 13-15 (the paper's numbers)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
