"""Commit cost per step of DiscretePreisach against a plain numpy relay-array update.

For 10, 100, 1000 and 5000 relays (``--sizes``; 20000 takes minutes because of the relay
array) identified from the paper's loop (Eq. 12), and for the same numbers of random relays
(a general, non-monotone family with scattered thresholds), both implementations are driven
by the same input; their outputs are asserted identical to round-off, then the time per
commit is measured side by side in one run (best of repeats), with the time to build the
model.  Three inputs:

* ``smooth``: a decaying sine (reversals inside the range every half period), the kind of
  voltage a solver's accepted steps produce;
* ``noisy``: the same plus 5 V of white noise, so about two steps in three are reversals;
* ``zigzag``: the same plus 5 V alternately added and subtracted: every step is a reversal
  (at the default 20000 steps; the ``reversals`` column gives the share).

Two relay arrays: ``relay array`` (state updated by scattering into a boolean array, then
``weights @ state``) and ``masks`` (the state rebuilt by whole-array boolean algebra, then a
masked sum; faster); ``speed-up`` is against the faster of the two.

Which kernel a model uses is in the ``kernel`` column: ``prefix`` (monotone relay family),
``table`` (Everett table on a small threshold grid), ``dominance`` (scattered thresholds:
blocked dominance-sum table, the same work at every step whatever the input; it replaced a
per-reversal row fallback that cost 62-74 µs per commit at 5000 relays on the noisy input).

Goals: issue 2, under 2 µs per commit at every size and at least 10x faster than the relay
array at 5000 relays; issue 9, scattered relays (``random``) under 5 µs per commit at 5000
relays with any input (summary line after the table).

Usage: ``python benchmarks/bench_preisach.py [--steps N] [--sizes ...] [--out results/preisach.json]``
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

from exudyn_atcm import __version__
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.hysteresis import DiscretePreisach
from exudyn_atcm.model.parameter_sets import paper_strain_preisach


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


class RelayArrayMasks(RelayArray):
    """The same with whole-array boolean algebra, no scatter into the state, and a masked sum
    (``weights @ bool_array`` takes a slow mixed-type path in numpy): 1.5-2x faster."""

    def commit(self, u: float) -> float:
        self.state = state = (u >= self.alpha) | (self.state & (u > self.beta))
        return self.offset + float(self.weights[state].sum())


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


def input_series(steps: int, noise: float, alternate: float = 0.0) -> list[float]:
    """Decaying sine [V] plus white noise of ``noise`` V rms plus ``±alternate`` V by step."""
    t = np.linspace(0.0, 4.0, steps)
    rng = np.random.default_rng(0)
    u = 500 + 1000 * np.sin(2 * np.pi * t) * np.exp(-0.2 * t) + noise * rng.standard_normal(steps)
    u += alternate * (1 - 2 * (np.arange(steps) % 2))
    return u.tolist()


INPUTS = {"smooth": (0.0, 0.0), "noisy": (5.0, 0.0), "zigzag": (0.0, 5.0)}


def reversal_fraction(u: list[float]) -> float:
    """Share of the steps after which the input changes direction."""
    du = np.diff(u)
    return float(np.mean(du[1:] * du[:-1] < 0)) if len(u) > 2 else 0.0


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
    parser.add_argument("--sizes", type=int, nargs="+", default=[10, 100, 1000, 5000], help="numbers of relays")
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "preisach.json"))
    args = parser.parse_args(argv)
    rows = []
    print(
        f"{'relays':>7} {'family':>9} {'kernel':>9} {'input':>6} {'reversals':>9} {'build [ms]':>10}"
        f" {'staircase [µs]':>15} {'relay array [µs]':>17} {'masks [µs]':>11} {'speed-up':>9} {'2 µs goal':>9}"
    )
    models: dict[tuple[str, int], DiscretePreisach] = {}
    for kind, (noise, alternate) in INPUTS.items():
        u = input_series(args.steps, noise, alternate)
        reversals = reversal_fraction(u)
        for family, build in (("from_loop", loop_relays), ("random", random_relays)):
            for n in args.sizes:
                model = models.get((family, n))
                if model is None:
                    model = models[(family, n)] = build(n)
                start = time.perf_counter()
                DiscretePreisach(model.alpha, model.beta, model.weights, model.offset)
                build_ms = (time.perf_counter() - start) * 1e3
                fast_t, fast_y = time_per_commit(lambda: DiscretePreisach(model.alpha, model.beta, model.weights, model.offset), u, args.repeats)
                slow_t, slow_y = time_per_commit(lambda: RelayArray(model.alpha, model.beta, model.weights, model.offset), u, args.repeats)
                masks_t, masks_y = time_per_commit(lambda: RelayArrayMasks(model.alpha, model.beta, model.weights, model.offset), u, args.repeats)
                scale = float(np.abs(model.weights).sum())
                error = float(np.max(np.abs(np.array(fast_y) - np.array(slow_y))))
                error = max(error, float(np.max(np.abs(np.array(masks_y) - np.array(slow_y)))))
                assert error <= 1e-12 * scale, f"outputs differ by {error} for {n} {family} relays"
                row = {
                    "relays": n,
                    "family": family,
                    "input": kind,
                    "reversal_fraction": reversals,
                    "kernel": model.kernel,
                    "build_ms": build_ms,
                    "staircase_us_per_commit": fast_t * 1e6,
                    "relay_array_us_per_commit": slow_t * 1e6,
                    "relay_array_masks_us_per_commit": masks_t * 1e6,
                    "speedup": min(slow_t, masks_t) / fast_t,
                    "max_output_difference": error,
                    "meets_2us_goal": fast_t * 1e6 < 2.0,
                }
                rows.append(row)
                print(
                    f"{n:>7} {family:>9} {model.kernel:>9} {kind:>6} {reversals:>8.0%} {build_ms:>10.2f}"
                    f" {row['staircase_us_per_commit']:>15.3f} {row['relay_array_us_per_commit']:>17.3f} {masks_t * 1e6:>11.3f}"
                    f" {row['speedup']:>8.1f}x {'yes' if row['meets_2us_goal'] else 'NO':>9}"
                )
    scattered = [r for r in rows if r["family"] == "random" and r["relays"] == 5000]
    if scattered:
        worst = max(scattered, key=lambda r: r["staircase_us_per_commit"])
        print(
            f"scattered relays, 5000, slowest input ({worst['input']}): {worst['staircase_us_per_commit']:.3f} µs per commit"
            f" (goal < 5 µs: {'yes' if worst['staircase_us_per_commit'] < 5.0 else 'NO'}),"
            f" relay array {worst['relay_array_us_per_commit']:.3f} µs, with masks {worst['relay_array_masks_us_per_commit']:.3f} µs"
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
        "sizes": args.sizes,
        "rows": rows,
    }
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    write_json(out, report)
    print(f"written {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
