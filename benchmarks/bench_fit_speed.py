"""Fit time of the relay-grid identification: the solver before issue 16 against the current one.

Old path (kept here only, for the comparison): the relay states of every sample as rows of a
dense Gram matrix, a dense smoothness matrix, a Cholesky factor and SciPy's Lawson-Hanson
``nnls`` on it.  New path (:meth:`DiscretePreisach.fit`, :meth:`EverettPreisach.fit`): distinct
relay states only, sparse smoothness, block principal pivoting on the normal equations
(:mod:`exudyn_atcm.hysteresis.nnls`) on one BLAS thread.  Both minimise the same objective
``½ wᵀ G w − bᵀ w`` (``G`` the regularised, centred Gram matrix of the scaled record); the table
gives both times, the speed-up and the relative difference of the objective at the two
minimisers (``|f_new − f_old| / |f_old|``) and of the fitted outputs.

Records: the shipped synthetic record (``cases/data/preisach_record.csv``: ramps through major
and minor loops, 250 Hz), its first 2000 samples; and a sine record like the one of issue 16
(1 Hz, 200 Hz sampling, 1750 samples, a Preisach truth plus 0.1 % noise).

Usage: ``python benchmarks/bench_fit_speed.py [--levels 20 40 60] [--out results/fit_speed.json]``
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
import scipy.linalg
from scipy.optimize import nnls

from exudyn_atcm import __version__
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.hysteresis import DiscretePreisach, EverettPreisach
from exudyn_atcm.hysteresis.identification import relay_gram, relay_grid
from exudyn_atcm.model.reference_record import reference_preisach, reference_samples


def old_weights(u: np.ndarray, y: np.ndarray, n_levels: int, smoothing: float = 1e-3) -> tuple[np.ndarray, dict]:
    """The solver of ``DiscretePreisach.fit`` before issue 16 (scaled weights and its problem)."""
    alpha, beta, index = relay_grid(float(u.min()), float(u.max()), n_levels)
    start = int(np.flatnonzero(u <= alpha.min())[0])
    scale = float(np.ptp(y[start:]))
    n_r = alpha.size
    gram, rhs, colsum = np.zeros((n_r, n_r)), np.zeros(n_r), np.zeros(n_r)
    state = np.zeros(n_r)
    rows, ys = [], []
    for k in range(u.size):
        state = np.where(u[k] >= alpha, 1.0, np.where(u[k] <= beta, 0.0, state))
        if k >= start:
            rows.append(state)
            ys.append(y[k] / scale)
    s, ys = np.array(rows), np.array(ys)
    for first in range(0, s.shape[0], 2048):
        block = s[first:first + 2048]
        gram += block.T @ block
        rhs += block.T @ ys[first:first + 2048]
        colsum += block.sum(axis=0)
    m = s.shape[0]
    mean_s = colsum / m
    gram_c = gram - m * np.outer(mean_s, mean_s)
    rhs_c = rhs - mean_s * ys.sum()
    position = -np.ones((n_levels, n_levels), dtype=int)
    position[index[:, 0], index[:, 1]] = np.arange(n_r)
    pairs = [(k, int(position[i + di, j + dj])) for k, (i, j) in enumerate(index.tolist())
             for di, dj in ((1, 0), (0, 1)) if i + di < n_levels and j + dj <= i + di]
    d = np.zeros((len(pairs), n_r))
    for r, (a, b) in enumerate(pairs):
        d[r, a], d[r, b] = 1.0, -1.0
    dtd = d.T @ d
    lam = smoothing * float(np.trace(gram_c)) / float(np.trace(dtd))
    matrix = gram_c + lam * dtd
    matrix = matrix + 1e-10 * float(np.trace(matrix)) / n_r * np.eye(n_r)
    upper = scipy.linalg.cholesky(matrix, lower=False)
    target = scipy.linalg.solve_triangular(upper, rhs_c, trans="T", lower=False)
    w, _ = nnls(upper, target, maxiter=50 * n_r)
    return w, {"G": matrix, "b": rhs_c, "scale": scale, "start": start, "alpha": alpha, "beta": beta}


def sine_record() -> tuple[np.ndarray, np.ndarray]:
    t = np.arange(1750) / 200.0
    u = 500.0 + 1000.0 * np.sin(2 * np.pi * 1.0 * t - np.pi / 2)
    y = reference_preisach().apply(u)
    return u, y + 1e-3 * np.ptp(y) * np.random.default_rng(16).standard_normal(u.size)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--levels", type=int, nargs="+", default=[20, 40, 60])
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "fit_speed.json"))
    args = parser.parse_args(argv)
    _, u_ref, _, y_ref = reference_samples()
    records = {"shipped record, 2000 samples": (u_ref[:2000], y_ref[:2000]), "sine 1 Hz, 1750 samples": sine_record()}
    DiscretePreisach.fit(u_ref[:300], y_ref[:300], 4)  # warm-up: imports and first calls
    rows = []
    print(f"{'record':<30}{'levels':>7}{'old [s]':>9}{'new [s]':>9}{'speed-up':>9}{'rel. obj. diff':>16}"
          f"{'output diff [% range]':>23}{'Everett new [s]':>17}")
    for name, (u, y) in records.items():
        for n in args.levels:
            started = time.perf_counter()
            w_old, problem = old_weights(u, y, n)
            t_old = time.perf_counter() - started
            started = time.perf_counter()
            model, report = DiscretePreisach.fit(u, y, n)
            t_new = time.perf_counter() - started
            started = time.perf_counter()
            EverettPreisach.fit(u, y, n)
            t_everett = time.perf_counter() - started
            g, b = problem["G"], problem["b"]
            w_new = model.weights / problem["scale"]
            f_old = 0.5 * w_old @ g @ w_old - b @ w_old
            f_new = 0.5 * w_new @ g @ w_new - b @ w_new
            old_model = DiscretePreisach(problem["alpha"], problem["beta"], w_old * problem["scale"], model.offset)
            out_diff = float(np.max(np.abs(old_model.apply(u) - model.apply(u)))) / float(np.ptp(y)) * 100.0
            row = {"record": name, "samples": int(u.size), "n_levels": n, "relays": int(w_old.size),
                   "old [s]": t_old, "new [s]": t_new, "speed_up": t_old / t_new,
                   "relative_objective_difference": abs(f_new - f_old) / abs(f_old),
                   "objective_new_minus_old": float(f_new - f_old),
                   "max_output_difference [% of range]": out_diff, "everett_new [s]": t_everett,
                   "positive_weights": int(np.count_nonzero(model.weights))}
            rows.append(row)
            print(f"{name:<30}{n:>7}{t_old:>9.3f}{t_new:>9.3f}{t_old / t_new:>9.1f}{row['relative_objective_difference']:>16.2e}"
                  f"{out_diff:>23.2e}{t_everett:>17.3f}", flush=True)
    meta = {"python": sys.version.split()[0], "numpy": np.__version__, "scipy": scipy.__version__,
            "exudyn_atcm": __version__, "machine": platform.machine(), "cpus": os.cpu_count(),
            "load_average": os.getloadavg() if hasattr(os, "getloadavg") else None,
            "goal": "DiscretePreisach.fit at 60 levels on about 2000 samples under 2 s (issue 16)"}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    path = write_json(args.out, {"meta": meta, "rows": rows})
    print(f"written {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
