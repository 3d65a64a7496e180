"""The Fig. 12 case's ``last_cycle_change``: the change between the last two cycles, never the first.

References: a synthetic record (a periodic part plus a decaying transient ``A exp(-t/tau)``)
whose cycle-to-cycle change is known in closed form; and the free vibration of the first
bending mode under the actuator's stiffness-proportional damping ``d = beta k``: modal damping
``zeta_1 = beta omega_1 / 2``, so the start transient, and with it the change from one cycle to
the next, decays by ``exp(-zeta_1 omega_1 T)`` per input period ``T`` (``omega_1`` from the
linearised actuator, :func:`exudyn_atcm.eigenfrequencies`).  The paper's loop starts at the
saturation voltage -500 V, which wipes out the Preisach memory (Mayergoyz 2003), so the drive's
strain is periodic from t = 0 and only the dynamics carry a transient.
"""

from __future__ import annotations

import importlib.util
import math
import sys

import numpy as np
import pytest

from exudyn_atcm import eigenfrequencies

from _cli_helpers import CASES


@pytest.fixture(scope="module")
def case_module():
    spec = importlib.util.spec_from_file_location("paper_bending_actuator_cycles", CASES / "paper_bending_actuator.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    yield module
    sys.modules.pop(spec.name, None)


@pytest.mark.parametrize("cycles", [3, 4, 5])
def test_change_of_a_decaying_transient_in_closed_form(case_module, cycles):
    T, tau, A = 1.0, 0.4, 2e-3
    t = np.round(np.arange(0, cycles * 1000 + 1) * 1e-3, 12)
    # the periodic part repeats exactly on the 1 ms record; the transient decays
    y = 5e-3 * np.sin(2 * np.pi * t / T) + 1e-3 * np.abs(np.sin(6 * np.pi * t / T)) + A * np.exp(-t / tau)
    # |A e^{-t/tau} - A e^{-(t-T)/tau}| is largest at the start of the last cycle, t = (N-1) T
    expected = A * math.exp(-(cycles - 2) * T / tau) * (1.0 - math.exp(-T / tau))
    assert case_module.last_cycle_change(t, y, T, cycles) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("cycles", [1, 2])
def test_fewer_than_three_cycles_give_no_number(case_module, cycles):
    t = np.linspace(0.0, cycles, 101)
    assert case_module.last_cycle_change(t, np.exp(-t), 1.0, cycles) is None


def test_case_change_decays_as_the_first_mode_per_cycle(case_module, tmp_path):
    T, cycles = 0.5, 4
    case = case_module.CASE
    # at the step the case used to fix (its default now chooses one for `accuracy`: 2.5e-4 s here, where the
    # decay ratios below hold too, 1.7 % and 0.3 % off, but the strain repeats to 1.4e-12 of its peak, not 1e-12)
    out = case.run({"cell": "rigid", "period": T, "cycles": cycles, "animation": False, "step": 1e-4}, out_dir=tmp_path,
                   plot=False)
    r = out.result
    t, y, strain = r["time"], r["actuator.tip_y"], r["actuator.strain"]
    # the drive is periodic from the start (the loop starts at its saturation voltage)
    n = int(round(T / 1e-3))
    np.testing.assert_allclose(strain[n:], strain[:-n], rtol=0, atol=1e-12 * np.max(np.abs(strain)))
    change_4_3 = out.scalars["last_cycle_change"]
    upto3 = t <= 3 * T + 1e-12
    change_3_2 = case_module.last_cycle_change(t[upto3], y[upto3], T, 3)
    change_2_1 = float(np.max(np.abs(y[(t >= T - 1e-12) & upto3][: n + 1] - y[: n + 1])))
    actuator = case_module.build(case.resolve({"cell": "rigid", "period": T, "cycles": cycles}))
    omega1 = 2 * math.pi * eigenfrequencies(actuator, n=1)[0]
    zeta1 = actuator.stiffness_damping_factor * omega1 / 2
    decay = math.exp(-zeta1 * omega1 * T)
    # 5 %: the largest change in a cycle falls within its first oscillation of the mode, where
    # the envelope varies by exp(-2 pi zeta1) (11 %); measured 0.2-1.5 % off
    assert change_4_3 / change_3_2 == pytest.approx(decay, rel=0.05)
    assert change_3_2 / change_2_1 == pytest.approx(decay, rel=0.05)
    # what the metric used to report (cycle 2 against cycle 1) is 1/decay ~ 8x larger here
    assert change_2_1 > 5 * change_3_2


def test_case_with_two_cycles_says_why_there_is_no_change(case_module, tmp_path):
    out = case_module.CASE.run({"cell": "rigid", "period": 0.2, "cycles": 2, "animation": False}, out_dir=tmp_path,
                               plot=False)
    assert "last_cycle_change" not in out.scalars
    assert "needs cycles >= 3 (ran 2)" in out.notes["last_cycle_change"]
    assert case_module.CASE.resolve({})["cycles"] >= 3  # the default reports it
