"""Comparing one benchmark's case output with its references: one :class:`MetricRow` per scalar
and per channel (RMS and maximum error), with a plot of each channel against its reference.

The rules (interpolation onto the reference's base, the ``abs``/``rel`` tolerances) are described in
:mod:`exudyn_atcm.casework.regression`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..plots.style import axis_label, display_scale, new_figure, save_figure

__all__ = ["MetricRow", "compare_benchmark"]


@dataclass
class MetricRow:
    """One row of the report: a metric of one benchmark."""

    case: str
    metric: str
    kind: str  # "analytic", "stored", "series rms", "series max", "run"
    unit: str
    reference: float
    value: float
    abs_error: float
    rel_error: float
    tolerance: str
    passed: bool
    wall_time: float
    steps: int | None
    note: str = ""


def _tolerance_text(metric: dict[str, Any]) -> str:
    parts = []
    if "abs" in metric:
        parts.append(f"abs {metric['abs']:g}")
    if "rel" in metric:
        parts.append(f"rel {metric['rel']:g}")
    return " or ".join(parts)


def compare_benchmark(bench: dict[str, Any], output: Any, reference: dict[str, Any] | None, plot_dir: Path | None, files: list[Path]) -> list[MetricRow]:
    """The metric rows of benchmark ``bench`` (a ``suite.json`` entry) for the case ``output``.

    ``reference`` is the stored reference (``{"meta": ..., "series": Result}``, or ``None``); with
    ``plot_dir`` a plot of each channel is written there and its path appended to ``files``.
    """
    bid = bench["id"]
    wall, steps = output.wall_time, output.steps
    rows: list[MetricRow] = []
    no_ref = "no stored reference: run exudyn-atcm bench --update-references --reason TEXT"

    for metric in bench.get("scalars", []):
        scalar = metric["scalar"]
        name = metric.get("name", scalar)
        unit = output.scalar_units.get(scalar, "-")
        tol = _tolerance_text(metric)
        if scalar not in output.scalars:
            rows.append(MetricRow(bid, name, "analytic" if "analytic" in metric else "stored", unit, math.nan, math.nan, math.nan, math.nan, tol, False, wall, steps, f"the case reports no scalar {scalar!r}; it has {sorted(output.scalars)}"))
            continue
        value = output.scalars[scalar]
        if "analytic" in metric:
            ref, kind, note = float(metric["analytic"]), "analytic", metric["source"]
        else:
            stored = (reference or {}).get("meta", {}).get("scalars", {}).get(scalar)
            if stored is None:
                rows.append(MetricRow(bid, name, "stored", unit, math.nan, value, math.nan, math.nan, tol, False, wall, steps, no_ref))
                continue
            ref, kind, note = float(stored["value"]), "stored", ""
        err = abs(value - ref)
        rel = err / abs(ref) if ref != 0.0 else (0.0 if err == 0.0 else math.inf)
        allowed = max(metric.get("abs", 0.0), metric.get("rel", 0.0) * abs(ref))
        rows.append(MetricRow(bid, name, kind, unit, ref, value, err, rel, tol, bool(err <= allowed), wall, steps, note))

    channels = bench.get("channels", {})
    if channels:
        series = (reference or {}).get("series")
        base = bench.get("base", "time")
        for channel, tol in channels.items():
            unit = output.result.unit(channel) if channel in output.result else "-"
            tol_rms, tol_max = f"abs {tol['rms']:g}", f"abs {tol['max']:g}"
            if series is None or channel not in series or base not in series:
                for kind, t in (("series rms", tol_rms), ("series max", tol_max)):
                    rows.append(MetricRow(bid, f"{channel} ({kind.split()[1]})", kind, unit, math.nan, math.nan, math.nan, math.nan, t, False, wall, steps, no_ref))
                continue
            if channel not in output.result or base not in output.result:
                for kind, t in (("series rms", tol_rms), ("series max", tol_max)):
                    rows.append(MetricRow(bid, f"{channel} ({kind.split()[1]})", kind, unit, math.nan, math.nan, math.nan, math.nan, t, False, wall, steps, f"the case output has no series {channel!r} or {base!r}"))
                continue
            x_ref, y_ref = series[base], series[channel]
            x_new, y_new = output.result[base], output.result[channel]
            note = ""
            span = max(abs(x_ref[-1] - x_ref[0]), 1e-300)
            covered = x_new.size > 0 and x_new[0] <= x_ref[0] + 1e-9 * span and x_new[-1] >= x_ref[-1] - 1e-9 * span
            if not covered or np.any(np.diff(x_new) < 0):
                note = f"the new {base} does not cover the reference range [{x_ref[0]:g}, {x_ref[-1]:g}] in increasing order"
                y_interp = np.full_like(y_ref, np.nan)
            else:
                y_interp = np.interp(x_ref, x_new, y_new)
            error = y_interp - y_ref
            rms_err = float(np.sqrt(np.mean(error**2))) if error.size else 0.0
            max_err = float(np.max(np.abs(error))) if error.size else 0.0
            ref_rms = float(np.sqrt(np.mean(y_ref**2))) if y_ref.size else 0.0
            ref_max = float(np.max(np.abs(y_ref))) if y_ref.size else 0.0
            new_rms = float(np.sqrt(np.mean(y_new**2))) if y_new.size else 0.0
            new_max = float(np.max(np.abs(y_new))) if y_new.size else 0.0
            ok_rms = bool(np.isfinite(rms_err) and rms_err <= tol["rms"])
            ok_max = bool(np.isfinite(max_err) and max_err <= tol["max"])
            rows.append(MetricRow(bid, f"{channel} (rms)", "series rms", unit, ref_rms, new_rms, rms_err, rms_err / ref_rms if ref_rms else math.nan, tol_rms, ok_rms, wall, steps, note))
            rows.append(MetricRow(bid, f"{channel} (max)", "series max", unit, ref_max, new_max, max_err, max_err / ref_max if ref_max else math.nan, tol_max, ok_max, wall, steps, note))
            if plot_dir is not None:
                files.append(_plot_channel(plot_dir / f"{bid}_{channel}.png", bid, base, series.unit(base), channel, unit, x_ref, y_ref, x_new, y_new, error, ok_rms and ok_max))
    return rows


def _plot_channel(path: Path, bid: str, base: str, base_unit: str, channel: str, unit: str, x_ref, y_ref, x_new, y_new, error, ok: bool) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fig, (ax, ax_err) = new_figure(2, sharex=True, height=4.8)
    factor, shown = display_scale(np.concatenate([y_ref, y_new]), unit)
    ax.plot(x_ref, factor * y_ref, color="0.3", linewidth=3.0, alpha=0.5, label="reference")
    ax.plot(x_new, factor * y_new, label="this run")
    ax.set_ylabel(axis_label(channel, shown))
    ax.legend(loc="best")
    ax.set_title(f"{bid}: {channel} against its reference ({'pass' if ok else 'FAIL'})")
    e_factor, e_unit = display_scale(error, unit)
    ax_err.plot(x_ref, e_factor * error)
    ax_err.set_ylabel(axis_label("error", e_unit))
    ax_err.set_xlabel(axis_label(base, base_unit))
    return save_figure(fig, path)
