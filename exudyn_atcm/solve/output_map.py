"""The quasi-static map from a drive's free strain to a mechanism output, from a static sweep.

:func:`output_map` sweeps one drive's voltage upwards over its range (a
:func:`~exudyn_atcm.solve.mechanism_solve.static_sweep` by continuation, each point held for ever so
that creep has settled) and reads the drive's free strain and the wanted output column at every
point.  The output of an elastic mechanism at rest depends on the free strain only (not on the
voltage history that produced it), so this one ascending sweep gives the map for both branches of
the hysteresis.  Every second sweep point is kept out of the map and used to measure its
interpolation error (:attr:`OutputMap.fit_error`).

The map is refused (``ValueError``) where it is not one-to-one over the wanted outputs (the message
names the output and strain range where the output turns back) and for wanted outputs outside
the reachable range (the message gives that range).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import shown
from ..hysteresis.bisection import default_input_range
from ..mechanism.assembly import Mechanism
from ..mechanism.points import MechanismError
from ..suggestions import close_names
from .mechanism_solve import static_sweep

__all__ = ["OutputMap", "output_map", "drive_name", "voltage_limits"]


def pchip(x: np.ndarray, y: np.ndarray, extrapolate: bool = False):
    """scipy's monotone cubic (PCHIP) interpolant of ``y(x)``, ``x`` increasing."""
    from scipy.interpolate import PchipInterpolator  # noqa: PLC0415 - lazy: scipy is slow to import

    return PchipInterpolator(x, y, extrapolate=extrapolate)


def drive_name(mech: Mechanism, drive: str | None) -> str:
    """The drive to compensate: ``drive`` checked, or the mechanism's only drive."""
    names = list(mech.drives)
    if drive is None:
        if len(names) != 1:
            raise ValueError(f"drive: mechanism {mech.name!r} has {len(names)} drives ({', '.join(names) or 'none'}); "
                             "name the one to compensate (drive='...')")
        return names[0]
    if drive not in mech.drives:
        hint = close_names(drive, names)
        raise ValueError(f"drive: mechanism {mech.name!r} has no drive {drive!r}"
                         f"{f' (did you mean {hint[0]!r}?)' if hint else ''}; drives: {', '.join(names) or 'none'}")
    return drive


def voltage_limits(pdrive: Any, voltage_range: tuple[float, float] | None) -> tuple[float, float]:
    """The voltages [V] the program may use: ``voltage_range``, else the drive's rating within the
    hysteresis operator's declared input range (where both exist)."""
    if voltage_range is not None:
        lo, hi = (float(v) for v in voltage_range)
        if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo):
            raise ValueError(f"voltage_range must be (low, high) [V] with high > low, got {shown(voltage_range)}")
        return lo, hi
    ranges = []
    if pdrive.rated_range is not None:
        ranges.append(tuple(pdrive.rated_range))
    if pdrive.hysteresis is not None:
        try:
            ranges.append(tuple(default_input_range(pdrive.hysteresis)))
        except (ValueError, TypeError, AttributeError):
            pass
    if not ranges:
        raise ValueError("voltage_range: the drive has neither a rated_range nor a hysteresis input range; "
                         "give voltage_range=(low, high) [V]")
    lo, hi = max(r[0] for r in ranges), min(r[1] for r in ranges)
    if not hi > lo:
        raise ValueError(f"voltage_range: the drive's rating and its operator's input range do not overlap ({ranges}); "
                         "give voltage_range=(low, high) [V]")
    return lo, hi


