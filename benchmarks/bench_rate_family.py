"""What each part of a rate model buys on a rate family with asymmetric loops (issue 28, part 5).

The family is the known actuator of :mod:`exudyn_atcm.model.rate_family`: an Everett density
that depends on ``α + β`` as well as on ``α − β`` (asymmetric loops), a creep law and a lag
``T = 1.5 ms``; six growing raised-cosine cycles from -500 V at 20, 40 and 100 Hz, sampled at
10 kHz, noise 0.1 % of the range.  Two trainings, each predicting the rate left out:

* the slowest and the fastest (20 + 100 Hz) predict 40 Hz (goal: 0.8 % RMS of the range);
* the two slower (20 + 40 Hz) predict 100 Hz (goal: 1.5 %).

Side by side, with the same grid size / number of plays:

* ``everett``: a rate-independent :meth:`EverettPreisach.fit` (``prior="pi"``) of the training
  records joined (each starts and ends at -500 V, so the join is a valid record);
* ``PI+lag``: :func:`~exudyn_atcm.hysteresis.dynamics_fit.fit_rate_lag` (Prandtl-Ishlinskii,
  the known creep, a fitted lag);
* ``everett+lag``: :func:`~exudyn_atcm.hysteresis.fit_rate_preisach` (Everett, the known creep,
  a fitted lag).

A second family (``--mismatch`` rows, always run) has a rate effect the models do not contain:
the same operator followed by two lags in series (1 ms and 0.5 ms, no creep); it shows how far
one fitted lag carries when the real dynamics are of higher order.

Usage: ``python benchmarks/bench_rate_family.py [--levels 12] [--out results/rate_family.json]``
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
from exudyn_atcm.hysteresis import EverettPreisach, fit_rate_preisach
from exudyn_atcm.hysteresis.creep import Creep
from exudyn_atcm.hysteresis.dynamics import LagSum
from exudyn_atcm.hysteresis.dynamics_fit import fit_rate_lag
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.model.rate_family import RATE_FAMILY, growing_cycles, rate_family_records, rate_family_truth

TRAININGS = (("20+100 Hz -> 40 Hz", (0, 2), 1, 0.008), ("20+40 Hz -> 100 Hz", (0, 1), 2, 0.015))


def share(predicted: np.ndarray, y: np.ndarray) -> float:
    """RMS error as a share of the record's output range."""
    return float(np.sqrt(np.mean((predicted - y) ** 2)) / np.ptp(y))


def second_order_family() -> list:
    """The family's operator followed by 1/((1 + 1 ms s)(1 + 0.5 ms s)), same records and noise level."""
    operator = rate_family_truth(lag=False, creep=False)
    t1, t2 = 1.0e-3, 0.5e-3
    block = LagSum(0.0, [t1, t2], [t1 / (t1 - t2), -t2 / (t1 - t2)])
    rng = np.random.default_rng(RATE_FAMILY["seed"])
    records = []
    for f in RATE_FAMILY["rates [Hz]"]:
        t, u = growing_cycles(f)
        clean = block.response(operator.apply(u), t, rest=operator.offset)
        records.append((t, u, clean, clean))
    sigma = RATE_FAMILY["noise [share of range]"] * float(np.ptp(records[0][2]))
    return [(t, u, y + sigma * rng.standard_normal(y.size), c) for t, u, y, c in records]


def fits(records: list, train: tuple, levels: int, creep: Creep | None) -> list:
    """(name, predict(t, u), T, fit time) of the three models trained on ``records[train]``."""
    chosen = [records[i][:3] for i in train]
    out = []
    started = time.perf_counter()
    everett, _ = EverettPreisach.fit(np.concatenate([u for _, u, _ in chosen]),
                                     np.concatenate([y for _, _, y in chosen]), levels, prior="pi")
    out.append(("everett", lambda t, u, m=everett: m.apply(u), None, time.perf_counter() - started))
    started = time.perf_counter()
    pi, info = fit_rate_lag(chosen, levels, creep=creep)
    out.append(("PI+lag", lambda t, u, m=pi: m.apply(u, t), info["T"], time.perf_counter() - started))
    started = time.perf_counter()
    model, info = fit_rate_preisach(chosen, levels, creep=creep)
    out.append(("everett+lag", lambda t, u, m=model: m.apply(u, t), info["T"], time.perf_counter() - started))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--levels", type=int, default=12, help="grid levels / plays of every fit (default 12)")
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "rate_family.json"))
    args = parser.parse_args(argv)
    creep = Creep(RATE_FAMILY["creep tau [s]"], RATE_FAMILY["creep c [-]"])
    families = (("asymmetric + creep + lag 1.5 ms", rate_family_records(), creep),
                ("mismatch: two lags 1 + 0.5 ms", second_order_family(), None))
    rows = []
    print(f"{'family':<32} {'training':<19} {'model':<12} {'T [ms]':>7} {'fit [s]':>7} {'fitted RMS %':>14} "
          f"{'predicted %':>11} {'vs truth %':>10} {'goal %':>6}")
    for family, records, known_creep in families:
        for training, train, test, goal in TRAININGS:
            for name, predict, T, fit_time in fits(records, train, args.levels, known_creep):
                fitted = [share(predict(*records[i][:2]), records[i][2]) for i in train]
                t, u, y, clean = records[test]
                row = {"family": family, "training": training, "model": name, "n_levels": args.levels,
                       "T [s]": T, "fit_time [s]": fit_time, "fitted_rms_share": fitted,
                       "predicted_rms_share": share(predict(t, u), y),
                       "predicted_rms_share_vs_truth": share(predict(t, u), clean), "goal_share": goal}
                rows.append(row)
                print(f"{family:<32} {training:<19} {name:<12} {'' if T is None else f'{1e3 * T:.3f}':>7} "
                      f"{fit_time:>7.2f} {' / '.join(f'{100 * f:.3f}' for f in fitted):>14} "
                      f"{100 * row['predicted_rms_share']:>11.3f} {100 * row['predicted_rms_share_vs_truth']:>10.3f} "
                      f"{100 * goal:>6.1f}")
    report = {
        "benchmark": "rate family with asymmetric loops: rate-independent Everett, PI + lag, Everett + lag",
        "exudyn_atcm": __version__,
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
        "family": {k: (list(v) if isinstance(v, tuple) else v) for k, v in RATE_FAMILY.items()},
        "goal": "20+100 Hz predicts 40 Hz within 0.8 % RMS of the range; 20+40 Hz predicts 100 Hz within 1.5 %",
        "rows": rows,
    }
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    print(f"wrote {write_json(args.out, report)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
