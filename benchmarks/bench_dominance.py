"""Structures for the dominance sums K(a, b) of scattered relays, side by side.

``K(a, b)`` = weight of the relays with ``alpha <= a`` and ``beta >= b`` is the one function a
staircase Preisach step evaluates (once per commit).  For random relays (thresholds
scattered, no Everett grid), this script records the ``K`` calls that ``DiscretePreisach``
makes on a smooth and on a noisy input (nearly every step a reversal), replays them against
each structure, checks that all return the same values, and prints per structure: build
time, memory and cost per ``K`` call (the replay loop's own cost subtracted):

* ``blocked-2`` / ``blocked-3``: the blocked dominance table of
  :mod:`exudyn_atcm.hysteresis._dominance` with two / three levels (the package's kernel);
* ``segment-tree``: a persistent segment tree over the ``beta`` ranks, one version per
  ``alpha`` prefix (``O(n log n)`` memory, one root look-up and an ``O(log n)`` descent);
* ``rows``: the former fallback, a prefix-sum row per reversal point built on first use
  (``O(n)``, vectorised) and cached;
* ``blocked-2+rows``: ``blocked-2``, switching to a cached row for the current reversal point
  once it has served ``max(64, n // 8)`` calls in a row (a cached row is one binary search
  and one list index; the row's O(n) cost is spread over those calls).

Inputs: ``smooth`` and ``noisy`` as in ``bench_preisach.py``, and ``adversarial``: a triangle
whose every half period (new extrema each time) has ``max(64, n // 8) + 1`` steps, the worst
case for ``blocked-2+rows`` (each row is built, then serves a single call).

Usage: ``python benchmarks/bench_dominance.py [--steps N] [--out results/dominance.json]``
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from bisect import bisect_left, bisect_right
from pathlib import Path

import numpy as np

from exudyn_atcm import __version__
from exudyn_atcm.io.atomic import write_json
from exudyn_atcm.hysteresis import DiscretePreisach
from exudyn_atcm.hysteresis._dominance import DominanceSums

sys.path.insert(0, str(Path(__file__).parent))
from bench_preisach import input_series, random_relays  # noqa: E402


def blocked(levels):
    def build(alpha, beta, weights):
        structure = DominanceSums(alpha, beta, weights, levels)
        return structure.query, structure.query, structure.nbytes

    return build


def segment_tree(alpha, beta, weights):
    """Persistent segment tree: version i holds the first i relays by alpha, keyed by beta rank."""
    n = alpha.size
    order = np.argsort(alpha, kind="stable")
    alpha_list = alpha[order].tolist()
    beta_list = np.sort(beta).tolist()
    rank = np.empty(n, dtype=np.intp)
    rank[np.argsort(beta, kind="stable")] = np.arange(n)
    left, right, total = [0], [0], [0.0]  # node 0: the empty tree
    roots = [0]
    for position, w in zip(rank[order].tolist(), weights[order].tolist()):
        old, lo, hi = roots[-1], 0, n
        path = []
        while True:
            node = len(total)
            left.append(left[old])
            right.append(right[old])
            total.append(total[old] + w)
            if path:
                parent, went_left = path[-1]
                if went_left:
                    left[parent] = node
                else:
                    right[parent] = node
            else:
                roots.append(node)
            if hi - lo == 1:
                break
            mid = (lo + hi) >> 1
            if position < mid:
                path.append((node, True))
                old, hi = left[old], mid
            else:
                path.append((node, False))
                old, lo = right[old], mid

    def query(a, b):
        j = bisect_left(beta_list, b)
        node = roots[bisect_right(alpha_list, a)]
        lo, hi, s = 0, n, 0.0
        while node:
            if j <= lo:
                return s + total[node]
            mid = (lo + hi) >> 1
            if j <= mid:
                s += total[right[node]]
                node, hi = left[node], mid
            else:
                node, lo = right[node], mid
        return s

    nbytes = 8 * 3 * len(total) + 32 * len(total) + 28 * 2 * len(total) + 32 * 2 * n  # lists of ints/floats
    return query, query, nbytes


def rows(alpha, beta, weights, cache_size=256):
    """The former fallback: one cached prefix-sum row per reversal point."""
    order = np.lexsort((beta, alpha))
    alpha_list = alpha[order].tolist()
    w_by_alpha, beta_by_alpha = weights[order], beta[order]
    border = np.argsort(beta, kind="stable")
    beta_list = beta[border].tolist()
    w_by_beta, alpha_by_beta = weights[border], alpha[border]
    row_cache, column_cache = {}, {}

    def k_rising(a, b):
        row = row_cache.get(b)
        if row is None:
            if len(row_cache) >= cache_size:
                row_cache.clear()
            row = row_cache[b] = [0.0, *np.cumsum(w_by_alpha * (beta_by_alpha >= b)).tolist()]
        return row[bisect_right(alpha_list, a)]

    def k_falling(a, b):
        column = column_cache.get(a)
        if column is None:
            if len(column_cache) >= cache_size:
                column_cache.clear()
            selected = w_by_beta * (alpha_by_beta <= a)
            column = column_cache[a] = [*np.cumsum(selected[::-1])[::-1].tolist(), 0.0]
        return column[bisect_left(beta_list, b)]

    return k_rising, k_falling, 8 * 4 * alpha.size  # the cache grows with use: not counted


def blocked_with_rows(alpha, beta, weights, cache_size=8):
    """blocked-2, plus a cached row for the current reversal point once it has served
    ``max(64, n // 8)`` calls in a row (so that the O(n) row costs little per call)."""
    blocked_query = DominanceSums(alpha, beta, weights, 2).query
    row_rising, row_falling, _ = rows(alpha, beta, weights, cache_size)
    hits_needed = max(64, alpha.size // 8)
    nan = float("nan")  # equal to nothing
    b_now, b_hits, b_row = nan, 0, False
    a_now, a_hits, a_row = nan, 0, False

    def k_rising(a, b):
        nonlocal b_now, b_hits, b_row
        if b == b_now:
            if b_row:
                return row_rising(a, b)
            b_hits += 1
            if b_hits >= hits_needed:
                b_row = True
                return row_rising(a, b)
            return blocked_query(a, b)
        b_now, b_hits, b_row = b, 1, False
        return blocked_query(a, b)

    def k_falling(a, b):
        nonlocal a_now, a_hits, a_row
        if a == a_now:
            if a_row:
                return row_falling(a, b)
            a_hits += 1
            if a_hits >= hits_needed:
                a_row = True
                return row_falling(a, b)
            return blocked_query(a, b)
        a_now, a_hits, a_row = a, 1, False
        return blocked_query(a, b)

    return k_rising, k_falling, DominanceSums(alpha, beta, weights, 2).nbytes + 8 * cache_size * 2 * alpha.size


STRUCTURES = {
    "blocked-2": blocked(2),
    "blocked-3": blocked(3),
    "segment-tree": segment_tree,
    "rows": rows,
    "blocked-2+rows": blocked_with_rows,
}


def triangle(steps: int, per_half: int, seed: int = 1) -> list[float]:
    """Triangle between 0-50 V and 1000-1050 V (new extrema each half period), ``per_half``
    steps per half period."""
    rng = np.random.default_rng(seed)
    u: list[float] = []
    while len(u) < steps:
        lo, hi = rng.uniform(0, 50), 1000 + rng.uniform(0, 50)
        u += np.linspace(lo, hi, per_half, endpoint=False).tolist()
        u += np.linspace(hi, lo, per_half, endpoint=False).tolist()
    return u[:steps]


def recorded_calls(model: DiscretePreisach, u: list[float]) -> list[tuple[bool, float, float]]:
    """The K calls (rising?, a, b) made by ``model`` while committing ``u``."""
    calls: list[tuple[bool, float, float]] = []
    k_rising, k_falling = model._k_rising, model._k_falling

    def rising(a, b):
        calls.append((True, a, b))
        return k_rising(a, b)

    def falling(a, b):
        calls.append((False, a, b))
        return k_falling(a, b)

    model._k_rising, model._k_falling = rising, falling
    for x in u:
        model.commit(x)
    return calls


def replay(calls, k_rising, k_falling, repeats):
    bound = [(k_rising if up else k_falling, a, b) for up, a, b in calls]
    best, values = float("inf"), []
    for _ in range(repeats):
        start = time.perf_counter()
        values = [f(a, b) for f, a, b in bound]
        best = min(best, time.perf_counter() - start)
    return best / max(1, len(calls)), values


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=10000, help="commits recorded per input")
    parser.add_argument("--repeats", type=int, default=5, help="repeats (best is kept)")
    parser.add_argument("--sizes", type=int, nargs="+", default=[1000, 5000, 20000])
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "dominance.json"))
    args = parser.parse_args(argv)

    def noop(a, b):
        return 0.0

    print(f"{'relays':>7} {'structure':>15} {'build [ms]':>11} {'memory [MB]':>12} {'K smooth [µs]':>14} {'K noisy [µs]':>13} {'K adversarial [µs]':>19}")
    rows_out = []
    for n in args.sizes:
        model = random_relays(n)
        inputs = {
            "smooth": input_series(args.steps, 0.0),
            "noisy": input_series(args.steps, 5.0),
            "adversarial": triangle(args.steps, max(64, n // 8) + 1),
        }
        calls = {kind: recorded_calls(DiscretePreisach(model.alpha, model.beta, model.weights, model.offset), u) for kind, u in inputs.items()}
        overhead = {kind: replay(c, noop, noop, args.repeats)[0] for kind, c in calls.items()}
        scale = float(np.abs(model.weights).sum())
        reference = {}
        for name, build in STRUCTURES.items():
            start = time.perf_counter()
            k_rising, k_falling, nbytes = build(model.alpha, model.beta, model.weights)
            build_s = time.perf_counter() - start
            row = {"relays": n, "structure": name, "build_ms": build_s * 1e3, "memory_MB": nbytes / 1e6}
            for kind, c in calls.items():
                cost, values = replay(c, k_rising, k_falling, args.repeats)
                reference.setdefault(kind, values)
                error = float(np.max(np.abs(np.array(values) - np.array(reference[kind])))) if values else 0.0
                assert error <= 1e-12 * scale, f"{name} differs by {error} for {n} relays ({kind})"
                row[f"k_{kind}_us"] = (cost - overhead[kind]) * 1e6
                row[f"calls_{kind}"] = len(c)
            rows_out.append(row)
            print(
                f"{n:>7} {name:>15} {row['build_ms']:>11.1f} {row['memory_MB']:>12.2f}"
                f" {row['k_smooth_us']:>14.3f} {row['k_noisy_us']:>13.3f} {row['k_adversarial_us']:>19.3f}"
            )
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    write_json(
        out,
        {
            "benchmark": "dominance sums K(a, b) of random relays: structures side by side",
            "exudyn_atcm": __version__,
            "python": sys.version.split()[0],
            "numpy": np.__version__,
            "platform": platform.platform(),
            "cpu_count": os.cpu_count(),
            "steps": args.steps,
            "repeats": args.repeats,
            "rows": rows_out,
        },
    )
    print(f"written {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
