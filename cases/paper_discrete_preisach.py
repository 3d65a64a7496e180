"""Figs. 13-15: a discrete Preisach model of 6 equal-gain relays, identified by Eq. 12.

The major loop of the paper's continuous model (exact exponents by default) stands in for the
measured loop of Fig. 14.  ``n_relays`` relays with equal gains ``Δy = (x_max - x_min)/n``
are identified from it as in the paper: relay i sits at level ``y_i = x_min + i·Δy``; its
switch-on point is where the ascending branch crosses that level, its switch-off point where
the descending branch does.  Both models are then driven by a piecewise-linear input with
reversals inside the range (the case the paper proposes the discrete model for), and the
X-Y plot (Fig. 15) shows the discrete staircase against the continuous model.

Key scalars: the gain, the largest and RMS difference between the two models along the
input (the equal-gain construction bounds it by one gain step), and both major-loop areas.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_atcm import PiezoDrive, Result
from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, RunContext
from exudyn_atcm.hysteresis import DiscretePreisach
from exudyn_atcm.model import PiecewiseLinear, paper_stroke_preisach
from exudyn_atcm.plots import Curve, plot_loops, plot_relays, plot_time_series

PARAMETERS = [
    Parameter("n_relays", 6, "-", "number of equal-gain relays (the paper: 6)", minimum=1),
    Parameter("exponents", "exact", "-", "exponents of the continuous model", choices=("exact", "rounded")),
    Parameter("loop_samples", 2000, "-", "samples of the major loop used for identification", minimum=4),
    Parameter(
        "voltage_points",
        (-500.0, 1500.0, 0.0, 1200.0, 300.0, 900.0, -200.0, 1500.0, -500.0),
        "V",
        "input corner voltages, reached in equal time segments",
    ),
    Parameter("segment_time", 0.5, "s", "duration of each input segment", exclusive_minimum=0.0),
    Parameter("samples_per_segment", 200, "-", "time samples per segment", minimum=1),
]


def loop_area_from_series(u: np.ndarray, y: np.ndarray) -> float:
    """Area enclosed by a closed input-output path, ``|∮ y du|`` (trapezoidal rule)."""
    return float(abs(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(u))))


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    if len(p.voltage_points) < 2:
        raise ValueError(f"voltage_points must hold at least 2 voltages, got {p.voltage_points}")
    continuous = paper_stroke_preisach(rounded=(p.exponents == "rounded"))

    # the "measured" major loop: one full cycle from the reset state
    half = p.loop_samples // 2
    u_up = np.linspace(continuous.u_min, continuous.u_max, half + 1)
    u_loop = np.concatenate([u_up, u_up[-2::-1]])
    y_loop = continuous.apply(u_loop)
    discrete = DiscretePreisach.from_loop(u_loop, y_loop, p.n_relays)

    corners = np.asarray(p.voltage_points, dtype=float)
    # against the MFC's rating, as a drive would check it (a program typed in kV peaks below 3 V)
    PiezoDrive(0.0).check_voltage_range(float(corners.min()), float(corners.max()), stacklevel=2,
                                        what=f"voltage_points={', '.join(f'{v:g}' for v in corners)} V")
    corner_times = p.segment_time * np.arange(corners.size)
    signal = PiecewiseLinear(corner_times, corners)
    t = np.linspace(0.0, corner_times[-1], (corners.size - 1) * p.samples_per_segment + 1)
    u = signal(t)
    y_c = continuous.apply(u)
    y_d = discrete.apply(u)
    error = y_d - y_c

    result = Result(
        {"time": t, "voltage": u, "stroke_continuous": y_c, "stroke_discrete": y_d, "difference": error},
        {"time": "s", "voltage": "V", "stroke_continuous": "m", "stroke_discrete": "m", "difference": "m"},
        parameters={"continuous_model": repr(continuous)},
    )
    order = np.argsort(discrete.alpha)
    relays = Result(
        {
            "relay": np.arange(1, p.n_relays + 1, dtype=float),
            "switch_on": discrete.alpha[order],
            "switch_off": discrete.beta[order],
            "gain": discrete.weights[order],
        },
        {"relay": "-", "switch_on": "V", "switch_off": "V", "gain": "m"},
        parameters={"offset [m]": discrete.offset},
    )
    gain = float(discrete.weights[0])
    y_loop_d = discrete.apply(u_loop)
    scalars = {
        "gain": (gain, "m"),
        "max_difference": (float(np.max(np.abs(error))), "m"),
        "rms_difference": (float(np.sqrt(np.mean(error**2))), "m"),
        "max_difference_per_gain": (float(np.max(np.abs(error))) / gain, "-"),
        "loop_area_continuous": (continuous.loop_area(), "m V"),
        "loop_area_discrete": (loop_area_from_series(u_loop, y_loop_d), "m V"),
    }
    return CaseOutput(result, scalars, tables={"relays": relays}, notes={"u_loop_samples": int(u_loop.size)})


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    relays = output.tables["relays"]
    xy, series, plane = (out_dir / f"{output.case}_{name}.png" for name in ("xy", "time", "relays"))
    plot_loops(
        [
            Curve(r["voltage"], r["stroke_continuous"], "continuous Preisach"),
            Curve(r["voltage"], r["stroke_discrete"], f"discrete Preisach, {p.n_relays} relays (Eq. 12)", {"drawstyle": "steps-post"}),
        ],
        path=xy,
        title="Input/output with reversals inside the range (Fig. 15)",
    )
    plot_time_series(
        r,
        [["voltage"], ["stroke_continuous", "stroke_discrete"], ["difference"]],
        path=series,
        labels={"stroke_continuous": "continuous", "stroke_discrete": "discrete"},
        title="Discrete against continuous Preisach model",
    )
    plot_relays(
        relays["switch_on"],
        relays["switch_off"],
        path=plane,
        u_min=-500.0,
        u_max=1500.0,
        title=f"{p.n_relays} relays on the Preisach plane (Fig. 13)",
    )
    return [xy, series, plane]


#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "discrete_preisach",
        "quick": True,
        "parameters": {"n_relays": 6, "exponents": "exact", "loop_samples": 2000, "segment_time": 0.5, "samples_per_segment": 200},
        "channels": {
            "voltage": {"rms": 1e-9, "max": 1e-9},
            "stroke_continuous": {"rms": 1e-12, "max": 1e-11},
            "stroke_discrete": {"rms": 1e-12, "max": 1e-11}
        },
        "scalars": [
            {"scalar": "gain", "analytic": 7.3333333e-6, "abs": 1e-12, "source": "Eq. 12: (40 µm - (-4 µm)) / 6"},
            {"scalar": "loop_area_continuous", "analytic": 0.0216050, "abs": 5e-8, "source": "docs/theory.rst, hysteresis: 21605.0 µm·V"},
            {"scalar": "max_difference", "rel": 1e-6},
            {"scalar": "loop_area_discrete", "rel": 1e-9}
        ]
    },
]

CASE = Case("paper_discrete_preisach", __doc__, PARAMETERS, run, plot, benchmarks=BENCHMARKS, table_order=3,
            summary="the paper's Figs. 6, 8, 9, 13-15 (the paper's numbers)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