@dataclass(frozen=True)
class OutputMap:
    """Free strain [-] to an output (its unit) at rest, and back, from a static sweep.

    Attributes
    ----------
    output : str
        The result column (e.g. ``"lever.end_y"``).
    voltages, strains, values : numpy.ndarray
        The sweep points kept for the map: voltage [V], the drive's free strain [-], the output.
    check_strains, check_values : numpy.ndarray
        The points in between, kept out of the map to measure it.
    fit_error : float
        Largest error of the interpolated map at the check points (output units): the accuracy
        a quasi-static program can have.
    """

    output: str
    voltages: np.ndarray
    strains: np.ndarray
    values: np.ndarray
    check_strains: np.ndarray
    check_values: np.ndarray
    fit_error: float

    @property
    def reachable(self) -> tuple[float, float]:
        """Lowest and highest output over the sweep (output units)."""
        return float(self.values.min()), float(self.values.max())

    def value(self, strain: Any) -> np.ndarray:
        """Output at rest for the free strain(s) (piecewise-cubic monotone interpolation)."""
        return pchip(self.strains, self.values)(np.asarray(strain, dtype=float))

    def strain(self, value: Any) -> np.ndarray:
        """Free strain(s) [-] that give the output(s) at rest (the map must be monotone: :meth:`check`)."""
        order = np.argsort(self.values)
        return pchip(self.values[order], self.strains[order])(np.asarray(value, dtype=float))

    def check(self, low: float, high: float, what: str = "wanted") -> None:
        """Refuse outputs in ``[low, high]`` beyond the reachable range, or where the map turns back."""
        lo, hi = self.reachable
        if low < lo or high > hi:
            raise ValueError(
                f"{what}: {self.output} from {low:.6g} to {high:.6g} is not reachable at rest; the drive's voltage "
                f"range ({self.voltages[0]:g} ... {self.voltages[-1]:g} V, free strain {self.strains[0]:.4g} ... "
                f"{self.strains[-1]:.4g}) reaches {self.output} from {lo:.6g} to {hi:.6g}")
        steps = np.diff(self.values)
        direction = np.sign(self.values[-1] - self.values[0])
        seg_lo = np.minimum(self.values[:-1], self.values[1:])
        seg_hi = np.maximum(self.values[:-1], self.values[1:])
        # segments whose outputs meet the wanted range and that do not move with the overall direction
        bad = np.flatnonzero((seg_hi >= low) & (seg_lo <= high) & (np.sign(steps) != direction))
        if direction == 0 or bad.size:
            sign = np.sign(steps)
            # the turning point nearest to the segments that move against the overall direction
            turns = [k for k in range(1, len(steps)) if sign[k] != sign[k - 1]]
            k = min(turns, key=lambda j: int(np.min(np.abs(bad - j)))) if turns and bad.size else 0
            k0, k1 = max(k - 1, 0), min(k + 1, len(self.strains) - 1)
            raise ValueError(
                f"{what}: the quasi-static map from the free strain to {self.output} is not monotone over the wanted "
                f"range {low:.6g} ... {high:.6g}: {self.output} turns back near free strain {self.strains[k]:.4g} "
                f"(between free strain {self.strains[k0]:.4g} and {self.strains[k1]:.4g} (voltage "
                f"{self.voltages[k0]:g} ... {self.voltages[k1]:g} V), at {self.output} = {self.values[k]:.6g}), so a "
                f"wanted value there has two strains; choose an output that moves one way with the drive, or "
                f"restrict voltage_range to one side")


def output_map(mech: Mechanism, output: str, drive: str, voltages: tuple[float, float], points: int = 41) -> OutputMap:
    """Sweep ``drive`` from ``voltages[0]`` to ``voltages[1]`` [V] (``2 points - 1`` static equilibria)
    and build the map of its free strain to the column ``output``.

    The other drives keep their programs' voltages at t = 0.  Raises ``ValueError`` for an
    ``output`` that is not a result column (with the closest name), a non-numeric one, or a drive
    whose strain does not grow with the voltage.
    """
    if points < 4:
        raise ValueError(f"points must be >= 4, got {shown(points)}")
    volts = np.linspace(voltages[0], voltages[1], 2 * points - 1)
    try:
        sweep = static_sweep(mech, {drive: volts})
    except MechanismError:
        raise
    columns = [c for c in sweep.names if c != "point"]
    if output not in columns:
        hint = close_names(output, columns)
        raise ValueError(f"output: {output!r} is not a column of mechanism {mech.name!r}"
                         f"{f' (did you mean {hint[0]!r}?)' if hint else ''}; its columns are the points' "
                         f"'<part>.<point>_x'/'_y', the angles and the drives' voltage and strain, e.g. "
                         f"{', '.join(columns[:6])}")
    strain = np.asarray(sweep[f"{drive}.strain"], dtype=float)
    value = np.asarray(sweep[output], dtype=float)
    if not np.all(np.diff(strain) >= 0.0) or strain[-1] <= strain[0]:
        raise ValueError(f"drive {drive!r}: its free strain does not grow with the voltage over {voltages[0]:g} ... "
                         f"{voltages[1]:g} V; the feedforward needs a drive whose strain rises with the voltage")
    keep = np.arange(0, volts.size, 2)
    mid = np.arange(1, volts.size, 2)
    s, v, u = strain[keep], value[keep], volts[keep]
    unique = np.concatenate([[True], np.diff(s) > 0.0])  # a saturated operator repeats its strain
    s, v, u = s[unique], v[unique], u[unique]
    fit = pchip(s, v, extrapolate=True)(strain[mid])
    return OutputMap(output, u, s, v, strain[mid], value[mid], float(np.max(np.abs(fit - value[mid]))))
