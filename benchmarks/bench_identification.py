"""Fit time and held-out error of the Preisach identification against grid size and record length.

The records are the synthetic reference record of ``cases/data/preisach_record.csv`` (a known
non-uniform Preisach density driven through major and minor loops, 0.4 µm noise), sampled at
125, 250 (the shipped record) and 500 Hz: the same input program, 1876 to 7501 samples.
The first 60 % of the duration is fitted, the rest held out.  For n_levels = 10, 20, 40 the
relay grid (:meth:`DiscretePreisach.fit`, staircase output) and the grid with each weight
spread over its cell (:meth:`EverettPreisach.fit`, continuous output) are fitted,
side by side with a Prandtl-Ishlinskii fit (n plays = n_levels) and the best linear model.
Errors are given against the noisy record (what a user sees) and against the noise-free
truth (the model error alone), both as multiples of the noise level.

Goal (issue 8): held-out RMS error within 1.5x the noise level on the shipped record.

Usage: ``python benchmarks/bench_identification.py [--out results/identification.json]``
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np
import scipy

from exudyn_atcm import __version__
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.hysteresis import DiscretePreisach, EverettPreisach, PrandtlIshlinskii
from exudyn_atcm.model.reference_record import REFERENCE, reference_samples

NOISE = REFERENCE["noise [m]"]


def rms(a: np.ndarray) -> float:
    return float(np.sqrt(np.mean(a**2)))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "identification.json"))
    args = parser.parse_args(argv)
    rows = []
    print(f"{'rate [Hz]':>9} {'samples':>7} {'levels':>6} {'model':>11} {'fit [s]':>8} "
          f"{'held-out RMS/noise':>18} {'vs truth /noise':>15} {'linear/noise':>12}")
    # warm-up: imports and first-call costs are not part of the fit times
    t, u, _, noisy = reference_samples(sample_rate=50.0)
    DiscretePreisach.fit(u, noisy, 4)
    PrandtlIshlinskii.fit(u, noisy, 4)
    for rate in (125.0, 250.0, 500.0):
        t, u, clean, noisy = reference_samples(sample_rate=rate)
        n_fit = int(np.searchsorted(t, 0.6 * t[-1]))
        held = slice(n_fit, None)
        for n in (10, 20, 40):
            started = time.perf_counter()
            grid, report = DiscretePreisach.fit(u, noisy, n, n_fit=n_fit)
            t_grid = time.perf_counter() - started
            started = time.perf_counter()
            everett, _ = EverettPreisach.fit(u, noisy, n, n_fit=n_fit)
            t_everett = time.perf_counter() - started
            started = time.perf_counter()
            pi, _ = PrandtlIshlinskii.fit(u, noisy, n, n_fit=n_fit)
            t_pi = time.perf_counter() - started
            linear = report.linear_errors["held_out"]["rms"] / NOISE
            for name, model, fit_time in (("relay grid", grid, t_grid), ("everett", everett, t_everett),
                                          ("PI", pi, t_pi)):
                predicted = model.apply(u)
                row = {
                    "sample_rate [Hz]": rate,
                    "samples": int(u.size),
                    "fitted_samples": n_fit,
                    "n_levels": n,
                    "model": name,
                    "fit_time [s]": fit_time,
                    "held_out_rms_per_noise": rms(predicted[held] - noisy[held]) / NOISE,
                    "held_out_rms_vs_truth_per_noise": rms(predicted[held] - clean[held]) / NOISE,
                    "linear_held_out_rms_per_noise": linear,
                }
                rows.append(row)
                print(f"{rate:>9.0f} {u.size:>7} {n:>6} {name:>11} {fit_time:>8.2f} "
                      f"{row['held_out_rms_per_noise']:>18.3f} {row['held_out_rms_vs_truth_per_noise']:>15.3f} {linear:>12.2f}")
    report = {
        "benchmark": "Preisach identification: fit time and held-out error",
        "exudyn_atcm": __version__,
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
        "noise [m]": NOISE,
        "goal": "held-out RMS <= 1.5 x noise on the shipped record (250 Hz)",
        "rows": rows,
    }
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    print(f"wrote {write_json(args.out, report)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
