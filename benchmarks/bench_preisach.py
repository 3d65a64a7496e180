"""Commit cost per step of DiscretePreisach against a plain numpy relay-array update.

For 10, 100, 1000 and 5000 relays identified from the paper's loop (Eq. 12), and for the same
numbers of random relays (a general, non-monotone family), both implementations are driven
by the same input; their outputs are asserted identical to round-off, then the time per
commit is measured side by side in one run (best of repeats).  Two inputs:

* ``smooth``: a decaying sine (reversals inside the range every half period), the kind of
  voltage a solver's accepted steps produce;
* ``noisy``: the same plus 5 V of white noise, so nearly every step is a reversal: the worst
  case for a large scattered relay set (``kernel == "rows"``: more distinct thresholds than
  the Everett table may hold), whose first step after a new reversal builds that
  reversal's prefix-sum row in O(n).

Goals (issue 2): under 2 µs per commit at every size, at least 10x faster than the relay
array at 5000 relays.

Usage: ``python benchmarks/bench_preisach.py [--steps N] [--out results/preisach.json]``
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from exudyn_atcm import __version__
from exudyn_atcm.hysteresis import DiscretePreisach
from exudyn_atcm.parameter_sets import paper_strain_preisach


class RelayArray:
    """The straightforward implementation: every relay updated with numpy at every step."""

    def __init__(self, alpha, beta, weights, offset):
        self.alpha, self.beta, self.weights, self.offset = alpha, beta, weights, offset
        self.state = np.zeros(alpha.size, dtype=bool)

    def commit(self, u: float) -> float:
        state = self.state
        state[u >= self.alpha] = True
        state[(u <= self.beta) & (u < self.alpha)] = False
        return self.offset + float(self.weights @ state)


def loop_relays(n: int) -> DiscretePreisach:
    model = paper_strain_preisach()
    u = np.linspace(model.u_min, model.u_max, 20001)
    y = np.r_[[model.ascending(v) for v in u], [model.descending(v) for v in u[::-1]]]
    return DiscretePreisach.from_loop(np.r_[u, u[::-1]], y, n)


def random_relays(n: int, seed: int = 1) -> DiscretePreisach:
    rng = np.random.default_rng(seed)
    alpha = rng.uniform(-500, 1500, n)
    beta = alpha - rng.uniform(0, 1000, n)
    return DiscretePreisach(alpha, beta, rng.uniform(0, 1e-6, n), offset=-1e-4)


def input_series(steps: int, noise: float) -> list[float]:
    t = np.linspace(0.0, 4.0, steps)
    rng = np.random.default_rng(0)
    u = 500 + 1000 * np.sin(2 * np.pi * t) * np.exp(-0.2 * t) + noise * rng.standard_normal(steps)
    return u.tolist()


def time_per_commit(make, u: list[float], repeats: int) -> tuple[float, list[float]]:
    best = float("inf")
    outputs: list[float] = []
    for _ in range(repeats):
        model = make()
        commit = model.commit
        start = time.perf_counter()
        outputs = [commit(x) for x in u]
        best = min(best, time.perf_counter() - start)
    return best / len(u), outputs


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=20000, help="commits per measurement")
    parser.add_argument("--repeats", type=int, default=3, help="repeats (best is kept)")
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "preisach.json"))
    args = parser.parse_args(argv)
    rows = []
    print(f"{'relays':>7} {'family':>9} {'kernel':>7} {'input':>6} {'staircase [µs]':>15} {'relay array [µs]':>17} {'speed-up':>9} {'2 µs goal':>9}")
    cases = [
        (family, build, kind, noise)
        for kind, noise in (("smooth", 0.0), ("noisy", 5.0))
        for family, build in (("from_loop", loop_relays), ("random", random_relays))
    ]
    for family, build, kind, noise in cases:
        u = input_series(args.steps, noise)
        for n in (10, 100, 1000, 5000):
            model = build(n)
            fast_t, fast_y = time_per_commit(lambda: DiscretePreisach(model.alpha, model.beta, model.weights, model.offset), u, args.repeats)
            slow_t, slow_y = time_per_commit(lambda: RelayArray(model.alpha, model.beta, model.weights, model.offset), u, args.repeats)
            scale = float(np.abs(model.weights).sum())
            error = float(np.max(np.abs(np.array(fast_y) - np.array(slow_y))))
            assert error <= 1e-12 * scale, f"outputs differ by {error} for {n} {family} relays"
            row = {
                "relays": n,
                "family": family,
                "input": kind,
                "kernel": model.kernel,
                "staircase_us_per_commit": fast_t * 1e6,
                "relay_array_us_per_commit": slow_t * 1e6,
                "speedup": slow_t / fast_t,
                "max_output_difference": error,
                "meets_2us_goal": fast_t * 1e6 < 2.0,
            }
            rows.append(row)
            print(
                f"{n:>7} {family:>9} {model.kernel:>7} {kind:>6} {row['staircase_us_per_commit']:>15.3f} {row['relay_array_us_per_commit']:>17.3f}"
                f" {row['speedup']:>8.1f}x {'yes' if row['meets_2us_goal'] else 'NO':>9}"
            )
    report = {
        "benchmark": "DiscretePreisach commit cost",
        "exudyn_atcm": __version__,
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
        "steps": args.steps,
        "repeats": args.repeats,
        "rows": rows,
    }
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=out.parent, suffix=".json")
    with os.fdopen(fd, "w") as handle:
        json.dump(report, handle, indent=2)
    os.replace(tmp, out)
    print(f"written {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
