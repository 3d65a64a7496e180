"""Exceptions of the solve layer that the layers below it raise too."""

from __future__ import annotations

__all__ = ["SolverError"]


class SolverError(RuntimeError):
    """The multibody solver failed; the message says where, what was tried and what to change."""
