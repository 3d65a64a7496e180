"""The package's dense algebra on one BLAS thread: :func:`one_blas_thread`, :func:`on_one_blas_thread`.

Its matrices have tens to a few hundred rows.  A second BLAS thread gains nothing there, and costs:

* on a machine whose cores are busy (a study's workers), threads waiting for each other made a
  192-row Cholesky factorisation 13 times slower (8.7 ms against 0.65 ms, measured);
* a threaded OpenBLAS leaves its workers spinning for about 0.1 s of CPU after each threaded call
  (measured on two cores: 0.20 s after building the micro gripper with 24 rigid cells, whose
  redundancy check takes an SVD; 0.42 s after its eigenfrequencies with 64 cells; 0.13 s after a
  cell choice's stand-in), a core taken from a parallel study's other worker.

So the package's own dense algebra (the redundancy check, eigenvalue analyses, linear models, the
stability checks, the stand-ins of the step and cell choices) runs inside :func:`one_blas_thread`;
the user's numpy code outside it keeps the process's thread counts.

May import: threadpoolctl (a declared dependency).
"""

from __future__ import annotations

import contextlib
import functools
import sys
from typing import Callable, TypeVar

try:  # a declared dependency
    from threadpoolctl import ThreadpoolController
except ImportError:  # pragma: no cover
    ThreadpoolController = None

__all__ = ["one_blas_thread", "on_one_blas_thread"]

F = TypeVar("F", bound=Callable)

#: the BLAS libraries' thread controllers and the number of modules loaded when they were found (a module imported
#: since may have brought its own BLAS: scipy's OpenBLAS is not numpy's)
_BLAS: list = []


@contextlib.contextmanager
def one_blas_thread():
    """Context manager: the BLAS calls inside on one thread.  The libraries are found once (threadpoolctl's
    controller), and again when modules were imported since; each use then only reads and sets their thread
    counts (a few us; threadpoolctl's ``limit`` scans the libraries again on every call: about 60 us, measured, a
    fifth of a continuation point's check).  Inside another use it only reads them (a sweep holds one around all
    its points' checks).  A library loaded inside the block (a lazy ``import scipy.linalg``) is not limited in
    it: import first, then enter."""
    if ThreadpoolController is None:
        yield
        return
    if not _BLAS or _BLAS[1] != len(sys.modules):
        _BLAS[:] = [ThreadpoolController().select(user_api="blas").lib_controllers, len(sys.modules)]
    libraries = _BLAS[0]
    saved = [lib.get_num_threads() for lib in libraries]
    try:
        for lib, n in zip(libraries, saved):
            if n != 1:
                lib.set_num_threads(1)
        yield
    finally:
        for lib, n in zip(libraries, saved):
            if n != 1:
                lib.set_num_threads(n)


def on_one_blas_thread(function: F) -> F:
    """Decorator: ``function``'s calls inside :func:`one_blas_thread`."""
    @functools.wraps(function)
    def wrapped(*args, **kwargs):
        with one_blas_thread():
            return function(*args, **kwargs)
    return wrapped  # type: ignore[return-value]
