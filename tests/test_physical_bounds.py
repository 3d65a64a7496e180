"""Values no material or model can have are refused before the run, with the reason (issue 17, part 5)."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.model.drive import PiezoDrive
from exudyn_atcm.hysteresis import DiscretePreisach, PrandtlIshlinskii
from exudyn_atcm.model.materials import Layer
from exudyn_atcm.physical_bounds import MAX_OPERATOR_ELEMENTS, PHYSICAL_LIMITS

from _cli_helpers import CASES, cli


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"d33": 1e300}, r"PiezoDrive: d33 = 1e\+300 m/V cannot be physical \(.*PMN-PT.*\); it must be <= 1e-07 m/V"),
        ({"d33": 1.01e-7}, r"d33 = 1.01e-07 m/V cannot be physical"),
        ({"electrode_spacing": 1e-300}, r"electrode_spacing = 1e-300 m cannot be physical .* it must be >= 1e-07 m"),
    ],
)
def test_drive_values_beyond_any_material_are_refused(kwargs, words):
    with pytest.raises(ValueError, match=words):
        PiezoDrive(100.0, **kwargs)


def test_drive_limits_admit_every_real_material():
    # the MFC P1 (4.6e-10 m/V, 0.5 mm), PZT-5H (5.9e-10), PMN-PT single crystal (2.8e-9): accepted
    for d33 in (460e-12, 593e-12, 2.8e-9, PHYSICAL_LIMITS["d33"][1]):
        assert PiezoDrive(100.0, d33=d33).d33 == d33
    assert PiezoDrive(100.0, electrode_spacing=1e-6).electrode_spacing == 1e-6


@pytest.mark.parametrize(
    "values, words",
    [
        ((0.2e-3, 1e300, 1550.0), r"Layer: youngs_modulus = 1e\+300 Pa cannot be physical \(.*diamond.*\); it must be <= 1e\+13 Pa"),
        ((0.2e-3, 70e9, 1e9), r"Layer: density = 1000000000.0 kg/m\^3 cannot be physical \(.*osmium.*\)"),
        ((1e-12, 70e9, 1550.0), r"Layer: thickness = 1e-12 m cannot be physical \(.*atomic layer.*\); it must be >= 1e-10 m"),
    ],
)
def test_layer_values_beyond_any_material_are_refused(values, words):
    with pytest.raises(ValueError, match=words):
        Layer(*values)


def test_real_extremes_are_accepted():
    Layer(0.2e-3, 1.2e12, 22600.0)  # diamond's modulus, osmium's density
    Layer(0.2e-3, 70e9, 1550.0)


def _loop(n_samples: int = 200):
    u = np.concatenate([np.linspace(0.0, 1.0, n_samples), np.linspace(1.0, 0.0, n_samples)[1:]])
    y = np.concatenate([u[:n_samples] ** 2, 1.0 - (1.0 - u[n_samples:]) ** 2])
    return u, y


def test_a_million_relays_or_plays_are_refused_before_computing():
    u, y = _loop()
    with pytest.raises(ValueError, match=rf"n = 1000000 relays is more than {MAX_OPERATOR_ELEMENTS} relays"):
        DiscretePreisach.from_loop(u, y, 1_000_000)
    with pytest.raises(ValueError, match=rf"n = 2000000 plays is more than {MAX_OPERATOR_ELEMENTS} plays"):
        PrandtlIshlinskii.fit(u, y, 2_000_000)
    n = MAX_OPERATOR_ELEMENTS + 1
    with pytest.raises(ValueError, match=r"len\(alpha\) = 100001 relays"):
        DiscretePreisach(np.ones(n), np.zeros(n), np.ones(n))
    with pytest.raises(ValueError, match=r"len\(radii\) = 100001 plays"):
        PrandtlIshlinskii(np.arange(n, dtype=float), np.ones(n), 1.0)
    # a usual count still identifies: 6 relays (the paper's model)
    assert DiscretePreisach.from_loop(u, y, 6).n_relays == 6


def test_the_command_line_refuses_a_million_relays_at_once(tmp_path):
    proc = cli(["run", str(CASES / "paper_discrete_preisach.py"), "--set", "n_relays=1000000", "--out", "o", "--no-plot"], tmp_path)
    assert proc.returncode == 1
    assert "n = 1000000 relays is more than 100000 relays" in proc.stderr.strip().splitlines()[-1]
