"""What a case's run function receives besides its parameters (:class:`RunContext`) and what it
returns (:class:`CaseOutput`, the JSON record of the run), with the :func:`versions` recorded.
"""

from __future__ import annotations

import datetime as _dt
import platform
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._version import __version__
from ..io.progress import ProgressCallback, no_progress
from ..io.result import Result
from ..mbs.solver_runs import exudyn_version
from ..solve.run_plan import PlannedRun, RunPlan
from .output_folder import OutputFolder
from .parameters import Parameters, json_value

__all__ = ["RunContext", "CaseOutput", "versions"]


# ----------------------------------------------------------------------------- outputs
@dataclass
class RunContext:
    """What the runner gives a case's ``run`` function besides the parameters.

    Attributes
    ----------
    case : str
        Case name.
    out_dir : pathlib.Path or None
        Output directory (``None`` when the run writes no files).
    plot : bool
        Whether plots will be written (a case may skip plot-only work otherwise).
    progress : callable
        ``progress(t, t_end)``: report simulated time [s]; draws a bar on terminals.
    folder : OutputFolder or None
        The run's files in ``out_dir`` (set by the runner; see :meth:`output_file`).
    """

    case: str
    out_dir: Path | None = None
    plot: bool = True
    progress: ProgressCallback = no_progress
    folder: OutputFolder | None = None

    def output_file(self, name: str) -> Path:
        """The path of a file named ``name`` that ``run`` writes into the output folder itself.

        The file becomes one of the run's outputs: listed in ``<case>.json``, removed with the
        run's other files by the next run into the folder, and the previous run's files are
        removed before it is written, so that the folder never mixes two runs (see
        :mod:`exudyn_atcm.casework.output_folder`).  Write files of the run this way, not by
        joining :attr:`out_dir` and a name.

        Raises
        ------
        ValueError
            If the run writes no files (``out_dir`` is ``None``) or ``name`` is not a plain file name.
        """
        if self.out_dir is None or self.folder is None:
            raise ValueError(f"output_file({name!r}): this run of {self.case} writes no files (no output directory); "
                             "check ctx.out_dir first")
        if not isinstance(name, str) or not name or Path(name).name != name or name in (".", ".."):
            raise ValueError(f"output_file: name must be a plain file name without directories, got {name!r}")
        self.folder.add(name)
        return Path(self.out_dir) / name

    def plan(self, runs: Sequence[PlannedRun]) -> RunPlan:
        """Declare the simulations of a run made of several, before the first starts.

        Announces the run once (``RuntimeWarning``) when their summed estimate exceeds a minute,
        in the wording of a single simulation's announcement; inside the returned plan's ``with``
        block the simulations do not announce themselves again, and ``plan.progress(k)`` is the
        ``progress`` of simulation ``k``, reporting the fraction of the whole run on
        :attr:`progress` (see :mod:`exudyn_atcm.solve.run_plan`)::

            with ctx.plan([PlannedRun(actuator, t_end, step)] * 4) as plan:
                for k in range(4):
                    simulate(..., progress=plan.progress(k))
        """
        return RunPlan(runs, self.progress, stacklevel=3)


@dataclass
class CaseOutput:
    """What a case's ``run`` function returns; the runner fills in the rest.

    Parameters
    ----------
    result : Result
        The main time series (written as ``<case>.csv``).
    scalars : mapping of str to float or (float, str)
        Key scalar results, each a value in SI units or a ``(value, unit)`` pair.
    steps : int, optional
        Number of time steps or recorded instants (default: the rows of ``result``).
    tables : mapping of str to Result, optional
        Further tables, written as ``<case>_<name>.csv``.
    notes : mapping, optional
        Extra JSON-serialisable information written into ``<case>.json``.

    Attributes
    ----------
    case : str
        Case name (set by the runner).
    parameters : Parameters
        The parameters of the run (set by the runner).
    wall_time : float
        Wall time of ``run`` [s] (set by the runner; plotting excluded).
    files : list of pathlib.Path
        Files written (set by the runner).
    """

    result: Result
    scalars: Mapping[str, Any] = field(default_factory=dict)
    steps: int | None = None
    tables: Mapping[str, Result] = field(default_factory=dict)
    notes: Mapping[str, Any] = field(default_factory=dict)
    case: str = ""
    parameters: Parameters | None = None
    wall_time: float = float("nan")
    plot_time: float = 0.0
    files: list[Path] = field(default_factory=list)
    scalar_units: dict[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.result, Result):
            raise ValueError(f"result must be an exudyn_atcm Result, got {type(self.result).__name__}")
        values: dict[str, float] = {}
        units = dict(self.scalar_units)
        for name, item in dict(self.scalars).items():
            if isinstance(item, tuple):
                value, unit = item
                units[name] = str(unit)
            else:
                value = item
                units.setdefault(name, "-")
            values[name] = float(value)
        self.scalars = values
        self.scalar_units = units
        if self.steps is None:
            self.steps = self.result.n_rows
        for name, table in dict(self.tables).items():
            if not isinstance(table, Result):
                raise ValueError(f"tables[{name!r}] must be an exudyn_atcm Result, got {type(table).__name__}")

    def scalar(self, name: str) -> float:
        """Value of key scalar ``name`` (SI units)."""
        return self.scalars[name]

    def to_dict(self) -> dict[str, Any]:
        """The JSON record of the run (``<case>.json``)."""
        params = self.parameters or Parameters([], {})
        return {
            "case": self.case,
            "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
            "parameters": {n: {"value": json_value(params[n]), "unit": params.unit(n)} for n in params},
            "scalars": {n: {"value": v, "unit": self.scalar_units[n]} for n, v in self.scalars.items()},
            "steps": self.steps,
            "wall_time [s]": self.wall_time,
            "plot_time [s]": self.plot_time,
            "series": [{"name": n, "unit": self.result.unit(n)} for n in self.result.names],
            "versions": versions(),
            "platform": platform.platform(),
            "notes": dict(self.notes),
            "files": [p.name for p in self.files],
        }


def versions() -> dict[str, str]:
    """Versions of this package, Exudyn, Python and NumPy."""
    import numpy

    try:
        exu = exudyn_version()
    except Exception:  # pragma: no cover - exudyn is a dependency
        exu = "unavailable"
    return {
        "exudyn_atcm": __version__,
        "exudyn": exu,
        "python": platform.python_version(),
        "numpy": numpy.__version__,
    }
