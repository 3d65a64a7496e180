"""Each bender's own cell-kind checks after a run, wherever the bender sits.

A cell kind may check a finished run (:meth:`exudyn_atcm.cells.CellKind.check_run`, e.g. the
``ritz`` kind's warning when the dynamic tip rotation leaves the quasi-static arc).  The check is
made for every bender of a mechanism, a lone actuator (a one-bender mechanism) included: the kind
sees :func:`bender_view`, the bender's own columns under their bare names.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..io.result import Result
from ..mechanism.assembly import Mechanism
from ..mechanism.bender import Bender

__all__ = ["bender_view", "check_benders"]


def bender_view(result: Result, bender: Bender) -> Result:
    """The columns of ``bender`` in a mechanism's ``result`` under their bare names.

    ``time`` (or ``point``), then every ``{bender}.x`` column as ``x`` (``tip_x``, ``tip_y``,
    ``cell_angle_j``, ...), with two columns in the bender's own frame: ``tip_angle`` is the tip's
    rotation against the base [rad], positive where a positive free strain bends the bender
    (``curvature_sign * (tip_angle - base_angle)``; for a lone actuator, whose base is clamped along
    +x, the recorded tip angle itself), and ``strain``/``voltage`` are those of the bender's drive
    (zero for a passive strip; a segmented bender: its first driven segment's).
    """
    base = "time" if "time" in result else "point"
    prefix = bender.name + "."
    series: dict[str, Any] = {base: result[base]}
    units = {base: result.unit(base)}
    for name in result:
        if name.startswith(prefix) and "." not in name[len(prefix):]:
            series[name[len(prefix):]] = result[name]
            units[name[len(prefix):]] = result.unit(name)
    if "tip_angle" in series and "base_angle" in series:
        series["tip_angle"] = bender.curvature_sign * (series["tip_angle"] - series["base_angle"])
    drives = list(bender.drives)
    zero = np.zeros(result.n_rows)
    for column, unit in (("strain", "-"), ("voltage", "V")):
        key = f"{drives[0]}.{column}" if drives else None
        series[column] = result[key] if key is not None and key in result else zero
        units[column] = unit
    return Result(series, units, parameters=bender.parameters(), info=result.info)


def check_benders(mech: Mechanism, result: Result, stacklevel: int = 2) -> None:
    """Run every bender's cell-kind check on ``result`` (warnings point ``stacklevel`` frames up)."""
    for bender in mech.benders:
        bender.cell.check_run(bender_view(result, bender), bender, stacklevel=stacklevel + 1)
