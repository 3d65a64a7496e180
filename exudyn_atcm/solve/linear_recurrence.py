"""Linear recurrences ``z_{n+1} = A z_n + b u_n`` evaluated in blocks with numpy (the step choice's stand-in).

:func:`first_component` gives ``e_0 . z_n`` for ``n = 1 ... N`` from ``z_0 = 0``, the output a linear
filter of ``u`` (what ``scipy.signal.lfilter`` computes from the transfer function), in the state
form: no characteristic polynomial, whose coefficients lose accuracy when poles crowd near 1, and no
import of :mod:`scipy.signal` (about a second with the :mod:`scipy.stats` it loads).  The samples are
cut into blocks of ``L``; inside every block the response from a zero state is one product with the
``L x L`` Toeplitz matrix of the impulse response ``e_0 A^m b``, and the states at the blocks'
starts follow from one short loop over the blocks (``z <- A^L z + ...``).  The cost is about
``N (L + 2 size)`` multiplications and ``N / L`` Python steps; ``A`` with a spectral radius at most 1
(stable or marginally stable, as the stand-in's integrators) keeps every product bounded.

May import: numpy.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["first_component", "first_order"]

#: Block length bounds: ``L`` is about ``sqrt(N)`` (the Toeplitz products against the loop over blocks).
SMALLEST_BLOCK, LARGEST_BLOCK = 16, 256


def block_length(n: int) -> int:
    """The block length ``L`` for ``n`` samples: the power of two nearest ``sqrt(n)`` within the bounds."""
    return int(min(LARGEST_BLOCK, max(SMALLEST_BLOCK, 2 ** round(math.log2(math.sqrt(max(n, 1)))))))


def first_component(a: np.ndarray, b: np.ndarray, u: np.ndarray) -> np.ndarray:
    """``e_0 . z_n`` for ``n = 1 ... len(u)`` of ``z_{n+1} = A z_n + b u_n``, ``z_0 = 0``.

    ``a``: the square matrix ``A``; ``b``: the input vector; ``u``: the input samples (real or
    complex; the result takes the common type).  Raises ``ValueError`` for mismatched shapes.
    """
    a = np.atleast_2d(np.asarray(a))
    b = np.atleast_1d(np.asarray(b))
    u = np.asarray(u)
    size = a.shape[0]
    if a.shape != (size, size) or b.shape != (size,) or u.ndim != 1:
        raise ValueError(f"first_component: a must be square, b a vector of its order and u 1-D, got shapes "
                         f"{a.shape}, {b.shape}, {u.shape}")
    dtype = np.result_type(a, b, u, float)
    n = u.size
    if n == 0:
        return np.zeros(0, dtype=dtype)
    length = block_length(n)
    # powers[m] = A^m, m = 0 ... L
    powers = np.empty((length + 1, size, size), dtype=dtype)
    powers[0] = np.eye(size)
    for m in range(length):
        powers[m + 1] = a @ powers[m]
    impulse = powers[:length, 0, :] @ b  # g_m = e_0 A^m b
    index = np.arange(length)
    lag = index[None, :] - index[:, None]  # T[j, i] = g_{i - j} for j <= i
    toeplitz = np.where(lag >= 0, impulse[np.clip(lag, 0, None)], 0.0)
    to_end = powers[length - 1::-1, :, :] @ b  # row j: A^(L-1-j) b, the input j's share of the block's end state
    from_start = powers[1:, 0, :]  # row i: e_0 A^(i+1), the start state's share of output i
    blocks = -(-n // length)
    inputs = np.zeros(blocks * length, dtype=dtype)
    inputs[:n] = u
    inputs = inputs.reshape(blocks, length)
    out = inputs @ toeplitz
    ends = inputs @ to_end
    across = powers[length]
    starts = np.zeros((blocks, size), dtype=dtype)
    for k in range(1, blocks):
        starts[k] = across @ starts[k - 1] + ends[k - 1]
    out += starts @ from_start.T
    return out.reshape(-1)[:n]


def first_order(pole: complex, x: np.ndarray) -> np.ndarray:
    """``c_k = x_k + pole c_{k-1}`` (``c_{-1} = 0``) for every sample of ``x``: :func:`first_component` of order 1."""
    return first_component(np.array([[pole]]), np.array([1.0]), x)
