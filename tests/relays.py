"""Independent reference: a plain relay-by-relay simulation (no staircase, no prefix sums)."""

from __future__ import annotations

import numpy as np


def relay_outputs(alpha, beta, weights, offset, inputs):
    """Outputs of parallel non-ideal relays, each updated individually at every input.

    Relay rule (Mayergoyz 2003): on if ``u >= alpha``; otherwise off if ``u <= beta``;
    otherwise unchanged.  All relays start off.
    """
    alpha = [float(a) for a in alpha]
    beta = [float(b) for b in beta]
    weights = [float(w) for w in weights]
    state = [0] * len(alpha)
    outputs = []
    for u in inputs:
        for i in range(len(alpha)):
            if u >= alpha[i]:
                state[i] = 1
            elif u <= beta[i]:
                state[i] = 0
        outputs.append(offset + sum(w for w, s in zip(weights, state) if s))
    return np.array(outputs)


def equal_gain_relays(model, n):
    """Eq. 12 relays of a ContinuousPreisach built from the analytic branch inverses.

    Relay i = 1..n at level y_i = y_min + i*dy switches on where the ascending branch
    reaches y_i and off where the descending branch does.
    """
    dy = (model.y_max - model.y_min) / n
    levels = model.y_min + dy * np.arange(1, n + 1)
    s = np.clip((levels - model.y_min) / (model.y_max - model.y_min), 0.0, 1.0)
    du = model.u_max - model.u_min
    alpha = model.u_min + du * s ** (1.0 / model.r1)
    beta = model.u_max - du * (1.0 - s) ** (1.0 / model.r2)
    return alpha, beta, np.full(n, dy), model.y_min
