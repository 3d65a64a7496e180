"""No private arguments in the public API (they would show in the API reference)."""

from __future__ import annotations

import inspect

import pytest

import exudyn_atcm
from exudyn_atcm import cell_drawing, hysteresis, signals


def _public_callables():
    for module in (exudyn_atcm, hysteresis, signals, cell_drawing):
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name)
            if inspect.isclass(obj):
                for attr, member in inspect.getmembers(obj, callable):
                    if not attr.startswith("_") or attr == "__init__":
                        yield f"{module.__name__}.{name}.{attr}", member
            elif callable(obj):
                yield f"{module.__name__}.{name}", obj


@pytest.mark.parametrize("qualname, member", list(_public_callables()), ids=lambda v: v if isinstance(v, str) else "")
def test_no_private_parameters(qualname, member):
    try:
        parameters = inspect.signature(member).parameters
    except (TypeError, ValueError):  # builtins without a signature
        return
    private = [p for p in parameters if p.startswith("_")]
    assert not private, f"{qualname} has private parameters {private}"


def test_evaluate_and_commit_take_only_the_input():
    for cls in (hysteresis.ContinuousPreisach, hysteresis.DiscretePreisach, hysteresis.StaircasePreisach):
        for method in ("evaluate", "commit"):
            assert list(inspect.signature(getattr(cls, method)).parameters) == ["self", "u"], (cls, method)
