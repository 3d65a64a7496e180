"""A known, non-uniform Preisach model and the synthetic "measured" record made from it.

No measured piezo record ships with the package, so identification is demonstrated and
tested on a record whose truth is known: the output of :func:`reference_preisach` (a
Preisach density that is *not* the equal-gain one of the paper's Eq. 12) driven by
:func:`reference_program` (major loops and minor loops), plus Gaussian noise.
``cases/data/preisach_record.csv`` was written by :func:`write_reference_record` (the script
``cases/data/make_preisach_record.py``); its header says so.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..io.atomic import write_text
from ..hysteresis.everett import EverettPreisach
from ..hysteresis.identification import relay_grid
from .signals import PiecewiseLinear

__all__ = ["REFERENCE", "reference_preisach", "reference_program", "reference_samples", "write_reference_record"]

#: Settings of the shipped record (SI units).
REFERENCE = {
    "u_min [V]": -500.0,
    "u_max [V]": 1500.0,
    "y_min [m]": -4e-6,
    "y_range [m]": 44e-6,
    "grid_levels": 120,
    "ramp_rate [V/s]": 2000.0,
    "sample_rate [Hz]": 250.0,
    "noise [m]": 0.4e-6,
    "seed": 20261123,
    "corners [V]": (-500, 1500, -500, 1500, 200, 900, -100, 1200, 500, 1500, -500, 600, 100, 1500, 800, 1100,
                    -500, 1500, 300, -500, 1300, 700, 1500, -200, 400, -500),
}


def reference_preisach(scale: float = 1.0) -> EverettPreisach:
    """The known model: a smooth, non-uniform Preisach density on a fine grid.

    Density over the Preisach triangle (``alpha >= beta``, volts)::

        mu(alpha, beta) = exp(-((alpha - beta) - 350)^2 / (2·300^2))
                          · exp(-((alpha + beta)/2 - 300)^2 / (2·600^2))
                          + a reversible part on the diagonal alpha = beta,
                            1.5 · exp(-((alpha + beta)/2 - 900)^2 / (2·500^2)) per grid cell,

    discretised with 120 cells over -500 ... 1500 V (7260 cell weights), each spread evenly
    over its cell (:class:`~exudyn_atcm.hysteresis.everett.EverettPreisach`: a continuous
    output, as of a real piezo layer), scaled to an output of -4 µm (all relays off) ... 40 µm
    (all on), the range of the paper's 29 mm cell.

    Parameters
    ----------
    scale : float, optional
        Factor on the output (e.g. ``1 / 29e-3`` for the free strain of a 29 mm cell).
    """
    r = REFERENCE
    n = r["grid_levels"]
    alpha, beta, _ = relay_grid(r["u_min [V]"], r["u_max [V]"], n)
    weights = np.exp(-((alpha - beta) - 350.0) ** 2 / (2 * 300.0**2)) * np.exp(
        -(((alpha + beta) / 2) - 300.0) ** 2 / (2 * 600.0**2)
    )
    weights = weights + 0.05 * (n / 4) * np.exp(-(((alpha + beta) / 2) - 900.0) ** 2 / (2 * 500.0**2)) * (alpha == beta)
    weights *= r["y_range [m]"] / weights.sum()
    edges = np.linspace(r["u_min [V]"], r["u_max [V]"], n + 1)
    return EverettPreisach(edges, alpha, beta, weights * scale, offset=r["y_min [m]"] * scale)


def reference_program() -> PiecewiseLinear:
    """The input program of the record: ramps at 2000 V/s through the corner voltages of ``REFERENCE``."""
    corners = np.asarray(REFERENCE["corners [V]"], dtype=float)
    times = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(corners)) / REFERENCE["ramp_rate [V/s]"])])
    return PiecewiseLinear(times, corners)


def reference_samples(noise: float | None = None, seed: int | None = None,
                      sample_rate: float | None = None) -> tuple[np.ndarray, ...]:
    """Time [s], voltage [V], noise-free and noisy displacement [m] of the reference record.

    ``noise`` [m], ``seed`` and ``sample_rate`` [Hz] default to the shipped record's.
    """
    program = reference_program()
    rate = REFERENCE["sample_rate [Hz]"] if sample_rate is None else float(sample_rate)
    t = np.arange(0.0, program.times[-1] + 0.5 / rate, 1.0 / rate)
    u = program(t)
    clean = reference_preisach().apply(u)
    rng = np.random.default_rng(REFERENCE["seed"] if seed is None else seed)
    sigma = REFERENCE["noise [m]"] if noise is None else noise
    return t, u, clean, clean + sigma * rng.standard_normal(t.size)


def write_reference_record(path: str | Path) -> Path:
    """Write the reference record as CSV (``time [s],voltage [V],displacement [m]``) with a header saying how."""
    t, u, _, y = reference_samples()
    r = REFERENCE
    header = [
        "# Synthetic hysteresis record (NOT a measurement), made by cases/data/make_preisach_record.py",
        "# with exudyn_atcm.model.reference_record.write_reference_record:",
        "# output = known non-uniform Preisach model exudyn_atcm.model.reference_record.reference_preisach()",
        f"#   ({r['grid_levels']}-cell grid over {r['u_min [V]']:g}...{r['u_max [V]']:g} V, weights spread over the cells, density",
        "#   exp(-((a-b)-350)^2/(2*300^2))*exp(-((a+b)/2-300)^2/(2*600^2)) plus a reversible diagonal part,",
        "#   output -4e-6 m with all relays off, 40e-6 m with all on)",
        f"# input  = ramps at {r['ramp_rate [V/s]']:g} V/s through the corners {list(r['corners [V]'])} V",
        "#   (major loops and minor loops), sampled at "
        f"{r['sample_rate [Hz]']:g} Hz, starting from the model's reset state",
        f"# noise  = Gaussian, standard deviation {r['noise [m]']:g} m, numpy default_rng(seed={r['seed']})",
        "time [s],voltage [V],displacement [m]",
    ]
    lines = [f"{a:.6f},{b:.6f},{c:.6e}" for a, b, c in zip(t, u, y)]
    return write_text(path, "\n".join(header + lines) + "\n")
