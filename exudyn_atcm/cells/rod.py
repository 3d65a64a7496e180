"""``cell="rod"``: the whole bender as a geometrically exact rod in assumed modes of its rotation field."""

from __future__ import annotations

import math

from .base import END_NODE, CellKind

__all__ = ["RodCell"]


class RodCell(CellKind):
    """The bender as ``n`` assumed modes of its rotation field with the exact nonlinear kinematics and inertia.

    :mod:`exudyn_atcm.theory.rotation_rod`: the modes of the ``ritz`` cell, but position, mass
    matrix, quadratic velocity terms and the tip pose are the exact functions of the
    coordinates, so large rotations, tip loads and end connections are modelled (the ``ritz``
    cell linearises about the quasi-static arc).  ``n_cells`` is the number of modes (per
    segment: a bender of segments has each segment's modes on its own length, so a piecewise
    free curvature is exact); ``cell_angle_j`` is the mean rotation of the ``j``-th of a
    segment's ``n_cells`` equal parts, counted from the base.  Exact arc under actuation for any
    ``n``.  Both ends are nodes with position and rotation that joints,
    welds and loads attach to: the rod rides on its base node (a moving frame) and its tip node
    is tied to the rod's exact tip pose.
    """

    name = "rod"
    stroke_paths = ("prestep",)
    summary = "geometrically exact rod in assumed modes of its rotation field (few coordinates)"
    chain_of_cells = False
    end_kind = END_NODE
    joint_label = "segment ends"
    # bench_run_cost.py of 2026-11-29 (0.2 s, best of 3, lone actuator, the set-up subtracted): 36, 44, 66, 113, 238
    # and 715 µs per step at 3, 6, 10, 16, 24 and 40 modes: the dense modal block grows as n^2; the fit a + c n^2
    # (relative least squares) is within -14 % ... +10 % of each.  The constants before, (70, 0.8, 0) µs from 3 to
    # 12 modes, predicted 0.14 of a 40-mode run's cost, so its long run was not announced
    cost_per_step = (31e-6, 0.0, 0.37e-6)
    # bench_build_cost.py of 2026-11-28 (best of 2, fresh process each): 0.016, 0.056 and 0.83 s and 0, 0.3 and
    # 8.2 MB at 8, 32 and 128 modes (dense in the modes); the fit n (a + b n) s, memory k = 8.2 MB / 128^2
    build_cost = (1.3e-3, 3.1e-5, 0.0, 500.0)
    # the inertia and the tip tie predicted to second order and re-evaluated at the solved state of each step
    # (exudyn_atcm.mbs.chains.rod): against an exact integration of the same modes, observed orders 1.8-2.0 at tip
    # rotations of 0.85-2.7 rad (tests/test_rod_dynamics.py); frozen at the step's start, as before, it was 1
    time_order = 2.0
    space_order = math.inf  # n assumed modes: f1 errors 4.7e-3, 2.8e-4, 1.7e-5 at n = 2, 3, 4 (bench_rod_vs_ritz.py)
    limits = ("one laminate per bender (segments with their own drives: each segment's n_cells modes on its own "
              "length); inextensible and shear-rigid (Euler-Bernoulli); the mass matrix, the quadratic velocity "
              "terms and the tip pose's linearisation are predicted for each step's end and re-evaluated after "
              "its Newton solve until they agree with the solved state (to 1e-7 rad)")
