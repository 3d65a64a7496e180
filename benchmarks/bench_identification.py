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

Growing-amplitude record (issue 28): triangles from the lowest input (0 V) with peaks rising
cycle by cycle to 1000 V, 12 750 samples, from a known asymmetric Preisach density (a relay
grid of 60 levels whose weights depend on alpha + beta as well as on alpha - beta) plus 0.2 %
noise.  Printed: :func:`identify` with its default split (interleaved cycles, held-out inputs
inside the fitted range) and with the old split (the first 60 %, which warns naming the
uncovered range); and the PI fits applied to the whole record from rest: the fit from the
first sample (``initial="auto"``: the better of the plays at rest and descended from the first
input), the same held at rest (``initial="rest"``), the old rule (``initial="covered"``: samples
before the input has covered its range left out), a plain least-squares PI fit of the whole
record from rest (numpy/SciPy, no package code) and the Everett fit.
Goals: identify's held-out RMS within 2x its fit RMS (or a warning); the PI fit held at rest
equal to the plain least squares (the same model and data: 1.000); ``"auto"`` no worse than it.
(Until 2026-11-29 the ``"auto"`` fit was compared with the plain least squares at rest, a
different initial state: its 0.76x measured the choice of the state, not the fit.)

Usage: ``python benchmarks/bench_identification.py [--out results/identification.json]``
"""

from __future__ import annotations

import argparse
import os
import warnings
import platform
import sys
import time
from pathlib import Path

import numpy as np
import scipy

from exudyn_atcm import __version__
from exudyn_atcm.io.atomic import write_json
from scipy.optimize import nnls

from exudyn_atcm.hysteresis import DiscretePreisach, EverettPreisach, PrandtlIshlinskii, identify
from exudyn_atcm.hysteresis.relay_gram import relay_grid
from exudyn_atcm.model.reference_record import REFERENCE, reference_samples

NOISE = REFERENCE["noise [m]"]


def rms(a: np.ndarray) -> float:
    return float(np.sqrt(np.mean(a**2)))


def growing_amplitude_record(n_cycles: int = 10, samples: int = 12750, noise: float = 0.002) -> tuple:
    """Input, clean and noisy output of the growing-amplitude record (see the module)."""
    peaks = 1000.0 * np.arange(1, n_cycles + 1) / n_cycles
    corners = np.r_[0.0, np.column_stack([peaks, np.zeros(n_cycles)]).ravel()]
    travel = np.r_[0.0, np.cumsum(np.abs(np.diff(corners)))]
    u = np.interp(np.linspace(0.0, travel[-1], samples), travel, corners)
    alpha, beta, _ = relay_grid(0.0, 1000.0, 60)
    a, b = alpha / 1000.0, beta / 1000.0
    w = np.exp(-((a - b - 0.3) ** 2) / 0.05) * np.exp(-(((a + b) / 2 - 0.7) ** 2) / 0.06)
    w = w + 3.0 * (alpha == beta) * np.exp(-(((a + b) / 2 - 0.3) ** 2) / 0.2)
    clean = DiscretePreisach(alpha, beta, 1e-3 * w / w.sum()).apply(u)
    noisy = clean + noise * np.ptp(clean) * np.random.default_rng(11).standard_normal(u.size)
    return u, clean, noisy


def plain_pi_from_rest(u: np.ndarray, y: np.ndarray, n: int) -> np.ndarray:
    """Least-squares PI of the whole record from rest at u[0]: plays written out, SciPy's NNLS."""
    v = u - u[0]
    radii = np.ptp(u) * np.arange(1, n) / (2.0 * n)
    z = np.zeros(radii.size)
    plays = np.empty((u.size, radii.size))
    for k, value in enumerate(v):
        z = np.maximum(value - radii, np.minimum(value + radii, z))
        plays[k] = z
    design = np.column_stack([v, plays])
    mean_d, mean_y = design.mean(axis=0), float(y.mean())
    coef, _ = nnls(design - mean_d, y - mean_y)
    return (design - mean_d) @ coef + mean_y


def growing_amplitude(rows: list) -> dict:
    """identify tables and the PI-fit comparison on the growing-amplitude record (printed)."""
    u, clean, y = growing_amplitude_record()
    out: dict = {"samples": int(u.size)}
    for split in ("auto", 0.6):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            choice = identify(u, y, split=split)
        print(f"\nidentify(u, y, split={split!r}) on the growing-amplitude record:")
        print(choice.to_text())
        for w in caught:
            print(f"warning: {w.category.__name__}: {w.message}")
        out[f"identify split={split}"] = {**choice.to_dict(), "warnings": [str(w.message) for w in caught]}
    range_y = float(np.ptp(y))
    percent = {}
    for name, fit in (("PI fit from the first sample (initial='auto')", lambda: PrandtlIshlinskii.fit(u, y, 20)),
                      ("PI fit held at rest (initial='rest')", lambda: PrandtlIshlinskii.fit(u, y, 20, initial="rest")),
                      ("PI fit, old rule (initial='covered')", lambda: PrandtlIshlinskii.fit(u, y, 20, initial="covered")),
                      ("Everett fit (30 levels, pi)", lambda: EverettPreisach.fit(u, y, 30))):
        started = time.perf_counter()
        model, report = fit()
        elapsed = time.perf_counter() - started
        percent[name] = (100 * rms(model.apply(u) - y) / range_y, report.fit_start, elapsed,
                         report.settings.get("initial", ""))
    started = time.perf_counter()
    percent["plain least-squares PI from rest (test reference)"] = (100 * rms(plain_pi_from_rest(u, y, 20) - y) / range_y,
                                                                    0, time.perf_counter() - started, "rest")
    print(f"\nmodels applied to the whole growing-amplitude record from rest ({u.size} samples), RMS in % of the "
          "output range:")
    print(f"{'model':<52}{'RMS [%]':>9}{'fit_start':>10}{'fit [s]':>9}  initial")
    for name, (err, start, elapsed, initial) in percent.items():
        print(f"{name:<52}{err:>9.3f}{start:>10d}{elapsed:>9.2f}  {initial}")
        rows.append({"record": "growing amplitude", "model": name, "rms [% of range]": err, "fit_start": start,
                     "fit_time [s]": elapsed, "initial": initial})
    plain = percent["plain least-squares PI from rest (test reference)"][0]
    ratio = percent["PI fit held at rest (initial='rest')"][0] / plain
    auto = percent["PI fit from the first sample (initial='auto')"][0] / plain
    print(f"PI fit held at rest / plain least squares (the same model): {ratio:.6f} (goal 1.000); "
          f"initial='auto' / plain: {auto:.3f} (goal <= the fit held at rest)")
    out["pi_rest_over_plain_least_squares"] = ratio
    out["pi_auto_over_plain_least_squares"] = auto
    return out


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
    growing = growing_amplitude(rows)
    report = {
        "benchmark": "Preisach identification: fit time and held-out error",
        "exudyn_atcm": __version__,
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
        "noise [m]": NOISE,
        "goal": "held-out RMS <= 1.5 x noise on the shipped record (250 Hz); growing amplitude: identify's held-out "
                "RMS <= 2 x its fit RMS, PI fit at rest = the plain least squares, initial='auto' no worse",
        "rows": rows,
        "growing_amplitude": growing,
    }
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    print(f"wrote {write_json(args.out, report)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
