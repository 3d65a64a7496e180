"""The drives' own cost per solver step, measured, for the run-time estimate.

The cells' measured costs (:attr:`exudyn_atcm.cells.CellKind.cost_per_step`, from
``benchmarks/bench_run_cost.py``) include one drive like the paper's: a triangle program and the
paper's continuous Preisach loop, evaluated once per attempted step and committed once per
accepted step.  A drive can cost far more than that: a controller whose feedforward inverts an
Everett plant by bisection, a fine relay grid, a creep operator.  :func:`extra_drive_cost`
measures each drive's trial-and-commit cycle on the drive itself, its operator's memory put back
afterwards, and returns what the drives cost beyond that reference drive, per step.

It does not measure on a copy: ``copy.deepcopy`` reads every copied object's ``__dict__``, and
CPython 3.11 then keeps that object's attributes in a dictionary for the rest of its life instead
of its faster inline storage.  Every later attribute access of the drive, its program and its
operator, in every step of the run, got dearer: +8 % of the instructions of a whole ``ritz``
actuator run (callgrind, 1,000 steps).  The run resets the operator and the controller at its
start, so measuring on the drive itself changes nothing the run sees.

Counting the drives narrows the gap between the estimate and the run but does not close it.
On ``cases/tip_tracking.py`` (4 s, 20,000 steps per run) the four runs were estimated at 0.48 s each from the cells alone; with the drives at 0.52
to 0.80 s, and they took 0.78 to 1.36 s (an earlier run on a busier machine: 0.67 to 0.83 s
estimated, 1.1 to 2.3 s taken).  The rest is the closed loop's extra Newton iterations and the
cells' constants, which were measured on another day.  A run of several simulations
(:class:`~exudyn_atcm.solve.run_plan.RunPlan`) says so when its first simulations run slower than
predicted.
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from typing import Any

from ..model.drive import PiezoDrive
from ..model.parameter_sets import paper_strain_preisach
from ..model.signals import Triangle
from ..model.strain_sources import InStepStrain

__all__ = ["drive_step_cost", "extra_drive_cost", "reference_drive_cost", "drive_share", "SAMPLES", "BATCHES", "NOISE_SHARE"]

#: Trial-and-commit cycles timed per batch (after two that warm it up): enough for an estimate, a
#: fraction of a millisecond for the paper's operator.
SAMPLES = 8

#: Batches timed per drive; the cheapest batch counts, so that one descheduling of the process (a
#: millisecond on a shared machine) does not make a cheap drive look dear.  A drive dearer than
#: :data:`SLOW_CYCLE` per cycle is timed once (its noise is small beside its cost).
BATCHES = 3
SLOW_CYCLE = 1e-4

#: Excess over the reference drive, as a share of its cost, below which a drive counts as the reference
#: (timings of the same drive on a shared machine differ by up to 1.4x between runs).
NOISE_SHARE = 0.5

_reference: list[float] = []  # the reference drive's cost, measured once per process


def drive_step_cost(drive: Any, step: float, samples: int = SAMPLES) -> float | None:
    """Wall time [s] of one solver step's work of ``drive``: the strain source's trial at the step's time,
    its commit and a controller's observation, averaged over ``samples`` steps of ``step`` [s] from
    ``t = 0``; the cheapest of :data:`BATCHES` such averages.

    Measured on the drive itself (not a copy, see the module's documentation): its operator's memory
    is put back afterwards (``checkpoint``/``restore``) and its controller is reset, as every run
    does at its start.

    ``None`` when the operator has no working ``checkpoint`` or the program fails (the estimate then
    leaves the drive out; the run itself reports such errors).
    """
    hysteresis = getattr(drive, "hysteresis", None)
    try:
        memory = None if hysteresis is None else hysteresis.checkpoint()
    except Exception:  # noqa: BLE001 - an estimate must never stop a run
        return None
    controller = getattr(drive, "controller", None)
    try:
        if controller is not None:
            controller.reset()
        source = InStepStrain(drive)
        observe = controller.observe if controller is not None else None
        for k in range(2):
            _cycle(source, observe, k * step)
        best = float("inf")
        first = 2  # the batches go on in time from the warm-up
        for _ in range(BATCHES):
            start = time.perf_counter()
            for k in range(first, first + samples):
                _cycle(source, observe, k * step)
            first += samples
            best = min(best, (time.perf_counter() - start) / samples)
            if best > SLOW_CYCLE:
                break
        return best
    except Exception:  # noqa: BLE001 - an estimate must never stop a run
        return None
    finally:
        try:
            if hysteresis is not None:
                hysteresis.restore(memory)
            if controller is not None:
                controller.reset()
        except Exception:  # noqa: BLE001 - the run resets both at its start anyway
            pass


def _cycle(source: InStepStrain, observe: Any, t: float) -> None:
    """One step's work of a drive: the trial at ``t``, the commit and, in closed loop, the observation
    (of a zero measurement: the cost, not the response, is measured)."""
    source.trial(t)
    source.commit(t)
    if observe is not None:
        observe(t, 0.0)


def reference_drive_cost(step: float) -> float:
    """Cost per step [s] of the drive the cells' measured costs include (the paper's triangle and
    Preisach loop), measured once per process."""
    if not _reference:
        drive = PiezoDrive(Triangle(500.0, 1000.0, 0.5), hysteresis=paper_strain_preisach())
        _reference.append(drive_step_cost(drive, step) or 0.0)
    return _reference[0]


def extra_drive_cost(drives: Iterable[Any], step: float) -> float:
    """What the distinct ``drives`` cost per step [s] beyond the one reference drive the cells' costs
    include: their summed cost minus the reference drive's (a drive counted once however many
    segments share it; a drive that cannot be measured counts as the reference).  An excess below
    :data:`NOISE_SHARE` of the reference drive's cost is the measurement's noise and counts as 0:
    a drive like the paper's then never adds a share to one run's estimate and not to its twin's."""
    seen: set[int] = set()
    total = 0.0
    for drive in drives:
        if id(drive) in seen:
            continue
        seen.add(id(drive))
        cost = drive_step_cost(drive, step)
        total += reference_drive_cost(step) if cost is None else cost
    if not seen:
        return 0.0
    reference = reference_drive_cost(step)
    extra = total - reference
    return extra if extra > NOISE_SHARE * reference else 0.0


def drive_share(extra_per_step: float) -> str:
    """``" (of them ~X µs the drives' programs, operators and controllers)"`` when ``extra_per_step`` > 0 [s]."""
    if extra_per_step <= 0.0:
        return ""
    return f" (of them ~{extra_per_step * 1e6:.3g} µs the drives' programs, operators and controllers)"
