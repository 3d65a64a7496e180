"""EverettPreisach: a relay grid's weights spread over their cells (continuous output)."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_atcm.hysteresis import DiscretePreisach, EverettPreisach
from exudyn_atcm.hysteresis.identification import relay_grid

from relays import relay_outputs

N = 5
EDGES = np.linspace(-1.0, 1.0, N + 1)
ALPHA, BETA, INDEX = relay_grid(-1.0, 1.0, N)
WEIGHTS = 0.5 + np.cos(ALPHA) * (1.0 + BETA)  # non-uniform, > 0
HISTORY = [-1.0, 0.83, -0.27, 0.41, -0.05, 0.66, 0.12, 0.2, -0.9, 0.95, 0.3, 0.31, -1.0]


def sub_relays(k):
    """Every cell cut into k x k sub-cells, each carrying its area's share of the weight;
    on diagonal cells only the sub-cells with alpha >= beta (the diagonal ones half)."""
    h = 2.0 / N
    offsets = (np.arange(k) + 0.5) * h / k
    a_list, b_list, w_list = [], [], []
    for (i, j), w in zip(INDEX.tolist(), WEIGHTS.tolist()):
        for sa in range(k):
            for sb in range(k):
                if i == j and sb > sa:
                    continue
                area = 0.5 if (i == j and sa == sb) else 1.0
                a_list.append(EDGES[i] + offsets[sa])
                b_list.append(EDGES[j] + offsets[sb])
                w_list.append(area)
    a, b, w = np.array(a_list), np.array(b_list), np.array(w_list)
    # normalise per cell so each cell keeps its weight
    cell_of = np.searchsorted(EDGES, a) - 1, np.searchsorted(EDGES, b) - 1
    total = np.zeros((N, N))
    np.add.at(total, cell_of, w)
    cell_weight = np.zeros((N, N))
    cell_weight[INDEX[:, 0], INDEX[:, 1]] = WEIGHTS
    return a, b, w / total[cell_of] * cell_weight[cell_of]


def test_everett_is_the_limit_of_finely_split_relays():
    path = np.concatenate([np.linspace(x0, x1, 40, endpoint=False) for x0, x1 in zip(HISTORY[:-1], HISTORY[1:])])
    model = EverettPreisach(EDGES, ALPHA, BETA, WEIGHTS, offset=0.3)
    got = model.apply(path)
    for k, bound in ((4, None), (16, None)):
        a, b, w = sub_relays(k)
        reference = relay_outputs(a, b, w, 0.3, path)
        error = np.abs(got - reference).max()
        # the split relays jump by at most one sub-cell's weight share (largest cell weight / k)
        # times the cells crossed at once; the error shrinks like 1/k
        assert error <= 2.0 * WEIGHTS.max() / k, (k, error)


def test_everett_equals_the_grid_at_cell_edges_and_is_continuous():
    grid = DiscretePreisach(ALPHA, BETA, WEIGHTS, offset=0.3)
    everett = EverettPreisach(EDGES, ALPHA, BETA, WEIGHTS, offset=0.3)
    # histories whose reversal points lie on cell edges: both models agree at every edge
    edges_path = [-1.0, 0.6, -0.2, 1.0, 0.2, 0.6, -1.0]
    fine = np.concatenate([np.linspace(x0, x1, 201) for x0, x1 in zip(edges_path[:-1], edges_path[1:])])
    on_edge = np.isclose(fine[:, None], EDGES[None, :], atol=1e-12).any(axis=1)
    np.testing.assert_allclose(everett.apply(fine)[on_edge], grid.apply(fine)[on_edge], atol=1e-12)
    # continuity: no jump larger than what a 0.002 input step can give (density <= w / h^2 area-wise)
    steps = np.abs(np.diff(everett.apply(fine)))
    assert steps.max() < 0.05 * WEIGHTS.sum() / N
    assert np.abs(np.diff(grid.apply(fine))).max() > 10 * steps.max()  # the grid's staircase


def test_everett_fit_recovers_a_spread_density_exactly():
    truth = EverettPreisach(EDGES, ALPHA, BETA, WEIGHTS)
    u = np.concatenate([np.linspace(x0, x1, 80, endpoint=False) for x0, x1 in zip(HISTORY[:-1], HISTORY[1:])])
    y = truth.apply(u)
    # no regularisation at all (prior="smooth" with smoothing 0): the plain least squares
    everett, rep_e = EverettPreisach.fit(u, y, N, input_range=(-1.0, 1.0), smoothing=0.0, prior="smooth")
    _, rep_d = DiscretePreisach.fit(u, y, N, input_range=(-1.0, 1.0), smoothing=0.0, prior="smooth")
    # the cell basis is the truth's own: the output is reproduced to round-off (NNLS tolerance)
    assert rep_e.model_errors["fit"]["max"] < 1e-8 * np.ptp(y)
    # the relay grid cannot: its staircase error stays
    assert rep_d.model_errors["fit"]["rms"] > 1e-3 * np.ptp(y)
    assert rep_e.method == "EverettPreisach.fit"
    assert rep_e.settings["basis"] == "cells"


def test_everett_rejects_bad_relays():
    with pytest.raises(ValueError, match="strictly inside the edges"):
        EverettPreisach(EDGES, [1.5], [0.0], [1.0])
    with pytest.raises(ValueError, match=r"weights must be >= 0 \(a non-negative density\), got weights\[0\] = -1.0"):
        EverettPreisach(EDGES, [0.5], [0.0], [-1.0])
    with pytest.raises(ValueError, match=r"alpha must be >= beta for every relay, got alpha\[0\] = 0.0 < beta\[0\] = 0.5"):
        EverettPreisach(EDGES, [0.0], [0.5], [1.0])
    with pytest.raises(ValueError, match=r"edges must be strictly increasing, got edges\[1\] = 0.0 after 0.0"):
        EverettPreisach([0.0, 0.0, 1.0], [0.5], [0.5], [1.0])
