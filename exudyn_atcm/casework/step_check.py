"""How much a case's key scalars depend on its time step: ``exudyn-atcm step-error CASE``.

A case with a ``step`` parameter (its time step [s]) is run at ``step``, ``step/2`` and
``step/4`` with otherwise the same parameters, and each key scalar's change is turned into an
estimate of its time-step error as :func:`exudyn_atcm.step_error` does for a run's columns:
second-order integration, so the error at ``step`` is about 4/3 of the change to ``step/2``
(Richardson's estimate), and the third run gives the observed order.  Scalars that do not come
from the time integration (a static sweep's) do not change: their error is zero, their order
``nan``.

A case whose ``step`` is 0 chooses its step itself (for an ``accuracy``, as
``paper_bending_actuator`` does): it is run once so, and the step it used (its notes'
``"step [s]"``, else its result's ``info["step [s]"]``) is the step examined; the finer runs fix
half and a quarter of it.

May import the case layer and :mod:`exudyn_atcm.io`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

from ..io.atomic import write_json
from ..solve.step_error import richardson
from .case import Case
from .parameters import CaseError

__all__ = ["ScalarStepError", "case_step_error", "format_step_errors", "write_step_errors", "STEP_PARAMETER"]

#: The parameter a case's time step must be declared as.
STEP_PARAMETER = "step"
#: Changes below this share of a scalar's value are round-off and Newton tolerance (no order is given).
NOISE = 1e-9
#: Observed orders in this range count as the second-order behaviour the estimate assumes.
ORDER_RANGE = (1.5, 3.0)


@dataclass(frozen=True)
class ScalarStepError:
    """The time-step error of one key scalar of a case.

    Attributes
    ----------
    name, unit : str
        The scalar and its unit.
    value : float
        Its value at the step examined.
    finest : float
        Its value at the finest step run.
    error : float
        Estimated error of ``value`` [unit]: 4/3 of its change from ``step`` to ``step/2``.
    relative : float
        ``error / |finest|`` (``nan`` when ``finest`` is 0).
    order : float
        Observed order from the three runs (``nan`` with two runs or a change at round-off level).
    """

    name: str
    unit: str
    value: float
    finest: float
    error: float
    relative: float
    order: float

    @property
    def reliable(self) -> bool | None:
        """True when the observed order is in :data:`ORDER_RANGE` (or the scalar does not change beyond
        round-off), False when it is not (a maximum picked from the samples, a nonsmooth input: the
        estimate can be far off), None without the third run."""
        if self.error <= NOISE * abs(self.finest):
            return True
        if math.isnan(self.order):
            return None
        return ORDER_RANGE[0] <= self.order <= ORDER_RANGE[1]


def case_step_error(case: Case, values: Mapping[str, Any] | Sequence[str] | None = None, *,
                    check_order: bool = True) -> tuple[float, list[ScalarStepError]]:
    """Run ``case`` at its step, half and (``check_order``) a quarter of it; each key scalar's step error.

    Parameters
    ----------
    case : Case
        A case declaring the parameter ``step`` [s].
    values : mapping or sequence of str, optional
        Parameter overrides, as for :meth:`Case.run <exudyn_atcm.casework.case.Case.run>` (``step``
        included: the step examined).
    check_order : bool, optional
        Run ``step/4`` too and report the observed order (default True).

    Returns
    -------
    (float, list of ScalarStepError)
        The step examined [s] and one entry per key scalar, in the case's order.

    Raises
    ------
    CaseError
        If the case has no ``step`` parameter, or for bad parameter values.
    """
    params = case.resolve(values)
    names = list(params)
    if STEP_PARAMETER not in names:
        raise CaseError(f"case {case.name} has no {STEP_PARAMETER!r} parameter, so its time step cannot be varied "
                        f"(its parameters: {', '.join(names)})")
    step = float(params[STEP_PARAMETER])
    given = {name: params[name] for name in names}
    first = None
    if step <= 0.0:  # the case chooses its step: run it so, and examine the step it used
        first = case.run(given)
        step = _step_used(case.name, first)
        given = {name: value for name, value in given.items() if name != "accuracy"}  # the step is now given
    steps = [step, step / 2.0] + ([step / 4.0] if check_order else [])
    outputs = [first if first is not None and h == step else case.run({**given, STEP_PARAMETER: h}) for h in steps]
    out = []
    for name, value in outputs[0].scalars.items():
        values_ = [o.scalars.get(name, math.nan) for o in outputs]
        changes = [abs(a - b) for a, b in zip(values_, values_[1:])]
        finest = values_[-1]
        error, order = richardson(changes, NOISE * abs(finest))
        relative = error / abs(finest) if finest != 0.0 else math.nan
        out.append(ScalarStepError(name, outputs[0].scalar_units.get(name, "-"), value, finest, error, relative, order))
    return step, out


def _step_used(case_name: str, output: Any) -> float:
    """The step [s] a case run with ``step`` 0 used: its notes' ``"step [s]"``, else its result's ``info``."""
    step = output.notes.get("step [s]") if isinstance(output.notes, Mapping) else None
    if step is None:
        step = getattr(output.result, "info", {}).get("step [s]")
    if not isinstance(step, (int, float)) or not math.isfinite(step) or step <= 0.0:
        raise CaseError(f"case {case_name} ran with step = 0 (the case chooses it) but reports no step used (notes or "
                        f"info 'step [s]'); give the step to examine with --set step=...")
    return float(step)


def format_step_errors(case_name: str, step: float, rows: list[ScalarStepError]) -> str:
    """The table printed by ``exudyn-atcm step-error``."""
    lines = [f"{case_name}: time-step error of the key scalars at step {step:.6g} s "
             f"(runs at step, step/2{', step/4' if any(math.isfinite(r.order) for r in rows) else ''})",
             f"{'scalar':>28} | {'unit':>5} | {'value':>12} | {'estimated error':>15} | {'relative':>9} | {'order':>5} | "
             f"estimate"]
    lines.append("-" * len(lines[-1]))
    verdict = {True: "ok", False: "unsure", None: "-"}
    for r in rows:
        lines.append(f"{r.name:>28} | {r.unit:>5} | {r.value:>12.6g} | {r.error:>15.3e} | {r.relative:>9.2e} | "
                     f"{r.order:>5.2f} | {verdict[r.reliable]}")
    lines.append("error: 4/3 of the change from step to step/2 (second-order integration); order: observed from the "
                 f"three runs; estimate 'ok' for an order in {ORDER_RANGE[0]:g} ... {ORDER_RANGE[1]:g} or no change "
                 "beyond round-off, 'unsure' otherwise (a maximum picked from the samples, a nonsmooth input: "
                 "compare runs at smaller steps yourself)")
    return "\n".join(lines)


def write_step_errors(path, case_name: str, step: float, rows: list[ScalarStepError]) -> None:
    """The same as JSON (written atomically)."""
    write_json(path, {"case": case_name, "step [s]": step,
                      "scalars": {r.name: {"unit": r.unit, "value": r.value, "finest": r.finest, "error": r.error,
                                           "relative": None if math.isnan(r.relative) else r.relative,
                                           "order": None if math.isnan(r.order) else r.order,
                                           "reliable": r.reliable} for r in rows}})
